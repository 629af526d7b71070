#pragma once
/// \file
/// \brief Loading and saving workspace clouds in the stage tools.

#include <pcl/io/pcd_io.h>

#include <optional>
#include <string>

#include "mcws/io/pcd_stream_writer.h"
#include "mcws/io/provenance.h"
#include "mcws/points/point_types.h"

namespace mcws {
struct Robot;
}  // namespace mcws

namespace mcws::app {

using WorkspaceCloud = pcl::PointCloud<WorkspacePoint>;

/// \brief Reads a PCD file with PCL's reader after checking all of it that PCL trusts (PCL's
/// reader crashes on some headers and allocates whatever sizes a file claims).
///
/// The header must be text (no control bytes) of the keywords VERSION, FIELDS, SIZE, TYPE,
/// COUNT, WIDTH, HEIGHT, VIEWPOINT, POINTS, DATA in this order (COUNT and VIEWPOINT may be
/// missing; comments `#` anywhere), each field TYPE I, U or F of SIZE 1, 2, 4 or 8 (F: 4 or 8),
/// COUNT >= 1, POINTS = WIDTH x HEIGHT of at most 4 GiB. A comment line may start with blanks (as
/// PCL's reader trims); one that reads `# mcws ...` records the robot (io::CloudProvenance) and
/// must be well formed, at most one. Binary data must be in the file;
/// binary_compressed sizes must agree with the header and the file; ASCII data must be exactly
/// POINTS rows of numbers of the fields' types, as many as the fields have.
/// \throws mcws::Error naming the file (and the line) when it is missing, unreadable, not such
///   a PCD file, has a malformed or second mcws provenance line, has no x y z, or holds no points.
pcl::PCLPointCloud2 loadPcd(const std::string& path);

/// \brief The robot a cloud file records in its header (checked as loadPcd() checks it), none
/// for clouds of other tools, of a --shape and of mcws before provenance was recorded.
/// \throws mcws::Error as loadPcd() does for the header.
std::optional<io::CloudProvenance> readProvenance(const std::string& path);

/// \brief The provenance of clouds made from `robot`: its name, the base name and SHA-256 of the
/// file it was read from (Robot::source), its length unit.
/// \throws mcws::Error naming the file when it cannot be read any more.
io::CloudProvenance robotProvenance(const Robot& robot);

/// \brief Checks that a cloud given with --`flag` comes from the --robot file: a cloud that
/// records another SHA-256 (another robot, or the same one whose file was edited since) is an
/// error; a cloud that records none passes.
/// \throws mcws::Error "--input 'a.pcd' was made from robot 'x' (x.yaml, sha256 0123456789ab...)
///   but --robot is 'y' (y.yaml, sha256 ...)".
void requireSameRobot(const std::string& flag, const std::string& path,
                      const std::optional<io::CloudProvenance>& recorded,
                      const io::CloudProvenance& robot);

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

/// \brief Saves the points `indices` of `cloud` as binary PCD, atomically, recording
/// `provenance` in the header: pass that of the robot (robotProvenance()), or that of the input
/// (readProvenance()) so that it travels through a pipeline.
void saveCloud(const WorkspaceCloud& cloud, const pcl::Indices& indices, const std::string& path,
               const std::optional<io::CloudProvenance>& provenance = std::nullopt);

}  // namespace mcws::app
