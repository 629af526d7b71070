#include "mcws/kinematics/robot_urdf.h"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/core/text_file.h"
#include "mcws/core/yaml_reader.h"

namespace mcws {
namespace {

/// Collects urdfdom's console_bridge messages instead of printing them, so that a failed parse
/// becomes one mcws::Error line.
class CapturedMessages : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) errors_.push_back(text);
  }
  std::string firstError() const { return errors_.empty() ? std::string() : errors_.front(); }
  const std::vector<std::string>& errors() const { return errors_; }

 private:
  std::vector<std::string> errors_;
};

/// Message text on one line.
std::string oneLine(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

/// The shortest text that reads back as `value` ("1e+308", "1000000000.5").
std::string shortest(double value) {
  char buffer[32];
  return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, value).ptr);
}

/// 1-based number of the line holding byte `at`.
std::size_t lineOf(const std::string& text, std::size_t at) {
  return 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n');
}

/// White space as TinyXML's IsWhiteSpace() sees it (isspace in the C locale).
bool isXmlSpace(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r';
}

bool isAsciiLetter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

/// The ASCII characters of an XML name after its first (TinyXML's ReadName()).
bool isNameChar(char c) {
  return isAsciiLetter(c) || (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.' || c == ':';
}

/// The offset just after the first `end` at or after `from`, or the end of the text.
std::size_t after(const std::string& text, std::size_t from, const char* end) {
  const std::size_t found = text.find(end, from);
  return found == std::string::npos ? text.size() : found + std::char_traits<char>::length(end);
}

/// The offset of the '>' that ends the start tag at `at` (quoted attribute values skipped, as
/// TinyXML skips them), or the end of the text.
std::size_t startTagEnd(const std::string& text, std::size_t at) {
  for (std::size_t i = at + 1; i < text.size(); ++i) {
    if (text[i] == '>') return i;
    if (text[i] == '"' || text[i] == '\'') {
      i = text.find(text[i], i + 1);
      if (i == std::string::npos) break;
    }
  }
  return text.size();
}

/// True when an attribute value, as TinyXML decodes it, holds a '%': a '%' itself or a numeric
/// character reference to it (`&#37;`, `&#x25;`, with any leading zeros).
bool decodesToPercent(const std::string& value) {
  if (value.find('%') != std::string::npos) return true;
  for (std::size_t at = value.find("&#"); at != std::string::npos; at = value.find("&#", at + 2)) {
    std::size_t i = at + 2;
    const bool hex = i < value.size() && (value[i] == 'x' || value[i] == 'X');
    if (hex) ++i;
    while (i < value.size() && value[i] == '0') ++i;
    if (value.compare(i, 3, hex ? "25;" : "37;") == 0) return true;
  }
  return false;
}

/// \brief Throws if an attribute of the start tag from `at` to `end` (its '>') holds a '%',
/// except a mesh's `filename`.
///
/// urdfdom 3.0 hands some messages that quote the file's text to console_bridge as the printf
/// format itself (a pose's xyz or rpy, a box's size, a radius, a length, a mass, an inertia, a
/// material's name and rgba), so "%n" or "%s" in them crashes the parser. No URDF number or name
/// needs a '%'; a file name may, and urdfdom quotes it only through "%s".
void checkNoPercentInAttributes(const std::string& text, std::size_t at, std::size_t end,
                                const std::string& source) {
  std::size_t i = at + 1;
  while (i < end && !isXmlSpace(text[i])) ++i;  // the element's name
  for (;;) {
    while (i < end && isXmlSpace(text[i])) ++i;
    const std::size_t name_at = i;
    while (i < end && !isXmlSpace(text[i]) && text[i] != '=' && text[i] != '/') ++i;
    const std::string name = text.substr(name_at, i - name_at);
    while (i < end && isXmlSpace(text[i])) ++i;
    if (name.empty() || i >= end || text[i] != '=') return;  // TinyXML's own error, if any
    ++i;
    while (i < end && isXmlSpace(text[i])) ++i;
    if (i >= end || (text[i] != '"' && text[i] != '\'')) return;
    const std::size_t close = text.find(text[i], i + 1);
    if (close == std::string::npos || close > end) return;
    const std::string value = text.substr(i + 1, close - i - 1);
    if (name != "filename" && decodesToPercent(value)) {
      throw Error(source + ": line " + std::to_string(lineOf(text, i)) + ": attribute " + name +
                  "=\"" + oneLine(value) +
                  "\" holds a '%', which no URDF number or name needs (urdfdom would misread it)");
    }
    i = close + 1;
  }
}

/// Throws unless every byte that TinyXML reads as the lead of a multi-byte UTF-8 character (0xC2
/// to 0xF4) is followed by its continuation bytes (0x80 to 0xBF). TinyXML takes a lead's whole
/// length without looking, so a cut-short character would swallow the '<' or quote after it and
/// the nesting count of checkXmlNesting() would lose step with the parser.
void checkUtf8(const std::string& text, const std::string& source) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto lead = static_cast<unsigned char>(text[i]);
    const int continuations = lead >= 0xC2 && lead <= 0xDF   ? 1
                              : lead >= 0xE0 && lead <= 0xEF ? 2
                              : lead >= 0xF0 && lead <= 0xF4 ? 3
                                                             : 0;
    for (int k = 1; k <= continuations; ++k) {
      const auto byte = i + k < text.size() ? static_cast<unsigned char>(text[i + k]) : 0;
      if (byte < 0x80 || byte > 0xBF) {
        std::ostringstream msg;
        msg << source << ": line " << lineOf(text, i) << " is not UTF-8 text (byte 0x" << std::hex
            << std::uppercase << int{lead} << " starts a cut-short character)";
        throw Error(msg.str());
      }
    }
    i += continuations;
  }
}

