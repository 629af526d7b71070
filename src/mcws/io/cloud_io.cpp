#include "mcws/io/cloud_io.h"

#include <pcl/common/common.h>
#include <pcl/common/io.h>
#include <pcl/common/point_tests.h>
#include <pcl/console/print.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "mcws/core/activity.h"
#include "mcws/core/decimal.h"
#include "mcws/core/error.h"
#include "mcws/io/binary_cloud_loader.h"
#include "mcws/io/pcd_header.h"

namespace mcws::io {

using namespace pcd;

namespace {

/// Largest |coordinate| the geometry accepts: differences stay within 2e18, so a squared 3-D
/// distance within 1.2e37, 28 times below FLT_MAX (3.4e38), room for search radii a few times
/// the cloud's extent. FLANN's kd-tree build recurses without end on coordinates near FLT_MAX,
/// and from about 1e19 on squared distances overflow to infinity.
constexpr float kMaxCoordinate = 1e18f;
/// Smallest extent (largest of the x, y, z spans) of a cloud whose points are not all at one
/// place: its square 1e-38 is about FLT_MIN (1.2e-38); below, squared distances lose their
/// precision and then flush to zero.
constexpr float kMinExtent = 1e-19f;

/// A field's type as a PCD header gives it (TYPE F SIZE 4 COUNT 1).
std::string describe(std::uint8_t datatype, std::uint32_t count) {
  const bool is_float =
      datatype == pcl::PCLPointField::FLOAT32 || datatype == pcl::PCLPointField::FLOAT64;
  const bool is_signed =
      datatype == pcl::PCLPointField::INT8 || datatype == pcl::PCLPointField::INT16 ||
      datatype == pcl::PCLPointField::INT32 || datatype == pcl::PCLPointField::INT64;
  return std::string("TYPE ") +
         (is_float    ? 'F'
          : is_signed ? 'I'
                      : 'U') +
         " SIZE " + std::to_string(pcl::getFieldSize(datatype)) + " COUNT " + std::to_string(count);
}

/// Rejects clouds whose finite coordinates the float geometry cannot handle (see kMaxCoordinate
/// and kMinExtent).
void requireRepresentable(const WorkspaceCloud& cloud, const std::string& path) {
  CoordinateRange range;
  range.add(cloud);
  range.check(path);
}

/// Throws when a field of WorkspacePoint (x y z q1..q8 label) has another type or count in
/// `fields` (PCL would read it as 0).
void requireWorkspaceFieldTypes(const std::vector<pcl::PCLPointField>& fields,
                                const std::string& path) {
  for (const pcl::PCLPointField& wanted : pcl::getFields<WorkspacePoint>()) {
    const auto field = std::find_if(fields.begin(), fields.end(),
                                    [&](const auto& f) { return f.name == wanted.name; });
    if (field == fields.end()) continue;
    if (field->datatype != wanted.datatype || field->count != wanted.count) {
      throw Error(path + ": field '" + field->name + "' is " +
                  describe(field->datatype, field->count) + ", not the " +
                  describe(wanted.datatype, wanted.count) +
                  " it is read as (PCL would read every value as 0)");
    }
  }
}

/// "deicing' (deicing.yaml, sha256 0123456789ab...)" for a mismatch message.
std::string describeRobot(const CloudProvenance& p) {
  return "'" + p.robot + "' (" + p.file + ", sha256 " + p.sha256.substr(0, 12) + "...)";
}

}  // namespace

pcl::PCLPointCloud2 readPcd(const std::string& path) {
  const Activity reading("reading '" + path + "'");
  const std::uint64_t file_size = cloudFileSize(path);
  const PcdHeader header = readHeader(path, file_size, true);
  requirePointsWithXyz(header, path);
  if (header.data == "ascii") {
    checkAsciiData(path, header);
  } else {
    checkBinaryData(path, header, file_size);
  }
  pcl::PCLPointCloud2 blob;
  pcl::console::VERBOSITY_LEVEL level = pcl::console::getVerbosityLevel();
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);  // our own one-line errors instead
  pcl::PCDReader reader;
  const int status = reader.read(path, blob);
  pcl::console::setVerbosityLevel(level);
  if (status < 0) throw Error(path + ": not a readable PCD file (PCL's reader failed on the data)");
  return blob;
}

