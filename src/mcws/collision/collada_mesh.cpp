#include "mcws/collision/collada_mesh.h"

#include <tinyxml.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "mcws/collision/detail/collada_geometry.h"
#include "mcws/collision/detail/mesh_checks.h"
#include "mcws/core/control_bytes.h"
#include "mcws/core/decimal.h"
#include "mcws/core/error.h"

namespace mcws {
namespace {

using detail::colladaElement;

/// Refuses a '&' that starts no XML entity (`&amp;` `&lt;` `&gt;` `&quot;` `&apos;` `&#N;`
/// `&#xH;`), outside comments and CDATA. XML forbids it, and parsers read it differently: TinyXML
/// drops it ("4&7" would be read as 47), assimp's parser stops a number at it.
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

/// The root element of a COLLADA document parsed into `document`. \throws mcws::Error when the
/// bytes are not XML (a '&' that starts no entity included) or the root element is not
/// `<COLLADA>`.
const TiXmlElement& colladaRoot(const std::string& bytes, const std::string& source,
                                TiXmlDocument& document) {
  checkEntities(bytes, source);
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
  return *root;
}

/// The length of the unit of a COLLADA document [m]: `<COLLADA><asset><unit meter>`, 1 when
/// absent. \throws mcws::Error when the unit is not a number > 0 of at most
/// kLargestMeshCoordinate.
double colladaUnitLength(const TiXmlElement& root, const std::string& source) {
  const TiXmlElement* asset = root.FirstChildElement("asset");
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

/// The `<visual_scene>` the file's `<scene><instance_visual_scene url>` names, else the first
/// one; null when the file has none.
const TiXmlElement* colladaVisualScene(const TiXmlElement& root, const detail::ColladaIds& ids,
                                       const std::string& source) {
  const TiXmlElement* scene = root.FirstChildElement("scene");
  const TiXmlElement* instance =
      scene ? scene->FirstChildElement("instance_visual_scene") : nullptr;
  if (instance != nullptr) {
    return &detail::referencedColladaElement(*instance, "url", "visual_scene", ids, source);
  }
  const TiXmlElement* library = root.FirstChildElement("library_visual_scenes");
  return library ? library->FirstChildElement("visual_scene") : nullptr;
}

/// The numbers of a transform element of `node`, exactly `n` finite ones.
std::vector<double> transformNumbers(const TiXmlElement& e, std::size_t n, const TiXmlElement& node,
                                     const std::string& source) {
  const std::string text = detail::colladaText(e);
  const std::vector<std::string_view> words = detail::colladaWords(text);
  const std::string element = "'" + source + "': " + colladaElement(node) + " <" + e.Value() + ">";
  if (words.size() != n) {
    throw Error(element + " holds " + std::to_string(words.size()) + " numbers, not " +
                std::to_string(n));
  }
  std::vector<double> numbers(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (!detail::parseMeshNumber(words[k], numbers[k]) || !std::isfinite(numbers[k])) {
      throw Error(element + " number " + std::to_string(k + 1) + " " +
                  detail::quotedMeshWord(words[k]) + " is not a finite number");
    }
  }
  return numbers;
}

/// The transform of a `<node>` relative to its parent: the product of its `<matrix>` (row by
/// row), `<translate>`, `<rotate>` (axis, angle [deg]) and `<scale>` elements in document order
/// (COLLADA's p_parent = T1 T2 ... p_node). \throws mcws::Error for a `<lookat>` or `<skew>`
/// (not read) or a transform that is not its numbers.
Eigen::Matrix4d nodeTransform(const TiXmlElement& node, const std::string& source) {
  const auto where = [&] { return "'" + source + "': " + colladaElement(node); };
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  for (const TiXmlElement* e = node.FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string_view kind = e->Value();
    Eigen::Matrix4d step = Eigen::Matrix4d::Identity();
    if (kind == "matrix") {
      const std::vector<double> m = transformNumbers(*e, 16, node, source);
      for (int k = 0; k < 16; ++k) step(k / 4, k % 4) = m[std::size_t(k)];
    } else if (kind == "translate") {
      const std::vector<double> t = transformNumbers(*e, 3, node, source);
      step.topRightCorner<3, 1>() = Eigen::Vector3d(t[0], t[1], t[2]);
    } else if (kind == "rotate") {
      const std::vector<double> r = transformNumbers(*e, 4, node, source);
      const Eigen::Vector3d axis(r[0], r[1], r[2]);
      if (!(axis.norm() > 0.0)) {
        throw Error(where() + " <rotate>: the axis 0 0 0 is no direction");
      }
      step.topLeftCorner<3, 3>() =
          Eigen::AngleAxisd(r[3] * M_PI / 180.0, axis.normalized()).toRotationMatrix();
    } else if (kind == "scale") {
      const std::vector<double> s = transformNumbers(*e, 3, node, source);
      step.diagonal().head<3>() = Eigen::Vector3d(s[0], s[1], s[2]);
    } else if (kind == "lookat" || kind == "skew") {
      throw Error(where() + " <" + std::string(kind) +
                  ">: not read by mcws (write the node's transform as "
                  "<matrix>, <translate>, <rotate> and <scale>)");
    } else {
      continue;
    }
    T = T * step;
  }
  return T;
}

/// At most this many triangles are placed, and nodes visited, for a file of `bytes` bytes: ten
/// per byte, at least a million and at most 50 million, so that instances of instances cannot
/// grow without bound (a collision mesh needs far fewer).
std::uint64_t colladaPlacementLimit(std::size_t bytes) {
  return std::clamp<std::uint64_t>(10 * std::uint64_t(bytes), 1'000'000, 50'000'000);
}

/// Places the geometries a visual scene's node tree instantiates (depth first, with an explicit
/// stack, so that no nesting depth can overflow the call stack).
class ColladaPlacer {
 public:
  ColladaPlacer(const detail::ColladaIds& ids, const std::string& source, std::size_t bytes)
      : ids_(ids), source_(source), limit_(colladaPlacementLimit(bytes)) {}

  TriangleMesh place(const TiXmlElement& visual_scene, double unit);

 private:
  /// What is left to do: place a node (a <node>, the <visual_scene>, or the target of an
  /// <instance_node>), or leave the target of an <instance_node> when its subtree is placed.
  enum class Step { kNode, kInstance, kLeave };
  struct Open {
    const TiXmlElement* node;
    Eigen::Matrix4d T_metre_parent;  ///< where its parent is [m per file unit]
    Step step;
  };
  void visit(const Open& open);
  void addInstance(const TiXmlElement& instance, const Eigen::Matrix4d& T_metre_node);

  const detail::ColladaIds& ids_;
  const std::string& source_;
  const std::uint64_t limit_;
  std::vector<Open> open_;
  std::unordered_set<const TiXmlElement*> instancing_;  ///< <instance_node> targets being placed
  std::unordered_map<const TiXmlElement*, detail::ColladaGeometry> geometries_;
  std::uint64_t visits_{0};
  TriangleMesh mesh_;
};

TriangleMesh ColladaPlacer::place(const TiXmlElement& visual_scene, double unit) {
  Eigen::Matrix4d T_metre_file = Eigen::Matrix4d::Identity();
  T_metre_file.topLeftCorner<3, 3>() *= unit;
  open_.push_back({&visual_scene, T_metre_file, Step::kNode});
  while (!open_.empty()) {
    const Open open = open_.back();
    open_.pop_back();
    if (open.step == Step::kLeave) {
      instancing_.erase(open.node);
    } else {
      visit(open);
    }
  }
  return std::move(mesh_);
}

void ColladaPlacer::visit(const Open& open) {
  if (++visits_ > limit_) {
    throw Error("'" + source_ + "': its scene places more than " + std::to_string(limit_) +
                " nodes (instances of instances?): not read");
  }
  const TiXmlElement& node = *open.node;
  if (open.step == Step::kInstance) instancing_.insert(&node);
  const Eigen::Matrix4d T_metre_node = open.T_metre_parent * nodeTransform(node, source_);
  std::vector<Open> children;
  for (const TiXmlElement* e = node.FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string_view kind = e->Value();
    if (kind == "instance_geometry") {
      addInstance(*e, T_metre_node);
    } else if (kind == "node") {
      children.push_back({e, T_metre_node, Step::kNode});
    } else if (kind == "instance_node") {
      const TiXmlElement& target =
          detail::referencedColladaElement(*e, "url", "node", ids_, source_);
      if (instancing_.count(&target) != 0) {
        throw Error("'" + source_ + "': " + colladaElement(*e) +
                    ": instantiates a node it is part of (a cycle)");
      }
      children.push_back({&target, T_metre_node, Step::kInstance});
    }
  }
  // Reversed onto the stack, so that the children are placed in document order; an
  // <instance_node>'s target is marked as being placed from its visit until the kLeave step under
  // it is reached, after its whole subtree.
  for (auto c = children.rbegin(); c != children.rend(); ++c) {
    if (c->step == Step::kInstance) open_.push_back({c->node, c->T_metre_parent, Step::kLeave});
    open_.push_back(*c);
  }
}

void ColladaPlacer::addInstance(const TiXmlElement& instance, const Eigen::Matrix4d& T_metre_node) {
  const TiXmlElement& element =
      detail::referencedColladaElement(instance, "url", "geometry", ids_, source_);
  auto found = geometries_.find(&element);
  if (found == geometries_.end()) {
    found =
        geometries_.emplace(&element, detail::readColladaGeometry(element, ids_, source_)).first;
  }
  const detail::ColladaGeometry& geometry = found->second;
  if (mesh_.triangles.size() + geometry.triangles.size() > limit_) {
    throw Error("'" + source_ + "': its scene places more than " + std::to_string(limit_) +
                " triangles (instances of instances?): not read");
  }
  const int offset = int(mesh_.vertices.size());
  for (std::size_t v = 0; v < geometry.vertices.size(); ++v) {
    const Eigen::Vector3d p = (T_metre_node * geometry.vertices[v].homogeneous()).head<3>();
    for (int k = 0; k < 3; ++k) {
      if (std::isfinite(p[k]) && std::abs(p[k]) <= kLargestMeshCoordinate) continue;
      // The message is made only for a bad coordinate (9 digits).
      detail::checkMeshCoordinate(p[k],
                                  "'" + source_ + "': mesh " + geometry.name + " vertex " +
                                      std::to_string(geometry.numbers[v]) + ": " + "xyz"[k] +
                                      " (placed, in metres)",
                                  formatNumber(p[k], 9));
    }
    mesh_.vertices.push_back(p);
  }
  for (const auto& t : geometry.triangles) {
    mesh_.triangles.push_back({offset + t[0], offset + t[1], offset + t[2]});
  }
}

}  // namespace

TriangleMesh parseColladaMesh(const std::string& bytes, const std::string& source) {
  TiXmlDocument document;
  const TiXmlElement& root = colladaRoot(bytes, source, document);
  const double unit = colladaUnitLength(root, source);
  const detail::ColladaIds ids = detail::colladaIds(root);
  const TiXmlElement* scene = colladaVisualScene(root, ids, source);
  if (scene == nullptr) return TriangleMesh();
  return ColladaPlacer(ids, source, bytes.size()).place(*scene, unit);
}

}  // namespace mcws
