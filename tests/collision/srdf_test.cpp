// Allowed collision pairs (issue 33, item 5): the <disable_collisions> entries of an SRDF file read
// and written, applied to the collision model by link name, and found by sampling as MoveIt's
// setup assistant does, on a robot of boxes whose adjacent, default and never-colliding pairs are
// worked out by hand.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <tuple>

#include "collision/column_urdf.h"
#include "mcws/collision/allowed_pairs.h"
#include "mcws/collision/collision_checker.h"
#include "mcws/collision/collision_model.h"
#include "mcws/collision/srdf.h"
#include "mcws/core/error.h"
#include "mcws/kinematics/robot_urdf.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

struct Column {
  Robot robot;
  CollisionModel model;
};

Column column() {
  const UrdfChainOptions chain{"", "link3"};
  Column c{parseRobotUrdf(test::kColumnUrdf, "column.urdf", chain), {}};
  c.model = parseCollisionUrdf(c.robot, test::kColumnUrdf, "column.urdf", chain);
  return c;
}

/// Entries as (lower link, higher link, reason), order aside.
std::set<std::tuple<std::string, std::string, std::string>> asSet(
    const std::vector<DisabledCollision>& pairs) {
  std::set<std::tuple<std::string, std::string, std::string>> out;
  for (const DisabledCollision& p : pairs) {
    out.insert({std::min(p.link1, p.link2), std::max(p.link1, p.link2), p.reason});
  }
  return out;
}

TEST(Srdf, WrittenAndReadBackTheSame) {
  const std::vector<DisabledCollision> pairs = {
      {"base_link", "link1", "Adjacent"}, {"a&b", "c\"d", "Never"}, {"link1", "link3", "Default"}};
  const std::string text = srdfText("column<1>", pairs);
  EXPECT_THAT(text, HasSubstr("<robot name=\"column&lt;1&gt;\">"));
  EXPECT_THAT(
      text,
      HasSubstr(R"(<disable_collisions link1="base_link" link2="link1" reason="Adjacent"/>)"));
  EXPECT_EQ(parseSrdf(text, "x.srdf"), pairs);
}

TEST(Srdf, ReadsMoveItFileSkippingOtherElements) {
  const std::string text = R"(<?xml version="1.0" ?>
<robot name="column">
  <group name="arm"><chain base_link="base_link" tip_link="link3"/></group>
  <!-- <disable_collisions link1="x" link2="y" reason="Never"/> -->
  <disable_collisions link1="link1" link2="link3" reason="Default" />
  <virtual_joint name="fixed" type="fixed" parent_frame="world" child_link="base_link"/>
  <disable_collisions link2="post" link1="link2"/>
</robot>)";
  const std::vector<DisabledCollision> expected = {{"link1", "link3", "Default"},
                                                   {"link2", "post", ""}};
  EXPECT_EQ(parseSrdf(text, "arm.srdf"), expected);
}

TEST(Srdf, BadInputIsOneLineNamingTheFile) {
  const auto error = [](const std::string& text) {
    return test::errorOf([&] { parseSrdf(text, "arm.srdf"); });
  };
  EXPECT_THAT(error("<robot><disable_collisions link1=\"a\" link2=\"b\"></robot>"),
              HasSubstr("arm.srdf: malformed XML on line 1"));
  EXPECT_EQ(error("<robot>\n<disable_collisions link1=\"a\"/></robot>"),
            "arm.srdf: line 2: disable_collisions needs link1 and link2");
  EXPECT_EQ(
      error("<robot><disable_collisions link1=\"a\" link2=\"a\"/></robot>"),
      "arm.srdf: line 1: disable_collisions link1=\"a\" link2=\"a\" pairs a link with itself");
  EXPECT_EQ(error("<kinbody/>"), "arm.srdf: not an SRDF file (its root element is not <robot>)");
  std::string deep = "<robot>";
  for (int i = 0; i < 1001; ++i) deep += "<a>";
  EXPECT_EQ(error(deep), "arm.srdf: XML nested deeper than 1000 elements");
}

TEST(Srdf, PairNamingAnUnknownLinkIsOneLineNamingFilePairAndLink) {
  Column c = column();
  const std::string message = test::errorOf([&] {
    applySrdf(c.model, {{"link1", "link2", ""}, {"link1", "lnk3", "Never"}}, "arm.srdf");
  });
  EXPECT_EQ(message,
            "arm.srdf: disable_collisions link1=\"link1\" link2=\"lnk3\": 'lnk3' is not a link of "
            "the robot");
  // A link without geometry is a link: accepted, and removes nothing.
  c = column();
  applySrdf(c.model, {{"marker", "link1", "Never"}}, "arm.srdf");
  EXPECT_TRUE(c.model.allowed.empty());
}

