#pragma once
/// \file
/// \brief Loading and saving workspace clouds in the stage tools.

#include <pcl/io/pcd_io.h>

#include <string>

#include "mcws/io/pcd_stream_writer.h"
#include "mcws/points/point_types.h"

namespace mcws::app {

using WorkspaceCloud = pcl::PointCloud<WorkspacePoint>;

/// \brief Reads a PCD file whose header has been checked (PCL's reader crashes on some files that
/// are not PCD) and which has fields x, y, z and at least one point.
/// \throws mcws::Error naming the file when it is missing, unreadable, not PCD, has no x y z, or
///   holds no points.
pcl::PCLPointCloud2 loadPcd(const std::string& path);

/// \brief Loads a PCD file into WorkspacePoint (fields the file lacks are zero, so pcl::PointXYZ
/// and pcl::PointXYZL files load too).
/// \throws mcws::Error naming the file when it is missing, unreadable, not PCD, has no x y z, or
///   holds no points.
WorkspaceCloud::Ptr loadCloud(const std::string& path);

/// \brief Checks that a cloud spans a volume: a flat cloud (one extent zero) has every point on
/// its 3-D boundary, which is never what was meant. \throws mcws::Error suggesting --plane.
void requireVolume(const WorkspaceCloud& cloud, const std::string& path);

/// \brief Saves the points `indices` of `cloud` as binary PCD, atomically.
void saveCloud(const WorkspaceCloud& cloud, const pcl::Indices& indices, const std::string& path);

}  // namespace mcws::app
