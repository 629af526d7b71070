#include "mcws/kinematics/robot_urdf.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <sstream>
#include <vector>

#include "kinematics/random_joints.h"
#include "kinematics/ur5_shaped_urdf.h"
#include "mcws/core/error.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/robot_yaml.h"
#include "test_support.h"
#if defined(MCWS_TEST_ASAN)
#include <sanitizer/lsan_interface.h>
#endif

namespace mcws {
namespace {

using ::testing::HasSubstr;

const std::string kInspectionUrdf = std::string(MCWS_ROBOTS_DIR) + "/inspection6.urdf";

// Poses of the same arm from two files differ only by rounding: the YAML is in mm and degrees
// (converted with pi/180), the URDF in metres and radians printed to 17 digits.
constexpr double kPositionTolMetre = 1e-12;
constexpr double kRotationTol = 1e-12;

// A planar arm with every feature of the mapping: a fixed joint between two moving joints, a
// prismatic joint, a continuous joint, a rotated origin and a fixed tool link after the last
// joint. Lengths in metres.
//   base -(j1 revolute z)- l1 -(fixed x+0.3)- l1b -(j2 continuous z, origin x+0.2)- l2
//   -(j3 prismatic x)- l3 -(fixed x+0.1, yaw 90 deg)- tool
const std::string kPlanar = R"(<?xml version="1.0"?>
<robot name="planar">
  <link name="base"/> <link name="l1"/> <link name="l1b"/> <link name="l2"/> <link name="l3"/>
  <link name="tool"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <axis xyz="0 0 2"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="mount" type="fixed"><parent link="l1"/><child link="l1b"/>
    <origin xyz="0.3 0 0"/></joint>
  <joint name="j2" type="continuous"><parent link="l1b"/><child link="l2"/>
    <origin xyz="0.2 0 0"/><axis xyz="0 0 1"/></joint>
  <joint name="j3" type="prismatic"><parent link="l2"/><child link="l3"/>
    <axis xyz="1 0 0"/><limit lower="0" upper="0.4" effort="1" velocity="1"/></joint>
  <joint name="flange" type="fixed"><parent link="l3"/><child link="tool"/>
    <origin xyz="0.1 0 0" rpy="0 0 1.5707963267948966"/></joint>
</robot>
)";

std::string urdfError(const std::string& urdf, const UrdfChainOptions& options = {}) {
  try {
    parseRobotUrdf(urdf, "bad.urdf", options);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for:\n" << urdf;
  return "";
}

TEST(RobotUrdf, InspectionArmGivesTheYamlPosesOverRandomJointVectors) {
  const Robot yaml = loadRobot(test::robotPath("inspection6"));
  const Robot urdf = loadRobot(kInspectionUrdf);  // dispatched on the extension
  ASSERT_EQ(urdf.dof(), yaml.dof());
  EXPECT_EQ(urdf.length_unit, LengthUnit::kMetre);
  const double mm = unitInMetres(yaml.length_unit);
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  for (int sample = 0; sample < 1000; ++sample) {
    Eigen::VectorXd q(6);
    for (int i = 0; i < 6; ++i) q[i] = angle(rng);
    const Eigen::Isometry3d T_yaml = toolPose(yaml, q);
    const Eigen::Isometry3d T_urdf = toolPose(urdf, q);
    ASSERT_LT((T_yaml.translation() * mm - T_urdf.translation()).norm(), kPositionTolMetre)
        << "q = " << q.transpose();
    ASSERT_LT((T_yaml.linear() - T_urdf.linear()).norm(), kRotationTol) << q.transpose();
  }
}

TEST(RobotUrdf, InspectionArmKeepsNamesAndLimits) {
  const Robot robot = loadRobotUrdf(kInspectionUrdf);
  EXPECT_EQ(robot.name, "inspection6");
  EXPECT_EQ(robot.source, kInspectionUrdf);
  ASSERT_EQ(robot.dof(), 6);
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(robot.joints[i].name, "j" + std::to_string(i + 1));
    EXPECT_EQ(robot.joints[i].type, JointType::kRevolute);
    EXPECT_DOUBLE_EQ(robot.joints[i].lower, -M_PI);
    EXPECT_DOUBLE_EQ(robot.joints[i].upper, M_PI);
  }
}

TEST(RobotUrdf, PlanarChainMatchesClosedForm) {
  const Robot robot = parseRobotUrdf(kPlanar, "planar.urdf");
  ASSERT_EQ(robot.dof(), 3);
  EXPECT_EQ(robot.joints[1].type, JointType::kRevolute);  // continuous: one full turn
  EXPECT_DOUBLE_EQ(robot.joints[1].lower, -M_PI);
  EXPECT_DOUBLE_EQ(robot.joints[1].upper, M_PI);
  EXPECT_EQ(robot.joints[2].type, JointType::kPrismatic);
  EXPECT_DOUBLE_EQ(robot.joints[2].upper, 0.4);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int sample = 0; sample < 100; ++sample) {
    const double q1 = -2 + 4 * unit(rng), q2 = -M_PI + 2 * M_PI * unit(rng);
    const double q3 = 0.4 * unit(rng);
    const Eigen::Isometry3d T = toolPose(robot, Eigen::Vector3d(q1, q2, q3));
    // Link 1 of length 0.5 (0.3 fixed + 0.2 origin), then link 2 of length q3 + 0.1.
    const double x = 0.5 * std::cos(q1) + (q3 + 0.1) * std::cos(q1 + q2);
    const double y = 0.5 * std::sin(q1) + (q3 + 0.1) * std::sin(q1 + q2);
    EXPECT_NEAR(T.translation().x(), x, 1e-12);
    EXPECT_NEAR(T.translation().y(), y, 1e-12);
    EXPECT_NEAR(T.translation().z(), 0.0, 1e-12);
    const double heading = q1 + q2 + M_PI / 2;  // tool x axis: fixed yaw of 90 deg
    EXPECT_NEAR(T.linear()(0, 0), std::cos(heading), 1e-12);
    EXPECT_NEAR(T.linear()(1, 0), std::sin(heading), 1e-12);
  }
}

