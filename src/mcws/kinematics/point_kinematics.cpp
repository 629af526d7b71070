#include "mcws/kinematics/point_kinematics.h"

namespace mcws {
namespace {

/// A rotation R with R * z = axis (axis: unit vector).
Eigen::Matrix3d rotationTakingZTo(const Eigen::Vector3d& axis) {
  return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis).toRotationMatrix();
}

std::array<double, 12> rowMajor3x4(const Eigen::Isometry3d& T) {
  std::array<double, 12> m{};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) m[4 * r + c] = T.matrix()(r, c);
  }
  return m;
}

}  // namespace

PointKinematics::PointKinematics(const Robot& robot, const Eigen::Vector3d& p_flange) {
  // T_world_flange = T_world_base * prod_i (F_i * R_i Mz(q_i) R_i^T) * T_last_flange, where R_i
  // turns z onto joint i's axis and Mz is a motion about / along z. Regrouping the fixed parts:
  // E_0 = T_world_base F_1 R_1, E_i = R_i^T F_{i+1} R_{i+1}, and the last one applied to the point.
  const int n = robot.dof();
  Eigen::Isometry3d T_before = robot.T_world_base;
  Eigen::Matrix3d R_previous_inverse = Eigen::Matrix3d::Identity();
  for (int i = 0; i < n; ++i) {
    const Joint& joint = robot.joints[i];
    const Eigen::Matrix3d R = rotationTakingZTo(joint.axis.normalized());
    Eigen::Isometry3d E = Eigen::Isometry3d::Identity();
    E.linear() = R_previous_inverse;
    E = (i == 0 ? T_before : E) * joint.T_parent_joint;
    E.linear() = E.linear() * R;
    fixed_.push_back(rowMajor3x4(E));
    revolute_.push_back(joint.type == JointType::kRevolute);
    R_previous_inverse = R.transpose();
  }
  Eigen::Isometry3d E_last = Eigen::Isometry3d::Identity();
  E_last.linear() = R_previous_inverse;
  p_last_ = n == 0 ? Eigen::Vector3d(robot.T_world_base * robot.T_last_flange * p_flange)
                   : Eigen::Vector3d(E_last * robot.T_last_flange * p_flange);
}

}  // namespace mcws
