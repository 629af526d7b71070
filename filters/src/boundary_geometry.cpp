#include "mcws/filters/boundary_geometry.h"

#include <pcl/common/common.h>

#include <parallel/algorithm>

#include <algorithm>
#include <cmath>
#include <vector>

#include "mcws/core/error.h"

namespace mcws {

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
  std::vector<std::uint64_t> keys(n);
  for (int round = 0; round < 2; ++round) {
    const double cell = 2.0 * h;  // 2^d cells of spacing h: 4 points (2-D) or 8 (3-D) each
    for (std::size_t i = 0; i < n; ++i) {
      std::uint64_t key = 0;
      for (int k = 0; k < dimensions; ++k) {
        const auto c = static_cast<std::uint64_t>((projected[i].data[k] - min.data[k]) / cell);
        key = key * 2097152u + std::min<std::uint64_t>(c, 2097151u);  // 21 bits per axis
      }
      keys[i] = key;
    }
    __gnu_parallel::sort(keys.begin(), keys.end());
    const auto occupied = static_cast<double>(std::unique(keys.begin(), keys.end()) - keys.begin());
    const double measure = occupied * std::pow(cell, dimensions);
    h = std::pow(measure / static_cast<double>(n), 1.0 / dimensions);
  }
  return h;
}

}  // namespace mcws