TEST(RobotUrdf, BaseAndTipSelectASubChain) {
  const Robot full = loadRobotUrdf(kInspectionUrdf);
  const Robot part = loadRobotUrdf(kInspectionUrdf, {"link2", "link4"});
  ASSERT_EQ(part.dof(), 2);
  EXPECT_EQ(part.joints[0].name, "j3");
  EXPECT_EQ(part.joints[1].name, "j4");
  const Eigen::VectorXd q = (Eigen::VectorXd(6) << 0.3, -0.7, 1.1, 0.4, -0.2, 0.9).finished();
  const ChainPoses poses = chainPoses(full, q);
  // link 4 in link 2's frame
  const Eigen::Isometry3d expected = poses.T_world_link[1].inverse() * poses.T_world_link[3];
  const Eigen::Isometry3d got = toolPose(part, q.segment(2, 2));
  EXPECT_LT((expected.matrix() - got.matrix()).norm(), 1e-12);
  // The tip alone: from the tree's root.
  EXPECT_EQ(loadRobotUrdf(kInspectionUrdf, {"", "link3"}).dof(), 3);
}

TEST(RobotUrdf, ReportsMissingFileAndMalformedXml) {
  try {
    loadRobot("/nonexistent/arm.urdf");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/arm.urdf: robot file does not exist");
  }
  EXPECT_THAT(urdfError("<robot name='x'><link name='a'></robot>"),
              HasSubstr("bad.urdf: malformed URDF: "));
  EXPECT_THAT(urdfError("not xml at all"), HasSubstr("bad.urdf: malformed URDF"));
  EXPECT_EQ(urdfError("<robot name='x'><link name='a'></robot>").find('\n'), std::string::npos);
}

