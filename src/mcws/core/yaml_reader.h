#pragma once
/// \file
/// \brief The checks the mcws YAML readers share: "file:line: message" errors, known keys,
/// required fields, single values, numbers and numbers with a unit.
///
/// Header-only; only the readers that link yaml-cpp include it (mcws::core does not link it).

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "mcws/core/control_bytes.h"
#include "mcws/core/decimal.h"
#include "mcws/core/error.h"

namespace mcws {

/// \brief The items of a container of strings, "a, b, c" ("" when empty).
template <typename Container>
std::string joined(const Container& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + std::string(item);
  return out;
}

/// \brief The 1-based line of `node` in its file, 0 when yaml-cpp does not know it (also for a
/// node that is not in the file, such as `map["absent"]`).
inline int lineOf(const YAML::Node& node) {
  return node.IsDefined() && node.Mark().line >= 0 ? node.Mark().line + 1 : 0;
}

/// \brief "source:line", or "source" alone when `line` is 0 (unknown).
inline std::string atLine(const std::string& source, int line) {
  return source + (line > 0 ? ":" + std::to_string(line) : "");
}

/// \brief How many nodes YAML aliases may add to a document in all: an alias stands for a copy
/// of the node its anchor names, so that a few hundred bytes of aliases of aliases expand to
/// billions of nodes (an "alias bomb"), and every reader that walks the document would run for
/// ever. No mcws file needs more than a few hundred aliased nodes; a million takes a reader well
/// under a second to walk.
constexpr unsigned long long kMaxAliasedYamlNodes = 1000000;

/// \brief What loadYamlDocument() learns from yaml-cpp's parser events before any node is built:
/// the lines (0-based) where documents start, and the size of the document with its aliases
/// expanded.
///
/// An anchored node records the number of nodes of its subtree (itself, keys, values and the
/// expansion of the aliases inside it); an alias adds that number. A document whose aliases add
/// more than kMaxAliasedYamlNodes nodes, or with an alias inside the node its anchor names (a
/// node that contains itself, which yaml-cpp builds as a cycle), is refused at that alias.
class DocumentEvents : public YAML::EventHandler {
 public:
  /// \param source names the file in messages.
  explicit DocumentEvents(std::string source) : source_(std::move(source)) {}

  std::vector<int> lines;  ///< the 0-based lines where documents start

  void OnDocumentStart(const YAML::Mark& mark) override {
    lines.push_back(mark.line);
    nodes_ = aliased_ = 0;
    sizes_.clear();  // anchors are numbered per document
    open_.clear();
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t anchor) override { leaf(anchor); }
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t anchor,
                const std::string&) override {
    leaf(anchor);
  }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    if (anchor >= sizes_.size() || sizes_[anchor] == kOpen) {
      throw Error(atLine(source_, mark.line + 1) +
                  ": YAML alias inside the node its anchor names (a node that contains itself)");
    }
    nodes_ += sizes_[anchor];
    aliased_ += sizes_[anchor];
    if (aliased_ > kMaxAliasedYamlNodes) {
      throw Error(atLine(source_, mark.line + 1) +
                  ": YAML aliases expand the document by more than " +
                  std::to_string(kMaxAliasedYamlNodes) + " nodes (the limit; an alias bomb?)");
    }
  }
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    open(anchor);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    open(anchor);
  }
  void OnMapEnd() override { close(); }

 private:
  /// The size of a node whose anchor's node has started and not ended.
  static constexpr unsigned long long kOpen = ~0ULL;

  /// Notes the size of anchor's node (anchors are numbered from 1 in the order they appear; an
  /// anchor named again is a new number).
  void setSize(YAML::anchor_t anchor, unsigned long long size) {
    if (anchor == YAML::NullAnchor) return;
    if (anchor >= sizes_.size()) sizes_.resize(anchor + 1, kOpen);
    sizes_[anchor] = size;
  }
  void leaf(YAML::anchor_t anchor) {
    ++nodes_;
    setSize(anchor, 1);
  }
  void open(YAML::anchor_t anchor) {
    open_.push_back({anchor, nodes_});
    ++nodes_;
    setSize(anchor, kOpen);
  }
  void close() {
    if (open_.empty()) return;
    setSize(open_.back().first, nodes_ - open_.back().second);
    open_.pop_back();
  }

  std::string source_;
  unsigned long long nodes_{0};            ///< nodes of the document so far, aliases expanded
  unsigned long long aliased_{0};          ///< of which added by aliases
  std::vector<unsigned long long> sizes_;  ///< by anchor: its node's size, or kOpen
  std::vector<std::pair<YAML::anchor_t, unsigned long long>> open_;  ///< anchor, nodes_ at start
};

