#include "mcws/collision/collada_mesh.h"

#include <tinyxml.h>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <assimp/Importer.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "mcws/collision/detail/mesh_checks.h"
#include "mcws/core/control_bytes.h"
#include "mcws/core/decimal.h"
#include "mcws/core/error.h"

namespace mcws {
namespace {

/// The whitespace-separated words of all of an element's text. TinyXML splits a text at a
/// character such as a stray '&' that other parsers (assimp's) keep: `GetText()` would give only
/// the part before it.
std::vector<std::string> words(const TiXmlElement& e) {
  std::string text;
  for (const TiXmlNode* n = e.FirstChild(); n; n = n->NextSibling()) {
    if (n->ToText() != nullptr) text += n->Value();
  }
  std::vector<std::string> out;
  std::string word;
  for (const char c : text) {
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
      if (!word.empty()) out.push_back(std::move(word));
      word.clear();
    } else {
      word += c;
    }
  }
  if (!word.empty()) out.push_back(word);
  return out;
}

/// A size the file could hold: a whole number of at most `bytes`, the file's length (every value
/// counted takes a byte at least). \throws mcws::Error naming the element and the word.
std::uint64_t checkedSize(const std::string& word, std::size_t bytes, const std::string& where) {
  const bool digits = !word.empty() && word.size() <= 19 &&
                      word.find_first_not_of("0123456789") == std::string::npos;
  const std::uint64_t value = digits ? std::stoull(word) : 0;
  if (!digits || value > bytes) {
    throw Error(where + " holds " + detail::quotedMeshWord(word) +
                ": not a whole number of at most " + std::to_string(bytes) + " (the file's bytes)");
  }
  return value;
}

/// The attributes COLLADA requires of an element that assimp reads without checking that they are
/// there (a missing one is a null pointer inside assimp).
std::vector<const char*> requiredAttributes(const std::string& element) {
  static const std::vector<std::pair<std::vector<std::string>, std::vector<const char*>>> rules{
      {{"float_array", "int_array", "bool_array", "Name_array", "IDREF_array"}, {"count"}},
      {{"accessor"}, {"count", "source"}},
      {{"triangles", "polylist", "polygons", "tristrips", "trifans", "lines", "linestrips"},
       {"count"}},
      {{"input"}, {"semantic", "source"}},
      {{"instance_geometry", "instance_node", "instance_visual_scene"}, {"url"}}};
  for (const auto& [elements, attributes] : rules) {
    if (std::find(elements.begin(), elements.end(), element) != elements.end()) return attributes;
  }
  return {};
}

/// Checks what assimp sizes its arrays by before it reads them, so that a damaged file is refused
/// in one line rather than by a multi-gigabyte allocation: every count and stride attribute and
/// every index (<p>, <v>, <h>, <int_array>) a whole number no larger than the file, the sum of a
/// <vcount> too, and a count times its stride; the words of a <float_array> made of number
/// characters.
void checkColladaSizes(const TiXmlElement& root, std::size_t bytes, const std::string& source) {
  std::vector<const TiXmlElement*> open{&root};
  while (!open.empty()) {
    const TiXmlElement& e = *open.back();
    open.pop_back();
    const std::string name = e.Value();
    const std::string where = "'" + source + "': <" + escapedControlBytes(name) + ">";
    for (const char* required : requiredAttributes(name)) {
      if (e.Attribute(required) == nullptr) {
        throw Error(where + " has no " + required + " attribute (COLLADA requires it)");
      }
    }
    std::uint64_t count = 1, stride = 1;
    if (const char* a = e.Attribute("count")) count = checkedSize(a, bytes, where + " count");
    if (const char* a = e.Attribute("stride")) stride = checkedSize(a, bytes, where + " stride");
    if (count * stride > bytes) {
      throw Error(where + ": count x stride " + std::to_string(count * stride) +
                  " is more than the file's " + std::to_string(bytes) + " bytes hold");
    }
    if (name == "p" || name == "v" || name == "h" || name == "int_array" || name == "vcount") {
      std::uint64_t sum = 0;
      for (const std::string& word : words(e)) sum += checkedSize(word, bytes, where);
      if (name == "vcount" && sum > bytes) {
        throw Error(where + ": its polygons have " + std::to_string(sum) +
                    " corners, more than the file's " + std::to_string(bytes) + " bytes hold");
      }
    } else if (name == "float_array") {
      for (const std::string& word : words(e)) {
        if (word.find_first_not_of("0123456789+-.eEnNaAiIfFtTyY") != std::string::npos) {
          throw Error(where + " holds " + detail::quotedMeshWord(word) + ": not a number");
        }
      }
    }
    for (const TiXmlElement* c = e.FirstChildElement(); c; c = c->NextSiblingElement()) {
      open.push_back(c);
    }
  }
}

/// Refuses a '&' that starts no XML entity (`&amp;` `&lt;` `&gt;` `&quot;` `&apos;` `&#N;`
/// `&#xH;`), outside comments and CDATA. XML forbids it, and the two parsers read it differently:
/// TinyXML drops it ("4&7" is 47), assimp's parser stops a number at it, so the sizes checked here
/// would not be the sizes assimp allocates.
void checkEntities(const std::string& bytes, const std::string& source) {
  const auto skip = [&](std::size_t at, const char* open, const char* close) {
    if (bytes.compare(at, std::strlen(open), open) != 0) return at;
    const std::size_t end = bytes.find(close, at + std::strlen(open));
    return end == std::string::npos ? bytes.size() : end + std::strlen(close);
  };
  for (std::size_t at = 0; at < bytes.size();) {
    const std::size_t next = skip(skip(at, "<!--", "-->"), "<![CDATA[", "]]>");
    if (next != at) {
      at = next;
      continue;
    }
    if (bytes[at++] != '&') continue;
    const std::size_t semicolon = bytes.find(';', at);
    const std::string name = bytes.substr(at, semicolon == std::string::npos ? 0 : semicolon - at);
    const bool decimal = name.size() > 1 && name[0] == '#' &&
                         name.find_first_not_of("0123456789", 1) == std::string::npos;
    const bool hex = name.size() > 2 && name.compare(0, 2, "#x") == 0 &&
                     name.find_first_not_of("0123456789abcdefABCDEF", 2) == std::string::npos;
    if (name == "amp" || name == "lt" || name == "gt" || name == "quot" || name == "apos" ||
        decimal || hex) {
      continue;
    }
    const auto line = 1 + std::count(bytes.begin(), bytes.begin() + std::ptrdiff_t(at), '\n');
    throw Error("'" + source + "': not a COLLADA file: malformed XML at line " +
                std::to_string(line) + ": a '&' that starts no entity (write &amp;)");
  }
}

/// The length of the unit of a COLLADA document [m]: `<COLLADA><asset><unit meter>`, 1 when
/// absent. \throws mcws::Error when the bytes are not XML, the root element is not `<COLLADA>`,
/// or the unit is not a number > 0 of at most kLargestMeshCoordinate.
double colladaUnitLength(const std::string& bytes, const std::string& source) {
  checkEntities(bytes, source);
  TiXmlDocument document;
  document.Parse(bytes.c_str());
  if (document.Error()) {
    const std::string line =
        document.ErrorRow() > 0 ? " at line " + std::to_string(document.ErrorRow()) : "";
    throw Error("'" + source + "': not a COLLADA file: malformed XML" + line + ": " +
                escapedControlBytes(document.ErrorDesc()));
  }
  const TiXmlElement* root = document.RootElement();
  if (root == nullptr || std::string(root->Value()) != "COLLADA") {
    throw Error("'" + source + "': not a COLLADA file: its root element is " +
                (root ? "<" + escapedControlBytes(root->Value()) + ">" : std::string("missing")) +
                ", not <COLLADA>");
  }
  checkColladaSizes(*root, bytes.size(), source);
  const TiXmlElement* asset = root->FirstChildElement("asset");
  const TiXmlElement* unit = asset ? asset->FirstChildElement("unit") : nullptr;
  const char* meter = unit ? unit->Attribute("meter") : nullptr;
  if (meter == nullptr) return 1.0;
  double length = 0.0;
  if (!detail::parseMeshNumber(meter, length) || !(length > 0.0) ||
      !(length <= kLargestMeshCoordinate)) {
    throw Error("'" + source + "': <unit meter=" + detail::quotedMeshWord(meter) +
                ">: the length of the file's unit must be a number > 0 [m] (at most 1e9)");
  }
  return length;
}

Eigen::Matrix4d toEigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  for (unsigned r = 0; r < 4; ++r) {
    for (unsigned c = 0; c < 4; ++c) out(r, c) = m[r][c];
  }
  return out;
}

