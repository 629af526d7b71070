#pragma once
/// \file
/// \brief Geometric Jacobian of a serial chain: tool-point velocity and angular velocity in the
/// world frame, and a chain prepared for evaluating the tool pose and the Jacobian together.

#include <Eigen/Geometry>
#include <vector>

#include "mcws/kinematics/robot.h"

namespace mcws {

/// \brief Geometric Jacobian, 6 x dof. Column i maps joint i's rate to the tool's twist in the
/// world frame, with the tool point as reference point: rows 0-2 the tool point's linear
/// velocity [length unit / rad] (revolute) or [1] (prismatic), rows 3-5 the angular velocity
/// [1] (revolute) or [rad / length unit] (prismatic, always zero).
using Jacobian = Eigen::Matrix<double, 6, Eigen::Dynamic>;

/// \brief A serial chain prepared for repeated evaluation of the tool pose and its Jacobian.
///
/// Every joint axis is turned onto z once, at construction, and the fixed rotations are folded
/// into the neighbouring fixed transforms:
/// T_world_tool(q) = G_0 * Z_0(q_0) * G_1 * ... * Z_{n-1}(q_{n-1}) * G_n, where Z_i is a rotation
/// about, or a translation along, z. One pass then costs a sin/cos pair and one 3x3 product per
/// joint, and the Jacobian's columns come from the same pass (Siciliano et al., "Robotics:
/// Modelling, Planning and Control", 2009, eq. 3.30): revolute z_i x (p_tool - p_i) and z_i,
/// prismatic z_i and 0, with z_i and p_i joint i's world axis and origin.
///
/// Mimic joints (Robot::mimic_joints) are moving joints of the chain too, each turned by
/// multiplier * q_master + offset; by the chain rule each adds multiplier times its own column to
/// its master's column.
class KinematicChain {
 public:
  explicit KinematicChain(const Robot& robot);

  /// \brief Number of joint values the chain reads.
  int dof() const { return dof_; }

  /// \brief T_world_tool(q).
  /// \param q joint values q[0 .. dof()) [rad | length unit]; limits are not checked.
  Eigen::Isometry3d toolPose(const double* q) const;

  /// \brief T_world_tool(q) and the geometric Jacobian in one pass.
  /// \param q joint values q[0 .. dof()) [rad | length unit]; limits are not checked.
  /// \param R_world_tool the tool's orientation.
  /// \param p_world_tool the tool point [length unit].
  /// \param J the Jacobian, column-major 6 x dof() (the data() of an Eigen 6 x N matrix).
  void toolPoseAndJacobian(const double* q, Eigen::Matrix3d& R_world_tool,
                           Eigen::Vector3d& p_world_tool, double* J) const;

 private:
  struct Fixed {
    Eigen::Matrix3d R;
    Eigen::Vector3d p;
  };
  /// What moves a mimic joint.
  struct Mimic {
    int master;  ///< the free joint it follows
    double multiplier, offset;
  };
  /// The value of moving joint `step` at the free joint values q.
  double value(int step, const double* q) const;
  /// Moves the frame (R, p) of moving joint i by its value q (a turn about z or a shift along
  /// it), then by the fixed transform to moving joint i + 1's frame.
  void advance(int i, double q, Eigen::Matrix3d& R, Eigen::Vector3d& p) const;
  /// toolPoseAndJacobian() of a chain with mimic joints.
  void withMimics(const double* q, Eigen::Matrix3d& R_world_tool, Eigen::Vector3d& p_world_tool,
                  double* J) const;
  int dof_{0};
  std::vector<Fixed> fixed_;  ///< G_0 .. G_n over the moving joints, free and mimic
  std::vector<char> revolute_;
  /// Per moving joint: its free joint's index, or -1 - k for mimic joint mimics_[k].
  std::vector<int> free_;
  std::vector<Mimic> mimics_;
};

/// \brief Geometric Jacobian of the tool point at q (see Jacobian).
/// \param q joint values, one per joint [rad | length unit]; limits are not checked.
/// \throws mcws::Error when q has the wrong size.
Jacobian toolJacobian(const Robot& robot, const Eigen::VectorXd& q);

}  // namespace mcws
