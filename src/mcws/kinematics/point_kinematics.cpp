#include "mcws/kinematics/point_kinematics.h"

#include "mcws/core/libmvec.h"  // vector sin, cos, atan2 for the simd loops
#include "mcws/kinematics/detail/chain_motions.h"

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

PointKinematics::PointKinematics(const Robot& robot, const Eigen::Vector3d& p_flange)
    : dof_(robot.dof()) {
  // T_world_flange = T_world_base * prod_i (F_i * R_i Mz(q_i) R_i^T) * T_last_flange, where R_i
  // turns z onto joint i's axis and Mz is a motion about / along z. Regrouping the fixed parts:
  // E_0 = T_world_base F_1 R_1, E_i = R_i^T F_{i+1} R_{i+1}, and the last one applied to the point.
  // The product runs over the moving joints in chain order, the mimic joints where they sit.
  const detail::ChainMotions motions = detail::chainMotions(robot);
  const std::vector<const Joint*>& moving = motions.joints;
  source_ = motions.source;
  for (const MimicJoint* mimic : motions.mimics) {
    mimics_.push_back({mimic->master, mimic->multiplier, mimic->offset});
  }
  const int n = static_cast<int>(moving.size());
  Eigen::Isometry3d T_before = robot.T_world_base;
  Eigen::Matrix3d R_previous_inverse = Eigen::Matrix3d::Identity();
  for (int i = 0; i < n; ++i) {
    const Joint& joint = *moving[i];
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

void PointKinematics::positions(const double* q, double* x, double* y, double* z) const {
  double c[kLanes], s[kLanes];
  for (int k = 0; k < kLanes; ++k) {
    x[k] = p_last_[0];
    y[k] = p_last_[1];
    z[k] = p_last_[2];
  }
  double mimic_q[kLanes];
  for (int i = static_cast<int>(revolute_.size()) - 1; i >= 0; --i) {
    const double* qi = mimic_q;
    if (source_[i] >= 0) {
      qi = q + source_[i] * kLanes;
    } else {
      const Mimic& mimic = mimics_[-1 - source_[i]];
      for (int k = 0; k < kLanes; ++k) {
        mimic_q[k] = mimic.multiplier * q[mimic.master * kLanes + k] + mimic.offset;
      }
    }
    if (revolute_[i]) {
      // Separate loops: together GCC would fuse them into a scalar sincos call first.
#pragma omp simd
      for (int k = 0; k < kLanes; ++k) c[k] = std::cos(qi[k]);
#pragma omp simd
      for (int k = 0; k < kLanes; ++k) s[k] = std::sin(qi[k]);
#pragma omp simd
      for (int k = 0; k < kLanes; ++k) {
        const double xr = c[k] * x[k] - s[k] * y[k];
        y[k] = s[k] * x[k] + c[k] * y[k];
        x[k] = xr;
      }
    } else {
#pragma omp simd
      for (int k = 0; k < kLanes; ++k) z[k] += qi[k];
    }
    const double* E = fixed_[i].data();
#pragma omp simd
    for (int k = 0; k < kLanes; ++k) {
      const double xn = E[0] * x[k] + E[1] * y[k] + E[2] * z[k] + E[3];
      const double yn = E[4] * x[k] + E[5] * y[k] + E[6] * z[k] + E[7];
      z[k] = E[8] * x[k] + E[9] * y[k] + E[10] * z[k] + E[11];
      x[k] = xn;
      y[k] = yn;
    }
  }
}

}  // namespace mcws
