#pragma once
/// \file
/// \brief Loading and saving workspace clouds in the stage tools.

#include <pcl/io/pcd_io.h>

#include <string>

#include "mcws/io/pcd_stream_writer.h"
#include "mcws/points/point_types.h"

namespace mcws::app {

using WorkspaceCloud = pcl::PointCloud<WorkspacePoint>;

/// \brief Reads a PCD file with PCL's reader after checking all of it that PCL trusts (PCL's
/// reader crashes on some headers and allocates whatever sizes a file claims).
///
/// The header must be text (no control bytes) of the keywords VERSION, FIELDS, SIZE, TYPE,
/// COUNT, WIDTH, HEIGHT, VIEWPOINT, POINTS, DATA in this order (COUNT and VIEWPOINT may be
/// missing; comments `#` anywhere), each field TYPE I, U or F of SIZE 1, 2, 4 or 8 (F: 4 or 8),
/// COUNT >= 1, POINTS = WIDTH x HEIGHT of at most 4 GiB. Binary data must be in the file;
/// binary_compressed sizes must agree with the header and the file; ASCII data must be exactly
/// POINTS rows of numbers of the fields' types, as many as the fields have.
/// \throws mcws::Error naming the file (and the line) when it is missing, unreadable, not such
///   a PCD file, has no x y z, or holds no points.
pcl::PCLPointCloud2 loadPcd(const std::string& path);

/// \brief Loads a PCD file into WorkspacePoint (fields the file lacks are zero, so pcl::PointXYZ
/// and pcl::PointXYZL files load too) whose coordinates the float geometry can handle.
/// \throws mcws::Error naming the file as loadPcd does; when a field of WorkspacePoint (x y z
///   q1..q8 label) has another type or count in the file (PCL would read it as 0); when a finite
///   coordinate exceeds 1e18 in magnitude (squared distances would overflow a float) or the
///   finite points span more than 0 and less than 1e-19 (their squares underflow).
WorkspaceCloud::Ptr loadCloud(const std::string& path);

/// \brief Checks that a cloud spans a volume: a flat cloud (one extent zero) has every point on
/// its 3-D boundary, which is never what was meant. \throws mcws::Error suggesting --plane.
void requireVolume(const WorkspaceCloud& cloud, const std::string& path);

/// \brief Saves the points `indices` of `cloud` as binary PCD, atomically.
void saveCloud(const WorkspaceCloud& cloud, const pcl::Indices& indices, const std::string& path);

}  // namespace mcws::app