/// Throws unless the `<?xml` declaration at `at` is plain: attributes `name="value"` (names and
/// values of letters, digits and "_-.:"), each after white space, then `?>` or `>`. TinyXML ends a
/// declaration at the first '>' outside the quoted value of a version, encoding or standalone
/// attribute; in the plain form that is its first '>', where checkXmlNesting() ends it too.
void checkPlainDeclaration(const std::string& text, std::size_t at, const std::string& source) {
  std::size_t i = at + 5;
  const auto skip = [&](bool (*is)(char)) {
    const std::size_t from = i;
    while (i < text.size() && is(text[i])) ++i;
    return i > from;
  };
  const auto at_char = [&](char c) { return i < text.size() && text[i] == c; };
  for (;;) {
    const bool spaced = skip(isXmlSpace);
    if (at_char('>') || text.compare(i, 2, "?>") == 0) return;
    if (!spaced || !isAsciiLetter(text[i]) || !skip(isNameChar)) break;
    skip(isXmlSpace);
    if (!at_char('=')) break;
    ++i;
    skip(isXmlSpace);
    if (!at_char('"') && !at_char('\'')) break;
    const char quote = text[i++];
    skip(isNameChar);
    if (!at_char(quote)) break;
    ++i;
  }
  throw Error(source + ": XML declaration on line " + std::to_string(lineOf(text, at)) +
              " is not of the form <?xml name=\"value\" ...?>");
}

