#pragma once
// A URDF written here in the shape of a ROS-generated one (issue 33): `world` -> `base_link` on a
// 0.5 m pedestal -> six revolute joints whose origins are the UR5's published standard D-H table
// (Universal Robots: d1 = 0.089159, a2 = -0.425, a3 = -0.39225, d4 = 0.10915, d5 = 0.09465,
// d6 = 0.0823 m; alpha = pi/2, 0, 0, pi/2, -pi/2, 0) written as URDF joint origins, and two
// leaves fixed to the last link: `tool0` (row 6 of the table: d6 along the last axis) and
// `ee_link` (5 cm off that axis, turned -90 deg about y). Collision: a sphere of radius 0.1 m at
// base_link's origin and one of 0.02 m at tool0's.
//
// Row i of the table, Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i), is the joint origin that follows
// joint i: translation (a_i, 0, d_i), roll alpha_i; joint 1's origin is base_link's frame.

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "mcws/kinematics/robot_urdf.h"

namespace mcws::test {

inline const std::string kUr5ShapedUrdf = R"(<?xml version="1.0"?>
<robot name="ur5_shaped">
  <link name="world"/>
  <link name="base_link">
    <collision><geometry><sphere radius="0.1"/></geometry></collision>
  </link>
  <link name="shoulder_link"/> <link name="upper_arm_link"/> <link name="forearm_link"/>
  <link name="wrist_1_link"/> <link name="wrist_2_link"/> <link name="wrist_3_link"/>
  <link name="tool0">
    <collision><geometry><sphere radius="0.02"/></geometry></collision>
  </link>
  <link name="ee_link"/>
  <joint name="world_joint" type="fixed"><parent link="world"/><child link="base_link"/>
    <origin xyz="0 0 0.5"/></joint>
  <joint name="shoulder_pan_joint" type="revolute">
    <parent link="base_link"/><child link="shoulder_link"/>
    <axis xyz="0 0 1"/><limit lower="-6.283185307179586" upper="6.283185307179586" effort="150" velocity="3.15"/></joint>
  <joint name="shoulder_lift_joint" type="revolute">
    <parent link="shoulder_link"/><child link="upper_arm_link"/>
    <origin xyz="0 0 0.089159" rpy="1.5707963267948966 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-6.283185307179586" upper="6.283185307179586" effort="150" velocity="3.15"/></joint>
  <joint name="elbow_joint" type="revolute">
    <parent link="upper_arm_link"/><child link="forearm_link"/>
    <origin xyz="-0.425 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-3.141592653589793" upper="3.141592653589793" effort="150" velocity="3.15"/></joint>
  <joint name="wrist_1_joint" type="revolute">
    <parent link="forearm_link"/><child link="wrist_1_link"/>
    <origin xyz="-0.39225 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-6.283185307179586" upper="6.283185307179586" effort="28" velocity="3.2"/></joint>
  <joint name="wrist_2_joint" type="revolute">
    <parent link="wrist_1_link"/><child link="wrist_2_link"/>
    <origin xyz="0 0 0.10915" rpy="1.5707963267948966 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-6.283185307179586" upper="6.283185307179586" effort="28" velocity="3.2"/></joint>
  <joint name="wrist_3_joint" type="revolute">
    <parent link="wrist_2_link"/><child link="wrist_3_link"/>
    <origin xyz="0 0 0.09465" rpy="-1.5707963267948966 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-6.283185307179586" upper="6.283185307179586" effort="28" velocity="3.2"/></joint>
  <joint name="tool0_fixed_joint" type="fixed"><parent link="wrist_3_link"/><child link="tool0"/>
    <origin xyz="0 0 0.0823"/></joint>
  <joint name="ee_fixed_joint" type="fixed"><parent link="wrist_3_link"/><child link="ee_link"/>
    <origin xyz="0.05 0 0.0823" rpy="0 -1.5707963267948966 0"/></joint>
</robot>
)";

/// The chain from the root (world) to tool0, the leaf the tests measure.
inline const UrdfChainOptions kUr5ToTool0{"", "tool0"};

/// Height of base_link's frame above world's [m].
constexpr double kUr5Pedestal = 0.5;

/// One row of a standard D-H table, Rz(theta) Tz(d) Tx(a) Rx(alpha), composed here with Eigen
/// (not the library's dhStandard()). Lengths [m], angles [rad].
inline Eigen::Isometry3d ur5Row(double a, double alpha, double d, double theta) {
  return Eigen::Isometry3d(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()) *
                           Eigen::Translation3d(a, 0.0, d) *
                           Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitX()));
}

/// The last link's frame (wrist_3_link) in base_link's frame: rows 1 to 5, then joint 6's turn.
inline Eigen::Isometry3d ur5BaseToWrist3(const Eigen::VectorXd& q) {
  const double a[] = {0.0, -0.425, -0.39225, 0.0, 0.0};
  const double alpha[] = {M_PI / 2, 0.0, 0.0, M_PI / 2, -M_PI / 2};
  const double d[] = {0.089159, 0.0, 0.0, 0.10915, 0.09465};
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 5; ++i) T = T * ur5Row(a[i], alpha[i], d[i], q[i]);
  return T * Eigen::AngleAxisd(q[5], Eigen::Vector3d::UnitZ());
}

/// tool0 in base_link's frame: the whole D-H table (row 6: d6 = 0.0823 m, a6 = alpha6 = 0).
inline Eigen::Isometry3d ur5BaseToTool0(const Eigen::VectorXd& q) {
  return ur5BaseToWrist3(q) * Eigen::Translation3d(0.0, 0.0, 0.0823);
}

/// ee_link in base_link's frame: (0.05, 0, 0.0823) in the last link's frame, turned -pi/2 about y.
inline Eigen::Isometry3d ur5BaseToEeLink(const Eigen::VectorXd& q) {
  return ur5BaseToWrist3(q) * Eigen::Translation3d(0.05, 0.0, 0.0823) *
         Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitY());
}

/// A frame in base_link's frame seen from world's (the pedestal).
inline Eigen::Isometry3d ur5FromWorld(const Eigen::Isometry3d& T_base_frame) {
  return Eigen::Translation3d(0.0, 0.0, kUr5Pedestal) * T_base_frame;
}

}  // namespace mcws::test
