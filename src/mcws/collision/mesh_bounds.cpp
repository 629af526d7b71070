#include "mcws/collision/mesh_bounds.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

namespace mcws {

BoundingSphere boundingSphere(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d lo = points.front(), hi = points.front();
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  BoundingSphere sphere;
  sphere.center = 0.5 * (lo + hi);
  for (const auto& p : points) sphere.radius = std::max(sphere.radius, (p - sphere.center).norm());
  return sphere;
}

BoundingCapsule boundingCapsule(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p;
  mean /= double(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& p : points) covariance += (p - mean) * (p - mean).transpose();
  const Eigen::Vector3d axis =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvectors().col(2);
  double radius = 0.0;
  for (const auto& p : points) {
    const Eigen::Vector3d v = p - mean;
    radius = std::max(radius, (v - v.dot(axis) * axis).norm());
  }
  // A point at t along the axis, off it by h, lies in the capsule when the nearer end is within
  // s = sqrt(r^2 - h^2) of t: the ends are the tightest that satisfy every point.
  double t_low = std::numeric_limits<double>::infinity(), t_high = -t_low;
  for (const auto& p : points) {
    const Eigen::Vector3d v = p - mean;
    const double t = v.dot(axis);
    const double s = std::sqrt(std::max(0.0, radius * radius - (v - t * axis).squaredNorm()));
    t_low = std::min(t_low, t + s);
    t_high = std::max(t_high, t - s);
  }
  if (t_low > t_high) t_low = t_high = 0.5 * (t_low + t_high);
  radius *= 1.0 + 1e-12;  // rounding must not push a vertex out
  return {mean + t_low * axis, mean + t_high * axis, radius};
}

}  // namespace mcws
