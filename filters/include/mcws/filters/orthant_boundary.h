#pragma once
/// \file
/// \brief Boundary points of a point cloud by the local quadrant (2-D) or octant (3-D) test of
/// Yin, Wang & Yu 2010, section 4.3, with the refinements described in filters/README.md.

#include <pcl/filters/filter_indices.h>

#include <cmath>
#include <memory>
#include <optional>

#include "mcws/filters/boundary_geometry.h"
#include "mcws/filters/orthant/frames.h"
#include "mcws/filters/orthant/point_test.h"
#include "mcws/points/point_types.h"

namespace mcws {

/// \brief How OrthantBoundary chooses its search radius.
enum class RadiusMode {
  kFixed,      ///< one radius r for every point (setRadiusSearch)
  kAutomatic,  ///< r = c h, h the mean spacing (setAutoRadius)
  kAdaptive,   ///< r_i = s d_k(p) per point (setAdaptiveRadius; the default)
};

/// \brief Keeps the points on the boundary of a sampled region (negative mode: the interior).
///
/// **Rule.** Around each point p, its neighbours within radius r (in the chosen plane or in 3-D;
/// copies of a point count as one position) are sorted into the 4 quadrants (2-D) or 8 octants
/// (3-D) of a local frame centred on p. p is a boundary point when at least one orthant holds no
/// neighbour in at least one of the frames (OrthantFrame):
/// - kAxis: the coordinate axes (the paper's rule);
/// - kOutward: a frame turned so that one orthant is centred on the outward direction -(c - p),
///   c the centroid of the neighbours; it finds the points just inside a boundary;
/// - kAnyRotation (2-D only; in 3-D it means kAxis | kOutward): some rotation of the frame has an
///   empty quadrant, i.e. the directions to the neighbours leave an empty sector of at least the
///   minimum gap (90 degrees or more, setMinimumGap).
/// Default frames: kAnyRotation in 2-D, kAxis | kOutward in 3-D.
///
/// **Radius** (RadiusMode). setRadiusSearch(r) fixes it [length unit]. setAutoRadius(c) takes
/// r = c h, h the mean spacing (meanSpacing()); c = 0 chooses c = sqrt(4 / pi ln(32 N)) (2-D) or
/// cbrt(6 / pi ln(32 N)) (3-D) for N points (orthantAutoFactor()). setAdaptiveRadius(k, s), the
/// default, gives each point its own r_i = s d_k(p), d_k the distance to its k-th nearest
/// neighbour, for clouds whose density varies. setOuterRadius(R) adds the paper's second stage:
/// points found at r are tested again at R > r (with an adaptive radius R is a factor > 1 of
/// each r_i).
///
/// **Hull depth (2-D).** setHullDepth(t) makes the test a first stage. The points it finds, and
/// every point within a quarter of its radius of one of them, are then kept only when their depth,
/// the distance from p to the edge of the convex hull of its neighbourhood (within r, or R), is
/// below t h_p, h_p = sqrt(hull area / number of neighbours) the local spacing. At a reflex corner
/// the hull spans the notch, so points within about r / 3 of the corner are lost.
///
/// **Defaults.** A default-constructed filter uses the recommended settings (kRecommended*): an
/// adaptive radius, 2 d_24 in 2-D and 2 d_16 in 3-D, a 92-degree minimum gap, and a hull depth of
/// 1 in 2-D; set a plane and run it.
///
/// **Special points.** Non-finite points are not searched and are removed in both modes (they are
/// in getRemovedIndices()). A point with no neighbour within r is a boundary point. Copies of p
/// count as neighbours in no orthant, so a cloud of identical points is all boundary.
///
/// **Search.** GridThenTreeSearch: a CellGrid for most points, a pcl::KdTreeFLANN for the rest
/// (every point with setGridSearch(false)); both give exactly the tree's neighbourhoods.
/// Multi-threaded (setNumberOfThreads); the result does not depend on the thread count.
///
/// \code
/// mcws::OrthantBoundary<pcl::PointXYZ> boundary;
/// boundary.setInputCloud(cloud);
/// boundary.setPlane(mcws::BoundaryPlane::kXZ);
/// pcl::PointCloud<pcl::PointXYZ> rim;
/// boundary.filter(rim);
/// \endcode
template <typename PointT>
class OrthantBoundary : public pcl::FilterIndices<PointT> {
 public:
  using Ptr = std::shared_ptr<OrthantBoundary<PointT>>;
  using ConstPtr = std::shared_ptr<const OrthantBoundary<PointT>>;

  /// \brief The recommended settings, which a default-constructed filter uses: an adaptive
  /// radius of twice the distance to the 24th (2-D) or 16th (3-D) neighbour, a 92-degree gap,
  /// and in 2-D the hull depth stage at one local spacing.
  static constexpr int kRecommendedNeighbours2D = 24;
  static constexpr int kRecommendedNeighbours3D = 16;
  static constexpr double kRecommendedScale = 2.0;
  static constexpr double kRecommendedGap = 92.0 * M_PI / 180.0;
  static constexpr double kRecommendedHullDepth2D = 1.0;

