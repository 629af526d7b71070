// URDF mimic joints on the chain (issue 33, item 2): a joint whose value is multiplier x master +
// offset is no degree of freedom of its own; FK against a hand composition of the joint origins,
// the Jacobian against central differences of that composition, IK back to a reachable pose.
// Also continuous joints' ranges and floating joints on the chain.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "mcws/core/error.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/inverse_kinematics.h"
#include "mcws/kinematics/jacobian.h"
#include "mcws/kinematics/point_kinematics.h"
#include "mcws/kinematics/robot_urdf.h"
#include "test_support.h"

namespace mcws {
namespace {

/// FK against the hand composition: rounding of a few dozen products of numbers below 1 [m].
constexpr double kFkTolerance = 1e-12;
/// Central differences with step 1e-6 [rad | m]: truncation ~1e-12, rounding ~1e-10.
constexpr double kJacobianTolerance = 1e-8;
constexpr double kStep = 1e-6;

// base -(j1 revolute z)- l1 -(j2 revolute y at z 0.3, mimic j1 x -0.5 + 0.2)- l2
// -(j3 prismatic x at x 0.4)- l3 -(j4 revolute x at (0.1, 0, 0.05), mimic j3 x 3)- l4
// -(fixed x 0.1)- tool. Free joints j1 and j3; j2 sits between them, j4 after the last.
const std::string kMimicChain = R"(<?xml version="1.0"?>
<robot name="mimic_chain">
  <link name="base"/> <link name="l1"/> <link name="l2"/> <link name="l3"/> <link name="l4"/>
  <link name="tool"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/>
    <origin xyz="0 0 0.3"/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/>
    <mimic joint="j1" multiplier="-0.5" offset="0.2"/></joint>
  <joint name="j3" type="prismatic"><parent link="l2"/><child link="l3"/>
    <origin xyz="0.4 0 0"/><axis xyz="1 0 0"/><limit lower="0" upper="0.2" effort="1" velocity="1"/></joint>
  <joint name="j4" type="revolute"><parent link="l3"/><child link="l4"/>
    <origin xyz="0.1 0 0.05"/><axis xyz="1 0 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/>
    <mimic joint="j3" multiplier="3"/></joint>
  <joint name="flange" type="fixed"><parent link="l4"/><child link="tool"/>
    <origin xyz="0.1 0 0"/></joint>
</robot>
)";

/// The tool pose of kMimicChain composed by hand from the joint origins (Eigen, not the library).
Eigen::Isometry3d handTool(double q1, double q3) {
  using Eigen::AngleAxisd;
  using Eigen::Translation3d;
  using Eigen::Vector3d;
  return Eigen::Isometry3d(AngleAxisd(q1, Vector3d::UnitZ()) * Translation3d(0, 0, 0.3) *
                           AngleAxisd(-0.5 * q1 + 0.2, Vector3d::UnitY()) *
                           Translation3d(0.4 + q3, 0, 0) * Translation3d(0.1, 0, 0.05) *
                           AngleAxisd(3 * q3, Vector3d::UnitX()) * Translation3d(0.1, 0, 0));
}

/// The message of parsing `urdf` as "bad.urdf".
std::string errorOf(const std::string& urdf) {
  return test::errorOf([&] { parseRobotUrdf(urdf, "bad.urdf"); });
}

TEST(UrdfMimic, MimicJointsOnTheChainAreNoDegreesOfFreedom) {
  // Before issue 33 this was "joint 'j2': mimic joints are not supported in a serial chain".
  const Robot robot = parseRobotUrdf(kMimicChain, "mimic.urdf");
  ASSERT_EQ(robot.dof(), 2);
  EXPECT_EQ(robot.joints[0].name, "j1");
  EXPECT_EQ(robot.joints[1].name, "j3");
  ASSERT_EQ(robot.mimic_joints.size(), 2u);
  EXPECT_EQ(robot.mimic_joints[0].joint.name, "j2");
  EXPECT_EQ(robot.mimic_joints[0].before, 1);
  EXPECT_EQ(robot.mimic_joints[0].master, 0);
  EXPECT_EQ(robot.mimic_joints[0].multiplier, -0.5);
  EXPECT_EQ(robot.mimic_joints[0].offset, 0.2);
  EXPECT_EQ(robot.mimic_joints[1].joint.name, "j4");
  EXPECT_EQ(robot.mimic_joints[1].before, 2);  // after the last free joint
  EXPECT_EQ(robot.mimic_joints[1].master, 1);
  EXPECT_EQ(robot.mimic_joints[1].multiplier, 3.0);
}

TEST(UrdfMimic, ForwardKinematicsFollowsTheHandComposition) {
  const Robot robot = parseRobotUrdf(kMimicChain, "mimic.urdf");
  std::mt19937_64 rng(33);
  std::uniform_real_distribution<double> angle(-3, 3), stroke(0, 0.2);
  for (int sample = 0; sample < 200; ++sample) {
    const Eigen::Vector2d q(angle(rng), stroke(rng));
    const Eigen::Isometry3d expected = handTool(q[0], q[1]);
    for (const Eigen::Isometry3d& T : {toolPose(robot, q), chainPoses(robot, q).T_world_tool,
                                       KinematicChain(robot).toolPose(q.data())}) {
      ASSERT_LT((T.matrix() - expected.matrix()).cwiseAbs().maxCoeff(), kFkTolerance)
          << q.transpose();
    }
    // The sampler's point kernel, one sample and a lane of kLanes copies.
    const PointKinematics point(robot, Eigen::Vector3d::Zero());
    ASSERT_EQ(point.dof(), 2);
    EXPECT_LT((point.position(q.data()) - expected.translation()).norm(), kFkTolerance);
    constexpr int kLanes = PointKinematics::kLanes;
    double lanes[2 * kLanes], x[kLanes], y[kLanes], z[kLanes];
    for (int k = 0; k < kLanes; ++k) lanes[k] = q[0], lanes[kLanes + k] = q[1];
    point.positions(lanes, x, y, z);
    EXPECT_LT(
        (Eigen::Vector3d(x[kLanes - 1], y[kLanes - 1], z[kLanes - 1]) - expected.translation())
            .norm(),
        kFkTolerance);
  }
}

TEST(UrdfMimic, JacobianIsTheChainRuleThroughTheMultiplier) {
  const Robot robot = parseRobotUrdf(kMimicChain, "mimic.urdf");
  std::mt19937_64 rng(34);
  std::uniform_real_distribution<double> angle(-3, 3), stroke(0, 0.2);
  for (int sample = 0; sample < 50; ++sample) {
    const Eigen::Vector2d q(angle(rng), stroke(rng));
    const Jacobian J = toolJacobian(robot, q);
    const Eigen::Isometry3d T = handTool(q[0], q[1]);
    for (int i = 0; i < 2; ++i) {
      Eigen::Vector2d plus = q, minus = q;
      plus[i] += kStep;
      minus[i] -= kStep;
      const Eigen::Isometry3d Tp = handTool(plus[0], plus[1]), Tm = handTool(minus[0], minus[1]);
      const Eigen::Vector3d v = (Tp.translation() - Tm.translation()) / (2 * kStep);
      // Angular velocity: the axis-angle of R(q + h) R(q - h)^T over 2h.
      const Eigen::AngleAxisd turn(Tp.linear() * Tm.linear().transpose());
      const Eigen::Vector3d w = turn.axis() * turn.angle() / (2 * kStep);
      EXPECT_LT((J.col(i).head<3>() - v).norm(), kJacobianTolerance) << i << ": " << q.transpose();
      EXPECT_LT((J.col(i).tail<3>() - w).norm(), kJacobianTolerance) << i << ": " << q.transpose();
    }
    (void)T;
  }
}

TEST(UrdfMimic, InverseKinematicsReachesAPoseOfTheChain) {
  const Robot robot = parseRobotUrdf(kMimicChain, "mimic.urdf");
  const Eigen::Vector2d q_true(0.7, 0.12);
  IkOptions options;
  options.position_only = true;
  const IkResult result =
      solveIk(robot, handTool(q_true[0], q_true[1]), Eigen::Vector2d(0.5, 0.05), options);
  ASSERT_EQ(result.status, IkStatus::kConverged);
  EXPECT_LT((handTool(result.q[0], result.q[1]).translation() -
             handTool(q_true[0], q_true[1]).translation())
                .norm(),
            1e-6);
}

TEST(UrdfMimic, MimicOfAJointOffTheChainIsFixedAtItsValue) {
  // A finger pair: `left` (prismatic, limits [0.01, 0.05]: default 0.01) and `right`, its mimic
  // (x -2 + 0.005, so -0.015). With `right` as tip its joint is fixed at that value.
  const std::string text = R"(<robot name="pair">
  <link name="base"/> <link name="palm"/> <link name="left"/> <link name="right"/>
  <joint name="wrist" type="revolute"><parent link="base"/><child link="palm"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="left_joint" type="prismatic"><parent link="palm"/><child link="left"/>
    <origin xyz="0 0.1 0"/><axis xyz="0 1 0"/><limit lower="0.01" upper="0.05" effort="1" velocity="1"/></joint>
  <joint name="right_joint" type="prismatic"><parent link="palm"/><child link="right"/>
    <origin xyz="0 -0.1 0"/><axis xyz="0 1 0"/><limit lower="-0.05" upper="0" effort="1" velocity="1"/>
    <mimic joint="left_joint" multiplier="-2" offset="0.005"/></joint>
</robot>)";
  const Robot robot = parseRobotUrdf(text, "pair.urdf", {"", "right"});
  ASSERT_EQ(robot.dof(), 1);
  EXPECT_TRUE(robot.mimic_joints.empty());
  const Eigen::Isometry3d T = toolPose(robot, Eigen::VectorXd::Constant(1, 0.5));
  const Eigen::Vector3d expected =
      Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()) * Eigen::Vector3d(0, -0.1 - 0.015, 0);
  EXPECT_LT((T.translation() - expected).norm(), kFkTolerance);
  // With `left` as tip the finger joint is free.
  EXPECT_EQ(parseRobotUrdf(text, "pair.urdf", {"", "left"}).dof(), 2);
}