WorkspaceCloud::Ptr readCloud(const std::string& path) {
  const Activity reading("reading '" + path + "'");
  const std::uint64_t file_size = cloudFileSize(path);
  const PcdHeader header = readHeader(path, file_size, true);
  if (header.data != "binary") return readCloudWithPcl(path);
  // The checks and the cloud of readCloudWithPcl(), the data read straight into the points.
  requirePointsWithXyz(header, path);
  checkBinaryData(path, header, file_size);
  const std::vector<pcl::PCLPointField> fields = pcdFields(header);
  requireWorkspaceFieldTypes(fields, path);
  auto cloud = std::make_shared<WorkspaceCloud>();
  CoordinateRange range;
  loadBinaryCloud(path, header, fields, *cloud, range);
  range.check(path);
  return cloud;
}

WorkspaceCloud::Ptr readCloudWithPcl(const std::string& path) {
  const pcl::PCLPointCloud2 blob = readPcd(path);
  requireWorkspaceFieldTypes(blob.fields, path);
  auto cloud = std::make_shared<WorkspaceCloud>();
  const pcl::console::VERBOSITY_LEVEL level = pcl::console::getVerbosityLevel();
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);  // missing q/label fields are fine
  pcl::fromPCLPointCloud2(blob, *cloud);
  pcl::console::setVerbosityLevel(level);
  if (cloud->empty()) throw Error(path + ": the cloud has no points");
  requireRepresentable(*cloud, path);
  return cloud;
}

void requireVolume(const WorkspaceCloud& cloud, const std::string& path) {
  CoordinateRange range;
  range.add(cloud);
  requireVolume(range, path);
}

void requireVolume(const CoordinateRange& range, const std::string& path) {
  const Eigen::Vector3f extent = range.extent().matrix();
  if (!(extent.minCoeff() >= 0.0f)) throw Error(path + ": the cloud has no finite points");
  const char* axis = "xyz";
  int flattest = 0;
  for (int k = 1; k < 3; ++k) {
    if (extent[k] < extent[flattest]) flattest = k;
  }
  if (!(extent[flattest] > 1e-6f * extent.maxCoeff())) {
    throw Error(path + ": the cloud is flat in " + axis[flattest] + " (extent " +
                formatNumber(extent[flattest]) + ", its largest " +
                formatNumber(extent.maxCoeff()) +
                "), so in 3-D every point is on its boundary; give --plane");
  }
}

std::optional<CloudProvenance> readProvenance(const std::string& path) {
  return readHeader(path, cloudFileSize(path), false).provenance;
}

void requireSameRobot(const std::string& flag, const std::string& path,
                      const std::optional<CloudProvenance>& recorded,
                      const CloudProvenance& robot) {
  if (!recorded) return;
  // One URDF holds several chains (--base, --tip); a cloud that records none predates the record.
  if (recorded->sha256 == robot.sha256 && !recorded->tip_link.empty() &&
      (recorded->base_link != robot.base_link || recorded->tip_link != robot.tip_link)) {
    throw Error("--" + flag + " '" + path + "' was made for the chain from link '" +
                recorded->base_link + "' to link '" + recorded->tip_link +
                "', not for the chain from '" + robot.base_link + "' to '" + robot.tip_link +
                "' (--base, --tip)");
  }
  if (recorded->sha256 == robot.sha256) return;
  const bool edited = recorded->robot == robot.robot && recorded->file == robot.file;
  throw Error("--" + flag + " '" + path + "' was made from robot " + describeRobot(*recorded) +
              " but --robot is " + describeRobot(robot) +
              (edited ? ": the robot file has changed since" : ""));
}

