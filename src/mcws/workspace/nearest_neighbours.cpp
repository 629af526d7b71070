#include "mcws/workspace/nearest_neighbours.h"

#include <omp.h>

#include <nanoflann.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "mcws/core/error.h"
#include "mcws/core/first_error.h"
#include "mcws/search/cell_grid.h"
#include "mcws/search/cell_kernels.h"
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

/// The grid search (CellGrid, the boundary filter's) for the points `only`: cells of about the
/// expected distance to the `wanted`-th point of a cloud spread evenly over its bounding box
/// (`reach`), each query collecting the cells that meet a ball of that radius, twice as wide while
/// too few points lie in it, up to four cells (the kd-tree answers the few that need more). Same
/// float distances as the kd-tree and the brute force.
template <int D>
void gridKthOf(const pcl::PointCloud<pcl::PointXYZ>& cloud, std::size_t wanted, double reach,
               const std::vector<pcl::index_t>& only, int threads, const CancelCheck& cancel_check,
               std::vector<float>& result) {
  const CellGrid grid(cloud, D, reach);
  std::vector<pcl::index_t> declined;
  FirstError error;  // running out of memory leaves the parallel region through it
#pragma omp parallel num_threads(threads)
  {
    CellGridSearch search(grid, cloud, reach, 4.0 * grid.cellSize());
    std::vector<pcl::index_t> own;
    CancelPacer pacer = detail::callingThreadPacer(cancel_check, detail::kPointCancelStride);
#pragma omp for schedule(dynamic, 4096)
    for (std::int64_t k = 0; k < static_cast<std::int64_t>(only.size()); ++k) {
      error.run(k, [&] {
        pacer.step();
        const pcl::index_t i = only[k];
        const std::optional<float> d2 = search.kthDistance2(i, static_cast<int>(wanted), nullptr);
        if (d2) {
          result[i] = *d2;
        } else {
          own.push_back(i);
        }
      });
    }
#pragma omp critical
    error.run(only.size(), [&] { declined.insert(declined.end(), own.begin(), own.end()); });
  }
  error.rethrow();
  if (!declined.empty()) {
    std::sort(declined.begin(), declined.end());  // the same tree queries for any thread count
    const std::vector<float> tree =
        kthNeighbour<D>(cloud, static_cast<int>(wanted) - 1, threads, cancel_check, &declined);
    for (std::size_t j = 0; j < declined.size(); ++j) result[declined[j]] = tree[j];
  }
}

/// The candidates first selected from: those below this many times the previous answer (squared
/// distances; 1.4 times the distance: about 25 points of a uniform cloud for k = 8).
constexpr float kNearHint = 2.0f;
/// Of those, the ones ranked first: below this many times the previous answer (1.14 times the
/// distance: about 13 points of a uniform cloud for k = 8).
constexpr float kFirstHint = 1.3f;

/// The search most queries take: the points sorted into cells of the grid search's geometry
/// (CellGrid's, edge `reach`), each cell's 3^D block of cells gathered once for the queries in
/// it, then for the queries that block does not settle their 5^D block. A block settles a query
/// when `wanted` of its points lie closer than the nearest cell outside it may (the squared
/// distances, as CellGrid computes them, below that bound less a relative 1e-5 for their
/// rounding, as CellGridSearch bounds its own): the `wanted`-th smallest of them is then that of
/// the whole cloud, exact. Whatever neither block settles (clouds far from uniform) goes to the
/// grid search.
template <int D>
class BlockSearch {
 public:
  BlockSearch(const pcl::PointCloud<pcl::PointXYZ>& cloud, double reach) {
    const std::size_t n = cloud.size();
    Eigen::Vector3d min = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
    Eigen::Vector3d max = -min;
    for (const auto& p : cloud) {
      min = min.cwiseMin(p.getVector3fMap().cast<double>());
      max = max.cwiseMax(p.getVector3fMap().cast<double>());
    }
    // CellGrid's sizing, so that a block holds the cells the grid search would visit.
    const Eigen::Vector3d extent = max - min;
    cell_ = mcws::cellGridEdge(extent, D, reach, n);
    std::int64_t total = 1;
    for (int a = 0; a < D; ++a) {
      origin_[a] = min[a];
      counts_[a] = static_cast<std::int64_t>(std::floor(extent[a] / cell_)) + 1;
      total *= counts_[a];
    }
    // Counting sort of the points by cell.
    std::vector<std::uint32_t> cell_of(n);
    start_.assign(static_cast<std::size_t>(total) + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
      std::int64_t c = 0;
      for (int a = D - 1; a >= 0; --a) c = c * counts_[a] + cellAlong(cloud[i].data[a], a);
      cell_of[i] = static_cast<std::uint32_t>(c);
      ++start_[c + 1];
    }
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    // Three arrays (z 0 in 2-D, where it adds 0 - 0 to the distances), padded (zeros) for
    // rowDistances(), which may read past the last row.
    for (auto& v : xyz_) v.assign(n + detail::kKernelSlack, 0.0f);
    index_.resize(n);
    std::vector<std::uint32_t> next(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t slot = next[cell_of[i]]++;
      for (int a = 0; a < D; ++a) xyz_[a][slot] = cloud[i].data[a];
      index_[slot] = static_cast<std::uint32_t>(i);
    }
  }

