#pragma once
/// \file
/// \brief Boundary points of a point cloud by the local quadrant (2-D) or octant (3-D) test of
/// seed 000 (Yin, Wang, Yu 2010, section 4.3).

#include <pcl/filters/filter_indices.h>

#include "mcws/filters/boundary_geometry.h"

namespace mcws {

/// \brief Keeps the points on the boundary of a sampled region (negative mode: the interior).
///
/// **Rule.** Around each point p, the neighbours within radius r (pcl::KdTreeFLANN over the
/// input's indices, in the chosen plane or in 3-D; copies of a point count as one position) are
/// sorted into the 4 quadrants (2-D) or 8 octants (3-D) of a local frame centred on p. p is a
/// boundary point when at least one orthant holds no neighbour in at least one of the enabled
/// frames:
/// - kAxisFrame: the coordinate axes (seed 000's rule);
/// - kOutwardFrame: a frame turned so that one orthant is centred on the outward direction
///   -(c - p), c the centroid of the neighbours. A point a distance d inside a flat boundary then
///   has an empty outward orthant with probability exp(-density * d^2) (2-D), whatever r is,
///   where the axis frame needs the two thin strips between p and a boundary parallel to an axis
///   both empty. The outward frame is what finds the points just inside the boundary.
/// - kAnyRotation (2-D only; ignored in 3-D): every rotation of the frame, i.e. some quadrant is
///   empty in some rotation, which holds exactly when the largest angle between the directions
///   to consecutive neighbours is at least 90 degrees (setMinimumGap: a wider sector). At 90
///   degrees it contains the other two frames' tests.
///   Default: kAnyRotation in 2-D, kAxisFrame | kOutwardFrame in 3-D.
///
/// **Radius.** setRadiusSearch(r) fixes it [length unit]. setAutoRadius(c) takes r = c h, h the
/// mean spacing (meanSpacing()); with N points an interior point's orthant of radius c h is
/// empty with probability exp(-pi c^2 / 4) (2-D) or exp(-pi c^3 / 6) (3-D), so c must grow like
/// sqrt(ln N) (2-D) or cbrt(ln N) (3-D) to keep false boundary points rare; c = 0 chooses
/// c = sqrt(4 / pi ln(32 N)) resp. cbrt(6 / pi ln(32 N)): about half a false point per cloud for
/// the fixed frames (the any-rotation test, which can find its gap in any direction, gives a few).
/// setAdaptiveRadius(k, s) gives each point its own r_i = s d_k(p), d_k the distance to its k-th
/// nearest neighbour, for clouds whose density varies (joint-space sampling of an arm).
/// setOuterRadius(R) makes it the paper's two-stage test: points that pass at r are tested again
/// at R > r, which removes the false boundary points of its Fig. 12. For the tests that more
/// neighbours can only fill (2-D any-rotation, or the axis frame alone) the result equals a single
/// test at R, reached faster; the outward frame depends on the neighbourhood, so with it the two
/// differ slightly. With an adaptive radius R is a factor (> 1) of each point's radius.
///
/// **Hull depth (2-D).** setHullDepth(t) turns the test into a first stage. The points it finds,
/// and every point within a quarter of its radius of one of them, are then kept only when their
/// depth, the distance from p to the edge of the convex hull of its neighbourhood (the points
/// within r, or R), is below t h_p. Here h_p = sqrt(A / m) is the local spacing: A is the hull's
/// area, m the number of neighbours. Every neighbour lies on p's side of the hull edge, so near a
/// boundary that is straight or convex on the scale of r, the depth never exceeds p's true distance
/// from the boundary. Points within t h_p of it are all kept. Points more than a few spacings
/// inside would need a whole hull edge that deep, which is rare. t = 1 (mcws_boundary's default in
/// 2-D) gives precision 1.0000 and recall 1.0000 on 1e6-point disks and annuli (BENCHMARKS.md). At
/// a reflex corner the hull spans the notch, so points within about r / 3 of the corner are lost.
///
/// **Special points.** Non-finite points are not searched and are removed in both modes (they are
/// in getRemovedIndices()). A point with no neighbour within r is a boundary point. Duplicates of
/// p count as neighbours in no orthant, so a cloud of identical points is all boundary.
///
/// **Search.** Most points are searched on a CellGrid, which returns exactly the neighbourhoods
/// the tree would; the rest in the KdTreeFLANN (see setGridSearch and filters/README.md).
///
/// Multi-threaded (setNumberOfThreads), and the result does not depend on the thread count.
///
/// \code
/// mcws::OrthantBoundary<pcl::PointXYZ> boundary;
/// boundary.setInputCloud(cloud);
/// boundary.setPlane(mcws::BoundaryPlane::kXZ);
/// boundary.setAutoRadius(0.0);
/// pcl::PointCloud<pcl::PointXYZ> rim;
/// boundary.filter(rim);
/// \endcode
template <typename PointT>
class OrthantBoundary : public pcl::FilterIndices<PointT> {
 public:
  using Ptr = std::shared_ptr<OrthantBoundary<PointT>>;
  using ConstPtr = std::shared_ptr<const OrthantBoundary<PointT>>;

