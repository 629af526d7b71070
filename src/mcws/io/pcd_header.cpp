#include "mcws/io/pcd_header.h"

#include <pcl/common/io.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <vector>

#include "mcws/core/control_bytes.h"
#include "mcws/core/decimal.h"
#include "mcws/core/error.h"
#include "mcws/core/input_files.h"

namespace mcws::io::pcd {

namespace {

/// The header keywords in the order a PCD (v0.7) header lists them.
constexpr const char* kKeywords[] = {"VERSION", "FIELDS", "SIZE",      "TYPE",   "COUNT",
                                     "WIDTH",   "HEIGHT", "VIEWPOINT", "POINTS", "DATA"};
constexpr std::size_t kKeywordCount = sizeof kKeywords / sizeof kKeywords[0];
/// COUNT (default 1) and VIEWPOINT (PCD v0.6 has none) may be missing; the others may not.
constexpr bool kRequired[] = {true, true, true, true, false, true, true, false, true, true};

constexpr std::uint64_t kMaxHeaderBytes = 1u << 20;  ///< a header (comments too) is text, not data
/// PCL keeps a cloud's bytes in 32-bit sizes (PCLPointCloud2::row_step, the two sizes of
/// binary_compressed data), and pcl::index_t is 32-bit.
constexpr std::uint64_t kMaxDataBytes = std::numeric_limits<std::uint32_t>::max();
constexpr std::uint64_t kMaxPoints = std::numeric_limits<std::int32_t>::max();
/// LZF (PCL's binary_compressed) writes at most 264 bytes as one 3-byte back reference, so n
/// compressed bytes expand to at most 88 n.
constexpr std::uint64_t kMaxLzfExpansion = 88;

/// `text` fit for a one-line message: at most 40 characters, bytes other than printable ASCII
/// as \xNN.
std::string printable(const std::string& text) {
  std::string out;
  for (std::size_t k = 0; k < text.size() && k < 40; ++k) {
    const auto c = static_cast<unsigned char>(text[k]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      out += escapedByte(c);
    }
  }
  return text.size() > 40 ? out + "..." : out;
}

/// `text` split at spaces, tabs and carriage returns (as PCL's reader splits a line).
std::vector<std::string> tokens(const std::string& text) {
  std::vector<std::string> out;
  std::size_t begin = text.find_first_not_of(" \t\r");
  while (begin != std::string::npos) {
    const std::size_t end = text.find_first_of(" \t\r", begin);
    out.push_back(text.substr(begin, end - begin));
    begin = end == std::string::npos ? end : text.find_first_not_of(" \t\r", end);
  }
  return out;
}

/// `text` as a whole number in [0, max], or -1 when it is something else.
std::int64_t parseCount(const std::string& text, std::uint64_t max) {
  if (text.empty() || text.size() > 18 || text.find_first_not_of("0123456789") != text.npos)
    return -1;
  const auto value = std::stoull(text);
  return value <= max ? static_cast<std::int64_t>(value) : -1;
}

/// Why `text` is not a value of `field` as PCL's ASCII reader reads it ("" when it is one): a
/// decimal whole number within the range of an I or U field, a decimal number, nan or inf
/// within the range of an F field.
std::string valueProblem(const std::string& text, const PcdField& field) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const int bits = static_cast<int>(8 * field.size);
  if (field.type == 'F') {
    const double value = std::strtod(begin, &end);
    if (end == begin || *end != '\0' || text.find_first_of("xX") != text.npos)
      return "is not a number";
    const bool overflow = errno == ERANGE && std::isinf(value);
    if (overflow || (field.size == 4 && std::isfinite(value) && std::fabs(value) > FLT_MAX))
      return "is beyond the range of a " + std::to_string(field.size) + "-byte float";
    return "";
  }
  if (field.type == 'U') {
    if (text.empty() || !(std::isdigit(static_cast<unsigned char>(text[0])) || text[0] == '+'))
      return "is not a whole number >= 0";
    const unsigned long long value = std::strtoull(begin, &end, 10);
    if (end == begin || *end != '\0') return "is not a whole number >= 0";
    if (errno == ERANGE || (bits < 64 && value > (1ull << bits) - 1))
      return "is beyond the range of a " + std::to_string(field.size) + "-byte unsigned integer";
    return "";
  }
  const long long value = std::strtoll(begin, &end, 10);
  if (end == begin || *end != '\0') return "is not a whole number";
  const long long limit = bits < 64 ? (1ll << (bits - 1)) : 0;
  if (errno == ERANGE || (bits < 64 && (value < -limit || value > limit - 1)))
    return "is beyond the range of a " + std::to_string(field.size) + "-byte integer";
  return "";
}

/// Checks a PCD header line by line, filling in `header`; throws for the first problem, naming
/// the line.
class HeaderChecker {
 public:
  /// \param in_memory the cloud will be loaded whole by PCL, whose cloud holds at most 4 GiB.
  HeaderChecker(const std::string& path, PcdHeader& header, bool in_memory)
      : path_(path), header_(header), in_memory_(in_memory) {}

