#pragma once
/// \file
/// \brief Reading and writing workspace clouds (PCD): every check PCL's reader leaves out, the
/// robot a cloud comes from (its provenance line), and clouds larger than memory read in pieces.

#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <string>

#include "mcws/core/length_unit.h"
#include "mcws/io/pcd_stream_writer.h"
#include "mcws/io/provenance.h"
#include "mcws/points/point_types.h"

namespace mcws::io {

using WorkspaceCloud = pcl::PointCloud<WorkspacePoint>;

/// \brief Reads a PCD file with PCL's reader after checking all of it that PCL trusts (PCL's
/// reader crashes on some headers and allocates whatever sizes a file claims).
///
/// The header must be text (no control bytes) of the keywords VERSION, FIELDS, SIZE, TYPE,
/// COUNT, WIDTH, HEIGHT, VIEWPOINT, POINTS, DATA in this order (COUNT and VIEWPOINT may be
/// missing; comments `#` anywhere), each field TYPE I, U or F of SIZE 1, 2, 4 or 8 (F: 4 or 8),
/// COUNT >= 1, POINTS = WIDTH x HEIGHT of at most 4 GiB. A comment line may start with blanks (as
/// PCL's reader trims); one that reads `# mcws ...` records the robot (CloudProvenance) and
/// must be well formed, at most one. Binary data must be in the file;
/// binary_compressed sizes must agree with the header and the file; ASCII data must be exactly
/// POINTS rows of numbers of the fields' types, as many as the fields have.
/// \throws mcws::Error naming the file (and the line) when it is missing, unreadable, not such
///   a PCD file, has a malformed or second mcws provenance line, has no x y z, or holds no points.
pcl::PCLPointCloud2 readPcd(const std::string& path);

/// \brief The robot a cloud file records in its header (checked as readPcd() checks it), none
/// for clouds of other tools, of a --shape and of mcws before provenance was recorded.
/// \throws mcws::Error as readPcd() does for the header.
std::optional<CloudProvenance> readProvenance(const std::string& path);

/// \brief Checks that a cloud given with --`flag` comes from the --robot file: a cloud that
/// records another SHA-256 (another robot, or the same one whose file was edited since) is an
/// error, and so is one of the same file that records another chain (base_link, tip_link); a
/// cloud that records none passes.
/// \throws mcws::Error "--input 'a.pcd' was made from robot 'x' (x.yaml, sha256 0123456789ab...)
///   but --robot is 'y' (y.yaml, sha256 ...)", or "--input 'a.pcd' was made for the chain from
///   link 'world' to link 'tool0', not for the chain from 'world' to 'ee_link' (--base, --tip)".
void requireSameRobot(const std::string& flag, const std::string& path,
                      const std::optional<CloudProvenance>& recorded, const CloudProvenance& robot);

/// \brief Loads a PCD file into WorkspacePoint (fields the file lacks are zero, so pcl::PointXYZ
/// and pcl::PointXYZL files load too) whose coordinates the float geometry can handle.
/// \throws mcws::Error naming the file as readPcd does; when a field of WorkspacePoint (x y z
///   q1..q8 label) has another type or count in the file (PCL would read it as 0); when a finite
///   coordinate exceeds 1e18 in magnitude (squared distances would overflow a float) or the
///   finite points span more than 0 and less than 1e-19 (their squares underflow).
WorkspaceCloud::Ptr readCloud(const std::string& path);

/// \brief The range of a cloud's finite coordinates, gathered piece by piece, to check as
/// readCloud() checks a whole cloud.
class CoordinateRange {
 public:
  void add(const WorkspaceCloud& cloud);
  /// \brief Adds one point (nothing when a coordinate is not finite).
  void add(const WorkspacePoint& p) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return;
    largest_ = std::max(largest_, p.getArray3fMap().abs().maxCoeff());
    min_ = min_.min(p.getArray3fMap());
    max_ = max_.max(p.getArray3fMap());
  }
  /// \brief Adds the points another range gathered (the result does not depend on the order).
  void merge(const CoordinateRange& other) {
    largest_ = std::max(largest_, other.largest_);
    min_ = min_.min(other.min_);
    max_ = max_.max(other.max_);
  }
  /// \throws mcws::Error naming `path` as readCloud() does for coordinates beyond 1e18 or an
  ///   extent below 1e-19.
  void check(const std::string& path) const;
  /// \brief The extent of the finite coordinates (negative when there were none).
  Eigen::Array3f extent() const { return max_ - min_; }