/// \brief Bounds the recursion of TinyXML (urdfdom's parser, one level per nested element)
/// before it runs, and finds where the content of the `<robot>` element begins.
///
/// The scan splits the text as TinyXML 2.6 does: comments end at `-->`, CDATA at `]]>`, a start
/// tag at its first '>' outside quotes (an empty element when `/>`), an end tag and any other
/// markup (`<?xml ?>`, `<!DOCTYPE>`) at its first '>'. So it counts the parser's depth exactly
/// up to the point where the parser stops at an error. Two places where TinyXML reads more than
/// that would let a crafted file hide nesting from the count, so they are errors: a cut-short
/// UTF-8 character (checkUtf8()) and a declaration with a '>' inside quotes
/// (checkPlainDeclaration()). Each start tag's attributes are checked on the way
/// (checkNoPercentInAttributes()).
/// \return the offset just after the first top-level `<robot ...>` tag, or npos.
/// \throws mcws::Error "source: XML nested deeper than 1000 elements", or as the two checks.
std::size_t checkXmlNesting(const std::string& text, const std::string& source) {
  checkUtf8(text, source);
  std::size_t robot_content = std::string::npos;
  int depth = 0;
  for (std::size_t at = text.find('<'); at < text.size(); at = text.find('<', at)) {
    const char next = at + 1 < text.size() ? text[at + 1] : '\0';
    if (text.compare(at, 4, "<!--") == 0) {
      at = after(text, at + 4, "-->");
    } else if (text.compare(at, 9, "<![CDATA[") == 0) {
      at = after(text, at + 9, "]]>");
    } else if (next == '/') {
      depth = std::max(depth - 1, 0);
      at = after(text, at, ">");
    } else if (isAsciiLetter(next) || next == '_' || static_cast<unsigned char>(next) >= 127) {
      const std::size_t end = startTagEnd(text, at);
      if (end == text.size()) break;
      checkNoPercentInAttributes(text, at, end, source);
      if (text[end - 1] != '/') {
        if (++depth > kMaxUrdfNesting) {
          throw Error(source + ": XML nested deeper than " + std::to_string(kMaxUrdfNesting) +
                      " elements");
        }
        if (depth == 1 && robot_content == std::string::npos &&
            text.compare(at + 1, 5, "robot") == 0 && !isNameChar(text[at + 6])) {
          robot_content = end + 1;
        }
      }
      at = end + 1;
    } else {
      std::string opening = text.substr(at, 5);
      std::transform(opening.begin(), opening.end(), opening.begin(),
                     [](char c) { return c >= 'A' && c <= 'Z' ? char(c - 'A' + 'a') : c; });
      if (opening == "<?xml") checkPlainDeclaration(text, at, source);
      at = after(text, at, ">");
    }
  }
  return robot_content;
}

/// \brief Throws unless the joints make the links a tree: no link its own ancestor, none with
/// two parent joints. urdfdom checks neither, and a loop would send the chain searches of
/// ChainReader round for ever.
///
/// A depth-first search from the root links (those no joint has as child) enters each link by
/// one joint. A joint leading back to a link on the current path closes a loop; one leading to a
/// link entered before gives it a second parent. Links the roots do not reach lie on or below a
/// loop: the search starts again from the first link met twice when walking up parent joints.
void checkTree(const urdf::ModelInterface& model, const std::string& source) {
  std::map<std::string, std::vector<const urdf::Joint*>> child_joints;  // by parent link
  std::map<std::string, const urdf::Joint*> some_parent_joint;          // by child link
  for (const auto& named : model.joints_) {
    child_joints[named.second->parent_link_name].push_back(named.second.get());
    some_parent_joint[named.second->child_link_name] = named.second.get();
  }
  enum class Visit { kNotYet, kOnPath, kDone };
  std::map<std::string, Visit> visit;
  std::map<std::string, const urdf::Joint*> entered_by;
  const auto search = [&](const std::string& start) {
    std::vector<std::pair<std::string, std::size_t>> path{{start, 0}};  // link, next child joint
    visit[start] = Visit::kOnPath;
    while (!path.empty()) {
      const std::vector<const urdf::Joint*>& joints = child_joints[path.back().first];
      if (path.back().second == joints.size()) {
        visit[path.back().first] = Visit::kDone;
        path.pop_back();
        continue;
      }
      const urdf::Joint& joint = *joints[path.back().second++];
      const std::string& child = joint.child_link_name;
      if (visit[child] == Visit::kOnPath) {
        throw Error(source + ": joint '" + joint.name + "' closes a loop: its child link '" +
                    child + "' is also its ancestor");
      }
      if (visit[child] == Visit::kDone) {
        throw Error(source + ": joint '" + joint.name + "': link '" + child +
                    "' already has parent joint '" + entered_by[child]->name +
                    "' (the joints must form a tree)");
      }
      entered_by[child] = &joint;
      visit[child] = Visit::kOnPath;
      path.emplace_back(child, 0);
    }
  };
  for (const auto& named : model.links_) {
    if (!some_parent_joint.count(named.first)) search(named.first);
  }
  for (const auto& named : model.links_) {
    if (visit[named.first] != Visit::kNotYet) continue;
    std::string on_loop = named.first;  // walked up until a link comes round again
    std::set<std::string> walked;
    while (walked.insert(on_loop).second) {
      on_loop = some_parent_joint.at(on_loop)->parent_link_name;
    }
    search(on_loop);  // throws: the search comes back round to on_loop
  }
}

