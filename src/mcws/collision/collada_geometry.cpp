#include "mcws/collision/detail/collada_geometry.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

#include "mcws/collision/detail/mesh_checks.h"
#include "mcws/collision/mesh_file.h"
#include "mcws/core/control_bytes.h"
#include "mcws/core/error.h"

namespace mcws {
namespace detail {

ColladaIds colladaIds(const TiXmlElement& root) {
  ColladaIds ids;
  std::vector<const TiXmlElement*> open{&root};
  while (!open.empty()) {
    const TiXmlElement& e = *open.back();
    open.pop_back();
    if (const char* id = e.Attribute("id")) ids.emplace(id, &e);
    // Reversed onto the stack: the elements are met in document order, the first of an id kept.
    for (const TiXmlNode* c = e.LastChild(); c; c = c->PreviousSibling()) {
      if (const TiXmlElement* child = c->ToElement()) open.push_back(child);
    }
  }
  return ids;
}

std::string colladaElement(const TiXmlElement& e) {
  std::string out = "<" + escapedControlBytes(e.Value());
  for (const char* attribute : {"id", "url", "source", "name", "semantic"}) {
    if (const char* value = e.Attribute(attribute)) {
      out += std::string(" ") + attribute + "=" + quotedMeshWord(value);
      break;
    }
  }
  return out + ">";
}

std::string requiredColladaAttribute(const TiXmlElement& e, const char* attribute,
                                     const std::string& source) {
  const char* value = e.Attribute(attribute);
  if (value == nullptr) {
    throw Error("'" + source + "': " + colladaElement(e) + " has no " + attribute +
                " attribute (COLLADA requires it)");
  }
  return value;
}

const TiXmlElement& referencedColladaElement(const TiXmlElement& e, const char* attribute,
                                             const char* wanted, const ColladaIds& ids,
                                             const std::string& source) {
  const char* reference = e.Attribute(attribute);
  if (reference == nullptr) requiredColladaAttribute(e, attribute, source);  // throws
  // Messages made only for an error: a scene of many instances resolves many references.
  const auto where = [&] { return "'" + source + "': " + colladaElement(e) + ": "; };
  if (reference[0] != '#') {
    throw Error(where() + attribute + "=" + quotedMeshWord(reference) +
                " is not a reference '#id' into this file (another file's elements are not read)");
  }
  const auto found = ids.find(reference + 1);
  if (found == ids.end() || std::strcmp(found->second->Value(), wanted) != 0) {
    throw Error(where() + "no " + wanted + " with id " + quotedMeshWord(reference + 1));
  }
  return *found->second;
}

std::string colladaText(const TiXmlElement& e) {
  std::string text;
  for (const TiXmlNode* n = e.FirstChild(); n; n = n->NextSibling()) {
    if (n->ToText() != nullptr) text += n->Value();
  }
  return text;
}

std::vector<std::string_view> colladaWords(const std::string& text) {
  std::vector<std::string_view> words;
  const char* blanks = " \t\n\r";
  for (std::size_t at = text.find_first_not_of(blanks); at != std::string::npos;) {
    const std::size_t end = std::min(text.find_first_of(blanks, at), text.size());
    words.emplace_back(text.data() + at, end - at);
    at = text.find_first_not_of(blanks, end);
  }
  return words;
}

bool parseColladaWholeNumber(std::string_view word, std::uint64_t& value) {
  if (word.empty() || word.size() > 18 || word.find_first_not_of("0123456789") != word.npos) {
    return false;
  }
  value = 0;
  for (const char c : word) value = 10 * value + std::uint64_t(c - '0');
  return true;
}

}  // namespace detail

namespace {

using detail::colladaElement;
using detail::ColladaGeometry;
using detail::ColladaIds;
using detail::quotedMeshWord;

/// A whole-number attribute (a count, a stride, an offset); `absent` when it is not there, or an
/// error when `absent` is negative (COLLADA requires it).
std::uint64_t wholeAttribute(const TiXmlElement& e, const char* attribute, long long absent,
                             const std::string& source) {
  if (e.Attribute(attribute) == nullptr && absent >= 0) return std::uint64_t(absent);
  const std::string text = detail::requiredColladaAttribute(e, attribute, source);
  std::uint64_t value = 0;
  if (!detail::parseColladaWholeNumber(text, value)) {
    throw Error("'" + source + "': " + colladaElement(e) + " " + attribute + "=" +
                quotedMeshWord(text) + ": not a whole number (of at most 18 digits)");
  }
  return value;
}

/// The positions of a mesh: its `<vertices>`' POSITION source, the numbers of that source's
/// `<float_array>` and how its `<accessor>` lays them out.
struct ColladaPositions {
  const TiXmlElement* vertices{nullptr};
  const TiXmlElement* accessor{nullptr};
  const TiXmlElement* array{nullptr};
  std::vector<double> numbers;
  std::uint64_t count{0}, stride{1}, offset{0};
  std::array<std::uint64_t, 3> component{0, 1, 2};  ///< x, y, z within a position's numbers
};

/// The numbers of a `<float_array>`, as many as its count says.
std::vector<double> floatArrayNumbers(const TiXmlElement& array, const std::string& source) {
  const std::uint64_t count = wholeAttribute(array, "count", -1, source);
  const std::string text = detail::colladaText(array);
  const std::vector<std::string_view> words = detail::colladaWords(text);
  const std::string where = "'" + source + "': " + colladaElement(array);
  if (words.size() != count) {
    throw Error(where + ": count='" + std::to_string(count) + "' but it holds " +
                std::to_string(words.size()) + " numbers");
  }
  std::vector<double> numbers(words.size());
  for (std::size_t k = 0; k < words.size(); ++k) {
    if (!detail::parseMeshNumber(words[k], numbers[k])) {
      throw Error(where + " number " + std::to_string(k + 1) + " " + quotedMeshWord(words[k]) +
                  " is not a number");
    }
  }
  return numbers;
}

/// The `<accessor>` of a `<source>`: where in its array each position's x, y, z are.
void readAccessor(const TiXmlElement& source_element, const ColladaIds& ids,
                  const std::string& source, ColladaPositions& out) {
  const TiXmlElement* common = source_element.FirstChildElement("technique_common");
  out.accessor = common ? common->FirstChildElement("accessor") : nullptr;
  if (out.accessor == nullptr) {
    throw Error("'" + source + "': " + colladaElement(source_element) +
                " has no <technique_common><accessor>");
  }
  const TiXmlElement& accessor = *out.accessor;
  out.count = wholeAttribute(accessor, "count", -1, source);
  out.stride = wholeAttribute(accessor, "stride", 1, source);
  out.offset = wholeAttribute(accessor, "offset", 0, source);
  out.array = &detail::referencedColladaElement(accessor, "source", "float_array", ids, source);
  out.numbers = floatArrayNumbers(*out.array, source);
  std::uint64_t slot = 0;
  for (const TiXmlElement* p = accessor.FirstChildElement("param"); p;
       p = p->NextSiblingElement("param"), ++slot) {
    const char* name = p->Attribute("name");
    const std::string axis = name ? name : "";
    if (axis == "X" || axis == "Y" || axis == "Z") out.component[axis[0] - 'X'] = slot;
  }
  const std::string where = "'" + source + "': " + colladaElement(accessor) + ": ";
  const std::uint64_t last = *std::max_element(out.component.begin(), out.component.end());
  if (out.stride <= last) {
    throw Error(where + "stride " + std::to_string(out.stride) +
                " leaves no place for a position's 3 coordinates");
  }
  const std::uint64_t n = out.numbers.size();
  if (out.count > n || out.stride > n || out.offset > n ||
      out.count * out.stride + out.offset > n) {
    throw Error(where + "count " + std::to_string(out.count) + " x stride " +
                std::to_string(out.stride) + " + offset " + std::to_string(out.offset) +
                " is more than the " + std::to_string(n) + " numbers of " +
                colladaElement(*out.array));
  }
}

/// The positions of `mesh`, from its `<vertices>` element's POSITION input.
ColladaPositions readPositions(const TiXmlElement& mesh, const std::string& geometry_where,
                               const ColladaIds& ids, const std::string& source) {
  ColladaPositions out;
  out.vertices = mesh.FirstChildElement("vertices");
  if (out.vertices == nullptr) throw Error(geometry_where + ": its <mesh> has no <vertices>");
  for (const TiXmlElement* input = out.vertices->FirstChildElement("input"); input;
       input = input->NextSiblingElement("input")) {
    if (detail::requiredColladaAttribute(*input, "semantic", source) != "POSITION") continue;
    readAccessor(detail::referencedColladaElement(*input, "source", "source", ids, source), ids,
                 source, out);
    return out;
  }
  throw Error("'" + source + "': " + colladaElement(*out.vertices) +
              " has no <input semantic='POSITION'>");
}

/// How a primitive's `<p>` lists its corners: `stride` indices each (the largest input offset
/// plus one), the position's at `vertex_offset`.
struct CornerLayout {
  std::uint64_t stride{0};
  std::uint64_t vertex_offset{0};
};

CornerLayout readCornerLayout(const TiXmlElement& primitive, const ColladaPositions& positions,
                              const std::string& where, const ColladaIds& ids,
                              const std::string& source) {
  CornerLayout layout;
  bool vertex = false;
  for (const TiXmlElement* input = primitive.FirstChildElement("input"); input;
       input = input->NextSiblingElement("input")) {
    const std::string semantic = detail::requiredColladaAttribute(*input, "semantic", source);
    const std::uint64_t offset = wholeAttribute(*input, "offset", 0, source);
    layout.stride = std::max(layout.stride, offset + 1);
    if (semantic != "VERTEX" || vertex) continue;
    vertex = true;
    layout.vertex_offset = offset;
    if (&detail::referencedColladaElement(*input, "source", "vertices", ids, source) !=
        positions.vertices) {
      throw Error("'" + source + "': " + colladaElement(*input) + ": not this mesh's " +
                  colladaElement(*positions.vertices));
    }
  }
  if (!vertex) throw Error(where + " has no <input semantic='VERTEX'>");
  return layout;
}

/// Builds a geometry's vertices (those its triangles use, each once) and triangles.
class GeometryBuilder {
 public:
  GeometryBuilder(const ColladaPositions& positions, const std::string& source,
                  ColladaGeometry& out)
      : positions_(positions), source_(source), out_(out), vertex_of_(positions.count, -1) {}