TEST(Srdf, DisabledPairIsNoLongerChecked) {
  Column c = column();
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(3);
  // link1 and link3 overlap at q = 0 (see test::kColumnUrdf): label link-link.
  EXPECT_EQ(CollisionChecker(c.robot, c.model).label(q), kLabelLinkLink);
  // link3 is the one link of body j3; link2 and link2_cap make body j2, so disabling only
  // link2 - base_link keeps the base - j2 pair checked.
  applySrdf(c.model, {{"link3", "link1", "Default"}, {"base_link", "link2", "Never"}}, "a.srdf");
  const std::vector<std::pair<std::string, std::string>> allowed = {{"j1", "j3"}};
  EXPECT_EQ(c.model.allowed, allowed);
  const CollisionChecker checker(c.robot, c.model);
  EXPECT_EQ(checker.label(q), kLabelFree);
  for (const PairReport& pair : checker.report(q)) {
    EXPECT_FALSE(pair.body_a == "j1" && pair.body_b == "j3");
  }
  applySrdf(c.model, {{"base_link", "link2", "Never"}, {"link2_cap", "base_link", "Never"}}, "a");
  EXPECT_EQ(c.model.allowed.back(), (std::pair<std::string, std::string>{"base", "j2"}));
}

TEST(AllowedPairs, FindsTheHandWorkedPairsOfTheColumn) {
  const Column c = column();
  using Entry = std::tuple<std::string, std::string, std::string>;
  const std::set<Entry> expected = {
      {"base_link", "link1", "Adjacent"}, {"link1", "link2", "Adjacent"},
      {"link1", "link2_cap", "Adjacent"}, {"link2", "link3", "Adjacent"},
      {"link2_cap", "link3", "Adjacent"}, {"link2", "link2_cap", "Adjacent"},
      {"base_link", "post", "Adjacent"},  {"link1", "link3", "Default"},
      {"base_link", "link2", "Never"},    {"base_link", "link2_cap", "Never"},
      {"base_link", "link3", "Never"},    {"link1", "post", "Never"},
      {"link2", "post", "Never"},         {"link2_cap", "post", "Never"},
      {"link3", "post", "Never"}};
  const std::vector<DisabledCollision> found = findAllowedPairs(c.robot, c.model, 200, 7);
  EXPECT_EQ(found.size(), expected.size());
  EXPECT_EQ(asSet(found), expected);
  // Adjacent entries first, then Default, then Never.
  EXPECT_TRUE(std::is_sorted(found.begin(), found.end(), [](const auto& a, const auto& b) {
    const auto rank = [](const std::string& r) {
      return r == "Adjacent" ? 0 : r == "Default" ? 1 : r == "Always" ? 2 : 3;
    };
    return rank(a.reason) < rank(b.reason);
  }));
  EXPECT_EQ(findAllowedPairs(c.robot, c.model, 200, 7), found);
  EXPECT_THAT(test::errorOf([&] { findAllowedPairs(c.robot, c.model, 0, 7); }),
              HasSubstr("at least one sample"));
}

TEST(AllowedPairs, PairThatCollidesInSomeSamplesIsKept) {
  // link2 made a 0.7 m arm along x that j1 and j2 swing round through a post moved to 0.6 m along
  // y at its height: they collide only when the arm points at the post (not at q = 0), so that
  // pair is neither Default, Always nor Never.
  std::string text = test::kColumnUrdf;
  const std::string post = "<origin xyz=\"1 0 0\"/>";
  text.replace(text.find(post), post.size(), "<origin xyz=\"0 0.6 0.5\"/>");
  const std::string link2 = "<link name=\"link2\"><collision>";
  text.replace(text.find(link2), link2.size(), link2 + "<origin xyz=\"0.35 0 0\"/>");
  text.replace(text.find("<box size=\"0.1 0.1 0.1\"/></geometry></collision></link>\n  <link "
                         "name=\"link2_cap\">"),
               std::string("<box size=\"0.1 0.1 0.1\"/>").size(), "<box size=\"0.7 0.1 0.1\"/>");
  const UrdfChainOptions chain{"", "link3"};
  const Robot robot = parseRobotUrdf(text, "swing.urdf", chain);
  const CollisionModel model = parseCollisionUrdf(robot, text, "swing.urdf", chain);
  const std::set<std::tuple<std::string, std::string, std::string>> found =
      asSet(findAllowedPairs(robot, model, 200, 3));
  for (const char* reason : {"Default", "Always", "Never"}) {
    EXPECT_FALSE(found.count({"link2", "post", reason})) << reason;
  }
  EXPECT_TRUE(found.count({"link1", "post", "Never"}));
}

}  // namespace
}  // namespace mcws
