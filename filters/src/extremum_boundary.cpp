#include "mcws/filters/extremum_boundary.h"

#include "mcws/filters/impl/extremum_boundary.hpp"
#include "mcws/points/point_types.h"

namespace mcws {

template class ExtremumBoundary<pcl::PointXYZ>;
template class ExtremumBoundary<pcl::PointXYZL>;
template class ExtremumBoundary<WorkspacePoint>;

}  // namespace mcws
