// The robot a scenario names (issue 33 item 1): `robot: FILE`, or `robot: {file: FILE, base: LINK,
// tip: LINK}` choosing a URDF's chain as the tools' --base and --tip do, the collision model of
// the same chain, and one line naming the file, the line and the key for a chain the URDF does not
// have. The URDF is the UR5-shaped one of tests/kinematics/ur5_shaped_urdf.h (two leaves).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "kinematics/ur5_shaped_urdf.h"
#include "mcws/core/error.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/planning/scenario.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

/// A scenario of the UR5-shaped arm whose `robot:` entry (line 2) is `robot`; the rest is the
/// least a scenario needs.
std::string scenarioWith(const std::string& robot) {
  return "name: ur\n" + robot +
         "\nstart: [0 rad, -1 rad, 1 rad, 0 rad, 0.5 rad, 0 rad]\n"
         "goal: [0.5 rad, -1 rad, 1 rad, 0 rad, 0.5 rad, 0 rad]\n"
         "sway:\n  pivot: [0 m, 0 m, 0 m]\n  line: [0, 1, 0]\n";
}

class ScenarioRobot : public ::testing::Test {
 protected:
  void SetUp() override { test::writeFile(urdf_, test::kUr5ShapedUrdf); }
  mcws::Scenario load(const std::string& robot) const {
    test::writeFile(path(), scenarioWith(robot));
    return loadScenario(path());
  }
  std::string path() const { return dir_.file("s.yaml"); }
  /// Loading fails with the one line "s.yaml:<line>: <message>".
  void expectError(const std::string& robot, int line, const std::string& message) const {
    test::writeFile(path(), scenarioWith(robot));
    EXPECT_EQ(test::errorOf([&] { loadScenario(path()); }),
              path() + ":" + std::to_string(line) + ": " + message);
  }
  test::TempDir dir_;
  const std::string urdf_ = dir_.file("ur5.urdf");
};

TEST_F(ScenarioRobot, TheMapFormChoosesTheChainAndItsCollisionModel) {
  Eigen::VectorXd q(6);  // not a comma-initialised temporary: GCC 12 -O1 warns of it
  q << 0.2, -1.0, 1.3, -0.5, 0.7, 0.4;
  const mcws::Scenario tool0 = load("robot: {file: ur5.urdf, tip: tool0}");
  EXPECT_EQ(tool0.robot_path, urdf_);
  const Robot& robot = tool0.problem.robot;
  ASSERT_EQ(robot.dof(), 6);
  EXPECT_EQ(robot.tip_link, "tool0");
  EXPECT_LT((toolPose(robot, q).matrix() - test::ur5FromWorld(test::ur5BaseToTool0(q)).matrix())
                .cwiseAbs()
                .maxCoeff(),
            1e-12);
  EXPECT_EQ(tool0.problem.collision.tool.shapes.size(), 1u);  // tool0's sphere

  // The block form, from base_link and to ee_link: tool0's sphere is then on the last link.
  const mcws::Scenario ee = load("robot:\n  file: ur5.urdf\n  base: base_link\n  tip: ee_link");
  EXPECT_EQ(ee.problem.robot.base_link, "base_link");
  EXPECT_LT((toolPose(ee.problem.robot, q).matrix() - test::ur5BaseToEeLink(q).matrix())
                .cwiseAbs()
                .maxCoeff(),
            1e-12);
  EXPECT_TRUE(ee.problem.collision.tool.shapes.empty());
  EXPECT_EQ(ee.problem.collision.links[6].shapes.size(), 1u);
}

TEST_F(ScenarioRobot, ChainErrorsNameTheLineAndTheKey) {
  expectError("robot: ur5.urdf", 2,
              "robot: " + urdf_ +
                  ": link 'world' has 2 leaf links below it (tool0, ee_link): choose one with "
                  "robot: {file: FILE, tip: LINK}");
  expectError("robot:\n  file: ur5.urdf\n  tip: hand", 4,
              "robot: tip: 'hand' is not a link of robot 'ur5_shaped' in " + urdf_);
  expectError("robot:\n  file: ur5.urdf\n  base: torso\n  tip: tool0", 4,
              "robot: base: 'torso' is not a link of robot 'ur5_shaped' in " + urdf_);
  expectError(
      "robot:\n  file: ur5.urdf\n  base: wrist_1_link\n  tip: upper_arm_link", 5,
      "robot: tip: link 'upper_arm_link' is not below base link 'wrist_1_link' in " + urdf_);
}

