#pragma once
/// \file
/// \brief Loading the binary data of a checked PCD file straight into a WorkspacePoint cloud, in
/// parallel pieces: the cloud PCL's reader and pcl::fromPCLPointCloud2 make of it, without the
/// intermediate copy. Internal to mcws::io (readCloud() uses it for DATA binary).

#include <pcl/PCLPointField.h>

#include <string>
#include <vector>

#include "mcws/io/cloud_io.h"
#include "mcws/io/pcd_header.h"

namespace mcws::io {

/// \brief The fields of a header as PCL's reader describes them: each at the byte offset the
/// sizes and counts of the fields before it add up to.
std::vector<pcl::PCLPointField> pcdFields(const pcd::PcdHeader& header);

/// \brief Loads the DATA binary points of `path` into `cloud`, whose every point, width, height
/// and is_dense are then what pcl::PCDReader::read() followed by pcl::fromPCLPointCloud2() give
/// (the bytes PCL's field mapping copies, is_dense false when a float value of any field is not
/// finite), and adds the points' coordinates to `range`. The file is read with pread() in pieces
/// converted on all OpenMP threads.
/// \param header checked by readHeader(), requirePointsWithXyz() and checkBinaryData().
/// \param fields pcdFields(header), whose WorkspacePoint fields have the types of the point.
/// \throws mcws::Error naming the file when its data cannot be read (it changed since the checks).
void loadBinaryCloud(const std::string& path, const pcd::PcdHeader& header,
                     const std::vector<pcl::PCLPointField>& fields, WorkspaceCloud& cloud,
                     CoordinateRange& range);

/// \brief readCloud() through PCL's reader and pcl::fromPCLPointCloud2() (the path for ascii and
/// binary_compressed data, and the reference the binary loader is tested against).
/// \throws mcws::Error as readCloud().
WorkspaceCloud::Ptr readCloudWithPcl(const std::string& path);

}  // namespace mcws::io