  /// Checks the header line `number`: text (no control bytes, no blank around the words), a
  /// comment or a keyword in its place with values that agree with the lines before.
  void line(int number, const std::string& text) {
    number_ = number;
    for (std::size_t k = 0; k < text.size(); ++k) {
      const auto byte = static_cast<unsigned char>(text[k]);
      if (byte == '\r' && k + 1 == text.size()) {
        fail(
            "ends with a carriage return (PCL's reader takes it for a value): write the "
            "header with \\n line ends");
      }
      if ((byte < 0x20 && byte != '\t') || byte == 0x7f) {
        fail("control byte " + printable(text.substr(k, 1)) +
             " in the header (a PCD header is text)");
      }
    }
    if (text.empty()) return;
    const std::size_t first = text.find_first_not_of(" \t");
    if (first != std::string::npos && text[first] == '#') {  // PCL's reader trims, then skips
      comment(text);
      return;
    }
    if (text.front() == ' ' || text.front() == '\t' || text.back() == ' ' || text.back() == '\t')
      fail("white space at the start or end (PCL's reader miscounts the values)");
    const std::vector<std::string> words = tokens(text);
    const std::string& keyword = words[0];
    std::size_t index = 0;
    while (index < kKeywordCount && keyword != kKeywords[index]) ++index;
    if (index == kKeywordCount) {
      fail("unknown header keyword '" + printable(keyword) + "' (a PCD header has " + order() +
           ")");
    }
    if (index < next_)
      fail(keyword + " repeated or out of order (a PCD header has " + order() + ")");
    for (std::size_t k = next_; k < index; ++k) {
      if (kRequired[k]) fail(keyword + " where " + kKeywords[k] + " belongs (" + order() + ")");
    }
    next_ = index + 1;
    const std::vector<std::string> values(words.begin() + 1, words.end());
    if (keyword == "VERSION") version(values);
    if (keyword == "FIELDS") names(values);
    if (keyword == "SIZE") sizes(values);
    if (keyword == "TYPE") types(values);
    if (keyword == "COUNT") counts(values);
    if (keyword == "WIDTH") width_ = single(keyword, values, UINT32_MAX);
    if (keyword == "HEIGHT") height_ = single(keyword, values, UINT32_MAX);
    if (keyword == "VIEWPOINT") viewpoint(values);
    if (keyword == "POINTS") points(values);
    if (keyword == "DATA") data(values);
  }

 private:
  [[noreturn]] void fail(const std::string& message) const {
    throw Error(path_ + ": not a readable PCD file: line " + std::to_string(number_) + ": " +
                message);
  }

  /// Reads the mcws provenance line among the comments; other comments are left alone.
  void comment(const std::string& text) {
    if (!io::isProvenanceComment(text)) return;
    if (header_.provenance) {
      throw Error(path_ + ": line " + std::to_string(number_) +
                  ": a second mcws provenance comment (the first is line " +
                  std::to_string(header_.provenance_line) + ")");
    }
    try {
      header_.provenance = io::parseProvenanceComment(text);
    } catch (const Error& e) {
      throw Error(path_ + ": line " + std::to_string(number_) +
                  ": malformed mcws provenance comment: " + e.what());
    }
    header_.provenance_line = number_;
  }

