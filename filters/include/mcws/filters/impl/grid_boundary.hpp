#pragma once

#include <pcl/common/common.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/filters/grid_boundary.h"

namespace mcws {
namespace detail {

/// Cells per axis a packed key holds: 21 bits (0 .. 2^21 - 1), less the empty cells on either side.
constexpr double kMaxCellsPerAxis = kMaxBaselineCellsPerAxis;

/// Cell coordinates packed 21 bits per axis (x high, z low); coordinates start at 1 so that the
/// neighbours of every occupied cell have a key.
inline std::uint64_t packCell(std::uint64_t cx, std::uint64_t cy, std::uint64_t cz) {
  return (cx << 42) | (cy << 21) | cz;
}

/// Throws unless `cell_size` is positive and the extent of `points` spans at most
/// kMaxCellsPerAxis cells along every axis.
inline void checkCellSize(const std::string& filter_name, const char* what, double cell_size,
                          const pcl::PointCloud<pcl::PointXYZ>& points) {
  if (!(cell_size > 0.0) || !std::isfinite(cell_size)) {
    std::ostringstream msg;
    msg << filter_name << ": " << what << " " << cell_size << " must be a positive number";
    throw Error(msg.str());
  }
  if (points.empty()) return;
  pcl::PointXYZ min, max;
  pcl::getMinMax3D(points, min, max);
  const double extent = (max.getVector3fMap() - min.getVector3fMap()).maxCoeff();
  if (extent / cell_size > kMaxCellsPerAxis) {
    std::ostringstream msg;
    msg << filter_name << ": " << what << " " << cell_size << " is too small for the extent "
        << extent << " (at most " << kMaxCellsPerAxis << " cells per axis)";
    throw Error(msg.str());
  }
}

/// (cell key, point index) for every point of `projected`, sorted: the points of a cell are
/// consecutive, in input order. Keys are packCell() of 1 + the cell coordinates from the low
/// corner of the points' bounding box.
inline std::vector<std::pair<std::uint64_t, pcl::index_t>> keyedByCell(
    const pcl::PointCloud<pcl::PointXYZ>& projected, int dimensions, double cell) {
  const std::size_t n = projected.size();
  std::vector<std::pair<std::uint64_t, pcl::index_t>> keyed(n);
  if (n == 0) return keyed;
  pcl::PointXYZ min, max;
  pcl::getMinMax3D(projected, min, max);
  for (std::size_t k = 0; k < n; ++k) {
    std::uint64_t c[3] = {0, 0, 0};
    for (int a = 0; a < dimensions; ++a) {
      c[a] = 1 + static_cast<std::uint64_t>(
                     std::floor((static_cast<double>(projected[k].data[a]) - min.data[a]) / cell));
    }
    keyed[k] = {packCell(c[0], c[1], c[2]), static_cast<pcl::index_t>(k)};
  }
  std::sort(keyed.begin(), keyed.end());
  return keyed;
}

/// Offsets of the 8 (26) neighbours in packed keys; coordinates never leave [0, 2^21).
inline std::vector<std::int64_t> neighbourOffsets(int dimensions) {
  std::vector<std::int64_t> offsets;
  for (int dx = -1; dx <= 1; ++dx) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dz = (dimensions == 3 ? -1 : 0); dz <= (dimensions == 3 ? 1 : 0); ++dz) {
        if (dx != 0 || dy != 0 || dz != 0) {
          offsets.push_back(dx * (std::int64_t{1} << 42) + dy * (std::int64_t{1} << 21) + dz);
        }
      }
    }
  }
  return offsets;
}

/// Whether a neighbour of occupied cell `key` (by `offsets`) is not among the occupied `cells`
/// (sorted).
inline bool hasEmptyNeighbour(const std::vector<std::uint64_t>& cells, std::uint64_t key,
                              const std::vector<std::int64_t>& offsets) {
  return std::any_of(offsets.begin(), offsets.end(), [&](auto d) {
    return !std::binary_search(cells.begin(), cells.end(),
                               static_cast<std::uint64_t>(static_cast<std::int64_t>(key) + d));
  });
}

