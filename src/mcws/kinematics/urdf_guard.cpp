#include "mcws/kinematics/detail/urdf_guard.h"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cstddef>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/kinematics/robot.h"
#include "mcws/kinematics/robot_urdf.h"

namespace mcws::detail {
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

/// Where the search of checkTree() stands with a link.
enum class Visit { kNotYet, kOnPath, kDone };

/// The joints of a model by link, and the depth-first searches of checkTree() over them.
class TreeSearch {
 public:
  TreeSearch(const urdf::ModelInterface& model, const std::string& source) : source_(source) {
    for (const auto& named : model.joints_) {
      child_joints_[named.second->parent_link_name].push_back(named.second.get());
      some_parent_joint_[named.second->child_link_name] = named.second.get();
    }
  }

  /// Whether a joint has `link` as its child.
  bool hasParent(const std::string& link) const { return some_parent_joint_.count(link) != 0; }

  /// The parent link of one of the joints that have `link` as child (one must).
  const std::string& someParentLink(const std::string& link) const {
    return some_parent_joint_.at(link)->parent_link_name;
  }

  Visit visit(const std::string& link) const {
    const auto found = visit_.find(link);
    return found == visit_.end() ? Visit::kNotYet : found->second;
  }

  /// Enters every link below `start` by one joint. \throws mcws::Error for a joint that leads
  /// back to a link on the current path (a loop) or to a link entered before (a second parent).
  void from(const std::string& start) {
    std::vector<std::pair<std::string, std::size_t>> path{{start, 0}};  // link, next child joint
    visit_[start] = Visit::kOnPath;
    while (!path.empty()) {
      const std::vector<const urdf::Joint*>& joints = child_joints_[path.back().first];
      if (path.back().second == joints.size()) {
        visit_[path.back().first] = Visit::kDone;
        path.pop_back();
        continue;
      }
      const urdf::Joint& joint = *joints[path.back().second++];
      const std::string& child = joint.child_link_name;
      if (visit(child) == Visit::kOnPath) {
        throw Error(source_ + ": joint '" + joint.name + "' closes a loop: its child link '" +
                    child + "' is also its ancestor");
      }
      if (visit(child) == Visit::kDone) {
        throw Error(source_ + ": joint '" + joint.name + "': link '" + child +
                    "' already has parent joint '" + entered_by_[child]->name +
                    "' (the joints must form a tree)");
      }
      entered_by_[child] = &joint;
      visit_[child] = Visit::kOnPath;
      path.emplace_back(child, 0);
    }
  }

 private:
  const std::string& source_;
  std::map<std::string, std::vector<const urdf::Joint*>> child_joints_;  // by parent link
  std::map<std::string, const urdf::Joint*> some_parent_joint_;          // by child link
  std::map<std::string, Visit> visit_;
  std::map<std::string, const urdf::Joint*> entered_by_;
};

/// \brief Throws unless the joints make the links a tree: no link its own ancestor, none with
/// two parent joints. urdfdom checks neither, and a loop would send the chain searches of
/// ChainReader round for ever.
///
/// A depth-first search from the root links (those no joint has as child) enters each link by
/// one joint. A joint leading back to a link on the current path closes a loop; one leading to a
/// link entered before gives it a second parent. Links the roots do not reach lie on or below a
/// loop: the search starts again from the first link met twice when walking up parent joints.
void checkTree(const urdf::ModelInterface& model, const std::string& source) {
  TreeSearch search(model, source);
  for (const auto& named : model.links_) {
    if (!search.hasParent(named.first)) search.from(named.first);
  }
  for (const auto& named : model.links_) {
    if (search.visit(named.first) != Visit::kNotYet) continue;
    std::string on_loop = named.first;  // walked up until a link comes round again
    std::set<std::string> walked;
    while (walked.insert(on_loop).second) on_loop = search.someParentLink(on_loop);
    search.from(on_loop);  // throws: the search comes back round to on_loop
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

}  // namespace

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

std::string oneLine(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

urdf::ModelInterfaceSharedPtr parseUrdfModel(const std::string& text, const std::string& source,
                                             std::vector<std::string>* logged) {
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

}  // namespace mcws::detail
