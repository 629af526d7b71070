#pragma once
/// \file
/// \brief Fast forward kinematics of one point fixed to the flange, for Monte Carlo sampling.

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <vector>

#include "mcws/kinematics/robot.h"

namespace mcws {

/// \brief World position of a point fixed to the flange, as a function of the joint values.
///
/// Equal to `(flangePose(robot, q) * p_flange)` but about four times cheaper: each joint axis is
/// turned onto z once, at construction, so that a revolute joint costs one sincos and a 2-D
/// rotation and a prismatic joint one addition; the point is carried from the flange back to the
/// world frame through fixed 3x4 transforms, never composing 4x4 matrices.
class PointKinematics {
 public:
  /// \param robot the chain.
  /// \param p_flange the point in the flange frame [length unit] (zero: the flange origin; the
  ///   tool frame's translation: the tool point).
  PointKinematics(const Robot& robot, const Eigen::Vector3d& p_flange);

  /// \brief Samples positions() computes together.
  static constexpr int kLanes = 8;

  /// \brief Number of joint values position() reads.
  int dof() const { return dof_; }

  /// \brief World positions of kLanes samples at once, vectorised (sin and cos from glibc's
  /// libmvec where available). Each sample's result depends only on its own joint values, not on
  /// its lane or its neighbours, and agrees with position() to about 1e-15 relative.
  /// \param q joint values, q[j * kLanes + k] = joint j of sample k [rad | length unit].
  /// \param x,y,z the positions of the kLanes samples [length unit].
  void positions(const double* q, double* x, double* y, double* z) const;

  /// \brief World position [length unit] for joint values q[0..dof()) [rad | length unit].
  Eigen::Vector3d position(const double* q) const {
    double x = p_last_[0], y = p_last_[1], z = p_last_[2];
    for (int i = static_cast<int>(revolute_.size()) - 1; i >= 0; --i) {
      const double qi = value(i, q);
      if (revolute_[i]) {
        const double c = std::cos(qi), s = std::sin(qi);
        const double xr = c * x - s * y;
        y = s * x + c * y;
        x = xr;
      } else {
        z += qi;
      }
      const double* E = fixed_[i].data();
      const double xn = E[0] * x + E[1] * y + E[2] * z + E[3];
      const double yn = E[4] * x + E[5] * y + E[6] * z + E[7];
      z = E[8] * x + E[9] * y + E[10] * z + E[11];
      x = xn;
      y = yn;
    }
    return {x, y, z};
  }

 private:
  /// What moves a mimic joint.
  struct Mimic {
    int master;  ///< the free joint it follows
    double multiplier, offset;
  };
  /// The value of moving joint i (free or mimic) at the free joint values q.
  double value(int i, const double* q) const {
    if (source_[i] >= 0) return q[source_[i]];
    const Mimic& mimic = mimics_[-1 - source_[i]];
    return mimic.multiplier * q[mimic.master] + mimic.offset;
  }
  int dof_{0};
  /// Over the moving joints, free and mimic (Robot::mimic_joints), in chain order:
  std::vector<std::array<double, 12>> fixed_;  ///< row-major 3x4 transform before joint i
  std::vector<bool> revolute_;
  std::vector<int> source_;  ///< the free joint's index, or -1 - k for mimic joint mimics_[k]
  std::vector<Mimic> mimics_;
  Eigen::Vector3d p_last_;  ///< the point in the frame after the last joint's motion
};

}  // namespace mcws