  explicit OrthantBoundary(bool extract_removed_indices = false)
      : pcl::FilterIndices<PointT>(extract_removed_indices) {
    filter_name_ = "OrthantBoundary";
  }

  /// \brief k3D (octants, ball neighbourhood; the default) or a coordinate plane (quadrants).
  void setPlane(BoundaryPlane plane) { plane_ = plane; }
  BoundaryPlane getPlane() const { return plane_; }

  /// \brief Fixed search radius r [length unit] (> 0).
  void setRadiusSearch(double radius) {
    radius_mode_ = RadiusMode::kFixed;
    radius_ = radius;
  }
  double getRadiusSearch() const { return radius_; }

  /// \brief r = factor * mean spacing; factor 0: chosen from the number of points (see above).
  void setAutoRadius(double factor) {
    radius_mode_ = RadiusMode::kAutomatic;
    auto_factor_ = factor;
  }

  /// \brief Per-point radius r_i = scale * (distance to the k-th nearest neighbour).
  void setAdaptiveRadius(int k, double scale) {
    radius_mode_ = RadiusMode::kAdaptive;
    adaptive_k_ = k;
    adaptive_scale_ = scale;
  }
  RadiusMode getRadiusMode() const { return radius_mode_; }
  /// \brief The adaptive radius's scale s.
  double getAdaptiveScale() const { return adaptive_scale_; }
  /// \brief The adaptive radius's k: as set, or the recommended one for the plane.
  int getAdaptiveNeighbours() const {
    return adaptive_k_.value_or(boundaryDimensions(plane_) == 2 ? kRecommendedNeighbours2D
                                                                : kRecommendedNeighbours3D);
  }

  /// \brief Second-stage radius R (0: single stage, the default). With an adaptive radius, R is
  /// a factor applied to each r_i.
  void setOuterRadius(double outer) { outer_radius_ = outer; }
  double getOuterRadius() const { return outer_radius_; }

  /// \brief Frames tested (empty: the default for the plane, see above).
  void setFrames(OrthantFrames frames) { frames_ = frames; }
  OrthantFrames getFrames() const { return frames_; }

  /// \brief OrthantFrame::kAnyRotation only: the empty sector that makes a boundary point
  /// [rad], in [pi/2, pi). pi/2 is the quadrant; a wider sector trades recall for precision.
  void setMinimumGap(double radians) { minimum_gap_ = radians; }
  double getMinimumGap() const { return minimum_gap_; }

  /// \brief 2-D: keep only the boundary points whose distance to the edge of the convex hull of
  /// their neighbourhood is below t local spacings (see above); 0 turns it off. Default: 1 in a
  /// plane, off in 3-D, where it must stay 0.
  void setHullDepth(double t) { hull_depth_ = t; }
  double getHullDepth() const {
    return hull_depth_.value_or(boundaryDimensions(plane_) == 2 ? kRecommendedHullDepth2D : 0.0);
  }

  /// \brief Search most points on a uniform grid (default) or every point in the
  /// pcl::KdTreeFLANN. Both give the same result; the tree alone is the reference the tests
  /// compare with.
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
  /// Throws mcws::Error for a setting out of range (those that need no data).
  void checkSettings(int dimensions) const;
  /// Resolves the radius rule on the distinct positions; sets used_spacing_ and used_radius_.
  orthant::PointTestSettings resolveSettings(const pcl::PointCloud<pcl::PointXYZ>& positions,
                                             int dimensions);

  BoundaryPlane plane_{BoundaryPlane::k3D};
  RadiusMode radius_mode_{RadiusMode::kAdaptive};
  double radius_{0.0};
  double auto_factor_{0.0};
  std::optional<int> adaptive_k_;  // none: the recommended k for the plane
  double adaptive_scale_{kRecommendedScale};
  double outer_radius_{0.0};
  OrthantFrames frames_;
  double minimum_gap_{kRecommendedGap};
  std::optional<double> hull_depth_;  // none: the recommended depth for the plane
  int threads_{0};
  bool grid_search_{true};
  double used_radius_{0.0};
  double used_spacing_{0.0};
};

/// \brief The automatic radius factor c for n points in `dimensions` dimensions (see
/// OrthantBoundary).
double orthantAutoFactor(std::size_t n, int dimensions);

}  // namespace mcws

#ifdef PCL_NO_PRECOMPILE
#include "mcws/filters/impl/orthant_boundary.hpp"
#endif

// The point types the filters library instantiates (filters/src/orthant_boundary.cpp): other
// translation units use those instantiations instead of compiling the implementation again.
namespace mcws {
extern template class OrthantBoundary<pcl::PointXYZ>;
extern template class OrthantBoundary<pcl::PointXYZL>;
extern template class OrthantBoundary<WorkspacePoint>;
}  // namespace mcws