/// \brief Whether the quoted YAML scalar that starts at text[begin] (a ' or ") closes on the
/// same line ('' and \" are escaped quotes).
inline bool closesOnItsLine(const std::string& text, std::size_t begin) {
  const char quote = text[begin];
  for (std::size_t k = begin + 1; k < text.size() && text[k] != '\n'; ++k) {
    if (quote == '"' && text[k] == '\\') {
      ++k;  // the escaped character
    } else if (text[k] == quote) {
      if (quote == '\'' && k + 1 < text.size() && text[k + 1] == '\'') {
        ++k;  // '' is a quote inside single quotes
      } else {
        return true;
      }
    }
  }
  return false;
}

/// \brief The one YAML document of a file (a Null node for an empty file).
///
/// yaml-cpp's syntax errors become "source:line: YAML syntax: ...", and a file of several
/// documents is an error naming `what` ("a robot file"), as is text after the document that the
/// parser cannot place. So is a document whose aliases expand it by more than
/// kMaxAliasedYamlNodes nodes, or one with a node that contains itself (see DocumentEvents). A
/// quoted value that spans lines is reported where it starts, as an unterminated quote: YAML
/// allows such values (folding the line breaks into blanks) and no mcws file needs them, while a
/// missing closing quote makes yaml-cpp read the rest of the file into one value and the reader
/// then reports a missing field far from the mistake.
/// \throws mcws::Error as above.
inline YAML::Node loadYamlDocument(const std::string& text, const std::string& source,
                                   const std::string& what) {
  // Control bytes are not YAML (its spec allows tab, line feed and carriage return only), and
  // yaml-cpp 0.7 loops forever on some inputs with NUL bytes: refused before it sees them.
  int line = 1;
  for (std::size_t k = 0, line_start = 0; k < text.size(); ++k) {
    const auto byte = static_cast<unsigned char>(text[k]);
    if (byte == '\n') {
      ++line;
      line_start = k + 1;
    } else if (isControlByte(byte) && byte != '\t' && byte != '\r') {
      throw Error(atLine(source, line) + ": control byte " + escapedByte(byte) + " at column " +
                  std::to_string(k - line_start + 1) + " (" + what + " is text)");
    }
  }
  // The documents are counted by yaml-cpp's parser before any is built, stopping at the second:
  // YAML::LoadAll() of yaml-cpp 0.7 loops for ever, allocating, when text it cannot place follows
  // the first document (a stray ',' at the start of a line), and YAML::Load() drops such text.
  // The same pass sizes the aliases, before anything walks the document they would expand.
  std::istringstream stream(text);
  YAML::Parser parser(stream);
  DocumentEvents starts(source);
  try {
    while (starts.lines.size() < 2 && parser.HandleNextDocument(starts)) {
    }
  } catch (const YAML::Exception& e) {
    throw Error(atLine(source, e.mark.line >= 0 ? e.mark.line + 1 : 0) + ": YAML syntax: " + e.msg);
  }
  if (starts.lines.size() > 1) {
    const int second = starts.lines[1];  // 0-based
    std::size_t at = 0;
    for (int k = 0; k < second && at != std::string::npos; ++k) {
      at = text.find('\n', at);
      if (at != std::string::npos) ++at;
    }
    if (at != std::string::npos && text.compare(at, 3, "---") == 0) {
      throw Error(source + ": holds more than one YAML document; " + what + " holds one");
    }
    throw Error(atLine(source, second + 1) +
                ": YAML syntax: text the parser cannot place in the document (a stray ',', ']' "
                "or '}', or a wrong indentation?)");
  }
  if (starts.lines.empty()) return YAML::Node();
  std::vector<YAML::Node> documents{YAML::Load(text)};
  std::vector<YAML::Node> pending{documents.front()};  // no recursion: depth is the file's
  while (!pending.empty()) {
    const YAML::Node node = pending.back();
    pending.pop_back();
    if (node.IsScalar() && node.Mark().pos >= 0) {
      const auto begin = static_cast<std::size_t>(node.Mark().pos);
      const char quote = begin < text.size() ? text[begin] : ' ';
      if ((quote == '"' || quote == '\'') && !closesOnItsLine(text, begin)) {
        throw Error(atLine(source, lineOf(node)) + ": a quoted value runs over several lines: a " +
                    "missing closing quote (" + std::string(1, quote) + ")?");
      }
    } else if (node.IsSequence()) {
      for (const YAML::Node& item : node) pending.push_back(item);
    } else if (node.IsMap()) {
      for (const auto& item : node) {
        pending.push_back(item.first);
        pending.push_back(item.second);
      }
    }
  }
  return documents.front();
}