TEST(UrdfMimic, BadMimicJoints) {
  const std::string missing = R"(<robot name="m"><link name="a"/><link name="b"/><link name="c"/>
  <joint name="j1" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="b"/><child link="c"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/><mimic joint="nope"/></joint></robot>)";
  EXPECT_EQ(errorOf(missing),
            "bad.urdf: joint 'j2': <mimic> joint 'nope' is not a joint of the robot");
  std::string loop = missing;
  loop.replace(loop.find("<limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>"),
               0, "<mimic joint=\"j2\"/>");
  loop.replace(loop.find("\"nope\""), 6, "\"j1\"");
  EXPECT_EQ(errorOf(loop), "bad.urdf: joint 'j2': its <mimic> joints follow one another round");
}

TEST(UrdfMimic, ContinuousJointsTakeOneTurnUnlessLimitsAreGiven) {
  const std::string text = R"(<robot name="c"><link name="a"/><link name="b"/><link name="c"/>
  <joint name="j1" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint>
  <joint name="j2" type="continuous"><parent link="b"/><child link="c"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="2" effort="1" velocity="1"/></joint></robot>)";
  const Robot robot = parseRobotUrdf(text, "c.urdf");
  ASSERT_EQ(robot.dof(), 2);
  EXPECT_EQ(robot.joints[0].lower, -M_PI);
  EXPECT_EQ(robot.joints[0].upper, M_PI);
  EXPECT_EQ(robot.joints[1].lower, -1.0);  // before: [-pi, pi] whatever the file said
  EXPECT_EQ(robot.joints[1].upper, 2.0);
}

TEST(UrdfMimic, FloatingAndPlanarJointsOnTheChainAreRefusedByName) {
  const std::string text = R"(<robot name="f"><link name="a"/><link name="b"/><link name="c"/>
  <joint name="j1" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="free_flyer" type="floating"><parent link="b"/><child link="c"/></joint></robot>)";
  EXPECT_EQ(errorOf(text),
            "bad.urdf: joint 'free_flyer': floating joints are not supported (revolute, "
            "continuous, prismatic, fixed)");
  // Off the chain, with no collision geometry below it, it is passed over.
  EXPECT_EQ(parseRobotUrdf(text, "f.urdf", {"", "b"}).dof(), 1);
}

}  // namespace
}  // namespace mcws
