#pragma once
/// \file
/// \brief The checks of a PCD file that PCL's reader trusts (its header, the size of its data),
/// shared by the cloud readers of cloud_io.h. Internal to mcws::io.

#include <pcl/PCLPointField.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mcws/io/provenance.h"

namespace mcws::io::pcd {

/// One field of a PCD header.
struct PcdField {
  std::string name;
  char type{'F'};          ///< I, U or F
  std::uint64_t size{4};   ///< bytes per value: 1, 2, 4 or 8
  std::uint64_t count{1};  ///< values per point
};

/// A checked PCD header and where its data begins.
struct PcdHeader {
  std::vector<PcdField> fields;
  std::uint64_t points{0};
  std::uint64_t width{0}, height{0};              ///< WIDTH and HEIGHT (POINTS = WIDTH x HEIGHT)
  std::string data;                               ///< ascii, binary or binary_compressed
  std::uint64_t data_offset{0};                   ///< bytes before the data [byte]
  int data_line{0};                               ///< line number of the DATA line
  std::optional<io::CloudProvenance> provenance;  ///< the mcws comment line, if any
  int provenance_line{0};                         ///< its line number

  /// Bytes per point [byte].
  std::uint64_t pointSize() const {
    std::uint64_t bytes = 0;
    for (const PcdField& f : fields) bytes += f.size * f.count;
    return bytes;
  }
};

/// \brief Reads and checks the header of the PCD file `path` (of `file_size` bytes), up to and
/// with its DATA line. `in_memory`: the cloud is to be held whole, so its data must fit the 4 GiB
/// of a PCL cloud.
PcdHeader readHeader(const std::string& path, std::uint64_t file_size, bool in_memory);
/// \brief Checks that binary or binary_compressed data fits the header and the file.
void checkBinaryData(const std::string& path, const PcdHeader& header, std::uint64_t file_size);
/// \brief Checks that ASCII data is exactly POINTS rows of numbers of the fields' types.
void checkAsciiData(const std::string& path, const PcdHeader& header);
/// \brief Throws unless the header declares points with fields x, y and z.
void requirePointsWithXyz(const PcdHeader& header, const std::string& path);
/// \brief PCL's field of a header's field at byte `offset` of the record.
pcl::PCLPointField pclField(const PcdField& f, std::uint32_t offset);
/// \brief The size of the cloud file `path` [byte]. \throws mcws::Error when it is missing, not a
/// regular file or unreadable.
std::uint64_t cloudFileSize(const std::string& path);

}  // namespace mcws::io::pcd
