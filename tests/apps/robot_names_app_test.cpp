// Names in results (issue 33 item 6): every tool's --json names the robot (its URDF <robot name>
// or the YAML robot's name), the frame whose origin it measures ("tip": a URDF's tip link, a D-H
// robot's tool or flange) and the length unit; the tools that read a cloud only take them from
// the cloud's header line (null when it records none), and the envelope's drawing, picture and
// mesh are titled by the robot, not by the cloud's file name. The robot is the UR5-shaped URDF of
// tests/kinematics/ur5_shaped_urdf.h, measured at ee_link, the leaf that is not the usual tool0.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "apps/tool_paths.h"
#include "kinematics/ur5_shaped_urdf.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

/// What every JSON of the UR5-shaped arm measured at ee_link must say.
void expectNamesEeLink(const test::RunResult& r, const std::string& tool) {
  ASSERT_EQ(r.exit_code, 0) << tool << ": " << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["robot"], "ur5_shaped") << tool << ": " << r.out;
  EXPECT_EQ(json["tip"], "ee_link") << tool << ": " << r.out;
  EXPECT_EQ(json["length_unit"], "m") << tool << ": " << r.out;
}

class RobotNamesApp : public ::testing::Test {
 protected:
  void SetUp() override { test::writeFile(urdf_, test::kUr5ShapedUrdf); }
  std::string file(const std::string& name) const { return dir_.file(name); }
  /// A cloud of the arm at ee_link and its boundary.
  void sampleEeLink() {
    ASSERT_EQ(test::run(kSample + robot_ + " --samples 3000 --output " + cloud_).exit_code, 0);
    ASSERT_EQ(test::run(kBoundary + " --input " + cloud_ + " --output " + rim_).exit_code, 0);
  }
  test::TempDir dir_;
  const std::string urdf_ = dir_.file("ur5.urdf");
  const std::string robot_ = " --robot " + urdf_ + " --tip ee_link";
  const std::string cloud_ = dir_.file("cloud.pcd"), rim_ = dir_.file("rim.pcd");
};

TEST_F(RobotNamesApp, EveryRobotToolNamesTheRobotTheTipAndTheUnit) {
  const std::string q = " --q '0.3 -1.1 1.4 -0.6 0.9 0.5'";
  expectNamesEeLink(test::run(kFk + robot_ + q + " --json"), "fk");
  expectNamesEeLink(test::run(kCollide + robot_ + q + " --json"), "collide");
  const auto fk = nlohmann::json::parse(test::run(kFk + robot_ + q + " --json").out);
  const auto& p = fk["position"];
  const std::string position = std::to_string(p[0].get<double>()) + " " +
                               std::to_string(p[1].get<double>()) + " " +
                               std::to_string(p[2].get<double>());
  expectNamesEeLink(
      test::run(kIk + robot_ + " --pose '" + position + " 0 0 0' --position-only --json"), "ik");
  expectNamesEeLink(test::run(kTraj + robot_ +
                              " --from '0.3 -1.1 1.4 -0.6 0.9 0.5' --to '0.3 "
                              "-1 1.4 -0.6 0.9 0.5' --duration 1 --rate 5 "
                              "--output " +
                              file("t.csv") + " --json"),
                    "traj");
  expectNamesEeLink(test::run(kReach + robot_ + " --resolution 20cm --samples 1000 --output " +
                              file("map.pcd") + " --json"),
                    "reach (map)");
  test::writeFile(file("targets.csv"), "x,y,z,normal_x,normal_y,normal_z\n" +
                                           std::to_string(p[0].get<double>()) + "," +
                                           std::to_string(p[1].get<double>()) + "," +
                                           std::to_string(p[2].get<double>()) + ",0,0,1\n");
  expectNamesEeLink(test::run(kReach + robot_ + " --targets " + file("targets.csv") +
                              " --no-collision --output " + file("heat.pcd") + " --json"),
                    "reach (targets)");
  expectNamesEeLink(
      test::run(kPlace + robot_ + " --targets " + file("targets.csv") +
                " --along '0 0 1' --resolution 20cm --samples 1000 --no-collision --map-cache off "
                "--output " +
                file("bases.pcd") + " --json"),
      "place");
  expectNamesEeLink(test::run(kSample + robot_ + " --samples 3000 --output " + cloud_ + " --json"),
                    "sample");
  ASSERT_EQ(test::run(kBoundary + " --input " + cloud_ + " --output " + rim_).exit_code, 0);
  expectNamesEeLink(test::run(kRefine + robot_ + " --input " + rim_ + " --samples 100 --output " +
                              file("r.pcd") + " --json"),
                    "refine");
}

TEST_F(RobotNamesApp, TheCloudRecordsTheChainAndTheCloudToolsNameIt) {
  sampleEeLink();
  EXPECT_THAT(test::readFile(cloud_),
              HasSubstr(" length_unit=m base_link=world tip_link=ee_link point=tool "));
  expectNamesEeLink(
      test::run(kBoundary + " --input " + cloud_ + " --output " + file("b.pcd") + " --json"),
      "boundary");
  expectNamesEeLink(test::run(kMeasure + " --input " + cloud_ + " --json"), "measure");
  expectNamesEeLink(test::run(kSelect + " --input " + cloud_ + " --label 0 --output " +
                              file("s.pcd") + " --json"),
                    "select");
  // The boundary and the selection carry the record on.
  EXPECT_THAT(test::readFile(rim_), HasSubstr(" tip_link=ee_link "));
  EXPECT_THAT(test::readFile(file("s.pcd")), HasSubstr(" tip_link=ee_link "));
}

