#include "common/cloud_io.h"

#include <pcl/common/common.h>
#include <pcl/common/io.h>
#include <pcl/console/print.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>

#include "mcws/core/error.h"

namespace mcws::app {

namespace {

/// PCL's reader crashes on some files that are not PCD and binds references into empty vectors
/// for clouds of no points, so the header is checked first: a FIELDS line, then a DATA line
/// (ascii, binary or binary_compressed) within the first 64 lines. Returns the POINTS count
/// (-1: not PCD).
long pcdPointCount(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  bool fields = false;
  long points = -1;
  std::string line;
  for (int k = 0; k < 64 && std::getline(in, line); ++k) {
    if (line.rfind("FIELDS ", 0) == 0) fields = true;
    if (line.rfind("POINTS ", 0) == 0) points = std::strtol(line.c_str() + 7, nullptr, 10);
    if (line.rfind("DATA ", 0) == 0) {
      const std::string kind = line.substr(5, line.find_last_not_of(" \r") - 4);
      const bool known = kind == "ascii" || kind == "binary" || kind == "binary_compressed";
      return fields && known && points >= 0 ? points : -1;
    }
  }
  return -1;
}

}  // namespace

pcl::PCLPointCloud2 loadPcd(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw Error(
        path + ": " +
        (std::filesystem::exists(path, ec) ? "not a regular file" : "cloud file does not exist"));
  }
  const long count = pcdPointCount(path);
  if (count < 0) throw Error(path + ": not a readable PCD file");
  if (count == 0) throw Error(path + ": the cloud has no points");
  pcl::PCLPointCloud2 blob;
  pcl::console::VERBOSITY_LEVEL level = pcl::console::getVerbosityLevel();
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);  // our own one-line errors instead
  pcl::PCDReader reader;
  const int status = reader.read(path, blob);
  pcl::console::setVerbosityLevel(level);
  if (status < 0) throw Error(path + ": not a readable PCD file");
  for (const char* axis : {"x", "y", "z"}) {
    if (pcl::getFieldIndex(blob, axis) < 0) {
      throw Error(path + ": has no field '" + axis + "'");
    }
  }
  if (blob.width * blob.height == 0) throw Error(path + ": the cloud has no points");
  return blob;
}

WorkspaceCloud::Ptr loadCloud(const std::string& path) {
  const pcl::PCLPointCloud2 blob = loadPcd(path);
  auto cloud = std::make_shared<WorkspaceCloud>();
  const pcl::console::VERBOSITY_LEVEL level = pcl::console::getVerbosityLevel();
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);  // missing q/label fields are fine
  pcl::fromPCLPointCloud2(blob, *cloud);
  pcl::console::setVerbosityLevel(level);
  if (cloud->empty()) throw Error(path + ": the cloud has no points");
  return cloud;
}

void requireVolume(const WorkspaceCloud& cloud, const std::string& path) {
  Eigen::Vector3f min = Eigen::Vector3f::Constant(std::numeric_limits<float>::max());
  Eigen::Vector3f max = -min;
  std::size_t finite = 0;
  for (const auto& p : cloud) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      continue;
    }
    min = min.cwiseMin(p.getVector3fMap());
    max = max.cwiseMax(p.getVector3fMap());
    ++finite;
  }
  if (finite == 0) throw Error(path + ": the cloud has no finite points");
  const Eigen::Vector3f extent = max - min;
  const char* axis = "xyz";
  for (int k = 0; k < 3; ++k) {
    if (!(extent[k] > 1e-6f * extent.maxCoeff())) {
      throw Error(path + ": the cloud is flat (" + axis[k] +
                  " extent 0), so in 3-D every point "
                  "is on its boundary; give --plane");
    }
  }
}

void saveCloud(const WorkspaceCloud& cloud, const pcl::Indices& indices, const std::string& path) {
  io::PcdStreamWriter<WorkspacePoint> writer(path, indices.size());
  std::vector<WorkspacePoint, Eigen::aligned_allocator<WorkspacePoint>> chunk;
  chunk.reserve(std::min<std::size_t>(indices.size(), 1u << 16));
  for (std::size_t begin = 0; begin < indices.size(); begin += 1u << 16) {
    chunk.clear();
    const std::size_t end = std::min(indices.size(), begin + (1u << 16));
    for (std::size_t k = begin; k < end; ++k) chunk.push_back(cloud[indices[k]]);
    writer.write(chunk.data(), chunk.size());
  }
  writer.commit();
}

}  // namespace mcws::app
