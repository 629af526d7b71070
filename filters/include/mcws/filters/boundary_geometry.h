#pragma once
/// \file
/// \brief What the boundary filters share: the plane a 2-D method works in, the projection of a
/// cloud onto it, and the mean point spacing of a cloud; what a cloud must be to have a boundary
/// in a plane or in 3-D, and the lengths a parameter may take for it.

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "mcws/points/unique_positions.h"

namespace mcws {

/// \brief Where a boundary method works: in 3-D, or in one coordinate plane.
enum class BoundaryPlane { k3D, kXY, kXZ, kYZ };

/// \brief "xy", "xz", "yz" -> plane. \throws mcws::Error naming the bad name.
BoundaryPlane parseBoundaryPlane(const std::string& name);
/// \brief Name of a plane ("3d", "xy", "xz", "yz").
const char* boundaryPlaneName(BoundaryPlane plane);
/// \brief 2 for a plane, 3 for k3D.
inline int boundaryDimensions(BoundaryPlane plane) { return plane == BoundaryPlane::k3D ? 3 : 2; }
/// \brief The input axes (0 x, 1 y, 2 z) a plane's first and second coordinates come from (k3D:
/// x and y).
std::array<int, 2> planeAxes(BoundaryPlane plane);

/// \brief The points' coordinates in the method's space: for a plane (a, b) its two coordinates
/// go to x and y and z is 0 (xz: x -> x, z -> y); for k3D a copy. Non-finite points are skipped;
/// `source_index[i]` is the input index of projected point i.
template <typename PointT>
void projectToPlane(const pcl::PointCloud<PointT>& cloud, const pcl::Indices& indices,
                    BoundaryPlane plane, pcl::PointCloud<pcl::PointXYZ>& projected,
                    pcl::Indices& source_index) {
  projected.clear();
  source_index.clear();
  projected.reserve(indices.size());
  source_index.reserve(indices.size());
  for (const auto i : indices) {
    const PointT& p = cloud[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
    switch (plane) {
      case BoundaryPlane::k3D:
        projected.emplace_back(p.x, p.y, p.z);
        break;
      case BoundaryPlane::kXY:
        projected.emplace_back(p.x, p.y, 0.0f);
        break;
      case BoundaryPlane::kXZ:
        projected.emplace_back(p.x, p.z, 0.0f);
        break;
      case BoundaryPlane::kYZ:
        projected.emplace_back(p.y, p.z, 0.0f);
        break;
    }
    source_index.push_back(i);
  }
}

/// \brief projectToPlane() of every point of `cloud` (the non-finite ones skipped).
template <typename PointT>
pcl::PointCloud<pcl::PointXYZ> projectedToPlane(const pcl::PointCloud<PointT>& cloud,
                                                BoundaryPlane plane) {
  pcl::Indices all(cloud.size()), source;
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<pcl::index_t>(i);
  pcl::PointCloud<pcl::PointXYZ> projected;
  projectToPlane(cloud, all, plane, projected, source);
  return projected;
}

/// \brief A boundary filter's output, in input order. `source` lists the input indices that were
/// projected (the finite points, in the order of `input`); projected point k is on the boundary
/// when `is_boundary(k)`. Kept: boundary != negative; input points not in `source` (non-finite)
/// are always removed; `removed` is filled only when `extract_removed`.
template <typename IsBoundary>
void splitByBoundary(const pcl::Indices& input, const pcl::Indices& source, IsBoundary is_boundary,
                     bool negative, bool extract_removed, pcl::Indices& kept,
                     pcl::Indices& removed) {
  kept.clear();
  kept.reserve(input.size());
  removed.clear();
  std::size_t next = 0;  // walks `source`
  for (const auto index : input) {
    bool keep = false;
    if (next < source.size() && source[next] == index) {
      keep = is_boundary(next) != negative;
      ++next;
    }
    if (keep) {
      kept.push_back(index);
    } else if (extract_removed) {
      removed.push_back(index);
    }
  }
}

/// \brief Mean point spacing h [length unit] of a projected cloud: (measure / n)^(1/d), with the
/// region's area (d = 2) or volume (d = 3) estimated by occupied cells of a grid whose cells hold
/// about 8 points each. For n points uniform in a region of area A this is sqrt(A / n).
/// \return 0 for fewer than 2 points or a cloud of identical points.
double meanSpacing(const pcl::PointCloud<pcl::PointXYZ>& projected, int dimensions);

/// \brief An extent below this share of a cloud's largest extent is float rounding of a flat
/// cloud, not a dimension (floats resolve 6e-8; cloud_io's requireVolume uses the same share).
constexpr double kFlatExtentShare = 1e-6;

/// \brief Distinct positions are counted up to this many (CloudSummary::distinct): enough for
/// every check (a region needs 3 or 4, an adaptive k at most 1000 below the count), and counting
/// stops there, so a large cloud is summarised in one pass without hashing every point.
constexpr std::size_t kDistinctCounted = 1001;

/// \brief What a boundary or a measure in `plane` sees of a cloud, for the checks below.
struct CloudSummary {
  BoundaryPlane plane{BoundaryPlane::k3D};
  std::size_t points{0};    ///< every point
  std::size_t finite{0};    ///< points with finite x, y and z
  std::size_t distinct{0};  ///< distinct positions of the finite points in the plane (or 3-D),
                            ///< counted up to kDistinctCounted
  Eigen::Vector3d extent{Eigen::Vector3d::Zero()};  ///< x, y, z extent of the finite points [unit]
  double largest{0.0};  ///< largest extent along the plane's two axes (3-D: all three) [unit]
  /// meanSpacing() of the distinct positions [unit] (0 for fewer than 2), the one OrthantBoundary
  /// computes; only when asked for (SummaryDetail::kSpacing): it costs a pass over every point.
  std::optional<double> spacing;
};

/// \brief How much summarizeCloud() works out: the counts and extents (one pass that stops
/// hashing positions at kDistinctCounted), or the mean spacing too.
enum class SummaryDetail { kCounts, kSpacing };

/// \brief Counts distinct positions up to kDistinctCounted (-0 and +0 are one position).
class DistinctCounter {
 public:
  /// \brief Counts (x, y, z) unless kDistinctCounted are counted already.
  void add(float x, float y, float z);
  bool full() const { return seen_.size() >= kDistinctCounted; }
  std::size_t count() const { return seen_.size(); }

 private:
  std::vector<std::array<float, 3>> seen_;  // sorted
};

/// \brief The mean spacing of the finite points of `cloud` in `plane`: meanSpacing() of their
/// distinct positions there, as OrthantBoundary computes it.
template <typename PointT>
double planeSpacing(const pcl::PointCloud<PointT>& cloud, BoundaryPlane plane) {
  std::vector<pcl::index_t> position_of;
  return meanSpacing(uniquePositions(projectedToPlane(cloud, plane), position_of),
                     boundaryDimensions(plane));
}

/// \brief CloudSummary gathered piece by piece (a cloud read from a file in pieces), without the
/// spacing; summarizeCloud() for a cloud in memory.
class CloudSummarizer {
 public:
  explicit CloudSummarizer(BoundaryPlane plane) { s_.plane = plane; }

  /// \brief Counts the points of `cloud` (non-finite ones counted and skipped).
  template <typename PointT>
  void add(const pcl::PointCloud<PointT>& cloud) {
    s_.points += cloud.size();
    const std::array<int, 2> axes = planeAxes(s_.plane);
    for (const PointT& p : cloud) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
      ++s_.finite;
      const Eigen::Array3d q(p.x, p.y, p.z);
      lo_ = lo_.min(q);
      hi_ = hi_.max(q);
      if (distinct_.full()) continue;
      if (s_.plane == BoundaryPlane::k3D) {
        distinct_.add(p.x, p.y, p.z);
      } else {
        distinct_.add(p.data[axes[0]], p.data[axes[1]], 0.0f);
      }
    }
  }

  /// \brief The summary of the points added so far.
  CloudSummary summary() const {
    CloudSummary s = s_;
    s.distinct = distinct_.count();
    if (s.finite == 0) return s;
    const std::array<int, 2> axes = planeAxes(s.plane);
    s.extent = (hi_ - lo_).matrix();
    s.largest = s.plane == BoundaryPlane::k3D ? s.extent.maxCoeff()
                                              : std::max(s.extent[axes[0]], s.extent[axes[1]]);
    return s;
  }
  /// \brief The finite points' lowest x, y and z (infinite before any).
  Eigen::Vector3d low() const { return lo_.matrix(); }

 private:
  CloudSummary s_;
  Eigen::Array3d lo_{Eigen::Array3d::Constant(std::numeric_limits<double>::infinity())};
  Eigen::Array3d hi_{-Eigen::Array3d::Constant(std::numeric_limits<double>::infinity())};
  DistinctCounter distinct_;
};

/// \brief CloudSummary of any cloud with x, y, z (non-finite points counted and skipped).
template <typename PointT>
CloudSummary summarizeCloud(const pcl::PointCloud<PointT>& cloud, BoundaryPlane plane,
                            SummaryDetail detail = SummaryDetail::kCounts) {
  CloudSummarizer summarizer(plane);
  summarizer.add(cloud);
  CloudSummary s = summarizer.summary();
  if (s.finite > 0 && detail == SummaryDetail::kSpacing) s.spacing = planeSpacing(cloud, plane);
  return s;
}

/// \brief The fewest distinct finite positions a region has: 3 in a plane (a triangle), 4 in
/// 3-D (a tetrahedron). With fewer, a cloud has no boundary, area or volume.
inline std::size_t minimumRegionPoints(BoundaryPlane plane) {
  return static_cast<std::size_t>(boundaryDimensions(plane)) + 1;
}

/// \brief Checks that a cloud can be a region in its plane (or 3-D): at least
/// minimumRegionPoints() distinct finite positions there, and in a plane, a cloud that extends
/// along two axes (one that is flat in one of the plane's axes but lies in another plane is for
/// requirePlaneFits() to name). The same rule for 2-D and 3-D, so that a single point, copies of
/// one point or an all-NaN cloud fail alike.
/// \param what names the cloud in the message (its file).
/// \throws mcws::Error "a.pcd: 2 distinct finite points in the xy plane (of 5 points, 3 not
///   finite); a region there needs at least 3" or "a.pcd: the points extend along x only (a
///   line): no region in the xy plane".
void requireRegionPoints(const CloudSummary& cloud, const std::string& what);

/// \brief Checks that a cloud that extends along two or three axes is not flat (extent below
/// kFlatExtentShare of the largest) along one of the plane's two axes. Nothing to check in 3-D
/// (a flat cloud has no volume: cloud_io's requireVolume). A genuinely 3-D cloud is projected to
/// any plane and passes.
/// \throws mcws::Error "a.pcd: the cloud is flat in y (extent 0, its largest 2), so in the xy
///   plane every point is on its boundary and the area is 0; it lies in the xz plane".
void requirePlaneFits(const CloudSummary& cloud, const std::string& what);

/// \brief The lengths a parameter of a boundary method or of the column area may take for a
/// cloud summarised with its spacing (SummaryDetail::kSpacing) [unit]: from a tenth of its mean
/// spacing (below, a point's neighbourhood, cell or column holds no other point) to its largest
/// extent in the plane (beyond, one neighbourhood, cell or column holds the whole cloud).
struct LengthRange {
  double min{0.0};
  double max{0.0};
};
LengthRange parameterLengths(const CloudSummary& cloud);
constexpr double kShortestLengthSpacings = 0.1;  ///< LengthRange::min in mean spacings

/// \brief The index of the first point of `subset` that is not a finite point of `cloud` (the
/// same float x, y and z; -0 equals 0), or none: every point of a boundary written by
/// mcws_boundary is a copy of a point of its cloud.
template <typename PointA, typename PointB>
std::optional<std::size_t> firstPointNotIn(const pcl::PointCloud<PointA>& subset,
                                           const pcl::PointCloud<PointB>& cloud) {
  using Key = std::array<float, 3>;
  auto key = [](const auto& p) { return Key{p.x + 0.0f, p.y + 0.0f, p.z + 0.0f}; };  // -0 -> 0
  std::vector<Key> keys;
  keys.reserve(cloud.size());
  for (const auto& p : cloud) {
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) keys.push_back(key(p));
  }
  std::sort(keys.begin(), keys.end());
  for (std::size_t i = 0; i < subset.size(); ++i) {
    const auto& p = subset[i];
    const bool finite = std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
    if (!finite || !std::binary_search(keys.begin(), keys.end(), key(p))) return i;
  }
  return std::nullopt;
}

}  // namespace mcws