void writeCloud(const WorkspaceCloud& cloud, const pcl::Indices& indices, const std::string& path,
                const std::optional<CloudProvenance>& provenance) {
  PcdStreamWriter<WorkspacePoint> writer(path, indices.size(), PcdFormat::kBinary, provenance);
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

std::optional<LengthUnit> recordedUnit(const std::string& cloud_path) {
  const std::optional<CloudProvenance> recorded = readProvenance(cloud_path);
  if (!recorded) return std::nullopt;
  return lengthUnitNamed(recorded->length_unit);
}

void CoordinateRange::add(const WorkspaceCloud& cloud) {
  for (const auto& p : cloud) add(p);
}

void CoordinateRange::check(const std::string& path) const {
  if (largest_ > kMaxCoordinate) {
    throw Error(path + ": coordinates up to " + formatNumber(largest_, 3) +
                " are beyond what the geometry can represent (|x| <= " +
                formatNumber(kMaxCoordinate, 3) + ")");
  }
  const float extent = (max_ - min_).maxCoeff();
  if (extent > 0.0f && extent < kMinExtent) {
    throw Error(path + ": the points span only " + formatNumber(extent, 3) +
                ", too little for the geometry to resolve (an extent >= " +
                formatNumber(kMinExtent, 3) + ", or all points at one place)");
  }
}

PcdPointReader::PcdPointReader(const std::string& path) : path_(path) {
  const Activity reading("reading '" + path + "'");
  const std::uint64_t file_size = cloudFileSize(path);
  const PcdHeader header = readHeader(path, file_size, false);  // read in pieces
  requirePointsWithXyz(header, path);
  if (header.data != "binary") {
    throw Error(path + ": DATA " + header.data +
                ", but a cloud read in pieces must be DATA binary (as every mcws tool writes; "
                "pcl_convert_pcd_ascii_binary FILE OUT 1 converts one)");
  }
  checkBinaryData(path, header, file_size);
  std::uint32_t offset = 0;
  for (const PcdField& f : header.fields) {
    blob_.fields.push_back(pclField(f, offset));
    offset += static_cast<std::uint32_t>(f.size * f.count);
  }
  requireWorkspaceFieldTypes(blob_.fields, path);  // x, y and z are floats
  point_step_ = offset;
  blob_.height = 1;
  blob_.point_step = point_step_;
  blob_.is_dense = false;
  for (const pcl::PCLPointField& f : blob_.fields) {
    const int axis = f.name == "x" ? 0 : f.name == "y" ? 1 : f.name == "z" ? 2 : -1;
    if (axis >= 0) xyz_offset_[axis] = f.offset;
  }
  points_ = header.points;
  data_offset_ = header.data_offset;
  provenance_ = header.provenance;
  in_.open(path, std::ios::binary);
  if (!in_) throw Error(path + ": cannot read the file");
}

void PcdPointReader::readBytes(std::uint64_t first, std::size_t count) {
  if (first > points_ || count > points_ - first) {
    throw Error(path_ + ": points " + std::to_string(first) + " to " +
                std::to_string(first + count) + " are beyond its " + std::to_string(points_));
  }
  // The buffer keeps its memory: a fresh one for every piece was zeroed and faulted in each time
  // (a third of a slab's time).
  if (blob_.data.size() < count * point_step_) blob_.data.resize(count * point_step_);
  in_.seekg(static_cast<std::streamoff>(data_offset_ + first * point_step_));
  if (!in_.read(reinterpret_cast<char*>(blob_.data.data()),
                static_cast<std::streamsize>(count * point_step_))) {
    throw Error(path_ + ": cannot read points " + std::to_string(first) + " to " +
                std::to_string(first + count) + " (the file changed while it was read?)");
  }
}

void PcdPointReader::convert(std::size_t count, WorkspaceCloud& out) {
  blob_.data.resize(count * point_step_);  // no reallocation: capacity stays
  blob_.width = static_cast<std::uint32_t>(count);
  blob_.row_step = static_cast<std::uint32_t>(count * point_step_);
  const pcl::console::VERBOSITY_LEVEL level = pcl::console::getVerbosityLevel();
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);  // missing q/label fields are fine
  pcl::fromPCLPointCloud2(blob_, out);
  pcl::console::setVerbosityLevel(level);
}

void PcdPointReader::read(std::uint64_t first, std::size_t count, WorkspaceCloud& out) {
  readBytes(first, count);
  convert(count, out);
}

void PcdPointReader::readWithin(std::uint64_t first, std::size_t count, int axis, double from,
                                double to, WorkspaceCloud& out, std::vector<std::uint64_t>& index) {
  readBytes(first, count);
  std::uint8_t* bytes = blob_.data.data();
  index.clear();
  std::size_t kept = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint8_t* record = bytes + k * point_step_;
    float xyz[3];
    for (int a = 0; a < 3; ++a) std::memcpy(&xyz[a], record + xyz_offset_[a], sizeof(float));
    if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2])) continue;
    if (!(xyz[axis] >= from && xyz[axis] <= to)) continue;
    if (kept != k) std::memmove(bytes + kept * point_step_, record, point_step_);
    ++kept;
    index.push_back(first + k);
  }
  convert(kept, out);
}

}  // namespace mcws::io
