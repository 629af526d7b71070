#pragma once
// What the boundary benchmarks share: precision and recall of reported boundary points on a
// validation shape, and the column area of Yin, Wang & Yu 2010 on the extremum method's own
// columns.

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "mcws/sampling/sampler.h"

namespace mcws::bench {

struct BoundaryQuality {
  double precision{0.0};  ///< share of reported points within 2 h of the true boundary
  double recall{1.0};     ///< share of the points within h / 2 of it that are reported
};

/// Precision and recall of `reported` (indices into `cloud`) for a shape of mean spacing h.
template <typename PointT>
BoundaryQuality boundaryQuality(Shape shape, const pcl::PointCloud<PointT>& cloud,
                                const pcl::Indices& reported, double h) {
  auto distance = [&](std::size_t i) {
    return shapeBoundaryDistance(shape, cloud[i].getVector3fMap().template cast<double>());
  };
  std::vector<char> is_reported(cloud.size(), 0);
  std::size_t close = 0;
  for (const auto i : reported) {
    is_reported[i] = 1;
    close += distance(i) <= 2 * h;
  }
  std::size_t near = 0, found = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (distance(i) <= 0.5 * h) {
      ++near;
      found += is_reported[i];
    }
  }
  BoundaryQuality quality;
  quality.precision = reported.empty() ? 0.0 : static_cast<double>(close) / reported.size();
  quality.recall = near ? static_cast<double>(found) / near : 1.0;
  return quality;
}

/// Eqs. (2) to (4) of Yin, Wang & Yu 2010 on the extremum method's own columns (width L along x,
/// the first at the cloud's smallest x): in each column the kept points sorted by y pair up as
/// (lowest, next), (next, next) ..., S = L sum (y_2j - y_2j-1); an unpaired last point adds
/// nothing.
template <typename PointT>
double extremumColumnArea(const pcl::PointCloud<PointT>& cloud, const pcl::Indices& kept,
                          double width) {
  if (cloud.empty()) return 0.0;
  float min_x = cloud[0].x;
  for (const auto& p : cloud) min_x = std::min(min_x, p.x);
  std::vector<std::pair<std::int64_t, float>> points;  // (column, y)
  for (const auto i : kept) {
    points.emplace_back(static_cast<std::int64_t>(std::floor((cloud[i].x - min_x) / width)),
                        cloud[i].y);
  }
  std::sort(points.begin(), points.end());
  double area = 0.0;
  for (std::size_t begin = 0; begin < points.size();) {
    std::size_t end = begin;
    while (end < points.size() && points[end].first == points[begin].first) ++end;
    for (std::size_t k = begin; k + 1 < end; k += 2) {
      area += width * (points[k + 1].second - points[k].second);
    }
    begin = end;
  }
  return area;
}

}  // namespace mcws::bench