TEST(RobotUrdf, MalformedUrdfPrintsNothing) {
  testing::internal::CaptureStderr();
  testing::internal::CaptureStdout();
  urdfError("<robot name='x'><joint name='j' type='revolute'/></robot>");
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

TEST(RobotUrdf, ReportsTipNotBelowBaseAndUnknownLinks) {
  EXPECT_EQ(urdfError(kPlanar, {"l2", "l1"}),
            "bad.urdf: tip link 'l1' is not below base link 'l2'");
  EXPECT_EQ(urdfError(kPlanar, {"", "hand"}),
            "bad.urdf: tip link 'hand' is not a link of robot 'planar'");
  EXPECT_EQ(urdfError(kPlanar, {"torso", ""}),
            "bad.urdf: base link 'torso' is not a link of robot 'planar'");
}

TEST(RobotUrdf, ReportsJointWithoutLimits) {
  // urdfdom itself rejects a revolute joint without <limit>; its message names the joint.
  const std::string text =
      test::replaceOnce(kPlanar, R"(<limit lower="-2" upper="2" effort="1" velocity="1"/>)", "");
  EXPECT_THAT(urdfError(text), HasSubstr("bad.urdf: malformed URDF: "));
  EXPECT_THAT(urdfError(text), HasSubstr("j1"));
}

TEST(RobotUrdf, ReportsFloatingAndPlanarJointsButReadsMimicJoints) {
  EXPECT_EQ(
      urdfError(test::replaceOnce(kPlanar, R"("j1" type="revolute")", R"("j1" type="floating")")),
      "bad.urdf: joint 'j1': floating joints are not supported (revolute, continuous, "
      "prismatic, fixed)");
  EXPECT_THAT(
      urdfError(test::replaceOnce(kPlanar, R"("j3" type="prismatic")", R"("j3" type="planar")")),
      HasSubstr("bad.urdf: joint 'j3': planar joints are not supported"));
  // A mimic joint is no error (issue 33): j2 follows j1 and is no degree of freedom.
  const Robot mimic =
      parseRobotUrdf(test::replaceOnce(kPlanar, "<axis xyz=\"0 0 1\"/></joint>",
                                       "<axis xyz=\"0 0 1\"/><mimic joint=\"j1\"/></joint>"),
                     "mimic.urdf");
  EXPECT_EQ(mimic.dof(), 2);
  ASSERT_EQ(mimic.mimic_joints.size(), 1u);
  EXPECT_EQ(mimic.mimic_joints[0].joint.name, "j2");
}

TEST(RobotUrdf, ReportsAmbiguousTipAndEmptyChain) {
  const std::string branched =
      test::replaceOnce(kPlanar, "</robot>",
                        "<link name='camera'/><joint name='cam' type='fixed'><parent link='l1'/>"
                        "<child link='camera'/></joint></robot>");
  EXPECT_EQ(urdfError(branched),
            "bad.urdf: link 'base' has 2 leaf links below it (tool, camera): choose the tip link");
  EXPECT_EQ(parseRobotUrdf(branched, "ok.urdf", {"", "camera"}).dof(), 1);
  EXPECT_EQ(urdfError(kPlanar, {"l3", "tool"}),
            "bad.urdf: no revolute, continuous or prismatic joint between base link 'l3' and tip "
            "link 'tool'");
}

TEST(RobotUrdf, ReportsLimitsInTheWrongOrderZeroAxisAndOddNames) {
  EXPECT_EQ(
      urdfError(test::replaceOnce(kPlanar, R"(lower="0" upper="0.4")", R"(lower="0.4" upper="0")")),
      "bad.urdf: joint 'j3': lower limit 0.4 is greater than upper limit 0");
  EXPECT_EQ(
      urdfError(test::replaceOnce(kPlanar, R"(<axis xyz="0 0 2"/>)", R"(<axis xyz="0 0 0"/>)")),
      "bad.urdf: joint 'j1': axis must be a finite non-zero vector");
  EXPECT_EQ(urdfError(test::replaceOnce(kPlanar, R"("j3" type)", R"("j,3" type)")),
            "bad.urdf: joint 'j,3': name contains '=', ',' or a space");
}

/// `count` copies of `text`.
std::string repeat(const std::string& text, int count) {
  std::string out;
  for (int i = 0; i < count; ++i) out += text;
  return out;
}

/// kPlanar with `content` inside its tool link: the robot and tool elements are two levels.
std::string planarWithToolContent(const std::string& content) {
  return test::replaceOnce(kPlanar, R"(<link name="tool"/>)",
                           R"(<link name="tool">)" + content + "</link>");
}

/// The error of loading `text` written to the file `path`.
std::string fileErrorOf(const std::string& path, const std::string& text) {
  test::writeFile(path, text);
  try {
    loadRobotUrdf(path);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for " << path;
  return "";
}

TEST(RobotUrdf, RefusesDeepNestingBeforeTheParserOverflowsItsStack) {
  test::TempDir dir;
  const std::string path = dir.file("deep.urdf");
  // robot + link + 998 = 1000 levels pass; one more does not.
  EXPECT_EQ(
      parseRobotUrdf(planarWithToolContent(repeat("<x>", 998) + repeat("</x>", 998)), "ok").dof(),
      3);
  EXPECT_EQ(urdfError(planarWithToolContent(repeat("<x>", 999) + repeat("</x>", 999))),
            "bad.urdf: XML nested deeper than 1000 elements");
  // TinyXML recursed once per level and overflowed an 8 MB stack at 100,000 levels.
  EXPECT_EQ(
      fileErrorOf(path, planarWithToolContent(repeat("<x>", 100000) + repeat("</x>", 100000))),
      path + ": XML nested deeper than 1000 elements");
  // A quoted "/>" does not close an element.
  EXPECT_EQ(
      urdfError(planarWithToolContent(repeat("<x a=\"/>\" b='>'>", 999) + repeat("</x>", 999))),
      "bad.urdf: XML nested deeper than 1000 elements");
}

TEST(RobotUrdf, NestingCountSkipsEmptyElementsCommentsCdataAndTheDeclaration) {
  // 2,000 empty elements side by side, and 2,000 tags inside a comment and CDATA at level 3.
  const std::string content = repeat("<x/><y a='1'/>", 1000) + "<x><!--" + repeat("<x>", 2000) +
                              "--></x><x><![CDATA[" + repeat("<x>", 2000) + "]]></x>";
  EXPECT_EQ(
      parseRobotUrdf("<?xml version='1.0' encoding=\"UTF-8\" ?>\n" + planarWithToolContent(content),
                     "ok")
          .dof(),
      3);
}

TEST(RobotUrdf, RefusesTextThatCouldHideNestingFromTheCount) {
  // TinyXML would read "></x>" as the declaration's version and never see an end tag.
  EXPECT_EQ(urdfError(planarWithToolContent("<x><?xml version=\"></x>\"?>")),
            "bad.urdf: XML declaration on line 4 is not of the form <?xml name=\"value\" ...?>");
  // TinyXML would take "\xC3<" as one character and never see the end tag.
  EXPECT_EQ(urdfError(planarWithToolContent("<x>\xC3</x>")),
            "bad.urdf: line 4 is not UTF-8 text (byte 0xC3 starts a cut-short character)");
  EXPECT_EQ(parseRobotUrdf(planarWithToolContent("<x>caf\xC3\xA9</x>"), "ok").dof(), 3);
}

TEST(RobotUrdf, RefusesAPercentThatUrdfdomWouldTakeForAPrintfFormat) {
  // urdfdom 3.0 passed "Unable to parse component [0%1n=] ..." to printf as the format: a
  // crash (found by the robot_urdf fuzzer).
  EXPECT_EQ(urdfError(test::replaceOnce(kPlanar, "xyz=\"0.1 0 0\"", "xyz=\"0%1n= 0 0.5\"")),
            "bad.urdf: line 14: attribute xyz=\"0%1n= 0 0.5\" holds a '%', which no URDF number "
            "or name needs (urdfdom would misread it)");
  // The same '%' written as a character reference, in another attribute, with single quotes.
  EXPECT_THAT(
      urdfError(test::replaceOnce(kPlanar, "<link name=\"tool\"/>",
                                  "<link name='tool'><visual><geometry><sphere radius='&#x025;s'/>"
                                  "</geometry></visual></link>")),
      HasSubstr("bad.urdf: line 4: attribute radius=\"&#x025;s\" holds a '%'"));
  EXPECT_THAT(urdfError(test::replaceOnce(kPlanar, "name=\"j1\"", "name=\"j&#0037;s\"")),
              HasSubstr("attribute name=\"j&#0037;s\" holds a '%'"));
  // A mesh's file name may hold one; other references are untouched.
  EXPECT_EQ(
      parseRobotUrdf(test::replaceOnce(kPlanar, "<link name=\"tool\"/>",
                                       "<link name='tool'><visual><geometry><mesh "
                                       "filename='tool%20v2.stl'/></geometry></visual></link>"),
                     "ok")
          .dof(),
      3);
  EXPECT_EQ(parseRobotUrdf(
                test::replaceOnce(kPlanar, "name=\"planar\"", "name=\"pl&#38;&#x26;nar\""), "ok")
                .dof(),
            3);
}

TEST(RobotUrdf, RefusesAFileLargerThan64MiB) {
  test::TempDir dir;
  const std::string path = dir.file("huge.urdf");
  test::writeFile(path, "");
  std::filesystem::resize_file(path, 64 * 1024 * 1024 + 1);  // sparse: nothing is written
  try {
    loadRobotUrdf(path);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), path + ": URDF of 67108865 bytes is larger than 64 MiB");
  }
}

