#include "mcws/filters/orthant_boundary.h"

#include <algorithm>
#include <cmath>

#include "mcws/filters/impl/orthant_boundary.hpp"
#include "mcws/points/point_types.h"

namespace mcws {

double orthantAutoFactor(std::size_t n, int dimensions) {
  // Expected false boundary points 16 n P(orthant empty) = 1/2 (filters/README.md).
  const double log_term = std::log(32.0 * static_cast<double>(std::max<std::size_t>(n, 2)));
  return dimensions == 2 ? std::sqrt(4.0 / M_PI * log_term) : std::cbrt(6.0 / M_PI * log_term);
}

template class OrthantBoundary<pcl::PointXYZ>;
template class OrthantBoundary<pcl::PointXYZL>;
template class OrthantBoundary<WorkspacePoint>;

}  // namespace mcws
