#pragma once
/// \file
/// \brief A uniform grid of cells over a cloud, for exact radius and k-nearest searches that
/// return what pcl::KdTreeFLANN returns, faster on the nearly uniform clouds of Monte Carlo
/// sampling.

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstdint>
#include <limits>
#include <vector>

#include "mcws/search/cell_kernels.h"
#include "mcws/search/neighbour_search.h"

namespace mcws {

/// \brief Points bucketed into square (2-D) or cubic (3-D) cells of side `cell`, stored cell by
/// cell.
///
/// Searches are exact, with the squared distances pcl::KdTreeFLANN computes (float,
/// (x - x')^2 + (y - y')^2 + (z - z')^2 summed in that order) and its strict comparison
/// d^2 < float(r * r), so a radius search returns the same set as KdTreeFLANN::radiusSearch and
/// the k-th nearest distance equals the largest of nearestKSearch's. Cells are visited only where
/// they meet the search ball. CellGridSearch bounds how far a search may reach; one that would
/// need more is declined, and the caller falls back to the tree (GridThenTreeSearch).
/// \brief The cell edge CellGrid uses for `points` points spanning `extent` (in their first
/// `dimensions` axes) when asked for `cell`: `cell`, widened until there are at most about 4 cells
/// a point, so that a sparse bounding box (outliers) cannot exhaust memory. Lengths in the
/// cloud's unit; `cell` must be positive and finite.
double cellGridEdge(const Eigen::Vector3d& extent, int dimensions, double cell, std::size_t points);

class CellGrid {
 public:
  /// \brief Buckets `cloud` (finite points; z ignored when `dimensions` == 2) into cells of side
  /// `cell` [length unit], enlarged if the grid would have more than 4 cells per point; the
  /// points' box and cells found on `threads` threads (the grid is the same for any number).
  CellGrid(const pcl::PointCloud<pcl::PointXYZ>& cloud, int dimensions, double cell,
           int threads = 1);

  /// \brief The cell side actually used [length unit].
  double cellSize() const { return cell_; }
  /// \brief Point indices in cell order (rows of cells, x fastest): a spatially sorted order.
  const std::vector<pcl::index_t>& order() const { return index_; }
  /// \brief After the cloud was reordered into order() (point k of the new cloud is point
  /// order()[k] of the old one), renumbers the grid to match without rebuilding it.
  void renumberInCellOrder() {
    for (std::size_t k = 0; k < index_.size(); ++k) index_[k] = static_cast<pcl::index_t>(k);
    slot_is_index_ = true;
  }
  /// \brief The cells' runs of slots: cell c holds slots [cellStarts()[c], cellStarts()[c + 1]).
  const std::vector<std::uint32_t>& cellStarts() const { return start_; }
  /// \brief Number of points in the cell holding `p`.
  std::size_t population(const pcl::PointXYZ& p) const;

  /// \brief Candidates of a search: slots (positions in cell order) and squared distances, in
  /// parallel arrays of which the first `size` entries are in use (the arrays only grow); and of
  /// them, in the same order, the near ones, those with d^2 < near_bound (first near_size
  /// entries of near_d2 and near_slot).
  struct Candidates {
    std::vector<std::uint32_t> slot;
    std::vector<float> d2;
    std::size_t size{0};
    std::vector<float> near_d2;
    std::vector<std::uint32_t> near_slot;
    std::size_t near_size{0};
    float near_bound{0.0f};
    std::vector<detail::RowSpan> rows;  ///< the rows of cells collected (scratch; only grows)
  };

  /// \brief Every point of the cells that meet the ball of radius `reach` [length unit] around p
  /// (so at least every point within `reach`), with its squared distance; and the near ones, with
  /// d^2 < `near_bound` [length unit^2].
  void collect(const pcl::PointXYZ& p, double reach, float near_bound, Candidates& out) const;

  /// \brief The point in `slot` as a neighbour of p (its squared distance from p is `d2`).
  Neighbour neighbour(std::uint32_t slot, const pcl::PointXYZ& p, float d2) const {
    // q - p is exactly -(p - q): these are the offsets whose squares collect() summed.
    const float pz = dimensions_ == 3 ? p.z : 0.0f;
    // (after renumberInCellOrder() the index is the slot: one load fewer)
    const auto index = slot_is_index_ ? static_cast<pcl::index_t>(slot) : index_[slot];
    return {x_[slot] - p.x, y_[slot] - p.y, z_[slot] - pz, d2, index};
  }

 private:
  std::int64_t cellOf(const pcl::PointXYZ& p, int axis) const;

  int dimensions_;
  double cell_;
  double inverse_cell_{1.0};  ///< 1 / cell_
  Eigen::Vector3d origin_;
  std::int64_t counts_[3]{1, 1, 1};
  std::vector<std::uint32_t> start_;  // points of cell c: [start_[c], start_[c + 1])
  std::vector<float> x_, y_, z_;      // coordinates in cell order
  std::vector<pcl::index_t> index_;   // cloud index in cell order
  bool slot_is_index_{false};         // index_[slot] == slot for every slot
};

/// \brief The NeighbourSearch of one thread on a CellGrid. It remembers the candidates it
/// collected for the last query point, so that a radius search after a k-nearest search on the
/// same point costs no second pass over the cells. It declines a search that would reach beyond
/// `max_reach`.
class CellGridSearch : public NeighbourSearch {
 public:
  /// \param first_reach the radius a k-nearest search first collects [length unit]: about the
  ///   radius searches expected next, so that they reuse its candidates.
  /// \param max_reach the farthest any search may collect [length unit].
  CellGridSearch(const CellGrid& grid, const pcl::PointCloud<pcl::PointXYZ>& cloud,
                 double first_reach, double max_reach)
      : grid_(grid), cloud_(cloud), first_reach_(first_reach), max_reach_(max_reach) {}

  std::optional<float> kthDistance2(pcl::index_t i, int count,
                                    std::vector<Neighbour>* nearest) override;
  bool radius(pcl::index_t i, double radius, std::vector<Neighbour>& found) override;
  /// \brief Proves r_i longer than one cell side when fewer than `count` points lie within
  /// cell / scale of i; the subset is then the points within one cell side (float arithmetic as
  /// in kthDistance2).
  bool adaptiveSubset(pcl::index_t i, int count, float scale,
                      std::vector<Neighbour>& subset) override;

 private:
  /// Candidates of point i up to `reach` (false beyond max_reach_), kept for the next search,
  /// with their near ones below at least `near_bound`.
  bool gather(pcl::index_t i, double reach, float near_bound);
  /// The candidates with d^2 < `limit`, as neighbours of point i, into `out`; returns how many
  /// candidates have d^2 < `count_below`. Both bounds at most the near bound.
  std::size_t within(pcl::index_t i, float limit, std::vector<Neighbour>& out,
                     float count_below = 0.0f);
  /// The `count` nearest of point i, whose count-th squared distance is d2, into `out`: those
  /// closer, then ties, in the candidates' order.
  void nearestOf(pcl::index_t i, int count, float d2, std::vector<Neighbour>& out);

  const CellGrid& grid_;
  const pcl::PointCloud<pcl::PointXYZ>& cloud_;
  double first_reach_, max_reach_;
  pcl::index_t point_{-1};
  double reach_{0.0};
  CellGrid::Candidates candidates_;
  std::vector<float> smallest_;
  std::vector<std::uint32_t> kept_;
  float hint_{std::numeric_limits<float>::infinity()};
};

}  // namespace mcws