TEST_F(ScenarioRobot, BadEntries) {
  expectError("robot: {file: ur5.urdf, tipp: tool0}", 2,
              "robot: unknown key 'tipp' (allowed: base, file, package_path, srdf, tip)");
  expectError("robot: {tip: tool0}", 2, "robot: missing field 'file'");
  expectError("robot: {file: ur5.urdf, tip: ''}", 2, "robot: tip: must not be empty");
  expectError("robot: {file: [ur5.urdf], tip: tool0}", 2, "robot: file: must be a single value");
  expectError(
      "robot: {file: nowhere.urdf, tip: tool0}", 2,
      "robot: 'nowhere.urdf' does not exist (looked for " + dir_.file("nowhere.urdf") + ")");
  // A D-H robot's chain is its joints.
  const std::string dh = test::robotPath("maintenance4");
  expectError("robot: {file: " + dh + ", tip: tool0}", 2,
              "robot: tip: base and tip need a .urdf robot ('" + dh + "' is not)");
}

TEST_F(ScenarioRobot, PackagePathFindsThePackageMeshes) {
  // base_link's sphere as a package:// mesh of a package in ws/, which the upward search from the
  // URDF's folder does not find.
  std::string text = test::kUr5ShapedUrdf;
  const std::string sphere = "<sphere radius=\"0.1\"/>";
  text.replace(text.find(sphere), sphere.size(),
               "<mesh filename=\"package://ur5_pkg/meshes/base.stl\"/>");
  test::writeFile(urdf_, text);
  std::filesystem::create_directories(dir_.file("ws/ur5_pkg/meshes"));
  test::writeFile(dir_.file("ws/ur5_pkg/package.xml"), "<package/>");
  test::writeFile(dir_.file("ws/ur5_pkg/meshes/base.stl"),
                  "solid t\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                  "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n");
  const mcws::Scenario scenario = load("robot: {file: ur5.urdf, tip: tool0, package_path: [ws]}");
  EXPECT_EQ(scenario.problem.robot.package_path, std::vector<std::string>{dir_.file("ws")});
  ASSERT_EQ(scenario.problem.collision.links[0].shapes.size(), 1u);
  EXPECT_EQ(scenario.problem.collision.links[0].shapes[0].type, ShapeType::kMesh);
  expectError("robot: {file: ur5.urdf, tip: tool0, package_path: wss}", 2,
              "robot: package_path: 'wss' is not a folder (looked for " + dir_.file("wss") + ")");
  const std::string dh = test::robotPath("maintenance4");
  expectError("robot: {file: " + dh + ", package_path: ws}", 2,
              "robot: package_path: needs a .urdf robot ('" + dh + "' is not)");
}

TEST_F(ScenarioRobot, SrdfEntryDisablesItsPairsInTheCollisionModel) {
  // base_link carries the base's sphere, tool0 the tool's (tip tool0): the one pair of links with
  // geometry is the base - tool pair of bodies.
  test::writeFile(dir_.file("ur5.srdf"),
                  "<robot name=\"ur5\"><disable_collisions link1=\"tool0\" link2=\"base_link\" "
                  "reason=\"Never\"/></robot>");
  EXPECT_TRUE(load("robot: {file: ur5.urdf, tip: tool0}").problem.collision.allowed.empty());
  const mcws::Scenario scenario = load("robot: {file: ur5.urdf, tip: tool0, srdf: ur5.srdf}");
  EXPECT_EQ(scenario.problem.robot.srdf, dir_.file("ur5.srdf"));
  const std::vector<std::pair<std::string, std::string>> allowed = {{"base", "tool"}};
  EXPECT_EQ(scenario.problem.collision.allowed, allowed);
  expectError("robot: {file: ur5.urdf, tip: tool0, srdf: ur6.srdf}", 2,
              "robot: srdf: 'ur6.srdf' is not a file (looked for " + dir_.file("ur6.srdf") + ")");
}

}  // namespace
}  // namespace mcws