/// \brief A number with its unit, "155 mm", as written (not converted).
struct Quantity {
  double value{0.0};
  std::string unit;
};

/// \brief Base of a reader of one YAML file: every check throws mcws::Error with the message
/// "source:line: where: what is wrong", the line being that of the offending node.
///
/// `where` names the item being read ("insulator", "faults[2]: at"); the helpers append the
/// problem to it.
///
/// \code
/// class FooReader : YamlReader {
///  public:
///   explicit FooReader(std::string source) : YamlReader(std::move(source)) {}
///   Foo read(const YAML::Node& root) {
///     checkKeys(root, "foo", {"name", "size"});
///     Foo foo;
///     foo.name = text(require(root, "name", "foo"), "foo: name");
///     ...
///   }
/// };
/// \endcode
class YamlReader {
 public:
  /// \param source the file name (or other label) that starts every message.
  explicit YamlReader(std::string source) : source_(std::move(source)) {}

  /// \brief The file name that starts every message.
  const std::string& source() const { return source_; }

  /// \brief Throws "source:line: message" at the line of `node` ("source: message" when its line
  /// is unknown). \throws mcws::Error always.
  [[noreturn]] void fail(const YAML::Node& node, const std::string& message) const {
    throw Error(atLine(source_, lineOf(node)) + ": " + message);
  }

  /// \brief Checks that `map` is a map whose keys are plain names, each given once and each one
  /// of `allowed`.
  /// \throws mcws::Error "where: must be a map", "where: a key must be a plain name", "where: key
  /// 'k' given twice" or "where: unknown key 'k' (allowed: a, b, c)".
  void checkKeys(const YAML::Node& map, const std::string& where,
                 const std::set<std::string>& allowed) const {
    if (!map.IsMap()) fail(map, where + ": must be a map");
    std::set<std::string> seen;
    for (const auto& item : map) {
      if (!item.first.IsScalar()) fail(item.first, where + ": a key must be a plain name");
      const std::string key = item.first.Scalar();
      if (!seen.insert(key).second) fail(item.first, where + ": key '" + key + "' given twice");
      if (!allowed.count(key)) {
        fail(item.first, where + ": unknown key '" + key + "' (allowed: " + joined(allowed) + ")");
      }
    }
  }

  /// \brief Checks a map whose keys are names of the file's own (states, events, ports): plain,
  /// not empty and given once.
  /// \throws mcws::Error "where: must be a map", "where: a key must be a plain name" or "where:
  /// key 'k' given twice".
  void checkNames(const YAML::Node& map, const std::string& where) const {
    if (!map.IsMap()) fail(map, where + ": must be a map");
    std::set<std::string> seen;
    for (const auto& item : map) {
      if (!item.first.IsScalar() || item.first.Scalar().empty()) {
        fail(item.first, where + ": a key must be a plain name");
      }
      if (!seen.insert(item.first.Scalar()).second) {
        fail(item.first, where + ": key '" + item.first.Scalar() + "' given twice");
      }
    }
  }