/// A URDF of links base, a, b and the given fixed joints "name parent child".
std::string linksAndJoints(const std::vector<std::string>& joints) {
  std::string text = R"(<robot name="r"><link name="base"/><link name="a"/><link name="b"/>)";
  for (const std::string& joint : joints) {
    std::istringstream words(joint);
    std::string name, parent, child;
    words >> name >> parent >> child;
    text += "<joint name='" + name + "' type='fixed'><parent link='" + parent + "'/><child link='" +
            child + "'/></joint>";
  }
  return text + "</robot>";
}

TEST(RobotUrdf, NamesTheJointThatClosesALoop) {
  test::TempDir dir;
  const std::string path = dir.file("loop.urdf");
  // base -> a -> b -> a: j2 leads back to a, which is on the path from base.
  EXPECT_EQ(fileErrorOf(path, linksAndJoints({"j0 base a", "j1 a b", "j2 b a"})),
            path + ": joint 'j2' closes a loop: its child link 'a' is also its ancestor");
  // A loop apart from the root: the search from base ended round the loop for ever.
  EXPECT_EQ(fileErrorOf(path, linksAndJoints({"j1 a b", "j2 b a"})),
            path + ": joint 'j2' closes a loop: its child link 'a' is also its ancestor");
  // A joint from a link to itself.
  EXPECT_EQ(urdfError(linksAndJoints({"j0 base a", "j1 a b", "j2 b b"})),
            "bad.urdf: joint 'j2' closes a loop: its child link 'b' is also its ancestor");
  // Every link has a parent, so urdfdom finds no root: the walk up from a meets a again first,
  // and the search from a returns to it by j2. urdfdom, rejecting this text itself, leaks the
  // links of the loop (they own each other by shared_ptr) where the loader cannot free them.
#if defined(MCWS_TEST_ASAN)
  const __lsan::ScopedDisabler urdfdom_leaks_the_loop_it_rejects;
#endif
  EXPECT_EQ(urdfError(R"(<robot name="r"><link name="a"/><link name="b"/>
      <joint name="j1" type="fixed"><parent link="a"/><child link="b"/></joint>
      <joint name="j2" type="fixed"><parent link="b"/><child link="a"/></joint></robot>)"),
            "bad.urdf: joint 'j2' closes a loop: its child link 'a' is also its ancestor");
}

