#include "mcws/collision/mesh_file.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <unordered_map>

#include "mcws/collision/collada_mesh.h"
#include "mcws/collision/detail/mesh_checks.h"
#include "mcws/core/control_bytes.h"
#include "mcws/core/decimal.h"
#include "mcws/core/error.h"
#include "mcws/core/file_name.h"
#include "mcws/core/input_files.h"
#include "mcws/core/text_file.h"

namespace mcws {
namespace {

/// A binary STL: an 80-byte header, a little-endian uint32 triangle count, then per triangle a
/// normal and three corners (12 float32) and a uint16 attribute.
constexpr std::size_t kStlHeaderBytes = 84;
constexpr std::size_t kStlTriangleBytes = 50;

bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

bool equalsIgnoringCase(std::string_view word, std::string_view keyword) {
  if (word.size() != keyword.size()) return false;
  for (std::size_t k = 0; k < word.size(); ++k) {
    char c = word[k];
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    if (c != keyword[k]) return false;
  }
  return true;
}

/// Collects the corners of triangles into vertices, one per distinct position.
class VertexMerger {
 public:
  explicit VertexMerger(TriangleMesh& mesh) : mesh_(mesh) {}

  int add(const Eigen::Vector3d& p) {
    std::array<std::uint64_t, 3> key;
    for (int k = 0; k < 3; ++k) {
      const double value = p[k] == 0.0 ? 0.0 : p[k];  // -0 and 0 are one position
      std::memcpy(&key[k], &value, sizeof value);
    }
    const auto [it, added] = index_.emplace(key, int(mesh_.vertices.size()));
    if (added) mesh_.vertices.push_back(p);
    return it->second;
  }

 private:
  struct Hash {
    std::size_t operator()(const std::array<std::uint64_t, 3>& key) const {
      std::uint64_t h = 1469598103934665603ULL;
      for (std::uint64_t word : key) h = (h ^ word) * 1099511628211ULL;
      return std::size_t(h ^ (h >> 29));
    }
  };
  TriangleMesh& mesh_;
  std::unordered_map<std::array<std::uint64_t, 3>, int, Hash> index_;
};

std::uint32_t littleEndian32(const char* bytes) {
  std::uint32_t value = 0;
  for (int k = 3; k >= 0; --k) value = (value << 8) | static_cast<unsigned char>(bytes[k]);
  return value;
}

TriangleMesh parseBinaryStl(const std::string& bytes, const std::string& source) {
  const std::string where = "'" + source + "'";
  const std::size_t count = littleEndian32(bytes.data() + 80);
  TriangleMesh mesh;
  mesh.triangles.reserve(count);
  VertexMerger merger(mesh);
  for (std::size_t t = 0; t < count; ++t) {
    const char* triangle = bytes.data() + kStlHeaderBytes + t * kStlTriangleBytes;
    std::array<int, 3> corners{};
    for (int c = 0; c < 3; ++c) {
      Eigen::Vector3d p;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t bits = littleEndian32(triangle + 12 * (c + 1) + 4 * k);
        float value = 0.f;
        std::memcpy(&value, &bits, sizeof value);
        if (!(std::abs(value) <= kLargestMeshCoordinate)) {  // the message only when it fails
          detail::checkMeshCoordinate(
              value,
              where + ": triangle " + std::to_string(t + 1) + " corner " + std::to_string(c + 1) +
                  ": " + std::string(1, "xyz"[k]),
              formatNumber(value, 9));  // 9 digits read back as the same float
        }
        p[k] = value;
      }
      corners[c] = merger.add(p);
    }
    mesh.triangles.push_back(corners);
  }
  return mesh;
}

/// The words of a text with the line each is on.
class Words {
 public:
  explicit Words(const std::string& text) : text_(text) {}

  /// The next word, "" at the end of the text (line() then stays that of the last word).
  std::string_view next() {
    const int last_line = line_;
    while (at_ < text_.size() && isSpace(text_[at_])) {
      if (text_[at_] == '\n') ++line_;
      ++at_;
    }
    if (at_ == text_.size()) line_ = last_line;
    const std::size_t begin = at_;
    while (at_ < text_.size() && !isSpace(text_[at_])) ++at_;
    return std::string_view(text_).substr(begin, at_ - begin);
  }

