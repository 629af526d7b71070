#pragma once
/// \file
/// \brief Collapsing copies of a point to one position.

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <vector>

namespace mcws {

/// \brief The distinct positions of a cloud, in order of first appearance.
/// \param position_of on return, for each input point the index of its position in the result.
pcl::PointCloud<pcl::PointXYZ> uniquePositions(const pcl::PointCloud<pcl::PointXYZ>& cloud,
                                               std::vector<pcl::index_t>& position_of);

}  // namespace mcws