TEST(RobotUrdf, RefusesALinkWithTwoParentJoints) {
  // base -> a by j1 and base -> b -> a by j3: the search reaches a by j1 first (name order).
  EXPECT_EQ(urdfError(linksAndJoints({"j1 base a", "j2 base b", "j3 b a"})),
            "bad.urdf: joint 'j3': link 'a' already has parent joint 'j1' (the joints must form "
            "a tree)");
}

TEST(RobotUrdf, RefusesLimitsAndOriginsLargerThan1e9LikeRobotYaml) {
  const std::string j1_limit = R"(lower="-2" upper="2")";
  EXPECT_EQ(urdfError(test::replaceOnce(kPlanar, j1_limit, R"(lower="-1e308" upper="2")")),
            "bad.urdf: joint 'j1': lower limit -1e+308 is out of range (at most 1e9 in size)");
  EXPECT_EQ(urdfError(test::replaceOnce(kPlanar, j1_limit, R"(lower="-2" upper="1e308")")),
            "bad.urdf: joint 'j1': upper limit 1e+308 is out of range (at most 1e9 in size)");
  EXPECT_EQ(
      urdfError(test::replaceOnce(kPlanar, R"(lower="0" upper="0.4")", R"(lower="0" upper="2e9")")),
      "bad.urdf: joint 'j3': upper limit 2e+09 is out of range (at most 1e9 in size)");
  EXPECT_EQ(urdfError(test::replaceOnce(kPlanar, R"(<origin xyz="0.2 0 0"/>)",
                                        R"(<origin xyz="0 -1e308 0"/>)")),
            "bad.urdf: joint 'j2': origin coordinate -1e+308 is out of range (at most 1e9 in "
            "size)");
  const Robot robot = parseRobotUrdf(
      test::replaceOnce(kPlanar, j1_limit, R"(lower="-1e9" upper="1e9")"), "ok.urdf");
  EXPECT_EQ(robot.joints[0].lower, -1e9);
  EXPECT_EQ(robot.joints[0].upper, 1e9);
}