/// checkTree(), and on failure emptying every link's list of child links first: urdfdom's links
/// own their children (shared_ptr), so a loop among them would never be freed.
void checkTreeFreeingLoops(urdf::ModelInterface& model, const std::string& source) {
  try {
    checkTree(model, source);
  } catch (const Error&) {
    for (const auto& named : model.links_) named.second->child_links.clear();
    throw;
  }
}

/// urdfdom's model of the text, or null with urdfdom's first error in `why`. When `logged` is
/// given it receives every error urdfdom logged, including those of a parse that succeeded
/// (urdfdom skips a `<collision>` or `<visual>` it cannot read and goes on).
urdf::ModelInterfaceSharedPtr tryParseModel(const std::string& text, std::string& why,
                                            std::vector<std::string>* logged = nullptr) {
  static std::mutex console_mutex;  // console_bridge's output handler is process-wide
  const std::lock_guard<std::mutex> lock(console_mutex);
  CapturedMessages messages;
  console_bridge::useOutputHandler(&messages);
  urdf::ModelInterfaceSharedPtr model;
  std::string exception_text;
  try {
    model = urdf::parseURDF(text);
  } catch (const std::exception& e) {
    exception_text = e.what();
  }
  console_bridge::restorePreviousOutputHandler();
  why = !exception_text.empty() ? exception_text : messages.firstError();
  if (logged) *logged = messages.errors();
  return model;
}

/// Throws unless the names of the robot, its links and its joints hold no control byte (an XML
/// character reference such as `&#10;` writes one).
void checkPrintableNames(const urdf::ModelInterface& model, const std::string& source) {
  checkPrintableName(model.getName(), source + ": robot");
  for (const auto& named : model.links_) checkPrintableName(named.first, source + ": link");
  for (const auto& named : model.joints_) checkPrintableName(named.first, source + ": joint");
}

/// urdfdom's model of the text, checked to be a tree (checkTreeFreeingLoops()) and to have
/// printable names (checkPrintableNames()).
///
/// urdfdom rejects a URDF in which every link has a parent joint (then the joints necessarily
/// form a loop) as having no root link, without naming a joint. To name the joint that closes the
/// loop, a failed text is parsed again with an extra link that no joint names: if urdfdom then
/// accepts it, that link was the only one without a parent and the tree check finds the loop.
/// \param logged as tryParseModel().
urdf::ModelInterfaceSharedPtr parseModel(const std::string& text, const std::string& source,
                                         std::vector<std::string>* logged = nullptr) {
  const std::size_t robot_content = checkXmlNesting(text, source);
  std::string why;
  urdf::ModelInterfaceSharedPtr model = tryParseModel(text, why, logged);
  if (model) {
    checkPrintableNames(*model, source);  // first: the tree check's messages name links
    checkTreeFreeingLoops(*model, source);
    return model;
  }
  if (robot_content != std::string::npos) {
    std::string with_root = text;
    with_root.insert(robot_content, "<link name=\"mcws_added_root_link\"/>");
    std::string ignored;
    if (const urdf::ModelInterfaceSharedPtr rooted = tryParseModel(with_root, ignored)) {
      checkPrintableNames(*rooted, source);
      checkTreeFreeingLoops(*rooted, source);
    }
  }
  if (why.empty()) why = "not a valid URDF document";
  throw Error(source + ": malformed URDF: " + oneLine(why));
}

/// Reads a chain from a model that checkTree() accepted, so its searches up and down the tree end.
class ChainReader {
 public:
  ChainReader(const urdf::ModelInterface& model, std::string source)
      : model_(model), source_(std::move(source)) {}