/// Adds one instance of `in`, placed by `T_file_node` [m per file unit], to `mesh`.
void addInstance(const aiMesh& in, const Eigen::Matrix4d& T_file_node, const std::string& source,
                 TriangleMesh& mesh) {
  const std::string name = "'" + source + "': mesh " + detail::quotedMeshWord(in.mName.C_Str());
  const int offset = int(mesh.vertices.size());
  // The message is made only for a bad coordinate (9 digits read back as the same float).
  const auto check = [&](double value, unsigned v, int k, const char* what) {
    if (std::isfinite(value) && std::abs(value) <= kLargestMeshCoordinate) return;
    detail::checkMeshCoordinate(value,
                                name + " vertex " + std::to_string(v + 1) + ": " + "xyz"[k] + what,
                                formatNumber(value, 9));
  };
  for (unsigned v = 0; v < in.mNumVertices; ++v) {
    const aiVector3D& written = in.mVertices[v];
    for (int k = 0; k < 3; ++k) check(written[k], v, k, "");
    const Eigen::Vector3d p =
        (T_file_node * Eigen::Vector4d(written.x, written.y, written.z, 1.0)).head<3>();
    for (int k = 0; k < 3; ++k) check(p[k], v, k, " (placed, in metres)");
    mesh.vertices.push_back(p);
  }
  for (unsigned f = 0; f < in.mNumFaces; ++f) {
    const aiFace& face = in.mFaces[f];
    if (face.mNumIndices != 3) continue;  // a point or a line
    std::array<int, 3> corners{};
    for (int c = 0; c < 3; ++c) {
      if (face.mIndices[c] >= in.mNumVertices) {
        throw Error(name + " face " + std::to_string(f + 1) + ": refers to a missing vertex");
      }
      corners[c] = offset + int(face.mIndices[c]);
    }
    mesh.triangles.push_back(corners);
  }
}

}  // namespace

