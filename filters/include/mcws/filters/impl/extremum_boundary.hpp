#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <tuple>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/filters/extremum_boundary.h"
#include "mcws/filters/grid_boundary.h"

namespace mcws {

template <typename PointT>
void ExtremumBoundary<PointT>::applyFilter(pcl::Indices& indices) {
  if (plane_ == BoundaryPlane::k3D) {
    throw Error(filter_name_ + ": the extremum method needs a plane (xy, xz or yz), not 3d");
  }
  pcl::PointCloud<pcl::PointXYZ> projected;  // x: along the columns' axis a, y: b
  pcl::Indices source;
  projectToPlane(*input_, *indices_, plane_, projected, source);
  const std::size_t n = projected.size();

  used_spacing_ = 0.0;
  if (auto_width_ || auto_gap_) used_spacing_ = meanSpacing(projected, 2);
  double width = width_;
  if (auto_width_) {
    width = baselineCellSize(n, used_spacing_, 2);
    if (!(width > 0.0)) width = 1.0;  // no spacing: identical points, one column
  }
  detail::checkCellSize(filter_name_, "column width", width, projected);
  double gap = gap_;
  if (auto_gap_) {
    gap = std::log(2.0 * static_cast<double>(std::max<std::size_t>(n, 1))) * used_spacing_ *
          used_spacing_ / width;
    if (!(gap > 0.0)) gap = 1.0;  // identical points: no gap to find
  }
  if (!(gap > 0.0) || !std::isfinite(gap)) {
    std::ostringstream msg;
    msg << filter_name_ << ": gap threshold " << gap << " must be a positive number";
    throw Error(msg.str());
  }
  used_width_ = width;
  used_gap_ = gap;

  // (column, b, point): a column's points are consecutive and sorted by b, copies by index.
  std::vector<std::tuple<std::int64_t, float, pcl::index_t>> keyed(n);
  float min_a = n > 0 ? projected[0].x : 0.0f;
  for (const auto& p : projected) min_a = std::min(min_a, p.x);
  for (std::size_t k = 0; k < n; ++k) {
    const auto column = static_cast<std::int64_t>(
        std::floor((static_cast<double>(projected[k].x) - min_a) / width));
    keyed[k] = {column, projected[k].y, static_cast<pcl::index_t>(k)};
  }
  std::sort(keyed.begin(), keyed.end());

  std::vector<char> boundary(n, 0);
  columns_ = 0;
  for (std::size_t begin = 0; begin < n;) {
    std::size_t end = begin + 1;
    while (end < n && std::get<0>(keyed[end]) == std::get<0>(keyed[begin])) ++end;
    ++columns_;
    // The lowest point: the first of its copies; the highest: the first copy of the last b.
    boundary[std::get<2>(keyed[begin])] = 1;
    std::size_t top = end - 1;
    while (top > begin && std::get<1>(keyed[top - 1]) == std::get<1>(keyed[end - 1])) --top;
    boundary[std::get<2>(keyed[top])] = 1;
    for (std::size_t k = begin; k + 1 < end; ++k) {
      if (static_cast<double>(std::get<1>(keyed[k + 1])) - std::get<1>(keyed[k]) > gap) {
        std::size_t below = k;  // the first copy of the point below the gap
        while (below > begin && std::get<1>(keyed[below - 1]) == std::get<1>(keyed[k])) --below;
        boundary[std::get<2>(keyed[below])] = 1;
        boundary[std::get<2>(keyed[k + 1])] = 1;
      }
    }
    begin = end;
  }

  splitByBoundary(
      *indices_, source, [&](std::size_t k) { return boundary[k] != 0; }, negative_,
      extract_removed_indices_, indices, *removed_indices_);
}

}  // namespace mcws