  /// The links and joints of a chain.
  struct Chain {
    urdf::LinkConstSharedPtr root, tip;
    std::vector<urdf::JointConstSharedPtr> joints;  ///< from the root to the tip
  };

  Chain chain(const UrdfChainOptions& options) const {
    Chain chain;
    chain.root = rootLink(options.root_link);
    chain.tip = options.tip_link.empty() ? singleLeaf(chain.root) : link(options.tip_link, "tip");
    for (urdf::LinkConstSharedPtr current = chain.tip; current != chain.root;) {
      if (!current->parent_joint) {
        fail("tip link '" + chain.tip->name + "' is not below root link '" + chain.root->name +
             "'");
      }
      chain.joints.push_back(current->parent_joint);
      current = model_.getLink(current->parent_joint->parent_link_name);
      if (!current) fail("joint '" + chain.joints.back()->name + "' has no parent link");
    }
    std::reverse(chain.joints.begin(), chain.joints.end());
    return chain;
  }

  Robot robot(const Chain& chain) const {
    Robot robot;
    robot.name = model_.getName();
    robot.source = source_;
    robot.length_unit = LengthUnit::kMetre;
    Eigen::Isometry3d T_fixed = Eigen::Isometry3d::Identity();  // fixed joints since the last move
    for (const urdf::JointConstSharedPtr& joint : chain.joints) {
      T_fixed = T_fixed * pose(*joint);
      if (joint->type == urdf::Joint::FIXED) continue;
      robot.joints.push_back(movingJoint(*joint, T_fixed));
      T_fixed = Eigen::Isometry3d::Identity();
    }
    if (robot.joints.empty()) {
      fail("no revolute, continuous or prismatic joint between root link '" + chain.root->name +
           "' and tip link '" + chain.tip->name + "'");
    }
    robot.T_last_flange = T_fixed;
    return robot;
  }

  /// The `<collision>` elements of the links the chain carries, placed on their bodies (see
  /// loadRobotUrdfGeometry()). `robot` is robot(chain).
  std::vector<UrdfCollision> collisions(const Chain& chain, const Robot& robot) const {
    const std::map<std::string, Place> places = linkPlaces(chain, robot);
    std::vector<UrdfCollision> out;
    for (const auto& named : model_.links_) {  // by link name
      const urdf::Link& link = *named.second;
      if (link.collision_array.empty()) continue;
      const auto place = places.find(link.name);
      if (place == places.end()) {
        fail("link '" + link.name +
             "' has <collision> elements but is not part of the chain: " + notCarried(chain, link));
      }
      for (std::size_t k = 0; k < link.collision_array.size(); ++k) {
        out.push_back(collisionElement(link, int(k) + 1, *link.collision_array[k], place->second));
      }
    }
    return out;
  }

 private:
  /// Where a link's frame sits on the chain.
  struct Place {
    UrdfBody body{UrdfBody::kBase};
    int joint{-1};  ///< kLink: the joint whose link carries it
    /// The link's frame in the body's frame [m]; for kTool in the last link's frame until the
    /// end of linkPlaces(), which turns it into the flange frame.
    Eigen::Isometry3d T_body_link{Eigen::Isometry3d::Identity()};
  };

