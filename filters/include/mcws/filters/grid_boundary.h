#pragma once
/// \file
/// \brief Boundary points by the grid method of Yin, Wang & Yu 2010 (section 4.1), a baseline for
/// OrthantBoundary.

#include <pcl/filters/filter_indices.h>

#include <cstddef>

#include "mcws/filters/boundary_geometry.h"
#include "mcws/points/point_types.h"

namespace mcws {

/// \brief Most cells (grid) or columns (extremum) the baselines lay along an axis: a cell's
/// coordinate is packed in 21 bits, less the empty cells on either side. A fixed cell size below
/// extent / this is an error.
constexpr double kMaxBaselineCellsPerAxis = 2097148.0;

/// \brief Keeps one point per boundary cell of a grid laid over the cloud (negative mode: every
/// other point).
///
/// **Rule (Yin, Wang & Yu 2010, section 4.1).** The plane (or, for BoundaryPlane::k3D, space) is
/// cut into square (cubic) cells of side dL, the first cell starting at the smallest coordinate of
/// the finite input points. A cell is occupied when it holds a point. An occupied cell is a
/// boundary cell when at least one of its 8 neighbours (26 in 3-D) is empty; cells outside the
/// points' extent are empty.
///
/// **The boundary point.** The paper represents a boundary cell by the mean of its points. A
/// FilterIndices filter returns input indices, so the filter keeps the cell's point nearest to
/// that mean (in the method's plane; ties go to the lowest input index). cellMeans() gives the
/// paper's means themselves, as a cloud, after filter().
///
/// **Cell size.** setCellSize(dL) fixes it [length unit]. By default (setAutoCellSize()) dL is
/// chosen from the number of points n and the mean spacing h (meanSpacing(), from the cloud's
/// extent): a cell holding m points on average is empty with probability e^-m, and n / m cells
/// make about (n / m) e^-m falsely empty interior cells, each one surrounded by false boundary
/// cells. m = ln(2 n / m) (solved by iteration) leaves half a false empty cell per cloud, and
/// dL = h m^(1/d): 2.7 h for n = 5000, 3.5 h for 10^6 (2-D).
///
/// **Special points.** Non-finite points are ignored and removed in both modes (they are in
/// getRemovedIndices()). An isolated point is its cell's only point and a boundary point.
/// Copies of a point are counted in its cell like any other point.
///
/// \code
/// mcws::GridBoundary<pcl::PointXYZ> grid;
/// grid.setInputCloud(cloud);
/// grid.setPlane(mcws::BoundaryPlane::kXY);
/// grid.setCellSize(0.02);
/// pcl::Indices rim;
/// grid.filter(rim);                                      // one point per boundary cell
/// const pcl::PointCloud<pcl::PointXYZ>& means = grid.cellMeans();  // the paper's points
/// \endcode
template <typename PointT>
class GridBoundary : public pcl::FilterIndices<PointT> {
 public:
  using Ptr = std::shared_ptr<GridBoundary<PointT>>;
  using ConstPtr = std::shared_ptr<const GridBoundary<PointT>>;

  explicit GridBoundary(bool extract_removed_indices = false)
      : pcl::FilterIndices<PointT>(extract_removed_indices) {
    filter_name_ = "GridBoundary";
  }

  /// \brief A coordinate plane (square cells, 8 neighbours) or k3D (cubes, 26 neighbours).
  void setPlane(BoundaryPlane plane) { plane_ = plane; }
  BoundaryPlane getPlane() const { return plane_; }

  /// \brief Fixed cell side dL [length unit], > 0.
  void setCellSize(double cell_size) {
    cell_size_ = cell_size;
    automatic_ = false;
  }
  /// \brief The cell size from the number of points and the mean spacing (the default).
  void setAutoCellSize() { automatic_ = true; }
  /// \brief The fixed cell size, or 0 when automatic.
  double getCellSize() const { return automatic_ ? 0.0 : cell_size_; }

  /// \brief The cell size used by the last filter() call [length unit]; the mean spacing it
  /// estimated (0 if the cell size was fixed).
  double usedCellSize() const { return used_cell_size_; }
  double usedSpacing() const { return used_spacing_; }
  /// \brief Occupied and boundary cells of the last filter() call.
  std::size_t occupiedCells() const { return occupied_cells_; }
  std::size_t boundaryCells() const { return cell_means_.size(); }

  /// \brief The mean of each boundary cell's points (the boundary points of Yin, Wang & Yu 2010) in
  /// the input's coordinates [length unit], one per boundary cell, from the last filter() call.
  /// Independent of negative mode.
  const pcl::PointCloud<pcl::PointXYZ>& cellMeans() const { return cell_means_; }

 protected:
  using pcl::PCLBase<PointT>::input_;
  using pcl::PCLBase<PointT>::indices_;
  using pcl::Filter<PointT>::filter_name_;
  using pcl::FilterIndices<PointT>::negative_;
  using pcl::FilterIndices<PointT>::extract_removed_indices_;
  using pcl::FilterIndices<PointT>::removed_indices_;

  /// \throws mcws::Error for a fixed cell size that is not a positive number, or one so small
  ///   that the points' extent spans more than 2097148 cells along an axis.
  void applyFilter(pcl::Indices& indices) override;

 private:
  BoundaryPlane plane_{BoundaryPlane::k3D};
  double cell_size_{0.0};
  bool automatic_{true};
  double used_cell_size_{0.0};
  double used_spacing_{0.0};
  std::size_t occupied_cells_{0};
  pcl::PointCloud<pcl::PointXYZ> cell_means_;
};

/// \brief The automatic cell side of the grid and extremum baselines [length unit]: h m^(1/d)
/// with m = ln(2 n / m) points per cell (see GridBoundary).
/// \param n number of points. \param spacing mean spacing h [length unit]. \param dimensions 2/3.
double baselineCellSize(std::size_t n, double spacing, int dimensions);

}  // namespace mcws

#ifdef PCL_NO_PRECOMPILE
#include "mcws/filters/impl/grid_boundary.hpp"
#endif

// The point types the filters library instantiates (filters/src/grid_boundary.cpp): other
// translation units use those instantiations instead of compiling the implementation again.
namespace mcws {
extern template class GridBoundary<pcl::PointXYZ>;
extern template class GridBoundary<pcl::PointXYZL>;
extern template class GridBoundary<WorkspacePoint>;
}  // namespace mcws
