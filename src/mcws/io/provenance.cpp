#include "mcws/io/provenance.h"

#include <openssl/evp.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <memory>
#include <vector>

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
  return std::string("# ") + kWord + " robot=" + encode(p.robot) + " file=" + encode(p.file) +
         " sha256=" + p.sha256 + " length_unit=" + p.length_unit;
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
  CloudProvenance p;
  std::string* const slots[] = {&p.robot, &p.file, &p.sha256, &p.length_unit};
  const char* const keys[] = {"robot", "file", "sha256", "length_unit"};
  bool seen[4] = {false, false, false, false};
  for (const std::string& word : words(line)) {
    const std::size_t equals = word.find('=');
    if (equals == std::string::npos || equals == 0) {
      throw Error("'" + shortText(word) + "' is not key=value (the line reads " + kForm + ")");
    }
    const std::string key = word.substr(0, equals);
    for (int k = 0; k < 4; ++k) {
      if (key != keys[k]) continue;
      if (seen[k]) throw Error(key + "= given twice");
      seen[k] = true;
      *slots[k] = decode(key, word.substr(equals + 1));
    }
  }
  for (int k = 0; k < 4; ++k) {
    if (!seen[k] || slots[k]->empty()) {
      throw Error(std::string("no ") + keys[k] + "= value (the line reads " + kForm + ")");
    }
  }
  if (!isSha256(p.sha256)) {
    throw Error("sha256=" + shortText(p.sha256) + " is not 64 lowercase hex digits");
  }
  if (!isUnit(p.length_unit)) {
    throw Error("length_unit=" + shortText(p.length_unit) + " is not m, cm or mm");
  }
  return p;
}

std::string sha256OfFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot read the file to hash it");
  const std::unique_ptr<EVP_MD_CTX, void (*)(EVP_MD_CTX*)> context(EVP_MD_CTX_new(),
                                                                   EVP_MD_CTX_free);
  if (!context || EVP_DigestInit_ex(context.get(), EVP_sha256(), nullptr) != 1) {
    throw Error(path + ": cannot hash the file (OpenSSL's SHA-256 failed to start)");
  }
  std::vector<char> buffer(1u << 16);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    const auto count = static_cast<std::size_t>(in.gcount());
    if (count > 0 && EVP_DigestUpdate(context.get(), buffer.data(), count) != 1) {
      throw Error(path + ": cannot hash the file (OpenSSL's SHA-256 failed)");
    }
  }
  if (in.bad()) throw Error(path + ": cannot read the file to hash it");
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int length = 0;
  if (EVP_DigestFinal_ex(context.get(), digest.data(), &length) != 1 || length != 32) {
    throw Error(path + ": cannot hash the file (OpenSSL's SHA-256 failed)");
  }
  std::string hex;
  for (unsigned int k = 0; k < length; ++k) {
    char byte[3];
    std::snprintf(byte, sizeof byte, "%02x", digest[k]);
    hex += byte;
  }
  return hex;
}

ScopedProvenance::ScopedProvenance(const CloudProvenance& provenance) : previous_(t_scoped) {
  t_scoped = provenance;
}

ScopedProvenance::~ScopedProvenance() { t_scoped = previous_; }

std::optional<CloudProvenance> scopedProvenance() { return t_scoped; }

}  // namespace mcws::io