  /// The place of every link the chain carries: the chain's own links, then the branches that
  /// hang off them by fixed joints.
  std::map<std::string, Place> linkPlaces(const Chain& chain, const Robot& robot) const {
    std::map<std::string, Place> places;
    std::set<std::string> chain_joints;
    Place place;
    places[chain.root->name] = place;
    int moving = -1;
    for (const urdf::JointConstSharedPtr& joint : chain.joints) {
      chain_joints.insert(joint->name);
      if (joint->type != urdf::Joint::FIXED) {
        place = Place{UrdfBody::kLink, ++moving, Eigen::Isometry3d::Identity()};
      } else {
        if (place.body == UrdfBody::kLink && place.joint == robot.dof() - 1) {
          place.body = UrdfBody::kTool;
        }
        place.T_body_link = place.T_body_link * pose(*joint);
      }
      places[joint->child_link_name] = place;
    }
    std::vector<std::string> stack;
    for (const auto& named : places) stack.push_back(named.first);
    while (!stack.empty()) {
      const urdf::LinkConstSharedPtr link = model_.getLink(stack.back());
      const Place parent = places.at(stack.back());
      stack.pop_back();
      for (const urdf::JointSharedPtr& joint : link->child_joints) {
        if (joint->type != urdf::Joint::FIXED || chain_joints.count(joint->name)) continue;
        Place child = parent;
        if (child.body == UrdfBody::kBase) child.body = UrdfBody::kEnvironment;
        child.T_body_link = child.T_body_link * pose(*joint);
        places[joint->child_link_name] = child;
        stack.push_back(joint->child_link_name);
      }
    }
    const Eigen::Isometry3d T_flange_last = robot.T_last_flange.inverse();
    for (auto& named : places) {
      if (named.second.body != UrdfBody::kTool) continue;
      named.second.joint = -1;
      named.second.T_body_link = T_flange_last * named.second.T_body_link;
    }
    return places;
  }

  /// Why the chain does not carry `link` (one that linkPlaces() did not place): below the root,
  /// a link that fixed joints do not tie to the chain moves with a joint outside it.
  std::string notCarried(const Chain& chain, const urdf::Link& link) const {
    const std::string chain_name =
        "the chain from link '" + chain.root->name + "' to link '" + chain.tip->name + "'";
    urdf::JointConstSharedPtr moving;  // the nearest moving joint above the link
    for (urdf::LinkConstSharedPtr current = model_.getLink(link.name); current;) {
      if (current->name == chain.root->name) {
        if (moving) {
          return "it moves with joint '" + moving->name + "', which is not in " + chain_name;
        }
        break;
      }
      if (!current->parent_joint) break;
      if (!moving && current->parent_joint->type != urdf::Joint::FIXED) {
        moving = current->parent_joint;
      }
      current = model_.getLink(current->parent_joint->parent_link_name);
    }
    return "it is not below root link '" + chain.root->name + "' of " + chain_name;
  }

  /// One `<collision>` element of a link at `place`.
  UrdfCollision collisionElement(const urdf::Link& link, int element,
                                 const urdf::Collision& collision, const Place& place) const {
    const std::string label = "link '" + link.name + "' <collision> " + std::to_string(element);
    UrdfCollision out;
    out.link = link.name;
    out.element = element;
    out.body = place.body;
    out.joint = place.joint;
    out.T_body_geometry = place.T_body_link * pose(collision.origin, label);
    if (!collision.geometry) fail(label + ": has no geometry");
    const urdf::Geometry& geometry = *collision.geometry;
    switch (geometry.type) {
      case urdf::Geometry::SPHERE:
        out.type = UrdfGeometry::kSphere;
        out.radius =
            size(static_cast<const urdf::Sphere&>(geometry).radius, label, "sphere radius");
        break;
      case urdf::Geometry::BOX: {
        out.type = UrdfGeometry::kBox;
        const urdf::Vector3& dim = static_cast<const urdf::Box&>(geometry).dim;
        out.size = {size(dim.x, label, "box size x"), size(dim.y, label, "box size y"),
                    size(dim.z, label, "box size z")};
        break;
      }
      case urdf::Geometry::CYLINDER: {
        out.type = UrdfGeometry::kCylinder;
        const auto& cylinder = static_cast<const urdf::Cylinder&>(geometry);
        out.radius = size(cylinder.radius, label, "cylinder radius");
        out.length = size(cylinder.length, label, "cylinder length");
        break;
      }
      case urdf::Geometry::MESH: {
        out.type = UrdfGeometry::kMesh;
        const auto& mesh = static_cast<const urdf::Mesh&>(geometry);
        if (mesh.filename.empty()) fail(label + ": mesh has no filename");
        out.filename = mesh.filename;
        out.scale = {size(mesh.scale.x, label, "mesh scale x"),
                     size(mesh.scale.y, label, "mesh scale y"),
                     size(mesh.scale.z, label, "mesh scale z")};
        break;
      }
      default:
        fail(label + ": unknown geometry type");
    }
    return out;
  }

