#pragma once
/// \file
/// \brief mcws's COLLADA reader, the geometry half (collada_geometry.cpp): a `<geometry>`'s
/// triangles as written, every size and index checked against what the file holds before
/// anything is allocated by it; and the pieces the scene half (collada_mesh.cpp) shares with it.
/// Internal to mcws::parseColladaMesh().

#include <tinyxml.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace mcws {
namespace detail {

/// The elements of a COLLADA document by their id (the first element of each id), for the
/// document's "#id" references.
using ColladaIds = std::unordered_map<std::string, const TiXmlElement*>;

/// Every element of the document under `root` with an id (explicit stack: no recursion).
ColladaIds colladaIds(const TiXmlElement& root);

/// `e` for a message: "<float_array id='box-array'>", its id (or else its url, source, name or
/// semantic attribute) shown, control bytes escaped, long values cut.
std::string colladaElement(const TiXmlElement& e);

/// The value of an attribute COLLADA requires.
/// \throws mcws::Error "'source': <accessor> has no count attribute (COLLADA requires it)".
std::string requiredColladaAttribute(const TiXmlElement& e, const char* attribute,
                                     const std::string& source);

/// The element an attribute such as url="#box" names, which must be a `<wanted>` of this file.
/// \throws mcws::Error "'source': <instance_geometry url='#nope'>: no geometry with id 'nope'",
///   or for a reference that is not "#id" (another file's element is not read).
const TiXmlElement& referencedColladaElement(const TiXmlElement& e, const char* attribute,
                                             const char* wanted, const ColladaIds& ids,
                                             const std::string& source);

/// All of an element's text (every text child: TinyXML splits a text at some characters).
std::string colladaText(const TiXmlElement& e);

/// The whitespace-separated words of `text` (views into it).
std::vector<std::string_view> colladaWords(const std::string& text);

/// A whole number of at most 18 digits (a count, a stride, an index) into `value`, or false.
bool parseColladaWholeNumber(std::string_view word, std::uint64_t& value);

/// A geometry's triangles as the file writes them [file units], before any node places them.
struct ColladaGeometry {
  std::string name;                           ///< quoted for messages: 'box'
  std::vector<Eigen::Vector3d> vertices;      ///< the positions the triangles use [file units]
  std::vector<std::uint64_t> numbers;         ///< each vertex's number in its accessor, from 1
  std::vector<std::array<int, 3>> triangles;  ///< indices into vertices
};

/// Reads a `<geometry>`: its `<mesh>`'s `<triangles>`, `<polylist>`, `<polygons>` (holes of a
/// `<ph>` skipped), `<trifans>` and `<tristrips>` as triangles (polygons fan-triangulated from
/// their first corner, strips with alternate winding); lines skipped; no triangle when the
/// geometry is not a `<mesh>`. Every vertex written is checked with checkMeshCoordinate().
/// \throws mcws::Error naming the file, the geometry and the element for a size or index the file
///   does not hold, a missing attribute or reference, or a coordinate that is not a number.
ColladaGeometry readColladaGeometry(const TiXmlElement& geometry, const ColladaIds& ids,
                                    const std::string& source);

}  // namespace detail
}  // namespace mcws
