#include "mcws/kinematics/jacobian.h"

#include <cmath>

#include "mcws/kinematics/detail/chain_motions.h"

namespace mcws {
namespace {

/// A rotation A with A * z = axis (axis: unit vector).
Eigen::Matrix3d rotationTakingZTo(const Eigen::Vector3d& axis) {
  return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis).toRotationMatrix();
}

/// Turns the parked columns of J (joint origin in rows 0-2, world axis in rows 3-5) into the
/// Jacobian's columns at the tool point p.
void finishColumns(int dof, const char* revolute, const Eigen::Vector3d& p, double* J) {
  for (int i = 0; i < dof; ++i) {
    double* column = J + 6 * i;
    Eigen::Map<Eigen::Vector3d> linear(column), angular(column + 3);
    if (revolute[i]) {
      linear = angular.cross(p - linear);
    } else {
      linear = angular;
      angular.setZero();
    }
  }
}

}  // namespace

KinematicChain::KinematicChain(const Robot& robot) : dof_(robot.dof()) {
  // Joint i's motion about / along its axis is A_i Z(q_i) A_i^T with A_i z = axis_i, so
  // G_0 = T_world_base P_0 A_0, G_i = A_{i-1}^T P_i A_i, G_n = A_{n-1}^T T_last_flange
  // T_flange_tool (P_i = joints[i].T_parent_joint), over the moving joints in chain order (the
  // free joints and, where they sit, the mimic joints).
  const detail::ChainMotions motions = detail::chainMotions(robot);
  const std::vector<const Joint*>& moving = motions.joints;
  free_ = motions.source;
  for (const MimicJoint* mimic : motions.mimics) {
    mimics_.push_back({mimic->master, mimic->multiplier, mimic->offset});
  }
  fixed_.reserve(moving.size() + 1);
  revolute_.reserve(moving.size());
  Eigen::Isometry3d before = robot.T_world_base;  // what stands left of P_i
  for (const Joint* joint : moving) {
    const Eigen::Matrix3d A = joint->axis == Eigen::Vector3d::UnitZ()
                                  ? Eigen::Matrix3d::Identity()
                                  : rotationTakingZTo(joint->axis.normalized());
    const Eigen::Isometry3d G = before * joint->T_parent_joint;
    fixed_.push_back({G.linear() * A, G.translation()});
    revolute_.push_back(joint->type == JointType::kRevolute);
    before = Eigen::Isometry3d(A.transpose());
  }
  const Eigen::Isometry3d G = before * robot.T_last_flange * robot.T_flange_tool;
  fixed_.push_back({G.linear(), G.translation()});
}

double KinematicChain::value(int step, const double* q) const {
  const int source = free_[step];
  if (source >= 0) return q[source];
  const Mimic& mimic = mimics_[-1 - source];
  return mimic.multiplier * q[mimic.master] + mimic.offset;
}

void KinematicChain::advance(int i, double q, Eigen::Matrix3d& R, Eigen::Vector3d& p) const {
  if (revolute_[i]) {
    const double c = std::cos(q), s = std::sin(q);
    const Eigen::Vector3d x = R.col(0);
    R.col(0) = c * x + s * R.col(1);
    R.col(1) = c * R.col(1) - s * x;
  } else {
    p += q * R.col(2);
  }
  const Fixed& G = fixed_[i + 1];
  p += R * G.p;
  R = R * G.R;
}

Eigen::Isometry3d KinematicChain::toolPose(const double* q) const {
  Eigen::Matrix3d R = fixed_[0].R;
  Eigen::Vector3d p = fixed_[0].p;
  for (int step = 0; step < static_cast<int>(revolute_.size()); ++step) {
    advance(step, value(step, q), R, p);
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = p;
  return T;
}

void KinematicChain::toolPoseAndJacobian(const double* q, Eigen::Matrix3d& R_world_tool,
                                         Eigen::Vector3d& p_world_tool, double* J) const {
  if (!mimics_.empty()) return withMimics(q, R_world_tool, p_world_tool, J);
  Eigen::Matrix3d R = fixed_[0].R;
  Eigen::Vector3d p = fixed_[0].p;
  for (int i = 0; i < dof(); ++i) {
    // Joint i's axis is z of the current frame, its origin p (before a prismatic motion; any
    // point on the axis serves). Park them in column i, finished once the tool point is known.
    Eigen::Map<Eigen::Matrix<double, 6, 1>> column(J + 6 * i);
    column.head<3>() = p;
    column.tail<3>() = R.col(2);
    advance(i, q[i], R, p);
  }
  finishColumns(dof(), revolute_.data(), p, J);
  R_world_tool = R;
  p_world_tool = p;
}

void KinematicChain::withMimics(const double* q, Eigen::Matrix3d& R_world_tool,
                                Eigen::Vector3d& p_world_tool, double* J) const {
  // Per free joint, the sums over the mimic joints that follow it, each weighted by its
  // multiplier m: m z (revolute), m z x p_k (revolute), m z (prismatic). A revolute mimic's column
  // m z x (p_tool - p_k) is then (sum m z) x p_tool - sum m z x p_k.
  std::vector<Eigen::Vector3d> turn(dof(), Eigen::Vector3d::Zero()), moment = turn, shift = turn;
  std::vector<char> free_revolute(dof());
  Eigen::Matrix3d R = fixed_[0].R;
  Eigen::Vector3d p = fixed_[0].p;
  for (int step = 0; step < static_cast<int>(revolute_.size()); ++step) {
    const int source = free_[step];
    if (source >= 0) {
      Eigen::Map<Eigen::Matrix<double, 6, 1>> column(J + 6 * source);
      column.head<3>() = p;
      column.tail<3>() = R.col(2);
      free_revolute[source] = revolute_[step];
    } else {
      const Mimic& mimic = mimics_[-1 - source];
      const Eigen::Vector3d z = mimic.multiplier * R.col(2);
      if (revolute_[step]) {
        turn[mimic.master] += z;
        moment[mimic.master] += z.cross(p);
      } else {
        shift[mimic.master] += z;
      }
    }
    advance(step, value(step, q), R, p);
  }
  finishColumns(dof(), free_revolute.data(), p, J);
  for (int i = 0; i < dof(); ++i) {
    Eigen::Map<Eigen::Vector3d> linear(J + 6 * i), angular(J + 6 * i + 3);
    linear += turn[i].cross(p) - moment[i] + shift[i];
    angular += turn[i];
  }
  R_world_tool = R;
  p_world_tool = p;
}

Jacobian toolJacobian(const Robot& robot, const Eigen::VectorXd& q) {
  robot.checkSize(q);
  Jacobian J(6, robot.dof());
  Eigen::Matrix3d R;
  Eigen::Vector3d p;
  KinematicChain(robot).toolPoseAndJacobian(q.data(), R, p, J.data());
  return J;
}

}  // namespace mcws