  /// `value` when it is a finite number in (0, 1e9]. \throws mcws::Error naming `what`.
  double size(double value, const std::string& label, const std::string& what) const {
    if (!std::isfinite(value) || value <= 0.0 || value > YamlReader::kLargestNumber) {
      fail(label + ": " + what + " " + shortest(value) + " must be a number > 0 (at most 1e9)");
    }
    return value;
  }

  [[noreturn]] void fail(const std::string& what) const { throw Error(source_ + ": " + what); }

  urdf::LinkConstSharedPtr link(const std::string& name, const std::string& role) const {
    urdf::LinkConstSharedPtr found = model_.getLink(name);
    if (!found)
      fail(role + " link '" + name + "' is not a link of robot '" + model_.getName() + "'");
    return found;
  }

  urdf::LinkConstSharedPtr rootLink(const std::string& name) const {
    if (!name.empty()) return link(name, "root");
    if (!model_.getRoot()) fail("the URDF has no root link");
    return model_.getRoot();
  }

  urdf::LinkConstSharedPtr singleLeaf(const urdf::LinkConstSharedPtr& root) const {
    // Leaves that only fixed joints lead to (objects fixed to the base) end no chain: they count
    // only when there is no other leaf, so that the message is then the missing moving joint.
    std::vector<urdf::LinkConstSharedPtr> leaves, fixed_leaves;
    std::vector<std::pair<urdf::LinkConstSharedPtr, bool>> stack{{root, false}};  // link, moved
    while (!stack.empty()) {
      const auto [current, moved] = stack.back();
      stack.pop_back();
      if (current->child_links.empty()) (moved ? leaves : fixed_leaves).push_back(current);
      for (const auto& child : current->child_links) {
        stack.emplace_back(child, moved || child->parent_joint->type != urdf::Joint::FIXED);
      }
    }
    if (leaves.empty()) leaves = fixed_leaves;
    if (leaves.size() != 1) {
      std::string list;
      for (const auto& leaf : leaves) list += (list.empty() ? "" : ", ") + leaf->name;
      fail("link '" + root->name + "' has " + std::to_string(leaves.size()) +
           " leaf links below it (" + list + "); choose the tip link");
    }
    return leaves.front();
  }

  Eigen::Isometry3d pose(const urdf::Joint& joint) const {
    return pose(joint.parent_to_joint_origin_transform, "joint '" + joint.name + "'");
  }