  std::size_t cells() const { return start_.size() - 1; }
  /// The mean, over the points, of the number of points in their cell.
  double crowding() const {
    double sum = 0.0;
    for (std::size_t c = 0; c + 1 < start_.size(); ++c) {
      const double m = start_[c + 1] - start_[c];
      sum += m * m;
    }
    return sum / static_cast<double>(index_.size());
  }

  /// One thread's working memory: a block's rows of cells (runs of points in the grid's arrays)
  /// and rowDistances()'s and valuesBelow()'s outputs.
  struct Scratch {
    std::vector<detail::RowSpan> rows;
    std::size_t size{0};  ///< the block's points
    std::vector<float> d2, near_d2, smallest;
    std::vector<std::uint32_t> slot, near_slot;
    float hint{std::numeric_limits<float>::infinity()};  ///< the last answer
  };

  /// Settles the queries of cell `c` that its blocks settle (result by point index); appends the
  /// others to `declined`.
  void settleCell(std::size_t c, std::size_t wanted, Scratch& block, Scratch& wide,
                  std::vector<float>& result, std::vector<pcl::index_t>& declined) const {
    if (start_[c] == start_[c + 1]) return;
    std::array<std::int64_t, 3> at{0, 0, 0};
    std::size_t rest = c;
    for (int a = 0; a < D; ++a) {
      at[a] = static_cast<std::int64_t>(rest % static_cast<std::size_t>(counts_[a]));
      rest /= static_cast<std::size_t>(counts_[a]);
    }
    gather(at, 1, block);
    bool wide_gathered = false;
    for (std::uint32_t slot = start_[c]; slot < start_[c + 1]; ++slot) {
      std::optional<float> d2 = settle(slot, at, 1, wanted, block);
      if (!d2) {
        if (!wide_gathered) gather(at, 2, wide);
        wide_gathered = true;
        d2 = settle(slot, at, 2, wanted, wide);
      }
      if (d2) {
        result[index_[slot]] = *d2;
      } else {
        declined.push_back(static_cast<pcl::index_t>(index_[slot]));
      }
    }
  }

 private:
  std::int64_t cellAlong(float v, int a) const {
    const double c = std::floor((static_cast<double>(v) - origin_[a]) / cell_);
    return std::clamp<std::int64_t>(static_cast<std::int64_t>(std::max(c, -1.0)), 0,
                                    counts_[a] - 1);
  }

