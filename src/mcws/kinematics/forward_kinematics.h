#pragma once
/// \file
/// \brief Forward kinematics of a serial chain (poses in the world frame, lengths in the robot's
/// length unit).

#include <Eigen/Geometry>
#include <vector>

#include "mcws/kinematics/robot.h"

namespace mcws {

/// \brief Every frame of a chain at one joint vector, all expressed in the world frame.
struct ChainPoses {
  std::vector<Eigen::Isometry3d> T_world_joint;  ///< joint i's frame before its motion
  std::vector<Eigen::Isometry3d> T_world_link;   ///< joint i's frame after its motion (link i)
  Eigen::Isometry3d T_world_flange{Eigen::Isometry3d::Identity()};  ///< end of the bare arm
  Eigen::Isometry3d T_world_tool{Eigen::Isometry3d::Identity()};    ///< tool point
};

/// \brief Motion of one joint: rotation by q [rad] about, or translation by q [length unit]
/// along, its axis.
Eigen::Isometry3d jointMotion(const Joint& joint, double q);

/// \brief The value of a mimic joint at the free joint values q: multiplier * q[master] + offset
/// [rad | length unit].
inline double mimicValue(const MimicJoint& mimic, const double* q) {
  return mimic.multiplier * q[mimic.master] + mimic.offset;
}

/// \brief Moves `T` through the mimic joints that sit before free joint `before` (before the flange
/// when `before` is robot.dof()): T = T * T_parent_joint * M(mimicValue()) for each, in order.
/// Leaves T untouched when there are none.
/// \param q the free joint values [rad | length unit], robot.dof() of them.
void applyMimicJoints(const Robot& robot, int before, const double* q, Eigen::Isometry3d& T);

/// \brief All frames of the chain.
/// \param q joint values [rad | length unit], one per joint (limits are not checked).
/// \throws mcws::Error when q has the wrong size.
ChainPoses chainPoses(const Robot& robot, const Eigen::VectorXd& q);

/// \brief Flange pose T_world_flange(q) (point P of Fu, Hu, Chen & Pan 2016).
/// \throws mcws::Error when q has the wrong size.
Eigen::Isometry3d flangePose(const Robot& robot, const Eigen::VectorXd& q);

/// \brief Tool pose T_world_tool(q) (point T of Fu, Hu, Chen & Pan 2016).
/// \throws mcws::Error when q has the wrong size.
Eigen::Isometry3d toolPose(const Robot& robot, const Eigen::VectorXd& q);

}  // namespace mcws