  /// The transform of an `<origin>`; `label` names its element in messages.
  Eigen::Isometry3d pose(const urdf::Pose& p, const std::string& label) const {
    const double numbers[] = {p.position.x, p.position.y, p.position.z, p.rotation.x,
                              p.rotation.y, p.rotation.z, p.rotation.w};
    for (double value : numbers) {
      if (!std::isfinite(value)) fail(label + ": origin is not finite");
    }
    for (double value : {p.position.x, p.position.y, p.position.z}) {
      if (std::abs(value) > YamlReader::kLargestNumber) {
        fail(label + ": origin coordinate " + shortest(value) +
             " is out of range (at most 1e9 in size)");
      }
    }
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
    T.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z)
                     .normalized()
                     .toRotationMatrix();
    return T;
  }

  Joint movingJoint(const urdf::Joint& joint, const Eigen::Isometry3d& T_parent_joint) const {
    const std::string label = "joint '" + joint.name + "'";
    Joint out;
    out.name = joint.name;
    if (out.name.find_first_of("=, \t") != std::string::npos) {
      fail(label + ": name contains '=', ',' or a space");
    }
    if (joint.mimic) fail(label + ": mimic joints are not supported in a serial chain");
    switch (joint.type) {
      case urdf::Joint::REVOLUTE:
      case urdf::Joint::CONTINUOUS:
        out.type = JointType::kRevolute;
        break;
      case urdf::Joint::PRISMATIC:
        out.type = JointType::kPrismatic;
        break;
      case urdf::Joint::FLOATING:
        fail(label +
             ": floating joints are not supported (revolute, continuous, prismatic, fixed)");
      case urdf::Joint::PLANAR:
        fail(label + ": planar joints are not supported (revolute, continuous, prismatic, fixed)");
      default:
        fail(label + ": unknown joint type");
    }
    out.T_parent_joint = T_parent_joint;
    const Eigen::Vector3d axis(joint.axis.x, joint.axis.y, joint.axis.z);
    if (!axis.allFinite() || axis.norm() < 1e-12) {
      fail(label + ": axis must be a finite non-zero vector");
    }
    out.axis = axis.normalized();
    if (joint.type == urdf::Joint::CONTINUOUS) {
      out.lower = -M_PI;
      out.upper = M_PI;
      return out;
    }
    if (!joint.limits) fail(label + ": a " + jointTypeName(out.type) + " joint needs <limit>");
    out.lower = joint.limits->lower;
    out.upper = joint.limits->upper;
    if (!std::isfinite(out.lower) || !std::isfinite(out.upper)) {
      fail(label + ": limits are not finite");
    }
    for (const auto& [bound, value] : {std::pair{"lower", out.lower}, {"upper", out.upper}}) {
      if (std::abs(value) > YamlReader::kLargestNumber) {
        fail(label + ": " + bound + " limit " + shortest(value) +
             " is out of range (at most 1e9 in size)");
      }
    }
    if (out.lower > out.upper) {
      std::ostringstream msg;
      msg.precision(10);
      msg << label << ": lower limit " << out.lower << " is greater than upper limit " << out.upper;
      fail(msg.str());
    }
    return out;
  }

  const urdf::ModelInterface& model_;
  std::string source_;
};

/// Throws when a URDF of `bytes` bytes is larger than kMaxUrdfBytes.
void checkUrdfSize(std::uintmax_t bytes, const std::string& source) {
  if (bytes > kMaxUrdfBytes) {
    throw Error(source + ": URDF of " + std::to_string(bytes) + " bytes is larger than " +
                std::to_string(kMaxUrdfBytes >> 20) + " MiB");
  }
}

}  // namespace

Robot parseRobotUrdf(const std::string& text, const std::string& source,
                     const UrdfChainOptions& options) {
  checkUrdfSize(text.size(), source);
  const urdf::ModelInterfaceSharedPtr model = parseModel(text, source);
  const ChainReader reader(*model, source);
  return reader.robot(reader.chain(options));
}

UrdfRobotGeometry parseRobotUrdfGeometry(const std::string& text, const std::string& source,
                                         const UrdfChainOptions& options) {
  checkUrdfSize(text.size(), source);
  std::vector<std::string> logged;
  const urdf::ModelInterfaceSharedPtr model = parseModel(text, source, &logged);
  if (!logged.empty()) {  // urdfdom skipped an element it could not read
    std::string what;
    for (const std::string& message : logged) what += (what.empty() ? "" : "; ") + message;
    throw Error(source + ": unsupported or malformed element: " + oneLine(what));
  }
  const ChainReader reader(*model, source);
  const ChainReader::Chain chain = reader.chain(options);
  UrdfRobotGeometry out;
  out.robot = reader.robot(chain);
  out.collisions = reader.collisions(chain, out.robot);
  return out;
}

Robot loadRobotUrdf(const std::string& path, const UrdfChainOptions& options) {
  checkPrintableName(std::filesystem::path(path).filename().string(), "robot file");
  std::error_code ec;  // a file that cannot be sized is left to readTextFile's messages
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (!ec) checkUrdfSize(bytes, path);
  return parseRobotUrdf(readTextFile(path, "robot file"), path, options);
}

UrdfRobotGeometry loadRobotUrdfGeometry(const std::string& path, const UrdfChainOptions& options) {
  checkPrintableName(std::filesystem::path(path).filename().string(), "robot file");
  std::error_code ec;
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (!ec) checkUrdfSize(bytes, path);
  return parseRobotUrdfGeometry(readTextFile(path, "robot file"), path, options);
}

}  // namespace mcws