  static std::string order() {
    std::string text;
    for (const char* keyword : kKeywords) text += (text.empty() ? "" : " ") + std::string(keyword);
    return text + ", in this order";
  }

  void version(const std::vector<std::string>& values) {
    const bool known = values.size() == 1 && (values[0] == "0.7" || values[0] == ".7" ||
                                              values[0] == "0.6" || values[0] == ".6");
    if (!known) fail("VERSION is not 0.7 (or 0.6)");
  }

  void names(const std::vector<std::string>& values) {
    if (values.empty()) fail("FIELDS names no field");
    for (const std::string& name : values) {
      for (const PcdField& f : header_.fields) {
        if (f.name == name && name != "_") fail("field '" + printable(name) + "' appears twice");
      }
      header_.fields.push_back({name});
    }
  }

  /// Checks that `keyword` has one value per field.
  void perField(const std::string& keyword, const std::vector<std::string>& values) const {
    if (values.size() != header_.fields.size()) {
      fail(keyword + " has " + std::to_string(values.size()) + " values for " +
           std::to_string(header_.fields.size()) + " FIELDS");
    }
  }

  void sizes(const std::vector<std::string>& values) {
    perField("SIZE", values);
    for (std::size_t k = 0; k < values.size(); ++k) {
      const std::int64_t size = parseCount(values[k], 8);
      if (size != 1 && size != 2 && size != 4 && size != 8) {
        fail("SIZE '" + printable(values[k]) + "' of field '" + header_.fields[k].name +
             "' is not 1, 2, 4 or 8");
      }
      header_.fields[k].size = static_cast<std::uint64_t>(size);
    }
  }

  void types(const std::vector<std::string>& values) {
    perField("TYPE", values);
    for (std::size_t k = 0; k < values.size(); ++k) {
      PcdField& f = header_.fields[k];
      if (values[k] != "I" && values[k] != "U" && values[k] != "F") {
        fail("TYPE '" + printable(values[k]) + "' of field '" + f.name + "' is not I, U or F");
      }
      f.type = values[k][0];
      if (f.type == 'F' && f.size < 4) {
        fail("field '" + f.name + "' is TYPE F SIZE " + std::to_string(f.size) +
             ": a float has SIZE 4 or 8");
      }
    }
  }

  void counts(const std::vector<std::string>& values) {
    perField("COUNT", values);
    for (std::size_t k = 0; k < values.size(); ++k) {
      const std::int64_t count = parseCount(values[k], kMaxDataBytes);
      if (count < 1) {
        fail("COUNT '" + printable(values[k]) + "' of field '" + header_.fields[k].name +
             "' is not a whole number >= 1");
      }
      header_.fields[k].count = static_cast<std::uint64_t>(count);
    }
  }

  std::uint64_t single(const std::string& keyword, const std::vector<std::string>& values,
                       std::uint64_t max) const {
    const std::int64_t value = values.size() == 1 ? parseCount(values[0], max) : -1;
    if (value < 0) {
      fail(keyword + " is not one whole number in [0, " + std::to_string(max) + "]");
    }
    return static_cast<std::uint64_t>(value);
  }

  void viewpoint(const std::vector<std::string>& values) const {
    const PcdField number{"", 'F', 8, 1};
    bool numbers = values.size() == 7;
    for (const std::string& value : values)
      numbers = numbers && valueProblem(value, number).empty();
    if (!numbers) fail("VIEWPOINT is not 7 numbers (tx ty tz qw qx qy qz)");
  }

  void points(const std::vector<std::string>& values) {
    header_.points = single("POINTS", values, kMaxPoints);
    header_.width = width_;
    header_.height = height_;
    if (width_ * height_ != header_.points) {
      fail("POINTS " + std::to_string(header_.points) +
           " is not WIDTH x HEIGHT = " + std::to_string(width_) + " x " + std::to_string(height_));
    }
    const std::uint64_t point_size = header_.pointSize();
    if (in_memory_ && (point_size > kMaxDataBytes || header_.points > kMaxDataBytes / point_size)) {
      fail("POINTS " + std::to_string(header_.points) + " of " + std::to_string(point_size) +
           " bytes exceed the 4 GiB of a PCL cloud");
    }
  }