  /// The position indices of a `<p>`'s corners. \throws mcws::Error for a word that is not a
  /// whole number, a length that is not whole corners, or a position the accessor does not hold.
  std::vector<std::uint64_t> corners(const TiXmlElement& p, const CornerLayout& layout,
                                     const std::string& where) const {
    const std::string text = detail::colladaText(p);
    const std::vector<std::string_view> words = detail::colladaWords(text);
    if (words.size() % layout.stride != 0) {
      throw Error(where + " <p> holds " + std::to_string(words.size()) +
                  " indices, not whole corners of " + std::to_string(layout.stride) + " each");
    }
    std::vector<std::uint64_t> out;
    out.reserve(words.size() / layout.stride);
    for (std::size_t k = 0; k < words.size(); ++k) {
      std::uint64_t index = 0;
      if (!detail::parseColladaWholeNumber(words[k], index)) {
        throw Error(where + " <p> word " + std::to_string(k + 1) + " " + quotedMeshWord(words[k]) +
                    " is not a whole number (an index)");
      }
      if (k % layout.stride != layout.vertex_offset) continue;
      if (index >= positions_.count) {
        throw Error(where + " <p> word " + std::to_string(k + 1) + ": position index " +
                    std::to_string(index) + ", but " + colladaElement(*positions_.accessor) +
                    " holds " + std::to_string(positions_.count) + " positions (from 0)");
      }
      out.push_back(index);
    }
    return out;
  }

