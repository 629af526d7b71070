#pragma once
/// \file
/// \brief Bounding volumes of a mesh's vertices for CollisionChecker's broad phase: a mesh pair
/// whose bounds are apart cannot collide, so only pairs whose bounds overlap reach the mesh test.

#include <Eigen/Core>
#include <vector>

namespace mcws {

/// \brief A sphere holding every point [length unit].
struct BoundingSphere {
  Eigen::Vector3d center{Eigen::Vector3d::Zero()};
  double radius{0.0};
};

/// \brief A capsule (line-swept sphere, the LSS of Fu, Hu, Chen & Pan 2016) holding every point:
/// the points within `radius` of the segment [p_from, p_to] [length unit].
struct BoundingCapsule {
  Eigen::Vector3d p_from{Eigen::Vector3d::Zero()}, p_to{Eigen::Vector3d::Zero()};
  double radius{0.0};
};

/// \brief Bounding sphere of `points` (not the smallest: centred on their bounding box).
/// \pre points is not empty.
BoundingSphere boundingSphere(const std::vector<Eigen::Vector3d>& points);

/// \brief A tight bounding capsule of `points`: its segment lies on their principal axis, its
/// radius is the largest distance of a point from that axis, and its ends are the nearest that
/// keep every point inside. \pre points is not empty.
BoundingCapsule boundingCapsule(const std::vector<Eigen::Vector3d>& points);

}  // namespace mcws
