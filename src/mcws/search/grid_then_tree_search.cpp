#include "mcws/search/grid_then_tree_search.h"

#include <algorithm>
#include <cmath>

namespace mcws {
namespace {

/// The grid's cell side as a fraction of the typical radius: the k nearest are then found within
/// one ring of cells and the radius neighbourhood within two. In 3-D coarser cells collect more
/// candidates but visit fewer rows of cells, and the k-nearest search hands the radius search the
/// candidates it needs: 0.85 measured fastest (1e6-point ball 1.61 -> 1.49 s, the de-icing arm's
/// 5e5 samples 0.95 -> 0.84 s against 0.55); in 2-D 0.55 still is (disk 0.55 s against 0.66).
double cellPerRadius(int dimensions) { return dimensions == 2 ? 0.55 : 0.85; }
/// How far a grid search may reach [cell sides]; beyond that (sparse regions) the tree searches.
/// A lonely point at the rim of a uniform cloud needs 4 or 5 cells in 2-D.
double maxReachInCells(int dimensions) { return dimensions == 2 ? 8.0 : 4.0; }
/// A k-nearest search first collects this many times the typical radius, so that the radius
/// searches after it mostly reuse its candidates (1e6-point ball: 1.05 collects 4 % fewer
/// instructions than 1.15, where the few points whose radius reaches farther collect again;
/// the disk is the same at either).
constexpr double kFirstReach = 1.05;
/// A cell holding this many times the expected number of points sends its points to the tree,
/// which copes better with density far above the mean.
constexpr double kCrowdedCell = 16.0;

}  // namespace

GridThenTreeSearch::GridThenTreeSearch(pcl::PointCloud<pcl::PointXYZ>&& positions,
                                       std::vector<pcl::index_t>& position_of, int dimensions,
                                       double typical_radius, double mean_spacing, bool use_grid,
                                       int threads)
    : positions_(std::make_shared<pcl::PointCloud<pcl::PointXYZ>>(std::move(positions))),
      grid_(*positions_, dimensions, cellPerRadius(dimensions) * typical_radius, threads),
      first_reach_(kFirstReach * typical_radius),
      max_reach_(maxReachInCells(dimensions) * grid_.cellSize()) {
  const std::size_t n = positions_->size();
  // Renumbered in cell order: point k of the new cloud is point order()[k] of the old one.
  auto sorted = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  sorted->resize(n);
  std::vector<pcl::index_t> rank(n);
  const std::vector<pcl::index_t>& order = grid_.order();
#pragma omp parallel num_threads(threads)
  {
#pragma omp for schedule(static)
    for (std::int64_t k = 0; k < static_cast<std::int64_t>(n); ++k) {
      (*sorted)[k] = (*positions_)[order[k]];
      rank[order[k]] = static_cast<pcl::index_t>(k);  // a permutation: every k its own place
    }
#pragma omp for schedule(static)
    for (std::int64_t k = 0; k < static_cast<std::int64_t>(position_of.size()); ++k) {
      position_of[k] = rank[position_of[k]];
    }
  }
  positions_ = sorted;
  grid_.renumberInCellOrder();
  const double expected = mean_spacing > 0.0 ? std::pow(grid_.cellSize() / mean_spacing, dimensions)
                                             : static_cast<double>(n);
  const auto crowded = static_cast<std::size_t>(kCrowdedCell * std::max(1.0, expected));
  // In cell order, the points of cell c are those in its slots.
  served_.assign(n, use_grid ? 1 : 0);
  const std::vector<std::uint32_t>& starts = grid_.cellStarts();
  for (std::size_t c = 0; use_grid && c + 1 < starts.size(); ++c) {
    if (starts[c + 1] - starts[c] > crowded) {
      std::fill(served_.begin() + starts[c], served_.begin() + starts[c + 1], 0);
    }
  }
}

const pcl::KdTreeFLANN<pcl::PointXYZ>& GridThenTreeSearch::tree() {
  if (!tree_) {
    tree_ = std::make_unique<pcl::KdTreeFLANN<pcl::PointXYZ>>(false);  // unsorted results
    tree_->setInputCloud(positions_);
  }
  return *tree_;
}

}  // namespace mcws