 private:
  float largest_{0.0f};
  Eigen::Array3f min_{Eigen::Array3f::Constant(std::numeric_limits<float>::max())};
  Eigen::Array3f max_{-Eigen::Array3f::Constant(std::numeric_limits<float>::max())};
};

/// \brief Reads the points of a binary PCD file piece by piece, for clouds larger than memory (and
/// than the 4 GiB of a PCL cloud):
/// the header and the data's size checked as readPcd() checks them, the pieces converted to
/// WorkspacePoint as readCloud() converts a whole cloud. Coordinates are not checked here:
/// gather them in a CoordinateRange.
class PcdPointReader {
 public:
  /// \throws mcws::Error naming the file as readCloud() does, and for ascii or compressed data.
  explicit PcdPointReader(const std::string& path);
  /// \brief The number of points in the file.
  std::uint64_t size() const { return points_; }
  /// \brief Points per piece: 2^20, fewer for records so long that a piece would pass 64 MiB.
  std::size_t piecePoints() const {
    return std::max<std::size_t>(
        1, std::min<std::size_t>(std::size_t{1} << 20, (std::size_t{64} << 20) / point_step_));
  }
  /// \brief The robot the header records, if any.
  const std::optional<CloudProvenance>& provenance() const { return provenance_; }
  /// \brief Points [first, first + count) into `out` (resized).
  /// \throws mcws::Error when they lie beyond the file or cannot be read.
  void read(std::uint64_t first, std::size_t count, WorkspaceCloud& out);
  /// \brief Of points [first, first + count), those with finite x, y, z whose coordinate
  /// `axis` (0 x, 1 y, 2 z) lies in [from, to] into `out`, and their indices in the file into
  /// `index` (both resized). Only these are converted, so that picking a slab costs little more
  /// than reading the bytes.
  void readWithin(std::uint64_t first, std::size_t count, int axis, double from, double to,
                  WorkspaceCloud& out, std::vector<std::uint64_t>& index);

 private:
  /// The bytes of points [first, first + count) into the start of blob_.data.
  void readBytes(std::uint64_t first, std::size_t count);
  /// Converts the first `count` records of blob_.data to `out`, as readCloud() does.
  void convert(std::size_t count, WorkspaceCloud& out);

  std::string path_;
  pcl::PCLPointCloud2 blob_;  ///< the file's fields; its data, the last piece read
  std::uint32_t point_step_{0};
  std::uint32_t xyz_offset_[3]{0, 0, 0};  ///< bytes into a record of x, y, z (float)
  std::uint64_t points_{0}, data_offset_{0};
  std::optional<CloudProvenance> provenance_;
  std::ifstream in_;
};

/// \brief Checks that a cloud spans a volume: a flat cloud (one extent zero) has every point on
/// its 3-D boundary, which is never what was meant. \throws mcws::Error suggesting --plane.
void requireVolume(const WorkspaceCloud& cloud, const std::string& path);
/// \brief requireVolume() for a cloud read in pieces.
void requireVolume(const CoordinateRange& range, const std::string& path);

/// \brief The length unit a cloud records (its mcws comment line), if any.
std::optional<LengthUnit> recordedUnit(const std::string& cloud_path);

/// \brief Saves the points `indices` of `cloud` as binary PCD, atomically, recording
/// `provenance` in the header: pass that of the robot (mcws::robotProvenance(),
/// workspace/sampler.h), or that of the input (readProvenance()) so that it travels through a
/// pipeline.
void writeCloud(const WorkspaceCloud& cloud, const pcl::Indices& indices, const std::string& path,
                const std::optional<CloudProvenance>& provenance = std::nullopt);

}  // namespace mcws::io