  /// \brief Frames tested (bit mask).
  enum Frame : unsigned { kAxisFrame = 1u, kOutwardFrame = 2u, kAnyRotation = 4u };

  explicit OrthantBoundary(bool extract_removed_indices = false)
      : pcl::FilterIndices<PointT>(extract_removed_indices) {
    filter_name_ = "OrthantBoundary";
  }

  /// \brief k3D (octants, ball neighbourhood) or a coordinate plane (quadrants).
  void setPlane(BoundaryPlane plane) { plane_ = plane; }
  BoundaryPlane getPlane() const { return plane_; }

  /// \brief Fixed search radius r [length unit] (> 0). Turns the automatic radius off.
  void setRadiusSearch(double radius) {
    radius_ = radius;
    auto_factor_ = -1.0;
    adaptive_k_ = 0;
  }
  double getRadiusSearch() const { return radius_; }

  /// \brief r = factor * mean spacing; factor 0: chosen from the number of points (see above).
  void setAutoRadius(double factor) {
    auto_factor_ = factor;
    adaptive_k_ = 0;
  }

  /// \brief Per-point radius r_i = scale * (distance to the k-th nearest neighbour).
  void setAdaptiveRadius(int k, double scale) {
    adaptive_k_ = k;
    adaptive_scale_ = scale;
    auto_factor_ = -1.0;
  }

  /// \brief Second-stage radius R (0: single stage). With an adaptive radius, R is a factor
  /// applied to each r_i.
  void setOuterRadius(double outer) { outer_radius_ = outer; }
  double getOuterRadius() const { return outer_radius_; }

  /// \brief Frames tested, a mask of Frame values (0: the default for the plane, see above).
  void setFrames(unsigned frames) { frames_ = frames; }
  unsigned getFrames() const { return frames_; }

  /// \brief kAnyRotation only: the empty sector that makes a boundary point [rad], in
  /// [pi/2, pi). pi/2 is the quadrant; a wider sector trades recall for precision.
  void setMinimumGap(double radians) { minimum_gap_ = radians; }
  double getMinimumGap() const { return minimum_gap_; }

  /// \brief 2-D: keep only the boundary points whose distance to the edge of the convex hull of
  /// their neighbourhood is below t local spacings (see above); 0 (the default) turns it off.
  void setHullDepth(double t) { hull_depth_ = t; }
  double getHullDepth() const { return hull_depth_; }

  /// \brief Search most points on a uniform grid (default) or every point in the
  /// pcl::KdTreeFLANN. Both give the same result (CellGrid reproduces the tree's distances);
  /// the tree alone is the reference the tests compare with.
  void setGridSearch(bool grid) { grid_search_ = grid; }
  bool getGridSearch() const { return grid_search_; }

  /// \brief Worker threads; 0 = all cores.
  void setNumberOfThreads(int threads) { threads_ = threads; }

  /// \brief The radius used by the last filter() call [length unit] (with an adaptive radius,
  /// the median r_i); the mean spacing it estimated (0 if it did not need it).
  double usedRadius() const { return used_radius_; }
  double usedSpacing() const { return used_spacing_; }

 protected:
  using pcl::PCLBase<PointT>::input_;
  using pcl::PCLBase<PointT>::indices_;
  using pcl::Filter<PointT>::filter_name_;
  using pcl::FilterIndices<PointT>::negative_;
  using pcl::FilterIndices<PointT>::extract_removed_indices_;
  using pcl::FilterIndices<PointT>::removed_indices_;

  /// \throws mcws::Error for a radius <= 0 or not finite, an outer radius below the radius, no
  ///   frame, adaptive k < 1, or a hull depth that is negative, not finite or set in 3-D.
  void applyFilter(pcl::Indices& indices) override;

 private:
  BoundaryPlane plane_{BoundaryPlane::k3D};
  double radius_{0.0};
  double auto_factor_{-1.0};
  int adaptive_k_{0};
  double adaptive_scale_{1.0};
  double outer_radius_{0.0};
  unsigned frames_{0};
  double minimum_gap_{M_PI / 2};
  double hull_depth_{0.0};
  int threads_{0};
  bool grid_search_{true};
  double used_radius_{0.0};
  double used_spacing_{0.0};
};

/// \brief The frames OrthantBoundary tests for `frames` (0: the default) in `dimensions`.
unsigned orthantFrames(unsigned frames, int dimensions);

/// \brief The automatic radius factor c for n points in `dimensions` dimensions (see
/// OrthantBoundary).
double orthantAutoFactor(std::size_t n, int dimensions);

}  // namespace mcws

#ifdef PCL_NO_PRECOMPILE
#include "mcws/filters/impl/orthant_boundary.hpp"
#endif
