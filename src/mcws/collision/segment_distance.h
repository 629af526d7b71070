#pragma once
/// \file
/// \brief Closest distance between two line segments, for swept-sphere (capsule) tests.

#include <Eigen/Core>

namespace mcws {

/// \brief Squared distance between segments [p1, q1] and [p2, q2] (any length unit, squared).
///
/// The clamped closest-point computation of Ericson, "Real-Time Collision Detection" (2005),
/// section 5.1.9, including degenerate (point) segments. Two capsules (line-swept spheres, the LSS
/// volumes of Fu, Hu, Chen & Pan 2016) of radii r1 and r2 overlap exactly when this is below
/// (r1 + r2)^2.
double segmentDistanceSquared(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1,
                              const Eigen::Vector3d& p2, const Eigen::Vector3d& q2);

/// \brief segmentDistanceSquared() with the closest points' parameters: p1 + s (q1 - p1) and
/// p2 + t (q2 - p2), s and t in [0, 1].
double segmentDistanceSquared(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1,
                              const Eigen::Vector3d& p2, const Eigen::Vector3d& q2, double& s,
                              double& t);

}  // namespace mcws
