#pragma once
/// \file
/// \brief How deep p lies inside the convex hull of its neighbourhood, in local spacings: the
/// second stage of the 2-D boundary test (OrthantBoundary::setHullDepth).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "mcws/search/neighbour_search.h"

namespace mcws::orthant {

/// \brief Scratch space of hullDepthInSpacings().
struct HullScratch {
  std::vector<Eigen::Vector2d> points, hull;
};

/// \brief The distance from p to the nearest edge of the convex hull of p and `neighbours`
/// (offsets from p, x-y plane), in local spacings h = sqrt(hull area / number of neighbours).
///
/// The hull is Andrew's monotone chain, counter-clockwise, without collinear points. Edge cases:
/// 0 when p is on the hull, and when the hull has no area (fewer than 3 positions, or all on a
/// line).
inline double hullDepthInSpacings(const std::vector<Neighbour>& neighbours, HullScratch& s) {
  s.points.clear();
  s.points.emplace_back(0.0, 0.0);
  for (const auto& q : neighbours) s.points.emplace_back(q.x, q.y);
  std::sort(s.points.begin(), s.points.end(),
            [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
              return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
            });
  auto turn = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  const std::size_t m = s.points.size();
  s.hull.resize(2 * m);
  std::size_t k = 0;
  for (std::size_t i = 0; i < m; ++i) {
    while (k >= 2 && turn(s.hull[k - 2], s.hull[k - 1], s.points[i]) <= 0.0) --k;
    s.hull[k++] = s.points[i];
  }
  for (std::size_t i = m - 1, lower = k + 1; i > 0; --i) {
    while (k >= lower && turn(s.hull[k - 2], s.hull[k - 1], s.points[i - 1]) <= 0.0) --k;
    s.hull[k++] = s.points[i - 1];
  }
  const std::size_t corners = k - 1;
  if (m < 3 || corners < 3) return 0.0;
  double twice_area = 0.0, depth = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < corners; ++i) {
    const Eigen::Vector2d& a = s.hull[i];
    const Eigen::Vector2d& b = s.hull[(i + 1) % corners];
    twice_area += a.x() * b.y() - a.y() * b.x();
    // p lies to the left of every counter-clockwise edge: its distance from the edge's line.
    depth = std::min(depth, turn(a, b, Eigen::Vector2d::Zero()) / (b - a).norm());
  }
  if (!(twice_area > 0.0)) return 0.0;
  const double spacing = std::sqrt(0.5 * twice_area / static_cast<double>(neighbours.size()));
  return std::max(depth, 0.0) / spacing;
}

}  // namespace mcws::orthant