  /// Skips the rest of the current line (a solid's name).
  void skipLine() {
    while (at_ < text_.size() && text_[at_] != '\n') ++at_;
  }

  int line() const { return line_; }

 private:
  const std::string& text_;
  std::size_t at_{0};
  int line_{1};
};

TriangleMesh parseAsciiStl(const std::string& text, const std::string& source) {
  Words words(text);
  const auto where = [&] { return "'" + source + "': line " + std::to_string(words.line()); };
  const auto expect = [&](std::string_view keyword) {
    const std::string_view word = words.next();
    if (!equalsIgnoringCase(word, keyword)) {
      throw Error(
          where() + ": expected '" + std::string(keyword) + "', found " +
          (word.empty() ? std::string("the end of the file") : detail::quotedMeshWord(word)));
    }
  };
  const auto number = [&](const std::string& what) {
    const std::string_view word = words.next();
    double value = 0.0;
    if (!detail::parseMeshNumber(word, value)) {
      throw Error(where() + ": " + what + ": " +
                  (word.empty() ? std::string("the file ends")
                                : detail::quotedMeshWord(word) + " is not a number"));
    }
    return std::make_pair(value, std::string(word));
  };

  TriangleMesh mesh;
  VertexMerger merger(mesh);
  expect("solid");
  words.skipLine();
  for (std::string_view word = words.next(); !word.empty(); word = words.next()) {
    if (equalsIgnoringCase(word, "endsolid")) {
      words.skipLine();
      word = words.next();
      if (word.empty()) break;
      if (!equalsIgnoringCase(word, "solid")) {
        throw Error(where() + ": expected 'solid' or the end of the file after 'endsolid', found " +
                    detail::quotedMeshWord(word));
      }
      words.skipLine();
      continue;
    }
    if (!equalsIgnoringCase(word, "facet")) {
      throw Error(where() + ": expected 'facet' or 'endsolid', found " +
                  detail::quotedMeshWord(word));
    }
    const std::string triangle = "triangle " + std::to_string(mesh.triangles.size() + 1);
    expect("normal");
    for (int k = 0; k < 3; ++k) number(triangle + ": normal");  // read, not used
    expect("outer");
    expect("loop");
    std::array<int, 3> corners{};
    for (int c = 0; c < 3; ++c) {
      expect("vertex");
      const std::string corner = triangle + " corner " + std::to_string(c + 1);
      Eigen::Vector3d p;
      for (int k = 0; k < 3; ++k) {
        const auto [value, written] = number(corner);
        detail::checkMeshCoordinate(
            value, where() + ": " + corner + ": " + std::string(1, "xyz"[k]), written);
        p[k] = value;
      }
      corners[c] = merger.add(p);
    }
    expect("endloop");
    expect("endfacet");
    mesh.triangles.push_back(corners);
  }
  return mesh;
}

TriangleMesh parseStl(const std::string& bytes, const std::string& source) {
  if (bytes.size() >= kStlHeaderBytes) {
    const std::uint64_t count = littleEndian32(bytes.data() + 80);
    if (bytes.size() == kStlHeaderBytes + count * kStlTriangleBytes)
      return parseBinaryStl(bytes, source);
  }
  std::size_t first = 0;
  while (first < bytes.size() && isSpace(bytes[first])) ++first;
  const bool ascii = equalsIgnoringCase(std::string_view(bytes).substr(first, 5), "solid");
  if (ascii && bytes.find('\0') == std::string::npos) return parseAsciiStl(bytes, source);
  const std::string as_ascii = ascii ? "starting with 'solid' (ASCII STL) but holding a NUL byte"
                                     : "not starting with 'solid' (ASCII STL)";
  const std::string size = std::to_string(bytes.size()) + " bytes";
  if (bytes.size() < kStlHeaderBytes) {
    throw Error("'" + source + "': not an STL file: " + size +
                ", too short for a binary STL (84-byte header), and " + as_ascii);
  }
  const std::uint64_t count = littleEndian32(bytes.data() + 80);
  throw Error("'" + source + "': not an STL file: " + as_ascii + ", and its size (" + size +
              ") is not that of a binary STL of the " + std::to_string(count) +
              " triangles its header counts (" +
              std::to_string(kStlHeaderBytes + count * kStlTriangleBytes) + " bytes)");
}

/// A face of an OBJ file, resolved once every vertex is known.
struct ObjFace {
  std::vector<long long> corners;  ///< 0-based vertex indices, possibly out of range
  int line;
};

/// The words of an OBJ line, its comment (from '#') cut off.
std::vector<std::string_view> objWords(std::string_view content) {
  content = content.substr(0, content.find('#'));
  std::vector<std::string_view> words;
  for (std::size_t k = 0; k < content.size();) {
    while (k < content.size() && isSpace(content[k])) ++k;
    const std::size_t start = k;
    while (k < content.size() && !isSpace(content[k])) ++k;
    if (k > start) words.push_back(content.substr(start, k - start));
  }
  return words;
}

/// The point of a 'v' line (`words`, "v" first), named `vertex` in errors.
Eigen::Vector3d objVertex(const std::vector<std::string_view>& words, const std::string& vertex) {
  if (words.size() < 4 || words.size() > 8) {
    throw Error(vertex + ": 'v' takes x y z (and an optional w, or r g b), not " +
                std::to_string(words.size() - 1) + " values");
  }
  Eigen::Vector3d p;
  for (std::size_t k = 1; k < words.size(); ++k) {
    double value = 0.0;
    if (!detail::parseMeshNumber(words[k], value))
      throw Error(vertex + ": " + detail::quotedMeshWord(words[k]) + " is not a number");
    if (k <= 3) {
      detail::checkMeshCoordinate(value, vertex + ": " + std::string(1, "xyz"[k - 1]),
                                  std::string(words[k]));
      p[int(k) - 1] = value;
    }
  }
  return p;
}

/// The face of an 'f' line (`words`, "f" first) at `line`, named `where` in errors, with
/// `vertex_count` vertices read before it (a negative index counts back from the last).
ObjFace objFace(const std::vector<std::string_view>& words, const std::string& where, int line,
                std::size_t vertex_count) {
  if (words.size() < 4) {
    throw Error(where + ": a face needs at least 3 corners, this one has " +
                std::to_string(words.size() - 1));
  }
  ObjFace face{{}, line};
  for (std::size_t k = 1; k < words.size(); ++k) {
    const std::string_view index = words[k].substr(0, words[k].find('/'));
    long long value = 0;
    const auto [stop, error] = std::from_chars(index.data(), index.data() + index.size(), value);
    if (index.empty() || stop != index.data() + index.size() || error != std::errc() ||
        value == 0) {
      throw Error(where + ": face corner " + detail::quotedMeshWord(words[k]) +
                  " does not start with a vertex number (1, 2, ... or -1, -2, ... from the "
                  "last vertex)");
    }
    face.corners.push_back(value > 0 ? value - 1 : static_cast<long long>(vertex_count) + value);
  }
  return face;
}

/// Adds the triangles of `faces` (fans from each face's first corner) to `mesh`, whose vertices
/// are all read. \throws mcws::Error naming `source` and the line for a missing vertex.
void addObjFaces(const std::vector<ObjFace>& faces, const std::string& source, TriangleMesh& mesh) {
  const auto vertex_count = static_cast<long long>(mesh.vertices.size());
  for (const ObjFace& face : faces) {
    for (long long corner : face.corners) {
      if (corner < 0 || corner >= vertex_count) {
        throw Error("'" + source + "': line " + std::to_string(face.line) +
                    ": a face refers to a missing vertex (" +
                    (corner < 0 ? "before the first" : "number " + std::to_string(corner + 1)) +
                    "; the file has " + std::to_string(vertex_count) + ")");
      }
    }
    for (std::size_t k = 2; k < face.corners.size(); ++k) {
      mesh.triangles.push_back(
          {int(face.corners[0]), int(face.corners[k - 1]), int(face.corners[k])});
    }
  }
}

TriangleMesh parseObj(const std::string& text, const std::string& source) {
  TriangleMesh mesh;
  std::vector<ObjFace> faces;
  int line = 0;
  for (std::size_t begin = 0; begin < text.size();) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    ++line;
    const std::string_view content = std::string_view(text).substr(begin, end - begin);
    begin = end + 1;
    const std::vector<std::string_view> words = objWords(content);
    if (words.empty()) continue;
    const std::string where = "'" + source + "': line " + std::to_string(line);
    const std::string_view keyword = words[0];
    if (keyword == "v") {
      mesh.vertices.push_back(
          objVertex(words, where + ": vertex " + std::to_string(mesh.vertices.size() + 1)));
    } else if (keyword == "f") {
      faces.push_back(objFace(words, where, line, mesh.vertices.size()));
    } else if (keyword != "vt" && keyword != "vn" && keyword != "vp" && keyword != "l" &&
               keyword != "p" && keyword != "g" && keyword != "o" && keyword != "s" &&
               keyword != "usemtl" && keyword != "mtllib") {
      throw Error(where + ": unknown keyword " + detail::quotedMeshWord(keyword) +
                  " (v and f are read; vt, vn, vp, l, p, g, o, s, usemtl and mtllib skipped)");
    }
  }
  addObjFaces(faces, source, mesh);
  return mesh;
}

}  // namespace