/// Of the points of one cell, entries [begin, end) of `keyed`: appends their mean in the input
/// to `cell_means` and returns the one nearest their mean in the method's plane (`projected`;
/// the lowest index wins a tie).
template <typename PointT>
pcl::index_t nearestToCellMean(const pcl::PointCloud<pcl::PointXYZ>& projected,
                               const pcl::PointCloud<PointT>& input, const pcl::Indices& source,
                               const std::vector<std::pair<std::uint64_t, pcl::index_t>>& keyed,
                               std::size_t begin, std::size_t end,
                               pcl::PointCloud<pcl::PointXYZ>& cell_means) {
  Eigen::Vector3d mean_projected = Eigen::Vector3d::Zero(), mean_input = Eigen::Vector3d::Zero();
  for (std::size_t k = begin; k < end; ++k) {
    const pcl::index_t i = keyed[k].second;
    mean_projected += projected[i].getVector3fMap().template cast<double>();
    mean_input += input[source[i]].getVector3fMap().template cast<double>();
  }
  const double count = static_cast<double>(end - begin);
  mean_projected /= count;
  mean_input /= count;
  cell_means.emplace_back(static_cast<float>(mean_input.x()), static_cast<float>(mean_input.y()),
                          static_cast<float>(mean_input.z()));
  pcl::index_t nearest = keyed[begin].second;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k = begin; k < end; ++k) {
    const pcl::index_t i = keyed[k].second;
    const double d2 =
        (projected[i].getVector3fMap().template cast<double>() - mean_projected).squaredNorm();
    if (d2 < best) {  // strict: the lowest index wins a tie
      best = d2;
      nearest = i;
    }
  }
  return nearest;
}

}  // namespace detail

template <typename PointT>
void GridBoundary<PointT>::applyFilter(pcl::Indices& indices) {
  const int dimensions = boundaryDimensions(plane_);
  pcl::PointCloud<pcl::PointXYZ> projected;
  pcl::Indices source;
  projectToPlane(*input_, *indices_, plane_, projected, source);
  const std::size_t n = projected.size();

  used_spacing_ = 0.0;
  double cell = cell_size_;
  if (automatic_) {
    used_spacing_ = meanSpacing(projected, dimensions);
    cell = baselineCellSize(n, used_spacing_, dimensions);
    // A cloud of identical points (or a single point) has no spacing: one cell holds it all.
    if (!(cell > 0.0)) cell = 1.0;
  }
  detail::checkCellSize(filter_name_, "cell size", cell, projected);
  used_cell_size_ = cell;

  // (cell key, point) sorted: the points of a cell are consecutive, in input order.
  const std::vector<std::pair<std::uint64_t, pcl::index_t>> keyed =
      detail::keyedByCell(projected, dimensions, cell);
  std::vector<std::uint64_t> cells;  // occupied cells, sorted
  std::vector<std::size_t> first;    // first entry of each cell in `keyed`
  for (std::size_t k = 0; k < n; ++k) {
    if (k == 0 || keyed[k].first != keyed[k - 1].first) {
      cells.push_back(keyed[k].first);
      first.push_back(k);
    }
  }
  first.push_back(n);
  occupied_cells_ = cells.size();

  const std::vector<std::int64_t> offsets = detail::neighbourOffsets(dimensions);
  std::vector<char> boundary(n, 0);
  cell_means_.clear();
  for (std::size_t c = 0; c < cells.size(); ++c) {
    if (!detail::hasEmptyNeighbour(cells, cells[c], offsets)) continue;
    boundary[detail::nearestToCellMean(projected, *input_, source, keyed, first[c], first[c + 1],
                                       cell_means_)] = 1;
  }

  splitByBoundary(
      *indices_, source, [&](std::size_t k) { return boundary[k] != 0; }, negative_,
      extract_removed_indices_, indices, *removed_indices_);
}

}  // namespace mcws