TriangleMesh parseColladaMesh(const std::string& bytes, const std::string& source) {
  const double unit = colladaUnitLength(bytes, source);
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFileFromMemory(
      bytes.data(), bytes.size(), aiProcess_Triangulate | aiProcess_ValidateDataStructure, "dae");
  if (scene == nullptr) {
    throw Error("'" + source + "': assimp cannot read this COLLADA file: " +
                escapedControlBytes(importer.GetErrorString()));
  }
  TriangleMesh mesh;
  // An incomplete scene (no geometry) holds a dummy mesh of assimp's: no triangle of the file.
  if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0 || scene->mRootNode == nullptr) return mesh;

  // Depth first from the root, whose transform (assimp's unit scaling and turn to Y up) is
  // replaced by the file's unit alone: <up_axis> is ignored, as in RViz and MoveIt.
  struct Placed {
    const aiNode* node;
    Eigen::Matrix4d T_file_node;
  };
  Eigen::Matrix4d T_root = Eigen::Matrix4d::Identity();
  T_root.topLeftCorner<3, 3>() *= unit;
  std::vector<Placed> open{{scene->mRootNode, T_root}};
  while (!open.empty()) {
    const Placed placed = open.back();
    open.pop_back();
    const aiNode& node = *placed.node;
    for (unsigned k = 0; k < node.mNumMeshes; ++k) {
      if (node.mMeshes[k] >= scene->mNumMeshes) continue;  // ValidateDataStructure refuses it
      addInstance(*scene->mMeshes[node.mMeshes[k]], placed.T_file_node, source, mesh);
    }
    for (unsigned c = node.mNumChildren; c-- > 0;) {
      const aiNode* child = node.mChildren[c];
      open.push_back({child, placed.T_file_node * toEigen(child->mTransformation)});
    }
  }
  return mesh;
}

}  // namespace mcws
