#include "mcws/workspace/nearest_neighbours.h"

#include <omp.h>

#include <nanoflann.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "mcws/core/error.h"
#include "mcws/core/first_error.h"
#include "mcws/search/cell_grid.h"
#include "mcws/workspace/detail/cancel_pacing.h"

namespace mcws {
namespace {

/// nanoflann's view of a PCL cloud.
struct CloudAdaptor {
  const pcl::PointCloud<pcl::PointXYZ>& cloud;
  std::size_t kdtree_get_point_count() const { return cloud.size(); }
  float kdtree_get_pt(std::size_t i, std::size_t axis) const { return cloud[i].data[axis]; }
  template <typename Box>
  bool kdtree_get_bbox(Box& /*box*/) const {
    return false;  // let the tree compute it
  }
};

/// Leaf size: 20 points measured fastest for k = 8 on 10^6 points (10 builds a deeper tree for
/// 10 % more time; 40 scans longer leaves).
constexpr std::size_t kLeafSize = 20;

/// The kd-tree search, for every point or, given `only`, for those points (the result in their
/// order).
template <int D>
std::vector<float> kthNeighbour(const pcl::PointCloud<pcl::PointXYZ>& cloud, int k, int threads,
                                const CancelCheck& cancel_check,
                                const std::vector<pcl::index_t>* only = nullptr) {
  using Tree =
      nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, CloudAdaptor>,
                                          CloudAdaptor, D, std::uint32_t>;
  const CloudAdaptor adaptor{cloud};
  const Tree tree(D, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(kLeafSize));  // builds it
  const std::size_t wanted = std::min<std::size_t>(static_cast<std::size_t>(k) + 1, cloud.size());
  const std::size_t queries = only ? only->size() : cloud.size();
  std::vector<float> result(queries, 0.0f);
  FirstError error;  // what cancel_check throws leaves the parallel region through it
#pragma omp parallel num_threads(threads)
  {
    std::vector<std::uint32_t> indices(wanted);
    std::vector<float> d2(wanted);
    CancelPacer pacer = detail::callingThreadPacer(cancel_check, detail::kPointCancelStride);
#pragma omp for schedule(static)
    for (std::int64_t j = 0; j < static_cast<std::int64_t>(queries); ++j) {
      error.run(j, [&] {
        pacer.step();
        // Every point in the tree's leaf order, or the given ones in theirs.
        const std::size_t at = only ? static_cast<std::size_t>(j) : tree.vAcc[j];
        const std::size_t i = only ? static_cast<std::size_t>((*only)[j]) : at;
        nanoflann::KNNResultSet<float, std::uint32_t> found(wanted);
        found.init(indices.data(), d2.data());
        tree.findNeighbors(found, cloud[i].data, nanoflann::SearchParams());
        // The point itself is among the k + 1 found (at distance 0); the largest is the k-th.
        result[at] = found.size() == 0 ? 0.0f : d2[found.size() - 1];
      });
    }
  }
  error.rethrow();
  return result;
}

/// Mean number of points that share a point's cell past which the grid is left for the kd-tree
/// (a uniform cloud: 1 to 3; a cloud crowded into a small part of its bounding box: more).
constexpr double kCrowdedCells = 16.0;

/// The grid search (CellGrid, the boundary filter's): cells of about the expected distance to the
/// `wanted`-th point of a cloud spread evenly over its bounding box, each query collecting the
/// cells that meet a ball of that radius, twice as wide while too few points lie in it, up to
/// four cells (the kd-tree answers the few that need more). Queries run in cell order, so
/// neighbouring queries read the same cells. Same float distances as the kd-tree and the brute
/// force. \return false (and leaves `result` alone) when the cloud is too crowded for the grid.
template <int D>
bool gridKth(const pcl::PointCloud<pcl::PointXYZ>& cloud, std::size_t wanted, int threads,
             const CancelCheck& cancel_check, std::vector<float>& result) {
  const std::size_t n = cloud.size();
  Eigen::Array3d lo = Eigen::Array3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& p : cloud) {
    lo = lo.min(p.getArray3fMap().cast<double>());
    hi = hi.max(p.getArray3fMap().cast<double>());
  }
  const double volume = (hi - lo).head<D>().prod();
  if (!(volume > 0.0) || !std::isfinite(volume)) return false;
  // The radius of a ball (disk) that holds `wanted` points at the box's mean density.
  const double unit = D == 2 ? M_PI : 4.0 * M_PI / 3.0;
  const double reach = std::pow(volume * static_cast<double>(wanted) / (unit * n), 1.0 / D);
  const CellGrid grid(cloud, D, reach);
  double crowding = 0.0;
  for (const auto& p : cloud) crowding += static_cast<double>(grid.population(p));
  if (crowding / static_cast<double>(n) > kCrowdedCells) return false;
  result.assign(n, 0.0f);
  std::vector<pcl::index_t> declined;
  FirstError error;  // running out of memory leaves the parallel region through it
#pragma omp parallel num_threads(threads)
  {
    CellGridSearch search(grid, cloud, reach, 4.0 * grid.cellSize());
    std::vector<pcl::index_t> own;
    CancelPacer pacer = detail::callingThreadPacer(cancel_check, detail::kPointCancelStride);
#pragma omp for schedule(dynamic, 4096)
    for (std::int64_t k = 0; k < static_cast<std::int64_t>(n); ++k) {
      error.run(k, [&] {
        pacer.step();
        const pcl::index_t i = grid.order()[k];
        const std::optional<float> d2 = search.kthDistance2(i, static_cast<int>(wanted), nullptr);
        if (d2) {
          result[i] = *d2;
        } else {
          own.push_back(i);
        }
      });
    }
#pragma omp critical
    error.run(n, [&] { declined.insert(declined.end(), own.begin(), own.end()); });
  }
  error.rethrow();
  if (!declined.empty()) {
    const std::vector<float> tree =
        kthNeighbour<D>(cloud, static_cast<int>(wanted) - 1, threads, cancel_check, &declined);
    for (std::size_t j = 0; j < declined.size(); ++j) result[declined[j]] = tree[j];
  }
  return true;
}

}  // namespace

std::vector<float> kthNeighbourSquaredDistance(const pcl::PointCloud<pcl::PointXYZ>& cloud,
                                               int dimensions, int k, int threads,
                                               const CancelCheck& cancel_check) {
  if (dimensions != 2 && dimensions != 3) {
    throw Error("dimensions must be 2 or 3, got " + std::to_string(dimensions));
  }
  if (k < 1) throw Error("the neighbour rank k must be at least 1, got " + std::to_string(k));
  if (cloud.empty()) return {};
  if (threads <= 0) threads = omp_get_max_threads();
  const std::size_t wanted = std::min<std::size_t>(static_cast<std::size_t>(k) + 1, cloud.size());
  std::vector<float> result;
  if (cloud.size() >= 2 &&
      (dimensions == 2 ? gridKth<2>(cloud, wanted, threads, cancel_check, result)
                       : gridKth<3>(cloud, wanted, threads, cancel_check, result))) {
    return result;
  }
  return dimensions == 2 ? kthNeighbour<2>(cloud, k, threads, cancel_check)
                         : kthNeighbour<3>(cloud, k, threads, cancel_check);
}

}  // namespace mcws