  /// Corners first .. first + n - 1 of `c` as a polygon, fan-triangulated from the first.
  void polygon(const std::vector<std::uint64_t>& c, std::size_t first, std::size_t n) {
    for (std::size_t k = 1; k + 1 < n; ++k) {
      triangle(c[first], c[first + k], c[first + k + 1]);
    }
  }

  /// `c` as a triangle strip: every other triangle turned so that all face the same way.
  void strip(const std::vector<std::uint64_t>& c) {
    for (std::size_t k = 0; k + 2 < c.size(); ++k) {
      if (k % 2 == 0) {
        triangle(c[k], c[k + 1], c[k + 2]);
      } else {
        triangle(c[k + 1], c[k], c[k + 2]);
      }
    }
  }

 private:
  void triangle(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
    out_.triangles.push_back({vertex(a), vertex(b), vertex(c)});
  }

  /// The geometry's vertex of position `index`, added (and checked) the first time.
  int vertex(std::uint64_t index) {
    int& v = vertex_of_[index];
    if (v >= 0) return v;
    Eigen::Vector3d p;
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t at =
          positions_.offset + index * positions_.stride + positions_.component[k];
      p[k] = positions_.numbers[at];
      if (!std::isfinite(p[k]) || !(std::abs(p[k]) <= kLargestMeshCoordinate)) {
        const std::string text = detail::colladaText(*positions_.array);
        detail::checkMeshCoordinate(p[k],
                                    "'" + source_ + "': mesh " + out_.name + " vertex " +
                                        std::to_string(index + 1) + ": " + "xyz"[k],
                                    std::string(detail::colladaWords(text)[at]));
      }
    }
    v = int(out_.vertices.size());
    out_.vertices.push_back(p);
    out_.numbers.push_back(index + 1);
    return v;
  }

