#include "mcws/io/provenance.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <vector>

#include "mcws/core/decimal.h"
#include "mcws/core/error.h"

namespace mcws::io {

namespace {

constexpr char kWord[] = "mcws";
constexpr char kForm[] = "'# mcws robot=NAME file=FILE sha256=HEX length_unit=UNIT'";

thread_local std::optional<CloudProvenance> t_scoped;

bool isBlank(char c) { return c == ' ' || c == '\t'; }

bool isUnreserved(unsigned char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' ||
         c == '.' || c == '_' || c == '~';
}

std::string encode(const std::string& value) {
  std::string out;
  for (const char c : value) {
    const auto byte = static_cast<unsigned char>(c);
    if (isUnreserved(byte)) {
      out += c;
    } else {
      char escaped[4];
      std::snprintf(escaped, sizeof escaped, "%%%02X", byte);
      out += escaped;
    }
  }
  return out;
}

int hexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

/// `text` cut to 40 characters for a one-line message.
std::string shortText(const std::string& text) {
  return text.size() > 40 ? text.substr(0, 40) + "..." : text;
}

std::string decode(const std::string& key, const std::string& value) {
  std::string out;
  for (std::size_t k = 0; k < value.size(); ++k) {
    if (value[k] != '%') {
      out += value[k];
      continue;
    }
    if (k + 2 >= value.size() || hexDigit(value[k + 1]) < 0 || hexDigit(value[k + 2]) < 0) {
      throw Error(key + "=" + shortText(value) + ": '%' not followed by two hex digits");
    }
    const int byte = hexDigit(value[k + 1]) * 16 + hexDigit(value[k + 2]);
    if (byte < 0x20 || byte == 0x7f) {
      throw Error(key + "=" + shortText(value) + ": encodes a control byte");
    }
    out += static_cast<char>(byte);
    k += 2;
  }
  return out;
}

bool isSha256(const std::string& text) {
  if (text.size() != 64) return false;
  for (const char c : text) {
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  }
  return true;
}

bool isUnit(const std::string& text) { return text == "m" || text == "cm" || text == "mm"; }

/// The words of `line` after "# mcws".
std::vector<std::string> words(const std::string& line) {
  std::size_t k = 0;
  while (k < line.size() && isBlank(line[k])) ++k;
  ++k;  // '#'
  while (k < line.size() && isBlank(line[k])) ++k;
  k += sizeof kWord - 1;
  std::vector<std::string> out;
  while (k < line.size()) {
    while (k < line.size() && isBlank(line[k])) ++k;
    const std::size_t begin = k;
    while (k < line.size() && !isBlank(line[k])) ++k;
    if (k > begin) out.push_back(line.substr(begin, k - begin));
  }
  return out;
}

/// "name:value,..." or "none".
std::string encodeFixed(const std::vector<std::pair<std::string, double>>& fixed) {
  if (fixed.empty()) return "none";
  std::string out;
  for (const auto& [name, value] : fixed) {
    if (!out.empty()) out += ',';
    out += encode(name) + ":" + formatNumber(value, 17);
  }
  return out;
}

/// The whole of `text` as a finite double, or none.
std::optional<double> parseNumber(const std::string& text) {
  if (text.empty()) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (errno != 0 || end != text.c_str() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

/// The value of fix= (still encoded).
std::vector<std::pair<std::string, double>> decodeFixed(const std::string& value) {
  std::vector<std::pair<std::string, double>> fixed;
  if (value == "none") return fixed;
  const auto bad = [&](const std::string& why) {
    return Error("fix=" + shortText(value) + ": " + why +
                 " (it reads none or NAME:VALUE,NAME:VALUE...)");
  };
  std::size_t begin = 0;
  while (begin <= value.size()) {
    std::size_t end = value.find(',', begin);
    if (end == std::string::npos) end = value.size();
    const std::string item = value.substr(begin, end - begin);
    const std::size_t colon = item.find(':');
    if (colon == std::string::npos || colon == 0)
      throw bad("'" + shortText(item) + "' is not NAME:VALUE");
    const std::string name = decode("fix", item.substr(0, colon));
    const std::optional<double> number = parseNumber(item.substr(colon + 1));
    if (!number) throw bad("'" + shortText(item.substr(colon + 1)) + "' is not a finite number");
    for (const auto& pinned : fixed) {
      if (pinned.first == name) throw bad("joint '" + shortText(name) + "' given twice");
    }
    fixed.emplace_back(name, *number);
    begin = end + 1;
  }
  return fixed;
}

}  // namespace

std::string provenanceComment(const CloudProvenance& p) {
  if (p.robot.empty() || p.file.empty()) {
    throw Error("cannot record the robot of a cloud: its name or file name is empty");
  }
  if (!isSha256(p.sha256)) {
    throw Error("cannot record the robot of a cloud: sha256 '" + p.sha256 +
                "' is not 64 lowercase hex digits");
  }
  if (!isUnit(p.length_unit)) {
    throw Error("cannot record the robot of a cloud: length unit '" + p.length_unit +
                "' is not m, cm or mm");
  }
  std::string line = std::string("# ") + kWord + " robot=" + encode(p.robot) +
                     " file=" + encode(p.file) + " sha256=" + p.sha256 +
                     " length_unit=" + p.length_unit;
  if (p.base_link.empty() != p.tip_link.empty()) {
    throw Error("cannot record the chain of a cloud: base link '" + p.base_link +
                "' and tip link '" + p.tip_link + "' come both or neither");
  }
  if (!p.tip_link.empty()) {
    line += " base_link=" + encode(p.base_link) + " tip_link=" + encode(p.tip_link);
  }
  if (p.sampling) {
    if (p.sampling->point != "tool" && p.sampling->point != "flange") {
      throw Error("cannot record how a cloud was sampled: point '" + p.sampling->point +
                  "' is not tool or flange");
    }
    for (const auto& pinned : p.sampling->fixed) {
      if (pinned.first.empty() || !std::isfinite(pinned.second)) {
        throw Error("cannot record how a cloud was sampled: fixed joint '" + pinned.first +
                    "' = " + formatNumber(pinned.second, 17));
      }
    }
    line += " point=" + p.sampling->point + " collision=" + (p.sampling->collision ? "1" : "0") +
            " fix=" + encodeFixed(p.sampling->fixed);
  }
  if (p.input) {
    if (!isSha256(p.input->sha256)) {
      throw Error("cannot record the input of a boundary: sha256 '" + p.input->sha256 +
                  "' is not 64 lowercase hex digits");
    }
    line += " input_points=" + std::to_string(p.input->points) +
            " input_sha256=" + p.input->sha256 +
            " boundary_points=" + std::to_string(p.input->boundary_points);
  }
  return line;
}

std::optional<std::string> recordedTip(const CloudProvenance& provenance) {
  if (!provenance.tip_link.empty()) return provenance.tip_link;
  if (provenance.sampling) return provenance.sampling->point;
  return std::nullopt;
}

std::string describeCloud(const std::string& path, const std::optional<CloudProvenance>& recorded) {
  if (!recorded) return path;
  const std::optional<std::string> tip = recordedTip(*recorded);
  return "robot '" + recorded->robot + "'" + (tip ? ", tip " + *tip : "") + ", from " + path;
}

std::string describeSampling(const SamplingRecord& sampling) {
  return "point=" + sampling.point + " collision=" + (sampling.collision ? "1" : "0") +
         " fix=" + encodeFixed(sampling.fixed);
}

bool isProvenanceComment(const std::string& line) {
  std::size_t k = 0;
  while (k < line.size() && isBlank(line[k])) ++k;
  if (k == line.size() || line[k] != '#') return false;
  ++k;
  while (k < line.size() && isBlank(line[k])) ++k;
  const std::size_t length = sizeof kWord - 1;
  return line.compare(k, length, kWord) == 0 &&
         (k + length == line.size() || isBlank(line[k + length]));
}

CloudProvenance parseProvenanceComment(const std::string& line) {
  // Raw (still encoded) values of the keys this version knows; others are ignored.
  const char* const known[] = {
      "robot", "file",         "sha256",       "length_unit",     "point",     "collision",
      "fix",   "input_points", "input_sha256", "boundary_points", "base_link", "tip_link"};
  std::map<std::string, std::string> raw;
  for (const std::string& word : words(line)) {
    const std::size_t equals = word.find('=');
    if (equals == std::string::npos || equals == 0) {
      throw Error("'" + shortText(word) + "' is not key=value (the line reads " + kForm + ")");
    }
    const std::string key = word.substr(0, equals);
    if (std::find(std::begin(known), std::end(known), key) == std::end(known)) continue;
    if (raw.count(key)) throw Error(key + "= given twice");
    raw[key] = word.substr(equals + 1);
  }
  CloudProvenance p;
  std::string* const slots[] = {&p.robot, &p.file, &p.sha256, &p.length_unit};
  for (int k = 0; k < 4; ++k) {
    const auto found = raw.find(known[k]);
    if (found != raw.end()) *slots[k] = decode(known[k], found->second);
    if (slots[k]->empty()) {
      throw Error(std::string("no ") + known[k] + "= value (the line reads " + kForm + ")");
    }
  }
  if (!isSha256(p.sha256)) {
    throw Error("sha256=" + shortText(p.sha256) + " is not 64 lowercase hex digits");
  }
  if (!isUnit(p.length_unit)) {
    throw Error("length_unit=" + shortText(p.length_unit) + " is not m, cm or mm");
  }
  if (raw.count("base_link") != raw.count("tip_link")) {
    throw Error("base_link= and tip_link= come together: the line has one of them");
  }
  if (raw.count("tip_link")) {
    p.base_link = decode("base_link", raw["base_link"]);
    p.tip_link = decode("tip_link", raw["tip_link"]);
    if (p.base_link.empty() || p.tip_link.empty()) {
      throw Error("base_link= and tip_link= name a link each: one is empty");
    }
  }
  const int sampling_keys =
      static_cast<int>(raw.count("point") + raw.count("collision") + raw.count("fix"));
  if (sampling_keys != 0 && sampling_keys != 3) {
    throw Error("point=, collision= and fix= come together: the line has " +
                std::to_string(sampling_keys) + " of them");
  }
  if (sampling_keys == 3) {
    SamplingRecord sampling;
    sampling.point = raw["point"];
    if (sampling.point != "tool" && sampling.point != "flange") {
      throw Error("point=" + shortText(sampling.point) + " is not tool or flange");
    }
    const std::string& collision = raw["collision"];
    if (collision != "0" && collision != "1") {
      throw Error("collision=" + shortText(collision) + " is not 0 or 1");
    }
    sampling.collision = collision == "1";
    sampling.fixed = decodeFixed(raw["fix"]);
    p.sampling = sampling;
  }
  const int input_keys = static_cast<int>(raw.count("input_points") + raw.count("input_sha256") +
                                          raw.count("boundary_points"));
  if (input_keys != 0 && input_keys != 3) {
    throw Error("input_points=, input_sha256= and boundary_points= come together: the line has " +
                std::to_string(input_keys) + " of them");
  }
  if (input_keys == 3) {
    const auto count = [&](const char* key) {
      const std::string& text = raw[key];
      if (text.empty() || text.size() > 19 ||
          text.find_first_not_of("0123456789") != std::string::npos) {
        throw Error(std::string(key) + "=" + shortText(text) + " is not a whole number");
      }
      return static_cast<std::uint64_t>(std::stoull(text));
    };
    InputCloud input;
    input.points = count("input_points");
    input.boundary_points = count("boundary_points");
    input.sha256 = raw["input_sha256"];
    if (!isSha256(input.sha256)) {
      throw Error("input_sha256=" + shortText(input.sha256) + " is not 64 lowercase hex digits");
    }
    p.input = input;
  }
  return p;
}

ScopedProvenance::ScopedProvenance(const CloudProvenance& provenance) : previous_(t_scoped) {
  t_scoped = provenance;
}

ScopedProvenance::~ScopedProvenance() { t_scoped = previous_; }

std::optional<CloudProvenance> scopedProvenance() { return t_scoped; }

}  // namespace mcws::io
