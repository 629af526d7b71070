#include "mcws/filters/boundary_geometry.h"

#include <pcl/common/common.h>

#include <parallel/algorithm>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "mcws/core/decimal.h"
#include "mcws/core/error.h"
#include "mcws/points/unique_positions.h"

namespace mcws {

std::array<int, 2> planeAxes(BoundaryPlane plane) {
  switch (plane) {
    case BoundaryPlane::kXZ:
      return {0, 2};
    case BoundaryPlane::kYZ:
      return {1, 2};
    default:
      return {0, 1};
  }
}

BoundaryPlane parseBoundaryPlane(const std::string& name) {
  if (name == "xy") return BoundaryPlane::kXY;
  if (name == "xz") return BoundaryPlane::kXZ;
  if (name == "yz") return BoundaryPlane::kYZ;
  throw Error("unknown plane '" + name + "' (known: xy, xz, yz)");
}

const char* boundaryPlaneName(BoundaryPlane plane) {
  switch (plane) {
    case BoundaryPlane::kXY:
      return "xy";
    case BoundaryPlane::kXZ:
      return "xz";
    case BoundaryPlane::kYZ:
      return "yz";
    case BoundaryPlane::k3D:
      break;
  }
  return "3d";
}

double meanSpacing(const pcl::PointCloud<pcl::PointXYZ>& projected, int dimensions) {
  const std::size_t n = projected.size();
  if (n < 2) return 0.0;
  pcl::PointXYZ min, max;
  pcl::getMinMax3D(projected, min, max);
  const Eigen::Vector3d extent = (max.getVector3fMap() - min.getVector3fMap()).cast<double>();
  const double largest = extent.head(dimensions).maxCoeff();
  if (!(largest > 0.0)) return 0.0;
  // First guess from the bounding box (degenerate axes count as one spacing thick), then refine
  // the measure by counting occupied cells of about 8 expected points.
  double h = 0.0;
  {
    double measure = 1.0;
    const double floor = largest / std::pow(static_cast<double>(n), 1.0 / dimensions);
    for (int k = 0; k < dimensions; ++k) measure *= std::max(extent[k], floor);
    h = std::pow(measure / static_cast<double>(n), 1.0 / dimensions);
  }
  std::vector<std::uint64_t> keys;
  std::vector<char> seen;
  for (int round = 0; round < 2; ++round) {
    const double cell = 2.0 * h;  // 2^d cells of spacing h: 4 points (2-D) or 8 (3-D) each
    auto coordinate = [&](std::size_t i, int k) {
      const auto c = static_cast<std::uint64_t>((projected[i].data[k] - min.data[k]) / cell);
      return std::min<std::uint64_t>(c, 2097151u);  // 21 bits per axis
    };
    // Occupied cells counted in a table when the box holds few enough cells, else by sorting.
    double cells = 1.0;
    for (int k = 0; k < dimensions; ++k) cells *= extent[k] / cell + 2.0;
    double occupied = 0.0;
    if (cells <= 16.0 * static_cast<double>(n)) {
      std::uint64_t size[3] = {1, 1, 1};
      for (int k = 0; k < dimensions; ++k)
        size[k] = static_cast<std::uint64_t>(extent[k] / cell) + 2;
      seen.assign(size[0] * size[1] * size[2], 0);
      for (std::size_t i = 0; i < n; ++i) {
        std::uint64_t key = 0;
        for (int k = dimensions - 1; k >= 0; --k) key = key * size[k] + coordinate(i, k);
        occupied += !seen[key];
        seen[key] = 1;
      }
    } else {
      keys.resize(n);
      for (std::size_t i = 0; i < n; ++i) {
        std::uint64_t key = 0;
        for (int k = 0; k < dimensions; ++k) key = key * 2097152u + coordinate(i, k);
        keys[i] = key;
      }
      __gnu_parallel::sort(keys.begin(), keys.end());
      occupied = static_cast<double>(std::unique(keys.begin(), keys.end()) - keys.begin());
    }
    const double measure = occupied * std::pow(cell, dimensions);
    h = std::pow(measure / static_cast<double>(n), 1.0 / dimensions);
  }
  return h;
}

namespace {

/// Whether the cloud extends along axis k: more than kFlatExtentShare of its largest extent.
bool extendsAlong(const CloudSummary& cloud, int k) {
  return cloud.extent[k] > kFlatExtentShare * cloud.extent.maxCoeff();
}

constexpr const char* kAxisName[] = {"x", "y", "z"};

}  // namespace

void DistinctCounter::add(float x, float y, float z) {
  if (full()) return;
  const std::array<float, 3> key{x + 0.0f, y + 0.0f, z + 0.0f};  // -0 + 0 = +0
  const auto at = std::lower_bound(seen_.begin(), seen_.end(), key);
  if (at == seen_.end() || *at != key) seen_.insert(at, key);
}

void requireRegionPoints(const CloudSummary& cloud, const std::string& what) {
  const std::string where =
      cloud.plane == BoundaryPlane::k3D
          ? std::string("in 3-D")
          : std::string("in the ") + boundaryPlaneName(cloud.plane) + " plane";
  const std::size_t needed = minimumRegionPoints(cloud.plane);
  if (cloud.distinct < needed) {
    std::string of = std::to_string(cloud.points) + (cloud.points == 1 ? " point" : " points");
    if (cloud.finite < cloud.points)
      of += ", " + std::to_string(cloud.points - cloud.finite) + " not finite";
    throw Error(what + ": " + std::to_string(cloud.distinct) + " distinct finite point" +
                (cloud.distinct == 1 ? "" : "s") + " " + where + " (of " + of +
                "); a region there needs at least " + std::to_string(needed));
  }
  if (cloud.plane == BoundaryPlane::k3D) return;
  int spanned = 0, along = 0;
  for (int k = 0; k < 3; ++k) {
    if (extendsAlong(cloud, k)) {
      ++spanned;
      along = k;
    }
  }
  if (spanned < 2) {
    throw Error(what + ": the points extend along " + kAxisName[along] +
                " only (a line): no region " + where);
  }
}

void requirePlaneFits(const CloudSummary& cloud, const std::string& what) {
  if (cloud.plane == BoundaryPlane::k3D) return;
  const std::array<int, 2> axes = planeAxes(cloud.plane);
  for (const int flat : axes) {
    if (extendsAlong(cloud, flat)) continue;
    // The two axes it extends along (requireRegionPoints() rules out fewer).
    std::string lies;
    for (int k = 0; k < 3; ++k) lies += extendsAlong(cloud, k) ? kAxisName[k] : "";
    throw Error(what + ": the cloud is flat in " + kAxisName[flat] + " (extent " +
                formatNumber(cloud.extent[flat]) + ", its largest " +
                formatNumber(cloud.extent.maxCoeff()) + "), so in the " +
                boundaryPlaneName(cloud.plane) +
                " plane every point is on its boundary and the area is 0; it lies in the " + lies +
                " plane");
  }
}

LengthRange parameterLengths(const CloudSummary& cloud) {
  if (!cloud.spacing) throw Error("parameterLengths: the cloud was summarised without its spacing");
  return {kShortestLengthSpacings * *cloud.spacing, cloud.largest};
}

}  // namespace mcws