  /// \brief The value of `key` in `map`.
  /// \throws mcws::Error "where: missing field 'key'" (at the map's line) when it is absent.
  YAML::Node require(const YAML::Node& map, const std::string& key,
                     const std::string& where) const {
    const YAML::Node node = map[key];
    if (!node) fail(map, where + ": missing field '" + key + "'");
    return node;
  }

  /// \brief The text of a single value, possibly empty.
  /// \throws mcws::Error "where: must be a single value" for a list, a map or no value.
  std::string scalar(const YAML::Node& node, const std::string& where) const {
    if (!node.IsScalar()) fail(node, where + ": must be a single value");
    return node.Scalar();
  }

  /// \brief The text of a single, non-empty value.
  /// \throws mcws::Error as scalar(), or "where: must not be empty".
  std::string text(const YAML::Node& node, const std::string& where) const {
    const std::string value = scalar(node, where);
    if (value.empty()) fail(node, where + ": must not be empty");
    return value;
  }

  /// \brief Numbers larger than this in size are typing mistakes (and would overflow the float
  /// coordinates of a cloud).
  static constexpr double kLargestNumber = 1e9;

  /// \brief A finite number as YAML writes it ("155", "1.5e2", "-.5"), at most kLargestNumber in
  /// size.
  /// \param what names the value in messages ("joint 1 'j1': field 'a'").
  /// \throws mcws::Error "what must be a number" for a list, a map or no value, "what: 'v' is not
  /// a number", "what: 'v' is not a finite number" or "what: v is out of range (at most 1e9 in
  /// size)".
  double finiteNumber(const YAML::Node& node, const std::string& what) const {
    if (!node.IsScalar()) fail(node, what + " must be a number");
    double value = 0.0;
    try {
      value = node.as<double>();
    } catch (const YAML::Exception&) {
      fail(node, what + ": '" + node.Scalar() + "' is not a number");
    }
    if (!std::isfinite(value))
      fail(node, what + ": '" + node.Scalar() + "' is not a finite number");
    if (std::abs(value) > kLargestNumber) {
      fail(node, what + ": " + node.Scalar() + " is out of range (at most 1e9 in size)");
    }
    return value;
  }

  /// \brief The texts of a single value or of a list of single values (each as text()).
  std::vector<std::string> texts(const YAML::Node& node, const std::string& where) const {
    std::vector<std::string> out;
    if (node.IsSequence()) {
      for (const YAML::Node& item : node) out.push_back(text(item, where));
    } else {
      out.push_back(text(node, where));
    }
    return out;
  }

  /// \brief `value`, the text of `node` as the reader read it, split into a number (a plain
  /// decimal, mcws::parseDecimal) and a unit: "155 mm".
  /// \param units the units allowed.
  /// \param example a valid value for the message, "155 mm".
  /// \throws mcws::Error "where: 'value' is not a number and a unit (e.g. 'example')" or "where:
  /// unknown unit 'u' in 'value' (a, b, c)".
  Quantity quantity(const YAML::Node& node, const std::string& where, const std::string& value,
                    const std::set<std::string>& units, const std::string& example) const {
    std::istringstream words(value);
    std::string number, unit, extra;
    words >> number >> unit;
    Quantity q;
    if (unit.empty() || (words >> extra) || !parseDecimal(number, q.value)) {
      fail(node, where + ": '" + value + "' is not a number and a unit (e.g. '" + example + "')");
    }
    if (!units.count(unit)) {
      fail(node,
           where + ": unknown unit '" + unit + "' in '" + value + "' (" + joined(units) + ")");
    }
    q.unit = unit;
    return q;
  }

 private:
  std::string source_;
};

}  // namespace mcws