TEST_F(RobotNamesApp, TheEnvelopesDrawingIsTitledByTheRobotAndTheTip) {
  sampleEeLink();
  const std::string svg = file("range.svg"), ply = file("env.ply");
  const test::RunResult r = test::run(kEnvelope + " --input " + cloud_ + " --drawing " + svg +
                                      " --output " + ply + " --json");
  expectNamesEeLink(r, "envelope");
  const std::string drawing = test::readFile(svg);
  EXPECT_THAT(drawing, HasSubstr("ur5_shaped: working range of ee_link (lengths in m)"));
  EXPECT_THAT(drawing, Not(HasSubstr("cloud.pcd")));
  EXPECT_THAT(test::readFile(ply),
              HasSubstr("comment mcws_envelope of robot 'ur5_shaped', tip ee_link, from " + cloud_ +
                        ", lengths in m\n"));
}

TEST_F(RobotNamesApp, ACloudOfNoRobotNamesNoneAndTheDrawingKeepsTheFileName) {
  const std::string ball = file("ball.pcd"), svg = file("ball.svg");
  const test::RunResult s =
      test::run(kSample + " --shape ball --samples 3000 --output " + ball + " --json");
  ASSERT_EQ(s.exit_code, 0) << s.err;
  EXPECT_TRUE(nlohmann::json::parse(s.out)["robot"].is_null()) << s.out;
  const test::RunResult m = test::run(kMeasure + " --input " + ball + " --json");
  ASSERT_EQ(m.exit_code, 0) << m.err;
  EXPECT_TRUE(nlohmann::json::parse(m.out)["robot"].is_null()) << m.out;
  EXPECT_TRUE(nlohmann::json::parse(m.out)["tip"].is_null()) << m.out;
  const test::RunResult e =
      test::run(kEnvelope + " --input " + ball + " --drawing " + svg + " --json");
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_TRUE(nlohmann::json::parse(e.out)["tip"].is_null()) << e.out;
  EXPECT_THAT(test::readFile(svg), HasSubstr("ball.pcd: working range (lengths in unrecorded)"));
}

TEST_F(RobotNamesApp, ADhRobotsTipIsItsToolOrItsFlange) {
  const std::string robot = " --robot " + test::robotPath("ta1400");
  const std::string q = " --q '0 0.3 0.2 0 0.5 0'";
  EXPECT_EQ(nlohmann::json::parse(test::run(kFk + robot + q + " --json").out)["tip"], "tool");
  EXPECT_EQ(nlohmann::json::parse(test::run(kFk + robot + q + " --frame flange --json").out)["tip"],
            "flange");
  const test::RunResult s =
      test::run(kSample + robot + " --point flange --samples 2000 --output " + cloud_ + " --json");
  ASSERT_EQ(s.exit_code, 0) << s.err;
  EXPECT_EQ(nlohmann::json::parse(s.out)["tip"], "flange");
  EXPECT_EQ(nlohmann::json::parse(s.out)["robot"], "ta1400");
  // A D-H robot has no chain to record; its tip is the sampling record's point.
  EXPECT_THAT(test::readFile(cloud_), Not(HasSubstr("tip_link=")));
  const test::RunResult m = test::run(kMeasure + " --input " + cloud_ + " --json");
  ASSERT_EQ(m.exit_code, 0) << m.err;
  EXPECT_EQ(nlohmann::json::parse(m.out)["tip"], "flange");
  EXPECT_EQ(nlohmann::json::parse(m.out)["robot"], "ta1400");
  EXPECT_EQ(nlohmann::json::parse(m.out)["length_unit"], "mm");
}

TEST_F(RobotNamesApp, RefineRefusesACloudOfAnotherTipOfTheSameFile) {
  sampleEeLink();
  test::TempDir nothing;
  test::expectToolFailure(kRefine,
                          "--robot " + urdf_ + " --tip tool0 --input " + rim_ +
                              " --samples 10 --output " + nothing.file("r.pcd"),
                          1,
                          "--input '" + rim_ +
                              "' was made for the chain from link 'world' to link 'ee_link', not "
                              "for the chain from 'world' to 'tool0' (--base, --tip)",
                          nothing);
}

TEST(RobotNamesPlan, ThePlanNamesTheScenariosRobotAndItsFile) {
  test::TempDir dir;
  const test::RunResult r =
      test::run(kPlan + " --scenario " + std::string(MCWS_SCENARIOS_DIR) +
                "/../tests/apps/data/planar2_quick.yaml --validation-poses 200 --output " +
                dir.file("p.csv") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["robot"], "planar2");
  EXPECT_EQ(json["tip"], "tool");
  EXPECT_EQ(json["length_unit"], "cm");
  EXPECT_THAT(json["robot_file"].get<std::string>(), HasSubstr("planar2.yaml"));
}

}  // namespace
}  // namespace mcws