TEST(RobotUrdf, RefusesControlCharactersInRobotLinkAndJointNames) {
  // XML character references write control characters into a name.
  EXPECT_EQ(urdfError(test::replaceOnce(kPlanar, R"(<robot name="planar">)",
                                        R"(<robot name="pla&#10;nar">)")),
            "bad.urdf: robot name 'pla\\x0anar' holds a control byte (names are printable text)");
  EXPECT_EQ(urdfError(test::replaceOnce(kPlanar, R"("j2" type)", R"("j&#9;2" type)")),
            "bad.urdf: joint name 'j\\x092' holds a control byte (names are printable text)");
  // A link off the chain too: every name of the file may reach a message.
  EXPECT_EQ(
      urdfError(test::replaceOnce(kPlanar, R"(<link name="tool"/>)",
                                  R"(<link name="tool"/><link name="spare&#127;"/>)"
                                  R"(<joint name="spare_mount" type="fixed"><parent link="tool"/>)"
                                  R"(<child link="spare&#127;"/></joint>)")),
      "bad.urdf: link name 'spare\\x7f' holds a control byte (names are printable text)");
}

// The UR5-shaped URDF of tests/kinematics/ur5_shaped_urdf.h: its tool0 and ee_link are fixed
// frames below the last joint, so the chain to either is six joints and a fixed flange. Poses
// composed from the published D-H table by hand agree with the file's to rounding (the URDF's
// pi/2 is printed to 17 digits).
constexpr double kUrPoseTol = 1e-12;

/// The largest entry of the difference of two poses' matrices.
double poseGap(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.matrix() - b.matrix()).cwiseAbs().maxCoeff();
}

TEST(RobotUrdf, AFixedFrameAsTipIsComposedIntoTheFlange) {
  const Robot tool0 = parseRobotUrdf(test::kUr5ShapedUrdf, "ur5.urdf", {"", "tool0"});
  const Robot ee = parseRobotUrdf(test::kUr5ShapedUrdf, "ur5.urdf", {"", "ee_link"});
  const Robot from_base = parseRobotUrdf(test::kUr5ShapedUrdf, "ur5.urdf", {"base_link", "tool0"});
  ASSERT_EQ(tool0.dof(), 6);
  ASSERT_EQ(ee.dof(), 6);
  ASSERT_EQ(from_base.dof(), 6);
  // At zero: tool0 at x = a2 + a3 = -0.81725, y = -(d4 + d6) = -0.19145, z = d1 - d5 = -0.005491
  // above base_link (the UR5's home pose, lying along -x).
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6);
  const Eigen::Vector3d home(-0.81725, -0.19145, -0.005491);
  EXPECT_LT((toolPose(from_base, zero).translation() - home).norm(), kUrPoseTol);
  EXPECT_LT((toolPose(tool0, zero).translation() - home - Eigen::Vector3d(0, 0, 0.5)).norm(),
            kUrPoseTol);
  std::mt19937_64 rng(33);
  for (int sample = 0; sample < 200; ++sample) {
    const Eigen::VectorXd q = test::randomJoints(tool0, rng);
    ASSERT_LT(poseGap(toolPose(tool0, q), test::ur5FromWorld(test::ur5BaseToTool0(q))), kUrPoseTol)
        << q.transpose();
    ASSERT_LT(poseGap(toolPose(ee, q), test::ur5FromWorld(test::ur5BaseToEeLink(q))), kUrPoseTol)
        << q.transpose();
    ASSERT_LT(poseGap(toolPose(from_base, q), test::ur5BaseToTool0(q)), kUrPoseTol)
        << q.transpose();
  }
}

TEST(RobotUrdf, TheRobotNamesTheLinksOfItsChain) {
  const Robot ee = parseRobotUrdf(test::kUr5ShapedUrdf, "ur5.urdf", {"", "ee_link"});
  EXPECT_EQ(ee.base_link, "world");
  EXPECT_EQ(ee.tip_link, "ee_link");
  const Robot part =
      parseRobotUrdf(test::kUr5ShapedUrdf, "ur5.urdf", {"base_link", "wrist_2_link"});
  EXPECT_EQ(part.base_link, "base_link");
  EXPECT_EQ(part.tip_link, "wrist_2_link");
  EXPECT_EQ(part.dof(), 5);
  // The defaults, named: the root link and the one leaf.
  const Robot planar = parseRobotUrdf(kPlanar, "planar.urdf");
  EXPECT_EQ(planar.base_link, "base");
  EXPECT_EQ(planar.tip_link, "tool");
  // A D-H robot has no links to name.
  EXPECT_EQ(loadRobot(test::robotPath("inspection6")).tip_link, "");
}

/// The UrdfChainError of a chain of the UR5-shaped URDF.
UrdfChainError chainErrorOf(const UrdfChainOptions& options) {
  try {
    parseRobotUrdf(test::kUr5ShapedUrdf, "ur5.urdf", options);
  } catch (const UrdfChainError& e) {
    return e;
  }
  ADD_FAILURE() << "no chain error for '" << options.base_link << "' to '" << options.tip_link
                << "'";
  return UrdfChainError(UrdfChainError::Problem::kUnknownTip, "", "", "", false, "", {});
}

TEST(RobotUrdf, ChainErrorsNameTheLeavesAndTheOptionsAsTheCallerCallsThem) {
  const UrdfChainError leaves = chainErrorOf({});
  EXPECT_EQ(leaves.problem(), UrdfChainError::Problem::kSeveralLeaves);
  EXPECT_STREQ(leaves.what(),
               "ur5.urdf: link 'world' has 2 leaf links below it (tool0, ee_link): choose the tip "
               "link");
  EXPECT_EQ(leaves.describe("--base", "--tip", "--tip"),
            "ur5.urdf: link 'world' has 2 leaf links below it (tool0, ee_link): choose one with "
            "--tip");
  // From a base below the branch's root, still the same two leaves.
  EXPECT_EQ(chainErrorOf({"forearm_link", ""}).describe("--base", "--tip", "--tip"),
            "ur5.urdf: link 'forearm_link' has 2 leaf links below it (tool0, ee_link): choose one "
            "with --tip");

  const UrdfChainError tip = chainErrorOf({"", "hand"});
  EXPECT_EQ(tip.problem(), UrdfChainError::Problem::kUnknownTip);
  EXPECT_STREQ(tip.what(), "ur5.urdf: tip link 'hand' is not a link of robot 'ur5_shaped'");
  EXPECT_EQ(tip.describe("--base", "--tip", "--tip"),
            "--tip: 'hand' is not a link of robot 'ur5_shaped' in ur5.urdf");

  const UrdfChainError base = chainErrorOf({"torso", "tool0"});
  EXPECT_EQ(base.problem(), UrdfChainError::Problem::kUnknownBase);
  EXPECT_EQ(base.describe("base", "tip", "a tip"),
            "base: 'torso' is not a link of robot 'ur5_shaped' in ur5.urdf");

  const UrdfChainError below = chainErrorOf({"wrist_1_link", "upper_arm_link"});
  EXPECT_EQ(below.problem(), UrdfChainError::Problem::kTipNotBelowBase);
  EXPECT_STREQ(below.what(),
               "ur5.urdf: tip link 'upper_arm_link' is not below base link "
               "'wrist_1_link'");
  EXPECT_EQ(below.describe("--base", "--tip", "--tip"),
            "--tip: link 'upper_arm_link' is not below --base link 'wrist_1_link' in ur5.urdf");
  // A sibling branch is not below either.
  EXPECT_EQ(chainErrorOf({"tool0", "ee_link"}).problem(),
            UrdfChainError::Problem::kTipNotBelowBase);
}

}  // namespace
}  // namespace mcws
