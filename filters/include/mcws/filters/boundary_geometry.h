#pragma once
/// \file
/// \brief What the boundary filters share: the plane a 2-D method works in, the projection of a
/// cloud onto it, and the mean point spacing of a cloud.

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <string>

namespace mcws {

/// \brief Where a boundary method works: in 3-D, or in one coordinate plane.
enum class BoundaryPlane { k3D, kXY, kXZ, kYZ };

/// \brief "xy", "xz", "yz" -> plane. \throws mcws::Error naming the bad name.
BoundaryPlane parseBoundaryPlane(const std::string& name);
/// \brief Name of a plane ("3d", "xy", "xz", "yz").
const char* boundaryPlaneName(BoundaryPlane plane);
/// \brief 2 for a plane, 3 for k3D.
inline int boundaryDimensions(BoundaryPlane plane) { return plane == BoundaryPlane::k3D ? 3 : 2; }

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

}  // namespace mcws
