#pragma once
/// \file
/// \brief Serial robot model: a chain of (fixed transform, joint axis, joint type).

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "mcws/core/control_bytes.h"
#include "mcws/core/length_unit.h"

namespace mcws {

/// \brief Kind of a one-degree-of-freedom joint.
enum class JointType { kRevolute, kPrismatic };

/// \brief Name of a joint type ("revolute", "prismatic").
const char* jointTypeName(JointType type);

/// \brief One joint of a serial chain.
///
/// The joint frame is reached from the previous link frame by the fixed transform
/// `T_parent_joint`; the joint then rotates about, or translates along, `axis` (a unit vector in
/// the joint frame). The frame after that motion is this joint's link frame.
struct Joint {
  std::string name;
  JointType type{JointType::kRevolute};
  Eigen::Isometry3d T_parent_joint{Eigen::Isometry3d::Identity()};
  Eigen::Vector3d axis{Eigen::Vector3d::UnitZ()};
  double lower{0.0};  ///< lower limit [rad] or [length unit]
  double upper{0.0};  ///< upper limit [rad] or [length unit]
};

/// \brief A moving joint of the chain whose value follows a free joint's (URDF `<mimic>`):
/// value = multiplier * q[master] + offset. It is no degree of freedom of its own.
///
/// It sits on the chain after free joint `before - 1`'s link frame (the base frame when `before`
/// is 0) and before free joint `before`'s `T_parent_joint` (before `T_last_flange` when `before`
/// is Robot::dof()); several with the same `before` follow one another in the order listed.
struct MimicJoint {
  Joint joint;  ///< name, type, `T_parent_joint` from the frame before it, axis (limits unused)
  int before{0};
  int master{0};  ///< index of the free joint it follows
  double multiplier{1.0};
  double offset{0.0};  ///< [rad] or [length unit]
};

/// \brief A serial manipulator.
///
/// T_world_tool(q) = T_world_base * prod_i (T_parent_joint_i * M_i(q_i)) * T_last_flange *
/// T_flange_tool, where M_i is the motion of joint i, and each mimic joint (MimicJoint) inserts
/// its own T_parent_joint * M(multiplier * q_master + offset) where it sits. The flange is the end
/// of the bare arm (point P of Fu, Hu, Chen & Pan 2016); the tool point is its point T. Every
/// length is in `length_unit`.
struct Robot {
  std::string name;
  std::string source;  ///< file the robot was read from, for messages
  LengthUnit length_unit{LengthUnit::kMetre};
  Eigen::Isometry3d T_world_base{Eigen::Isometry3d::Identity()};
  std::vector<Joint> joints;
  Eigen::Isometry3d T_last_flange{Eigen::Isometry3d::Identity()};
  Eigen::Isometry3d T_flange_tool{Eigen::Isometry3d::Identity()};
  /// A URDF robot's chain (loadRobotUrdf()): the link whose frame is the base frame and the link
  /// whose frame is the flange frame, so that what else is read from the file (its collision
  /// model) follows the same chain. Empty for a D-H robot.
  std::string base_link, tip_link;
  /// A URDF robot's folders to look for `package://` packages in, before `ROS_PACKAGE_PATH` (the
  /// tools' --package-path), for what else is read from the file (its meshes).
  std::vector<std::string> package_path;
  /// An SRDF file whose `<disable_collisions>` pairs the collision model drops (the tools'
  /// --srdf; applySrdf(), collision/srdf.h); empty for none.
  std::string srdf;
  /// Joints of the chain that follow a free joint (URDF `<mimic>`), in chain order; empty for a
  /// D-H robot.
  std::vector<MimicJoint> mimic_joints;

