#include "mcws/workspace/measure.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "mcws/core/error.h"

namespace mcws {

ColumnArea columnArea(const pcl::PointCloud<pcl::PointXYZ>& boundary, double width, double gap) {
  if (boundary.size() < 3) {
    throw Error("the column method needs at least 3 boundary points, got " +
                std::to_string(boundary.size()));
  }
  if (width < 0.0 || gap < 0.0 || !std::isfinite(width) || !std::isfinite(gap)) {
    throw Error("column width and gap must be 0 (automatic) or positive");
  }
  ColumnArea result;
  float min_x = boundary[0].x, max_x = boundary[0].x;
  for (const auto& p : boundary) {
    min_x = std::min(min_x, p.x);
    max_x = std::max(max_x, p.x);
  }
  if (width == 0.0) {
    // About sqrt(n) columns for n boundary points: each crossing then holds a few points, so no
    // column misses a side, and columns stay narrow next to the region.
    width = (max_x - min_x) / std::sqrt(static_cast<double>(boundary.size()));
    if (!(width > 0.0)) throw Error("the boundary points have no extent in x: no columns");
  }
  if (gap == 0.0) gap = 3.0 * width;
  result.width = width;
  result.gap = gap;

  std::vector<std::pair<std::int64_t, float>> cells;  // (column, y)
  cells.reserve(boundary.size());
  for (const auto& p : boundary) {
    cells.emplace_back(static_cast<std::int64_t>((p.x - min_x) / width), p.y);
  }
  std::sort(cells.begin(), cells.end());
  for (std::size_t begin = 0; begin < cells.size();) {
    std::size_t end = begin;
    while (end < cells.size() && cells[end].first == cells[begin].first) ++end;
    // Crossings of this column: (lowest y, highest y, mean y).
    struct Crossing {
      double low, high, sum;
      std::size_t count;
    };
    std::vector<Crossing> crossings;
    for (std::size_t k = begin; k < end; ++k) {
      const double y = cells[k].second;
      if (crossings.empty() || y - crossings.back().high > gap) {
        crossings.push_back({y, y, y, 1});
      } else {
        crossings.back().high = y;
        crossings.back().sum += y;
        ++crossings.back().count;
      }
    }
    std::vector<double> ys;
    if (crossings.size() % 2 == 1) {
      ++result.odd_columns;
      std::size_t tallest = 0;
      for (std::size_t k = 1; k < crossings.size(); ++k) {
        if (crossings[k].high - crossings[k].low >
            crossings[tallest].high - crossings[tallest].low) {
          tallest = k;
        }
      }
      for (std::size_t k = 0; k < crossings.size(); ++k) {
        if (k == tallest) {
          ys.push_back(crossings[k].low);
          ys.push_back(crossings[k].high);
        } else {
          ys.push_back(crossings[k].sum / crossings[k].count);
        }
      }
    } else {
      for (const Crossing& c : crossings) ys.push_back(c.sum / c.count);
    }
    for (std::size_t j = 0; j + 1 < ys.size(); j += 2) result.area += width * (ys[j + 1] - ys[j]);
    ++result.columns;
    begin = end;
  }
  return result;
}

}  // namespace mcws
