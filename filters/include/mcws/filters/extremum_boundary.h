#pragma once
/// \file
/// \brief Boundary points by the extremum method of Yin, Wang & Yu 2010 (section 4.2), a baseline
/// for OrthantBoundary.

#include <pcl/filters/filter_indices.h>

#include <cstddef>

#include "mcws/filters/boundary_geometry.h"
#include "mcws/points/point_types.h"

namespace mcws {

/// \brief Keeps the extreme points of each column of a planar cloud, and the points on either
/// side of a wide gap inside a column (negative mode: every other point).
///
/// **Rule (Yin, Wang & Yu 2010, section 4.2, Fig. 9).** In the chosen plane (a, b) (xy: a = x, b =
/// y; xz: a = x, b = z as in the paper; yz: a = y, b = z) the points are cut into columns of width
/// dL along a, the first column starting at the smallest a of the finite points. In each column the
/// points are sorted by b: the lowest and the highest are the column's outer boundary points (the
/// paper's a and d); where two consecutive points are more than the gap threshold t apart along b,
/// both are inner boundary points (the paper's b and c), which finds the hole of an annulus. A
/// column holding one point keeps it. The method needs a plane: it has no 3-D form.
///
/// **Column width.** setColumnWidth(dL) fixes it [length unit]; by default it is the grid
/// method's automatic cell size (baselineCellSize(): dL = h sqrt(m), m = ln(2 n / m), h the mean
/// spacing from meanSpacing()).
///
/// **Gap threshold.** setGapThreshold(t) fixes it [length unit]; by default it is chosen so that
/// a uniform cloud shows no false gap: in a column of width dL the b-distances between
/// consecutive interior points are exponential with mean h^2 / dL, so with about n of them
/// t = ln(2 n) h^2 / dL leaves half a false gap per cloud (about 4 h for n = 10^6 at the automatic
/// dL). Columns only partly inside the region (at its ends in a) are sparser and may still show
/// one.
///
/// **Special points.** Non-finite points are ignored and removed in both modes (they are in
/// getRemovedIndices()). Where points of a column share the extreme b (copies of a point, a row
/// of a grid), the one with the lowest input index is kept; likewise next to a gap.
///
/// \code
/// mcws::ExtremumBoundary<pcl::PointXYZ> extremum;
/// extremum.setInputCloud(cloud);
/// extremum.setPlane(mcws::BoundaryPlane::kXZ);
/// extremum.setColumnWidth(0.5);
/// extremum.setGapThreshold(2.0);
/// pcl::Indices rim;
/// extremum.filter(rim);
/// \endcode
template <typename PointT>
class ExtremumBoundary : public pcl::FilterIndices<PointT> {
 public:
  using Ptr = std::shared_ptr<ExtremumBoundary<PointT>>;
  using ConstPtr = std::shared_ptr<const ExtremumBoundary<PointT>>;

  explicit ExtremumBoundary(bool extract_removed_indices = false)
      : pcl::FilterIndices<PointT>(extract_removed_indices) {
    filter_name_ = "ExtremumBoundary";
  }

  /// \brief The plane: xy, xz or yz (k3D is rejected by filter()).
  void setPlane(BoundaryPlane plane) { plane_ = plane; }
  BoundaryPlane getPlane() const { return plane_; }

  /// \brief Fixed column width dL [length unit], > 0.
  void setColumnWidth(double width) {
    width_ = width;
    auto_width_ = false;
  }
  /// \brief The column width from the number of points and the mean spacing (the default).
  void setAutoColumnWidth() { auto_width_ = true; }
  /// \brief The fixed width, or 0 when automatic.
  double getColumnWidth() const { return auto_width_ ? 0.0 : width_; }

  /// \brief Fixed gap threshold t [length unit], > 0.
  void setGapThreshold(double gap) {
    gap_ = gap;
    auto_gap_ = false;
  }
  /// \brief The threshold from the density (the default, see above).
  void setAutoGapThreshold() { auto_gap_ = true; }
  /// \brief The fixed threshold, or 0 when automatic.
  double getGapThreshold() const { return auto_gap_ ? 0.0 : gap_; }

  /// \brief What the last filter() call used [length unit]: column width, gap threshold, mean
  /// spacing (0 if nothing needed it); and the number of columns holding points.
  double usedColumnWidth() const { return used_width_; }
  double usedGapThreshold() const { return used_gap_; }
  double usedSpacing() const { return used_spacing_; }
  std::size_t columns() const { return columns_; }

 protected:
  using pcl::PCLBase<PointT>::input_;
  using pcl::PCLBase<PointT>::indices_;
  using pcl::Filter<PointT>::filter_name_;
  using pcl::FilterIndices<PointT>::negative_;
  using pcl::FilterIndices<PointT>::extract_removed_indices_;
  using pcl::FilterIndices<PointT>::removed_indices_;

  /// \throws mcws::Error for the plane k3D, a fixed width or threshold that is not a positive
  ///   number, or a width so small that the extent spans more than 2097148 columns.
  void applyFilter(pcl::Indices& indices) override;

 private:
  BoundaryPlane plane_{BoundaryPlane::kXY};
  double width_{0.0};
  bool auto_width_{true};
  double gap_{0.0};
  bool auto_gap_{true};
  double used_width_{0.0};
  double used_gap_{0.0};
  double used_spacing_{0.0};
  std::size_t columns_{0};
};

}  // namespace mcws

#ifdef PCL_NO_PRECOMPILE
#include "mcws/filters/impl/extremum_boundary.hpp"
#endif

// The point types the filters library instantiates (filters/src/extremum_boundary.cpp): other
// translation units use those instantiations instead of compiling the implementation again.
namespace mcws {
extern template class ExtremumBoundary<pcl::PointXYZ>;
extern template class ExtremumBoundary<pcl::PointXYZL>;
extern template class ExtremumBoundary<WorkspacePoint>;
}  // namespace mcws