  /// \brief Number of free joints (degrees of freedom; mimic joints do not count).
  int dof() const { return static_cast<int>(joints.size()); }
  /// \brief Index of the joint called `joint_name`.
  /// \throws mcws::Error naming the robot and the joint when there is no such joint.
  int jointIndex(const std::string& joint_name) const;
  /// \brief Lower limits [rad | length unit].
  Eigen::VectorXd lowerLimits() const;
  /// \brief Upper limits [rad | length unit].
  Eigen::VectorXd upperLimits() const;
  /// \brief Checks that q has dof() entries. \throws mcws::Error naming both counts.
  void checkSize(const Eigen::VectorXd& q) const;
  /// \brief Checks that q has dof() finite entries, each within its joint's limits.
  /// \throws mcws::Error naming the joint, its value and its limits.
  void checkJointVector(const Eigen::VectorXd& q) const;
};

/// \brief A joint's limits for messages, at full precision and, for revolute joints, in degrees
/// too: "[-1.047197551, 1.047197551] rad ([-60, 60] deg)" or "[25, 70] cm".
std::string describeLimits(const Joint& joint, LengthUnit unit);

/// \brief The unit of each joint's value: "rad" (revolute) or the robot's length unit (prismatic),
/// followed by `per` (e.g. "/s" for velocities).
std::vector<std::string> jointUnits(const Robot& robot, const std::string& per = "");
/// \brief jointUnits() in words: "rad" when every joint's value has the same unit, else each
/// joint's: "rad, rad, rad, cm (joint by joint)".
std::string jointUnitsText(const Robot& robot);

/// \brief Throws unless `name` is free of control bytes (hasControlByte(), core/control_bytes.h).
/// \param where names the field in the message: "bad.urdf: link".
/// \throws mcws::Error "where name 'arm\x0a2' holds a control byte (names are printable text)".
void checkPrintableName(const std::string& name, const std::string& where);

/// \brief Transform of one row of a standard (distal) D-H table:
/// Rz(theta) * Tz(d) * Tx(a) * Rx(alpha). Lengths in any unit, angles [rad].
Eigen::Isometry3d dhStandard(double a, double alpha, double d, double theta);
/// \brief Transform of one row of a modified (proximal, Craig) D-H table:
/// Rx(alpha) * Tx(a) * Rz(theta) * Tz(d). Lengths in any unit, angles [rad].
Eigen::Isometry3d dhModified(double a, double alpha, double d, double theta);
/// \brief Pose from a translation and fixed-axis roll, pitch, yaw (as URDF):
/// R = Rz(yaw) * Ry(pitch) * Rx(roll). Angles [rad].
Eigen::Isometry3d poseFromXyzRpy(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy);

/// \brief Largest |R^T R - I| entry accepted from a typed matrix (poseFromTypedMatrix()): a
/// matrix printed with 4 decimals (as Liu, Han, Xu & Li 2021 print theirs) passes, a wrong entry
/// does not.
constexpr double kTypedRotationTolerance = 1e-3;
/// \brief The pose of a homogeneous 4x4 matrix typed by hand [length unit]: its rotation, within
/// kTypedRotationTolerance of orthonormal, replaced by the nearest rotation matrix (Frobenius
/// norm: U V^T of its singular value decomposition).
/// \throws mcws::Error for a last row other than 0 0 0 1 ("last row is 0 0 1 1, not 0 0 0 1"),
///   a rotation further from orthonormal, or a reflection.
Eigen::Isometry3d poseFromTypedMatrix(const Eigen::Matrix4d& M);

/// \brief Throws when the robot has a mimic joint on its chain (Robot::mimic_joints), for the
/// computations that do not model them yet.
/// \param what names the computation in the message ("the reach map").
/// \throws mcws::Error "arm.urdf: joint 'j4' mimics another joint of the chain, which the reach
///   map does not support yet (mimic joints off the chain are fine)".
void refuseMimicJoints(const Robot& robot, const std::string& what);

/// \brief Length scale of a chain [length unit]: the sum of its fixed offsets (base to flange,
/// flange to tool) and prismatic strokes, an upper bound on the tool point's distance from the
/// first joint. 1 when that sum is 0 or not finite. Used to make position and orientation errors
/// or Jacobian rows comparable.
double chainLengthScale(const Robot& robot);

}  // namespace mcws
