#pragma once
/// \file
/// \brief The orthant filter's search of a whole cloud: a CellGrid for most points, a
/// pcl::KdTreeFLANN for the rest, each point's work on all threads.

#include <omp.h>
#include <pcl/kdtree/kdtree_flann.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "mcws/core/first_error.h"
#include "mcws/search/cell_grid.h"
#include "mcws/search/kdtree_search.h"

namespace mcws {

/// \brief Runs a per-point task over a cloud with exact neighbour searches, fast on the nearly
/// uniform clouds of Monte Carlo sampling.
///
/// The cloud is bucketed into a CellGrid whose cells are about half the typical search radius
/// wide, and renumbered in cell order so that neighbours lie close in memory. forEachPoint() runs
/// the task with a CellGridSearch; the points it cannot serve (cells crowded far above the mean
/// density, searches that reach beyond 8 cells in 2-D or 4 in 3-D, or every point when the grid
/// is off) are then run again with a KdTreeSearch, on a tree built at the first need. Both
/// searches give the same answers (NeighbourSearch), so the result depends neither on which
/// search served a point nor on the thread count.
class GridThenTreeSearch {
 public:
  /// \param positions the cloud (z = 0 in a plane), taken over and renumbered in cell order.
  /// \param position_of indices into `positions`, rewritten to the new numbering.
  /// \param typical_radius the largest search radius most points will ask for [length unit].
  /// \param mean_spacing the cloud's mean spacing [length unit] (0: unknown), which tells what
  ///   a crowded cell is.
  /// \param use_grid false: every point is searched in the tree (the reference).
  /// \param threads threads of the grid's construction and the renumbering (the result does not
  ///   depend on them).
  GridThenTreeSearch(pcl::PointCloud<pcl::PointXYZ>&& positions,
                     std::vector<pcl::index_t>& position_of, int dimensions, double typical_radius,
                     double mean_spacing, bool use_grid, int threads = 1);

  /// \brief The cloud, in cell order.
  const pcl::PointCloud<pcl::PointXYZ>& positions() const { return *positions_; }
  std::size_t size() const { return positions_->size(); }

  /// \brief A grid search for one thread; it declines what the grid cannot serve.
  CellGridSearch gridSearch() const {
    return CellGridSearch(grid_, *positions_, first_reach_, max_reach_);
  }

  /// \brief Runs `task(search, i, scratch)` for every i in `points` on `threads` threads, each
  /// with its own `Scratch`. The task returns false when `search` declined one of its queries;
  /// such points, and those the grid does not serve, run again with the tree. With more than one
  /// thread a task must write only what belongs to its point i; a task that writes elsewhere
  /// runs on one thread.
  template <typename Scratch, typename Task>
  void forEachPoint(const std::vector<pcl::index_t>& points, int threads, Task task) {
    std::vector<char> declined(points.size(), 0);
    FirstError error;  // what a task throws leaves the parallel regions through it
#pragma omp parallel num_threads(threads)
    {
      CellGridSearch search = gridSearch();
      Scratch scratch;
#pragma omp for schedule(dynamic, 1024)
      for (std::int64_t k = 0; k < static_cast<std::int64_t>(points.size()); ++k) {
        error.run(k, [&] {
          const pcl::index_t i = points[k];
          declined[k] = !servedByGrid(i) || !task(search, i, scratch);
        });
      }
    }
    error.rethrow();
    std::vector<pcl::index_t> rest;
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (declined[k]) rest.push_back(points[k]);
    }
    if (rest.empty()) return;
    const pcl::KdTreeFLANN<pcl::PointXYZ>& kdtree = tree();
#pragma omp parallel num_threads(threads)
    {
      KdTreeSearch search(kdtree, *positions_);
      Scratch scratch;
#pragma omp for schedule(dynamic, 256)
      for (std::int64_t k = 0; k < static_cast<std::int64_t>(rest.size()); ++k) {
        error.run(k, [&] { task(search, rest[k], scratch); });
      }
    }
    error.rethrow();
  }

 private:
  bool servedByGrid(pcl::index_t i) const { return served_[i] != 0; }
  /// The tree, built on the first call (not thread-safe: call it outside parallel regions).
  const pcl::KdTreeFLANN<pcl::PointXYZ>& tree();

  std::shared_ptr<pcl::PointCloud<pcl::PointXYZ>> positions_;
  CellGrid grid_;
  double first_reach_, max_reach_;
  /// Per point: the grid serves it (the grid is on and its cell holds at most a crowded cell's
  /// population).
  std::vector<char> served_;
  std::unique_ptr<pcl::KdTreeFLANN<pcl::PointXYZ>> tree_;
};

}  // namespace mcws
