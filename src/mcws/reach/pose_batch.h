#pragma once
/// \file
/// \brief Tool poses and Jacobians of sixteen joint vectors at once: the kernel of the
/// reachability map.

#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "mcws/kinematics/robot.h"
#include "mcws/reach/quality.h"

namespace mcws {

/// \brief Forward kinematics of the whole tool frame, and optionally the Jacobian's
/// manipulability, for kLanes joint vectors at once (vectorised across them, as
/// PointKinematics is for a point).
///
/// The tool frame is carried from the flange back to the world through the fixed transforms
/// (each joint axis turned onto z once, at construction). On the way, at joint i, the tool point
/// p and axes R are known in joint i's frame, whose z axis is the joint axis through its origin,
/// so the Jacobian's column i in the tool frame is (R^T (z x p), R^T z) for a revolute joint and
/// (R^T z, 0) for a prismatic one; a rotation of all columns leaves the singular values, and so
/// manipulability(), unchanged.
class PoseBatch {
 public:
  static constexpr int kLanes = 16;

  /// \param wide four lanes at a time in AVX registers where the processor has them (the
  ///   results are the same bits; false: two at a time in SSE2 registers, as the build targets).
  /// \throws mcws::Error for a robot with more than 8 joints.
  explicit PoseBatch(const Robot& robot, bool wide = true);
  int dof() const { return static_cast<int>(revolute_.size()); }

  /// \brief Tool poses of kLanes joint vectors.
  /// \param q q[j * kLanes + k] = joint j of sample k [rad | length unit].
  /// \param p p[a * kLanes + k] = coordinate a of sample k's tool point [length unit].
  /// \param approach the tool's z axis, laid out as p.
  /// \param x_axis the tool's x axis, laid out as p; nullptr when not wanted (not computed then).
  /// \param quality when not null, also writes manipulability[k] as mcws::manipulability() of
  ///   the sample's Jacobian would, with these options.
  /// \param manipulability kLanes values (used only with quality).
  ///
  /// Each lane's values are those of the straightforward per-sample formulas in the same order
  /// (the point and axes turned and transformed joint by joint, the Jacobian's Gram matrix summed
  /// from 0, its Cholesky factor), bit for bit: the same IEEE operations on two or four lanes at
  /// once (no fused multiply-adds: the build does not enable them).
  void poses(const double* q, double* p, double* approach, double* x_axis,
             const QualityOptions* quality, double* manipulability) const;

  /// \brief The cosines and sines of kLanes angles [rad] as poses() computes them (glibc's
  /// vector functions where available, which may differ from std::cos and std::sin in the last
  /// bit).
  static void cosinesAndSines(const double* angles, double* c, double* s);

 private:
  /// Per joint its fixed transform (row-major 3x4), each element 4 times: a vector kernel's lanes.
  std::vector<double> fixed_;
  std::vector<char> revolute_;
  Eigen::Matrix3d R_last_;  ///< the tool's axes in the frame after the last joint's motion
  Eigen::Vector3d p_last_;  ///< the tool point there
  bool wide_{false};        ///< four lanes at a time (AVX)
};

}  // namespace mcws