namespace detail {

/// At most this many bytes of a word are quoted in a message.
constexpr std::size_t kMeshQuotedBytes = 32;

/// `word` in quotes for a message: cut to kMeshQuotedBytes, control bytes written as \xNN so that a
/// binary file's bytes cannot break the one-line message.
std::string quotedMeshWord(std::string_view word) {
  return "'" + escapedControlBytes(word.substr(0, kMeshQuotedBytes)) +
         (word.size() > kMeshQuotedBytes ? "...'" : "'");
}

/// The number a whole word spells ("1.5", "-2e3", "+4", "nan"), or false.
bool parseMeshNumber(std::string_view word, double& value) {
  if (word.size() > 1 && word[0] == '+' && word[1] != '+' && word[1] != '-') word.remove_prefix(1);
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (word.empty() || end != word.data() + word.size()) return false;
  if (error == std::errc::result_out_of_range) {
    // Too large for a double (refused by the caller as out of range) or too small (0 or a
    // denormal); strtod tells which.
    value = std::strtod(std::string(word).c_str(), nullptr);
    return true;
  }
  return error == std::errc();
}

/// Throws unless a coordinate is finite and at most kLargestMeshCoordinate in size. `where`
/// names it ("'a.obj': line 5: vertex 3: y"), `text` is as the file writes it: "inf" is not a
/// finite number, "1e400" (a finite number too large for a double) is out of range.
void checkMeshCoordinate(double value, const std::string& where, const std::string& text) {
  std::string lower = text;
  for (char& c : lower) c = c >= 'A' && c <= 'Z' ? char(c - 'A' + 'a') : c;
  if (std::isnan(value) || lower.find("inf") != std::string::npos)
    throw Error(where + " coordinate " + text + " is not a finite number");
  if (!(std::abs(value) <= kLargestMeshCoordinate))
    throw Error(where + " coordinate " + text + " is out of range (at most 1e9 in size)");
}

}  // namespace detail

