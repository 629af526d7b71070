#pragma once
// planar2's annulus, its manipulability in closed form, study options and small geometric
// helpers, shared by reach_study_test.cpp, reach_study_inputs_test.cpp and base_placement_test.cpp.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "mcws/kinematics/robot_yaml.h"
#include "mcws/reach/reach_study.h"
#include "reach/planar2.h"

namespace mcws::test {

/// Outer radius of planar2's annulus (the arm stretched out).
constexpr double kOuter = kL1 + kL2;

/// Angle between two directions [rad], well conditioned at 0 and pi.
inline double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

/// Difference of two angles wrapped into (-pi, pi].
inline double angleDifference(double a, double b) { return std::remainder(a - b, 2.0 * M_PI); }

/// The planar arm's manipulability of the tool point at distance r from the base: l1 l2 |sin q2|
/// with cos q2 = (r^2 - l1^2 - l2^2) / (2 l1 l2).
inline double planarManipulability(double r) {
  const double c = (r * r - kL1 * kL1 - kL2 * kL2) / (2.0 * kL1 * kL2);
  return kL1 * kL2 * std::sqrt(std::max(0.0, 1.0 - c * c));
}

/// |dm/dr| of planarManipulability(): dc/dr = r / (l1 l2), so |dm/dr| = |c| r / sqrt(1 - c^2).
inline double planarManipulabilitySlope(double r) {
  const double c = (r * r - kL1 * kL1 - kL2 * kL2) / (2.0 * kL1 * kL2);
  return std::abs(c) * r / std::sqrt(std::max(1e-300, 1.0 - c * c));
}

/// A pure translation by (x, y, z).
inline Eigen::Isometry3d translation(double x, double y, double z) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

/// A study of the tool point's position manipulability (characteristic length 1).
inline ReachStudyOptions planarOptions() {
  ReachStudyOptions options;
  options.quality = QualityOptions{QualityTask::kPosition, 1.0};
  return options;
}

}  // namespace mcws::test