  void data(const std::vector<std::string>& values) {
    const bool known = values.size() == 1 && (values[0] == "ascii" || values[0] == "binary" ||
                                              values[0] == "binary_compressed");
    if (!known) fail("DATA is not ascii, binary or binary_compressed");
    header_.data = values[0];
    header_.data_line = number_;
  }

  const std::string& path_;
  PcdHeader& header_;
  bool in_memory_;
  int number_{0};
  std::size_t next_{0};  ///< index of the first keyword that may follow
  std::uint64_t width_{0}, height_{0};
};

/// PCL's reader goes on reading header lines after DATA while the lines are empty or comments;
/// checks that the binary data does not start with something it would take for a keyword.
void checkDataStart(const std::string& path, const PcdHeader& header) {
  std::ifstream in(path, std::ios::binary);
  in.seekg(static_cast<std::streamoff>(header.data_offset));
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t first = line.find_first_not_of(" \t\r\v\f");
    if (first == std::string::npos) {
      if (line.empty()) continue;
      return;
    }
    if (line[first] == '#') continue;
    for (const char* keyword : {"VERSION", "FIELDS", "COLUMNS", "SIZE", "TYPE", "COUNT", "WIDTH",
                                "HEIGHT", "VIEWPOINT", "POINTS", "DATA"}) {
      if (line.compare(first, std::strlen(keyword), keyword) == 0) {
        throw Error(path +
                    ": the binary data begins with bytes PCL's reader takes for the "
                    "header line " +
                    keyword);
      }
    }
    return;
  }
}

}  // namespace

/// Reads and checks the header of the PCD file `path` (of `file_size` bytes), up to and with
/// its DATA line.
/// The checked header of `path`; `in_memory` as HeaderChecker's.
PcdHeader readHeader(const std::string& path, std::uint64_t file_size, bool in_memory) {
  std::ifstream in(path, std::ios::binary);
  std::string head(std::min(file_size, kMaxHeaderBytes), '\0');
  if (!in.read(head.data(), static_cast<std::streamsize>(head.size()))) {
    throw Error(path + ": cannot read the file");
  }
  PcdHeader header;
  HeaderChecker checker(path, header, in_memory);
  std::size_t begin = 0;
  for (int number = 1; header.data.empty(); ++number) {
    const std::size_t end = head.find('\n', begin);
    if (end == std::string::npos && head.size() == kMaxHeaderBytes) {
      throw Error(path + ": not a readable PCD file: no DATA line in the first 1 MiB");
    }
    if (end == std::string::npos && begin >= head.size()) {
      throw Error(path + ": not a readable PCD file: the header has no DATA line");
    }
    const std::string line = head.substr(begin, end - begin);
    begin = end == std::string::npos ? head.size() : end + 1;
    checker.line(number, line);
  }
  header.data_offset = begin;
  return header;
}

/// Checks that the file holds the binary or compressed data its header declares.
void checkBinaryData(const std::string& path, const PcdHeader& header, std::uint64_t file_size) {
  const std::uint64_t available = file_size - header.data_offset;
  const std::uint64_t needed = header.points * header.pointSize();
  const std::string claim = "POINTS " + std::to_string(header.points) + " x " +
                            std::to_string(header.pointSize()) + " bytes";
  if (header.data == "binary" && available < needed) {
    throw Error(path + ": the binary data is " + std::to_string(available) + " bytes, " + claim +
                " need " + std::to_string(needed) + " (the file is cut short)");
  }
  if (header.data == "binary_compressed") {
    std::uint32_t sizes[2] = {0, 0};  // compressed, uncompressed [byte]
    std::ifstream in(path, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(header.data_offset));
    if (available < sizeof sizes || !in.read(reinterpret_cast<char*>(sizes), sizeof sizes)) {
      throw Error(path + ": the compressed data has no sizes (the file is cut short)");
    }
    if (sizes[0] > available - sizeof sizes) {
      throw Error(path + ": the compressed data claims " + std::to_string(sizes[0]) +
                  " bytes, the file holds " + std::to_string(available - sizeof sizes));
    }
    if (sizes[1] != needed) {
      throw Error(path + ": the compressed data claims " + std::to_string(sizes[1]) +
                  " bytes uncompressed, " + claim + " are " + std::to_string(needed));
    }
    if (needed > kMaxLzfExpansion * sizes[0]) {
      throw Error(path + ": " + std::to_string(sizes[0]) + " compressed bytes cannot hold " +
                  claim + " (LZF expands at most 88 times)");
    }
  }
  checkDataStart(path, header);
}

