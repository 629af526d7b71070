#pragma once
/// \file
/// \brief Which robot a cloud was made from, recorded as one comment line of its PCD header.

#include <optional>
#include <string>

namespace mcws::io {

/// \brief The robot a cloud's points and joint values come from.
///
/// Recorded in the PCD header, right after PCL's own first comment line, as
///
///     # mcws robot=deicing file=deicing.yaml sha256=<64 hex digits> length_unit=cm
///
/// PCL's reader (and so pcl_viewer, pcl_pcd2ply & co.) skips every header line that starts
/// with '#'. Values are percent-encoded (bytes other than A-Z a-z 0-9 - . _ ~ as %XX), so a name
/// with spaces stays one word. Readers ignore keys they do not know, so later versions may add
/// some.
struct CloudProvenance {
  std::string robot;        ///< the robot's name from its description
  std::string file;         ///< base name of the robot file, for messages
  std::string sha256;       ///< SHA-256 of the robot file's bytes, 64 lowercase hex digits
  std::string length_unit;  ///< the unit of the cloud's coordinates: "m", "cm" or "mm"

  bool operator==(const CloudProvenance& other) const {
    return robot == other.robot && file == other.file && sha256 == other.sha256 &&
           length_unit == other.length_unit;
  }
  bool operator!=(const CloudProvenance& other) const { return !(*this == other); }
};

/// \brief The header line recording `provenance` (without the line end).
/// \throws mcws::Error when a field is empty or the hash is not 64 lowercase hex digits.
std::string provenanceComment(const CloudProvenance& provenance);

/// \brief Whether a PCD header line is an mcws provenance line: after optional blanks, '#', then
/// the word `mcws` (followed by a blank or nothing).
bool isProvenanceComment(const std::string& line);

/// \brief Reads a provenance line (one for which isProvenanceComment() holds).
/// \throws mcws::Error saying what is wrong (a word without '=', a key given twice, a missing or
///   empty robot, file, sha256 or length_unit, a hash that is not 64 lowercase hex digits, a
///   unit other than m, cm, mm, a bad %XX escape); the caller adds the file and line.
CloudProvenance parseProvenanceComment(const std::string& line);

/// \brief SHA-256 of a file's bytes (OpenSSL's EVP interface), as 64 lowercase hex digits.
/// \throws mcws::Error naming the file when it cannot be read.
std::string sha256OfFile(const std::string& path);

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