  const ColladaPositions& positions_;
  const std::string& source_;
  ColladaGeometry& out_;
  std::vector<int> vertex_of_;  ///< each position's vertex, -1 until a triangle uses it
};

/// Throws unless a primitive holds the number of polygons its count attribute says.
void expectCount(std::uint64_t count, std::uint64_t held, const char* what,
                 const std::string& where) {
  if (count != held) {
    throw Error(where + ": count='" + std::to_string(count) + "' but it holds " +
                std::to_string(held) + " " + what);
  }
}

/// A `<polylist>`: `<vcount>` corners per polygon, all in one `<p>`.
void readPolylist(const TiXmlElement& e, std::uint64_t count,
                  const std::vector<std::uint64_t>& corners, const std::string& where,
                  GeometryBuilder& builder) {
  const TiXmlElement* vcount = e.FirstChildElement("vcount");
  const std::string text = vcount ? detail::colladaText(*vcount) : std::string();
  const std::vector<std::string_view> words = detail::colladaWords(text);
  expectCount(count, words.size(), "<vcount> numbers", where);
  std::size_t first = 0;
  for (std::size_t k = 0; k < words.size(); ++k) {
    std::uint64_t n = 0;
    if (!detail::parseColladaWholeNumber(words[k], n) || n > corners.size() - first) {
      throw Error(where + " <vcount> number " + std::to_string(k + 1) + " " +
                  quotedMeshWord(words[k]) + ": not a whole number of at most the " +
                  std::to_string(corners.size() - first) + " corners <p> has left");
    }
    builder.polygon(corners, first, std::size_t(n));
    first += std::size_t(n);
  }
  if (first != corners.size()) {
    throw Error(where + ": <vcount> adds up to " + std::to_string(first) +
                " corners but <p> holds " + std::to_string(corners.size()));
  }
}

/// One primitive element of a `<mesh>` into `builder`; lines and other elements are skipped.
void readPrimitive(const TiXmlElement& e, const std::string& where,
                   const ColladaPositions& positions, const ColladaIds& ids,
                   const std::string& source, GeometryBuilder& builder) {
  const std::string kind = e.Value();
  const CornerLayout layout = readCornerLayout(e, positions, where, ids, source);
  const std::uint64_t count = wholeAttribute(e, "count", -1, source);
  if (kind == "triangles" || kind == "polylist") {
    std::vector<std::uint64_t> corners;
    if (const TiXmlElement* p = e.FirstChildElement("p")) {
      corners = builder.corners(*p, layout, where);
    }
    if (kind == "polylist") return readPolylist(e, count, corners, where, builder);
    if (corners.size() != 3 * count) {
      throw Error(where + ": count='" + std::to_string(count) + "' but <p> holds " +
                  std::to_string(corners.size()) + " corners, not " + std::to_string(3 * count));
    }
    for (std::size_t first = 0; first < corners.size(); first += 3) {
      builder.polygon(corners, first, 3);
    }
    return;
  }
  // <polygons> (a <p> or a <ph> per polygon), <trifans> and <tristrips> (a <p> each).
  std::uint64_t held = 0;
  for (const TiXmlElement* c = e.FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string name = c->Value();
    const TiXmlElement* p = name == "ph" && kind == "polygons" ? c->FirstChildElement("p")
                            : name == "p"                      ? c
                                                               : nullptr;
    if (p == nullptr) continue;
    ++held;
    const std::vector<std::uint64_t> corners = builder.corners(*p, layout, where);
    if (kind == "tristrips") {
      builder.strip(corners);
    } else {
      builder.polygon(corners, 0, corners.size());
    }
  }
  expectCount(count, held, kind == "polygons" ? "polygons" : "<p> elements", where);
}

}  // namespace

namespace detail {

ColladaGeometry readColladaGeometry(const TiXmlElement& geometry, const ColladaIds& ids,
                                    const std::string& source) {
  ColladaGeometry out;
  const char* name = geometry.Attribute("name");
  if (name == nullptr) name = geometry.Attribute("id");
  out.name = quotedMeshWord(name ? name : "");
  const TiXmlElement* mesh = geometry.FirstChildElement("mesh");
  if (mesh == nullptr) return out;  // a <convex_mesh> or a <spline>: no triangles
  const std::string where = "'" + source + "': geometry " + out.name;
  const auto isPrimitive = [](const std::string& kind) {
    return kind == "triangles" || kind == "polylist" || kind == "polygons" || kind == "trifans" ||
           kind == "tristrips";
  };
  std::size_t number = 0;
  for (const TiXmlElement* e = mesh->FirstChildElement(); e; e = e->NextSiblingElement()) {
    if (isPrimitive(e->Value())) ++number;
  }
  if (number == 0) return out;
  const ColladaPositions positions = readPositions(*mesh, where, ids, source);
  GeometryBuilder builder(positions, source, out);
  number = 0;
  for (const TiXmlElement* e = mesh->FirstChildElement(); e; e = e->NextSiblingElement()) {
    if (!isPrimitive(e->Value())) continue;
    const std::string primitive_where =
        where + " <" + std::string(e->Value()) + "> " + std::to_string(++number);
    readPrimitive(*e, primitive_where, positions, ids, source, builder);
  }
  return out;
}

}  // namespace detail
}  // namespace mcws