TriangleMesh parseMesh(const std::string& bytes, MeshFormat format, const std::string& source) {
  TriangleMesh mesh;
  switch (format) {
    case MeshFormat::kStl:
      mesh = parseStl(bytes, source);
      break;
    case MeshFormat::kObj:
      mesh = parseObj(bytes, source);
      break;
    case MeshFormat::kCollada:
      mesh = parseColladaMesh(bytes, source);
      break;
  }
  if (mesh.triangles.empty()) throw Error("'" + source + "': holds no triangles");
  return mesh;
}

TriangleMesh readMeshFile(const std::string& path) {
  std::error_code ec;
  if (!path.empty() && !std::filesystem::exists(path, ec))
    throw Error("'" + path + "': file does not exist");
  const std::string extension = lowercaseExtension(path);
  MeshFormat format = MeshFormat::kStl;
  if (extension == ".obj") {
    format = MeshFormat::kObj;
  } else if (extension == ".dae") {
    format = MeshFormat::kCollada;
  } else if (extension != ".stl") {
    throw Error("'" + path + "': not an STL, OBJ or COLLADA (.dae) file (by its extension)");
  }
  requireInputFile(path, "collision mesh");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("'" + path + "': cannot open: " + std::strerror(errno));
  const std::string bytes = readRest(in);
  if (in.bad()) throw Error("'" + path + "': cannot read");
  return parseMesh(bytes, format, path);
}

}  // namespace mcws
