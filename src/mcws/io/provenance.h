#pragma once
/// \file
/// \brief Which robot a cloud was made from, recorded as one comment line of its PCD header.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mcws/io/sha256.h"  // sha256OfFile(), whose digests the provenance records

namespace mcws::io {

/// \brief How a cloud's samples were drawn: what, besides the robot, decides where its points lie
/// and how they are labelled, so that mcws_refine can draw more the same way.
///
/// Recorded as `point=tool|flange collision=0|1 fix=NAME:VALUE,...` (`fix=none` for no pinned
/// joint; names percent-encoded, values [rad | length unit] printed to round-trip a double).
/// --quality adds fields but moves no point, so it is not part of the record.
struct SamplingRecord {
  std::string point{"tool"};  ///< the point recorded: "tool" or "flange"
  bool collision{false};      ///< labels are CollisionChecker::label() (mcws_sample --collision)
  /// Joints pinned instead of sampled (mcws_sample --fix), by name [rad | length unit].
  std::vector<std::pair<std::string, double>> fixed;

  bool operator==(const SamplingRecord& other) const {
    return point == other.point && collision == other.collision && fixed == other.fixed;
  }
  bool operator!=(const SamplingRecord& other) const { return !(*this == other); }
};

/// \brief The cloud a boundary was found in (mcws_boundary's --input) and the boundary's size,
/// recorded as `input_points=N input_sha256=HEX boundary_points=K` so that mcws_measure
/// --boundary can check that a boundary is the whole boundary of the cloud it measures, not that
/// of a subset or an older cloud, nor a part of it (mcws_select copies the line as it is).
struct InputCloud {
  std::uint64_t points{0};           ///< points of the input file
  std::string sha256;                ///< SHA-256 of the input file's bytes, 64 lowercase hex digits
  std::uint64_t boundary_points{0};  ///< points mcws_boundary wrote to its boundary output

  bool operator==(const InputCloud& other) const {
    return points == other.points && sha256 == other.sha256 &&
           boundary_points == other.boundary_points;
  }
  bool operator!=(const InputCloud& other) const { return !(*this == other); }
};

/// \brief The robot a cloud's points and joint values come from, and how they were drawn.
///
/// Recorded in the PCD header, right after PCL's own first comment line, as
///
///     # mcws robot=deicing file=deicing.yaml sha256=<64 hex digits> length_unit=cm
///       [base_link=LINK tip_link=LINK] point=tool collision=0 fix=theta3:0
///       [input_points=N input_sha256=<64 hex digits> boundary_points=K]
///
/// (one line). PCL's reader (and so pcl_viewer, pcl_pcd2ply & co.) skips every header line that
/// starts with '#'. Values are percent-encoded (bytes other than A-Z a-z 0-9 - . _ ~ as %XX), so a
/// name with spaces stays one word. Readers ignore keys they do not know, so later versions may
/// add some. Clouds written before the sampling keys existed have no `sampling`; the keys come
/// all three or none. `base_link` and `tip_link` (a URDF robot's chain, Robot::base_link and
/// Robot::tip_link) come both or neither: a D-H robot has none, and clouds written before the
/// chain could be chosen have none.
struct CloudProvenance {
  std::string robot;        ///< the robot's name from its description
  std::string file;         ///< base name of the robot file, for messages
  std::string sha256;       ///< SHA-256 of the robot file's bytes, 64 lowercase hex digits
  std::string length_unit;  ///< the unit of the cloud's coordinates: "m", "cm" or "mm"
  /// A URDF robot's chain: the link whose frame the coordinates are in and the link whose
  /// frame's origin the points are (--base, --tip); both empty for a D-H robot or when not
  /// recorded.
  std::string base_link, tip_link;
  std::optional<SamplingRecord> sampling;  ///< how the samples were drawn, if recorded
  std::optional<InputCloud> input;         ///< a boundary's input cloud (mcws_boundary only)

  CloudProvenance() = default;
  CloudProvenance(std::string robot_name, std::string file_name, std::string file_sha256,
                  std::string unit)
      : robot(std::move(robot_name)),
        file(std::move(file_name)),
        sha256(std::move(file_sha256)),
        length_unit(std::move(unit)) {}

  bool operator==(const CloudProvenance& other) const {
    return robot == other.robot && file == other.file && sha256 == other.sha256 &&
           length_unit == other.length_unit && base_link == other.base_link &&
           tip_link == other.tip_link && sampling == other.sampling && input == other.input;
  }
  bool operator!=(const CloudProvenance& other) const { return !(*this == other); }
};

/// \brief The frame whose origin a cloud's points are, as `provenance` records it: its URDF
/// chain's tip link, else the point of its sampling record ("tool" or "flange" of a D-H robot);
/// none when it records neither.
std::optional<std::string> recordedTip(const CloudProvenance& provenance);

/// \brief What a cloud is of, for titles and file comments: "robot 'arm', tip tool0, from
/// a.pcd" (", tip ..." when recordedTip() knows it), or just `path` when `recorded` is none.
std::string describeCloud(const std::string& path, const std::optional<CloudProvenance>& recorded);

/// \brief `point=... collision=... fix=...` as recorded, for messages.
std::string describeSampling(const SamplingRecord& sampling);

/// \brief The header line recording `provenance` (without the line end).
/// \throws mcws::Error when a field is empty or the hash is not 64 lowercase hex digits.
std::string provenanceComment(const CloudProvenance& provenance);

/// \brief Whether a PCD header line is an mcws provenance line: after optional blanks, '#', then
/// the word `mcws` (followed by a blank or nothing).
bool isProvenanceComment(const std::string& line);

/// \brief Reads a provenance line (one for which isProvenanceComment() holds).
/// \throws mcws::Error saying what is wrong (a word without '=', a key given twice, a missing or
///   empty robot, file, sha256 or length_unit, one of base_link and tip_link without the other, a
///   hash that is not 64 lowercase hex digits, a unit other than m, cm, mm, a bad %XX escape, a
///   point other than tool or flange, a collision other than 0 or 1, a fix that is not none or
///   NAME:VALUE,..., some but not all of point, collision and fix, some but not all of
///   input_points, input_sha256 and boundary_points, or one of them malformed); the caller adds the
///   file and line.
CloudProvenance parseProvenanceComment(const std::string& line);

/// \brief Sets the provenance that every PcdStreamWriter constructed on this thread without one
/// of its own records, while the object lives (the previous one is restored after): for writers
/// that a library function makes (mcws::writeSamples()).
class ScopedProvenance {
 public:
  explicit ScopedProvenance(const CloudProvenance& provenance);
  ~ScopedProvenance();
  ScopedProvenance(const ScopedProvenance&) = delete;
  ScopedProvenance& operator=(const ScopedProvenance&) = delete;

 private:
  std::optional<CloudProvenance> previous_;
};

/// \brief The provenance of the innermost ScopedProvenance alive on this thread, if any.
std::optional<CloudProvenance> scopedProvenance();

}  // namespace mcws::io