/// Checks every row of ASCII data: as many values as the fields have, each a number of its
/// field's type, exactly POINTS rows (empty lines aside, as PCL's reader skips them).
void checkAsciiData(const std::string& path, const PcdHeader& header) {
  std::vector<const PcdField*> columns;
  for (const PcdField& f : header.fields) columns.insert(columns.end(), f.count, &f);
  std::ifstream in(path, std::ios::binary);
  in.seekg(static_cast<std::streamoff>(header.data_offset));
  std::string line;
  std::uint64_t rows = 0;
  for (int number = header.data_line + 1; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    const std::string where = path + ": line " + std::to_string(number) + ": ";
    if (rows == header.points) {
      throw Error(where + "a row beyond the " + std::to_string(header.points) +
                  " POINTS the header declares");
    }
    const std::vector<std::string> values = tokens(line);
    if (values.size() != columns.size()) {
      throw Error(where + std::to_string(values.size()) + " values, the fields need " +
                  std::to_string(columns.size()));
    }
    for (std::size_t k = 0; k < values.size(); ++k) {
      const std::string problem = valueProblem(values[k], *columns[k]);
      if (!problem.empty()) {
        throw Error(where + "value " + std::to_string(k + 1) + " '" + printable(values[k]) +
                    "' of field '" + columns[k]->name + "' (TYPE " + columns[k]->type + " SIZE " +
                    std::to_string(columns[k]->size) + ") " + problem);
      }
    }
    ++rows;
  }
  if (rows < header.points) {
    throw Error(path + ": the ascii data has " + std::to_string(rows) + " rows, POINTS says " +
                std::to_string(header.points));
  }
}

/// Throws unless the header declares points with fields x, y and z.
void requirePointsWithXyz(const PcdHeader& header, const std::string& path) {
  if (header.points == 0) throw Error(path + ": the cloud has no points");
  for (const char* axis : {"x", "y", "z"}) {
    bool found = false;
    for (const PcdField& f : header.fields) found = found || f.name == axis;
    if (!found) throw Error(path + ": has no field '" + axis + "'");
  }
}

/// PCL's field of a header's field at byte `offset` of the record.
pcl::PCLPointField pclField(const PcdField& f, std::uint32_t offset) {
  static const std::map<std::pair<char, std::uint64_t>, std::uint8_t> kTypes = {
      {{'I', 1}, pcl::PCLPointField::INT8},    {{'I', 2}, pcl::PCLPointField::INT16},
      {{'I', 4}, pcl::PCLPointField::INT32},   {{'I', 8}, pcl::PCLPointField::INT64},
      {{'U', 1}, pcl::PCLPointField::UINT8},   {{'U', 2}, pcl::PCLPointField::UINT16},
      {{'U', 4}, pcl::PCLPointField::UINT32},  {{'U', 8}, pcl::PCLPointField::UINT64},
      {{'F', 4}, pcl::PCLPointField::FLOAT32}, {{'F', 8}, pcl::PCLPointField::FLOAT64}};
  pcl::PCLPointField field;
  field.name = f.name;
  field.offset = offset;
  field.datatype = kTypes.at({f.type, f.size});  // readHeader() admits only these
  field.count = static_cast<std::uint32_t>(f.count);
  return field;
}

/// The size of the cloud file `path` [byte]. \throws mcws::Error when it is missing, not a regular
/// file or unreadable.
std::uint64_t cloudFileSize(const std::string& path) {
  requireInputFile(path, "cloud file");  // a FIFO or device would block or never end
  std::error_code ec;
  const std::uint64_t file_size = std::filesystem::file_size(path, ec);
  if (ec) throw Error(path + ": cannot read the file");
  return file_size;
}

}  // namespace mcws::io::pcd
