#include "mcws/filters/grid_boundary.h"

#include <algorithm>
#include <cmath>

#include "mcws/filters/impl/grid_boundary.hpp"
#include "mcws/points/point_types.h"

namespace mcws {

double baselineCellSize(std::size_t n, double spacing, int dimensions) {
  // m = ln(2 n / m): a fixed point reached in a few steps from m = ln(2 n) (m >= 1).
  const double points = static_cast<double>(std::max<std::size_t>(n, 1));
  double m = std::max(1.0, std::log(2.0 * points));
  for (int step = 0; step < 8; ++step) m = std::max(1.0, std::log(2.0 * points / m));
  return spacing * std::pow(m, 1.0 / dimensions);
}

template class GridBoundary<pcl::PointXYZ>;
template class GridBoundary<pcl::PointXYZL>;
template class GridBoundary<WorkspacePoint>;

}  // namespace mcws
