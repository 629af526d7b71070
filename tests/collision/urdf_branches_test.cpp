// Links off the chain in the collision model (issue 33, item 2): a gripper with a mimic finger pair
// on the UR5-shaped arm keeps its fingers, posed at their joints' default values and carried by
// the chain link they hang from; the tip's FK and the dof do not see them. Floating joints off
// the chain, and links moved by a mimic joint of the chain, are refused by name when they carry
// geometry.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "kinematics/ur5_shaped_urdf.h"
#include "mcws/collision/collision_checker.h"
#include "mcws/collision/collision_model.h"
#include "mcws/core/error.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/robot_urdf.h"
#include "test_support.h"

namespace mcws {
namespace {

/// Hand-worked positions against the reader's [m]: rounding of a few sums of centimetres.
constexpr double kTolerance = 1e-12;

/// A gripper on tool0: a palm box fixed 1 cm above tool0, two prismatic fingers 2 cm either side
/// of it and 1 cm above, moving along y. The left finger's limits [0.005, 0.04] put it at
/// 0.005 by default; the right one mimics it (x -1 + 0.001), so sits at -0.004. Each finger's
/// box is 3 cm above its link frame.
const std::string kGripper = R"(
  <link name="palm"><collision><geometry><box size="0.04 0.1 0.02"/></geometry></collision></link>
  <joint name="palm_joint" type="fixed"><parent link="tool0"/><child link="palm"/>
    <origin xyz="0 0 0.01"/></joint>
  <link name="finger_left"><collision><origin xyz="0 0 0.03"/>
    <geometry><box size="0.01 0.01 0.06"/></geometry></collision></link>
  <link name="finger_right"><collision><origin xyz="0 0 0.03"/>
    <geometry><box size="0.01 0.01 0.06"/></geometry></collision></link>
  <joint name="finger_left_joint" type="prismatic"><parent link="palm"/><child link="finger_left"/>
    <origin xyz="0 0.02 0.01"/><axis xyz="0 1 0"/>
    <limit lower="0.005" upper="0.04" effort="10" velocity="0.1"/></joint>
  <joint name="finger_right_joint" type="prismatic"><parent link="palm"/><child link="finger_right"/>
    <origin xyz="0 -0.02 0.01"/><axis xyz="0 1 0"/>
    <limit lower="-0.04" upper="0" effort="10" velocity="0.1"/>
    <mimic joint="finger_left_joint" multiplier="-1" offset="0.001"/></joint>
</robot>
)";

std::string ur5WithGripper() {
  std::string text = test::kUr5ShapedUrdf;
  return text.replace(text.find("</robot>"), std::string("</robot>\n").size(), kGripper);
}

const UrdfCollision& element(const UrdfRobotGeometry& geometry, const std::string& link) {
  for (const UrdfCollision& collision : geometry.collisions) {
    if (collision.link == link) return collision;
  }
  throw Error("no collision element on link " + link);
}

TEST(UrdfBranches, GripperFingersDoNotChangeTheTipOrTheDof) {
  const Robot arm = parseRobotUrdf(test::kUr5ShapedUrdf, "ur5.urdf", test::kUr5ToTool0);
  const Robot gripped = parseRobotUrdf(ur5WithGripper(), "ur5_gripper.urdf", test::kUr5ToTool0);
  EXPECT_EQ(gripped.dof(), 6);  // the finger joints are off the chain
  EXPECT_TRUE(gripped.mimic_joints.empty());
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  for (int sample = 0; sample < 50; ++sample) {
    Eigen::VectorXd q(6);
    for (int i = 0; i < 6; ++i) q[i] = angle(rng);
    const Eigen::Isometry3d expected = test::ur5FromWorld(test::ur5BaseToTool0(q));
    EXPECT_LT((toolPose(gripped, q).matrix() - expected.matrix()).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_EQ(toolPose(gripped, q).matrix(), toolPose(arm, q).matrix());
  }
}

TEST(UrdfBranches, FingersAreCarriedByTheToolAtTheirDefaultValues) {
  // Before issue 33 item 2: "link 'finger_left' has <collision> elements but is not part of the
  // chain: it moves with joint 'finger_left_joint', which is not in the chain ...".
  const UrdfRobotGeometry geometry =
      parseRobotUrdfGeometry(ur5WithGripper(), "ur5_gripper.urdf", test::kUr5ToTool0);
  // In the flange frame (tool0's): palm 1 cm up; left finger frame (0, 0.02 + 0.005, 0.02), its
  // box 3 cm above; right (0, -0.02 - 0.004, 0.02).
  const std::pair<const char*, Eigen::Vector3d> expected[] = {
      {"palm", {0.0, 0.0, 0.01}},
      {"finger_left", {0.0, 0.025, 0.05}},
      {"finger_right", {0.0, -0.024, 0.05}}};
  for (const auto& [link, p_flange] : expected) {
    SCOPED_TRACE(link);
    const UrdfCollision& found = element(geometry, link);
    EXPECT_EQ(found.body, UrdfBody::kTool);
    EXPECT_LT((found.T_body_geometry.translation() - p_flange).norm(), kTolerance);
    EXPECT_TRUE(found.T_body_geometry.linear().isIdentity(kTolerance));
  }
  // The collision model's tool body holds them, in the same place, by link name: finger_left,
  // finger_right, palm, tool0.
  const Robot robot = parseRobotUrdf(ur5WithGripper(), "ur5_gripper.urdf", test::kUr5ToTool0);
  const CollisionModel model =
      parseCollisionUrdf(robot, ur5WithGripper(), "ur5_gripper.urdf", test::kUr5ToTool0);
  ASSERT_EQ(model.tool.shapes.size(), 4u);
  EXPECT_EQ(model.tool.shapes[0].type, ShapeType::kBox);
  EXPECT_LT((model.tool.shapes[0].T_body_shape.translation() - expected[1].second).norm(),
            kTolerance);
  EXPECT_LT((model.tool.shapes[1].T_body_shape.translation() - expected[2].second).norm(),
            kTolerance);
}

std::string geometryError(const std::string& text, const UrdfChainOptions& chain = {"", "tool0"});

TEST(UrdfBranches, AFingerAsTipTakesItsJointAsAFreeOne) {
  EXPECT_EQ(parseRobotUrdf(ur5WithGripper(), "ur5_gripper.urdf", {"", "finger_left"}).dof(), 7);
  // The right finger then moves with a joint of the chain, so cannot hang at one value.
  EXPECT_EQ(geometryError(ur5WithGripper(), {"", "finger_left"}),
            "ur5_gripper.urdf: link 'finger_right' has <collision> elements but is not part of "
            "the chain: it moves with joint 'finger_right_joint', which mimics joint "
            "'finger_left_joint' of the chain (a joint off the chain is posed at one value)");
  // Without the mimic the right finger sits at its own default, 0 (limits [-0.04, 0]), on the
  // sixth joint's link with the palm: in wrist_3_link's frame, tool0 is 0.0823 up, the palm 0.01
  // more, the finger 0.01 more and its box 0.03 more, at y = -0.02.
  std::string text = ur5WithGripper();
  const std::string mimic =
      "<mimic joint=\"finger_left_joint\" multiplier=\"-1\" offset=\"0.001\"/>";
  text.erase(text.find(mimic), mimic.size());
  const UrdfRobotGeometry geometry =
      parseRobotUrdfGeometry(text, "ur5_gripper.urdf", {"", "finger_left"});
  const UrdfCollision& right = element(geometry, "finger_right");
  EXPECT_EQ(right.body, UrdfBody::kLink);
  EXPECT_EQ(right.joint, 5);
  EXPECT_LT((right.T_body_geometry.translation() - Eigen::Vector3d(0, -0.02, 0.1323)).norm(),
            kTolerance);
}

std::string geometryError(const std::string& text, const UrdfChainOptions& chain) {
  return test::errorOf([&] { parseRobotUrdfGeometry(text, "ur5_gripper.urdf", chain); });
}

TEST(UrdfBranches, FloatingJointOffTheChainIsRefusedOnlyWithGeometryBelowIt) {
  std::string text = ur5WithGripper();
  const std::string camera =
      "<link name='camera'/><joint name='camera_mount' type='floating'><parent link='palm'/>"
      "<child link='camera'/></joint></robot>";
  const std::string bare = std::string(text).replace(text.find("</robot>"), 8, camera);
  EXPECT_EQ(parseRobotUrdfGeometry(bare, "ur5_gripper.urdf", test::kUr5ToTool0).robot.dof(), 6);
  const std::string with_box = std::string(text).replace(
      text.find("</robot>"), 8,
      "<link name='camera'><collision><geometry><sphere radius='0.01'/></geometry></collision>"
      "</link><joint name='camera_mount' type='floating'><parent link='palm'/>"
      "<child link='camera'/></joint></robot>");
  EXPECT_EQ(geometryError(with_box),
            "ur5_gripper.urdf: link 'camera' has <collision> elements but is not part of the "
            "chain: it hangs below floating joint 'camera_mount' (revolute, continuous, "
            "prismatic and fixed joints are supported)");
}

TEST(UrdfBranches, LinksMovedByAMimicJointOfTheChainAreRefused) {
  // wrist_3_joint mimics wrist_2_joint: tool0's sphere moves with it.
  std::string text = test::kUr5ShapedUrdf;
  const std::string wrist3 = "<parent link=\"wrist_2_link\"/><child link=\"wrist_3_link\"/>";
  text.insert(text.find(wrist3) + wrist3.size(), "<mimic joint=\"wrist_2_joint\"/>");
  EXPECT_EQ(parseRobotUrdf(text, "ur5_gripper.urdf", test::kUr5ToTool0).dof(), 5);
  EXPECT_EQ(geometryError(text),
            "ur5_gripper.urdf: link 'tool0' has <collision> elements but is not part of the "
            "chain: it moves with joint 'wrist_3_joint', a mimic joint of the chain (not "
            "supported yet)");
}

TEST(UrdfBranches, TheCheckerPlacesTheBodiesPastAMimicJointOfTheChain) {
  // j1 (z), then m (y at x 0.3, mimic j1 x 0.5 + 0.1), then j2 (x at x 0.2) carrying a sphere, and
  // a tool frame 0.1 along y. The checker's body of j2 against the hand composition.
  const std::string text = R"(<robot name="m">
    <link name="a"><collision><geometry><sphere radius="0.05"/></geometry></collision></link>
    <link name="b"/><link name="c"/><link name="tool"/>
    <link name="d"><collision><geometry><sphere radius="0.02"/></geometry></collision></link>
    <joint name="j1" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
      <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
    <joint name="m" type="revolute"><parent link="b"/><child link="c"/><origin xyz="0.3 0 0"/>
      <axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/>
      <mimic joint="j1" multiplier="0.5" offset="0.1"/></joint>
    <joint name="j2" type="revolute"><parent link="c"/><child link="d"/><origin xyz="0.2 0 0"/>
      <axis xyz="1 0 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
    <joint name="t" type="fixed"><parent link="d"/><child link="tool"/><origin xyz="0 0.1 0"/>
    </joint></robot>)";
  const Robot robot = parseRobotUrdf(text, "m.urdf");
  ASSERT_EQ(robot.dof(), 2);
  const CollisionChecker checker(robot, parseCollisionUrdf(robot, text, "m.urdf"));
  CollisionChecker::Scratch scratch;
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> angle(-3, 3);
  for (int sample = 0; sample < 50; ++sample) {
    const double q[2] = {angle(rng), angle(rng)};
    const Eigen::Isometry3d expected(
        Eigen::AngleAxisd(q[0], Eigen::Vector3d::UnitZ()) * Eigen::Translation3d(0.3, 0, 0) *
        Eigen::AngleAxisd(0.5 * q[0] + 0.1, Eigen::Vector3d::UnitY()) *
        Eigen::Translation3d(0.2, 0, 0) * Eigen::AngleAxisd(q[1], Eigen::Vector3d::UnitX()));
    checker.place(q, Eigen::Isometry3d::Identity(), scratch);
    EXPECT_LT((checker.bodyPose(2, scratch).matrix() - expected.matrix()).cwiseAbs().maxCoeff(),
              kTolerance);
    const Eigen::Isometry3d tool = expected * Eigen::Translation3d(0, 0.1, 0);
    EXPECT_LT((checker.bodyPose(checker.toolBody(), scratch).matrix() - tool.matrix())
                  .cwiseAbs()
                  .maxCoeff(),
              kTolerance);
  }
}

}  // namespace
}  // namespace mcws