  /// The rows of the cells within `half` cells of cell `at` along every axis (each a run of
  /// points in the grid's arrays), and room for the kernels' outputs.
  void gather(const std::array<std::int64_t, 3>& at, std::int64_t half, Scratch& out) const {
    std::array<std::int64_t, 3> lo{0, 0, 0}, hi{0, 0, 0};
    for (int a = 0; a < D; ++a) {
      lo[a] = std::max<std::int64_t>(at[a] - half, 0);
      hi[a] = std::min<std::int64_t>(at[a] + half, counts_[a] - 1);
    }
    out.rows.clear();
    out.size = 0;
    for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y) {
        const std::int64_t row = (z * counts_[1] + y) * counts_[0];
        const detail::RowSpan span{start_[row + lo[0]], start_[row + hi[0] + 1]};
        if (span.begin == span.end) continue;
        out.rows.push_back(span);
        out.size += span.end - span.begin;
      }
    }
    // Room for the points and the entries the kernels may write past them.
    if (out.d2.size() < out.size + detail::kKernelSlack) {
      const std::size_t room = 2 * (out.size + detail::kKernelSlack);
      for (auto* v : {&out.d2, &out.near_d2, &out.smallest}) v->resize(room);
      for (auto* v : {&out.slot, &out.near_slot}) v->resize(room);
    }
  }

  /// The `wanted`-th smallest squared distance from the point in `slot` (in cell `at`) when the
  /// block of `half` cells around `at` (gathered in `block`) settles it.
  std::optional<float> settle(std::uint32_t slot, const std::array<std::int64_t, 3>& at,
                              std::int64_t half, std::size_t wanted, Scratch& block) const {
    // How near a point outside the block may be: the distance to the nearest face of the block
    // beyond which cells lie, less a little for the rounding of the points' cells.
    double gap = std::numeric_limits<double>::infinity();
    for (int a = 0; a < D; ++a) {
      const double v = xyz_[a][slot];
      if (at[a] - half > 0) gap = std::min(gap, v - (origin_[a] + (at[a] - half) * cell_));
      if (at[a] + half < counts_[a] - 1) {
        gap = std::min(gap, origin_[a] + (at[a] + half + 1) * cell_ - v);
      }
    }
    gap -= 1e-9 * cell_;
    if (!(gap > 0.0)) return std::nullopt;
    const float limit = std::isinf(gap)
                            ? std::numeric_limits<float>::infinity()
                            : static_cast<float>(std::min(gap * gap * (1.0 - 1e-5), 1e38));
    // The wanted-th smallest below the limit. First below a few times the previous query's
    // answer (a neighbour's: a hint only, the answer does not depend on it), which far fewer
    // candidates pass: if `wanted` of them do, the wanted-th smallest of those is that of all
    // below the limit. The distances as CellGrid computes them (the search's kernels).
    const float near = std::min(limit, kNearHint * block.hint);
    const auto count = static_cast<int>(wanted);
    std::size_t m = detail::rowDistances(
        xyz_[0].data(), xyz_[1].data(), xyz_[2].data(), block.rows.data(), block.rows.size(),
        xyz_[0][slot], xyz_[1][slot], xyz_[2][slot], near, block.d2.data(), block.slot.data(),
        block.near_d2.data(), block.near_slot.data());
    float* values = block.near_d2.data();
    // Of those, the ones below kFirstHint times the previous answer, when `wanted` are: a shorter
    // list to rank, the same wanted-th smallest.
    const float first = std::min(limit, kFirstHint * block.hint);
    if (m >= wanted && first < near) {
      const std::size_t f = detail::valuesBelow(values, m, first, block.smallest.data());
      if (f >= wanted) {
        values = block.smallest.data();
        m = f;
      }
    }
    if (m < wanted && near < limit) {
      m = detail::valuesBelow(block.d2.data(), block.size, limit, block.smallest.data());
      values = block.smallest.data();
    }
    if (m < wanted) return std::nullopt;
    block.hint = detail::kthSmallest(values, m, count);
    return block.hint;
  }

  double cell_{0.0};
  std::array<double, 3> origin_{0.0, 0.0, 0.0};
  std::array<std::int64_t, 3> counts_{1, 1, 1};
  std::vector<std::uint32_t> start_;       // points of cell c: [start_[c], start_[c + 1])
  std::array<std::vector<float>, 3> xyz_;  // x, y, z (0 in 2-D) in cell order
  std::vector<std::uint32_t> index_;       // cloud index in cell order
};

/// The k-th neighbour distances on a grid: the block search (BlockSearch) for most points, the
/// grid search (gridKthOf()) for the others. \return false (and leaves `result` alone) when the
/// cloud is too crowded for a grid (its points share cells with kCrowdedCells others on average).
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
  const BlockSearch<D> blocks(cloud, reach);
  if (blocks.crowding() > kCrowdedCells) return false;
  result.assign(n, 0.0f);
  std::vector<pcl::index_t> declined;
  FirstError error;  // running out of memory or cancelling leaves the parallel region through it
#pragma omp parallel num_threads(threads)
  {
    typename BlockSearch<D>::Scratch block, wide;
    std::vector<pcl::index_t> own;
    CancelPacer pacer = detail::callingThreadPacer(cancel_check, detail::kPointCancelStride / 4);
#pragma omp for schedule(dynamic, 1024)
    for (std::int64_t c = 0; c < static_cast<std::int64_t>(blocks.cells()); ++c) {
      error.run(c, [&] {
        pacer.step();
        blocks.settleCell(static_cast<std::size_t>(c), wanted, block, wide, result, own);
      });
    }
#pragma omp critical
    error.run(blocks.cells(), [&] { declined.insert(declined.end(), own.begin(), own.end()); });
  }
  error.rethrow();
  if (!declined.empty()) {
    std::sort(declined.begin(), declined.end());
    gridKthOf<D>(cloud, wanted, reach, declined, threads, cancel_check, result);
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
