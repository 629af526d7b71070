#include "mcws/reach/map_cache.h"

#include <gnu/libc-version.h>
#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <ostream>
#include <streambuf>
#include <utility>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/io/atomic_file.h"
#include "mcws/io/sha256.h"
#include "mcws/reach/quality.h"
#include "mcws/reach/reach_report.h"
#include "mcws/sampling/sampler.h"

namespace mcws {

namespace {

/// The map file format the entries are written in (ReachMap::write()'s first line).
constexpr char kCacheMapFormat[] = "MCWS-REACH-MAP 1";

/// A JSON value as one line; bytes that are not UTF-8 (a robot name or path in Latin-1) become
/// U+FFFD instead of failing the run over its optional cache.
std::string dumped(const nlohmann::json& value) {
  return value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

/// SHA-256 of the map inputs, fed value by value.
class CacheDigest {
 public:
  void add(const void* data, std::size_t size) { digest_.add(data, size); }
  template <typename T>
  void addValue(const T& value) {
    add(&value, sizeof value);
  }
  /// A string with its length first, so that two strings never hash as their concatenation.
  void addText(const std::string& text) {
    addValue(static_cast<std::uint64_t>(text.size()));
    add(text.data(), text.size());
  }
  /// The digest as 64 lowercase hex digits.
  std::string hex() { return digest_.hex(); }

 private:
  io::Sha256 digest_{"map cache"};
};

void addPose(CacheDigest& digest, const Eigen::Isometry3d& pose) {
  digest.add(pose.matrix().data(), 16 * sizeof(double));
}

void addBody(CacheDigest& digest, const BodySpec& body) {
  digest.addText(body.name);
  digest.addValue(static_cast<std::uint64_t>(body.shapes.size()));
  for (const ShapeSpec& shape : body.shapes) {
    digest.addValue(static_cast<int>(shape.type));
    addPose(digest, shape.T_body_shape);
    digest.add(shape.p_from.data(), 3 * sizeof(double));
    digest.add(shape.p_to.data(), 3 * sizeof(double));
    digest.addValue(shape.radius);
    digest.add(shape.size.data(), 3 * sizeof(double));
    digest.addValue(shape.length);
    const std::uint64_t vertices = shape.mesh ? shape.mesh->vertices.size() : 0;
    const std::uint64_t triangles = shape.mesh ? shape.mesh->triangles.size() : 0;
    digest.addValue(vertices);
    digest.addValue(triangles);
    if (!shape.mesh) continue;
    for (const Eigen::Vector3d& v : shape.mesh->vertices) digest.add(v.data(), 3 * sizeof(double));
    digest.add(shape.mesh->triangles.data(), triangles * sizeof(std::array<int, 3>));
  }
}

/// SHA-256 of everything of a collision model that decides which poses collide.
std::string collisionModelDigest(const CollisionModel& model) {
  CacheDigest digest;
  const auto addPairs = [&](const std::vector<std::pair<std::string, std::string>>& pairs) {
    digest.addValue(static_cast<std::uint64_t>(pairs.size()));
    for (const auto& [a, b] : pairs) {
      digest.addText(a);
      digest.addText(b);
    }
  };
  for (const auto* bodies : {&model.links, &model.environment}) {
    digest.addValue(static_cast<std::uint64_t>(bodies->size()));
    for (const BodySpec& body : *bodies) addBody(digest, body);
  }
  addBody(digest, model.tool);
  addPairs(model.allowed);
  addPairs(model.link_bodies);
  digest.addValue(static_cast<std::uint64_t>(model.link_names.size()));
  for (const std::string& name : model.link_names) digest.addText(name);
  return digest.hex();
}

nlohmann::json poseJson(const Eigen::Isometry3d& pose) {
  nlohmann::json values = nlohmann::json::array();
  for (int k = 0; k < 16; ++k) values.push_back(pose.matrix().data()[k]);
  return values;
}

nlohmann::json jointJson(const Joint& joint) {
  return {{"name", joint.name},
          {"type", jointTypeName(joint.type)},
          {"T_parent_joint", poseJson(joint.T_parent_joint)},
          {"axis", {joint.axis.x(), joint.axis.y(), joint.axis.z()}},
          {"limits", {joint.lower, joint.upper}}};
}

/// Every number of the robot's kinematics (what the map's tool poses and joint draws follow).
nlohmann::json kinematicsJson(const Robot& robot) {
  nlohmann::json joints = nlohmann::json::array(), mimics = nlohmann::json::array();
  for (const Joint& joint : robot.joints) joints.push_back(jointJson(joint));
  for (const MimicJoint& m : robot.mimic_joints) {
    mimics.push_back({{"joint", jointJson(m.joint)},
                      {"before", m.before},
                      {"master", m.master},
                      {"multiplier", m.multiplier},
                      {"offset", m.offset}});
  }
  return {{"T_world_base", poseJson(robot.T_world_base)},
          {"joints", joints},
          {"T_last_flange", poseJson(robot.T_last_flange)},
          {"T_flange_tool", poseJson(robot.T_flange_tool)},
          {"mimic_joints", mimics}};
}

/// A file name part from a robot's name: letters, digits, '.', '_', '-' kept, others '_'.
std::string fileNamePart(const std::string& name) {
  std::string part;
  for (const char c : name.substr(0, 64)) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '.' || c == '_' || c == '-';
    part += keep ? c : '_';
  }
  return part.empty() || part[0] == '.' ? "robot" + part : part;
}

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

/// An output stream buffer handing its bytes, 64 KiB at a time, to `sink`.
class SinkBuffer : public std::streambuf {
 public:
  explicit SinkBuffer(std::function<void(const char*, std::size_t)> sink)
      : sink_(std::move(sink)), buffer_(1u << 16) {
    setp(buffer_.data(), buffer_.data() + buffer_.size());
  }

 protected:
  int_type overflow(int_type c) override {
    drain();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override {
    drain();
    return 0;
  }

 private:
  void drain() {
    if (pptr() > pbase()) sink_(pbase(), static_cast<std::size_t>(pptr() - pbase()));
    setp(buffer_.data(), buffer_.data() + buffer_.size());
  }
  std::function<void(const char*, std::size_t)> sink_;
  std::vector<char> buffer_;
};

/// ReachMap::write() into `sink` (exceptions of the sink pass through).
void writeMapTo(const ReachMap& map, const std::string& header,
                const std::function<void(const char*, std::size_t)>& sink) {
  SinkBuffer buffer(sink);
  std::ostream out(&buffer);
  out.exceptions(std::ios::badbit);
  map.write(out, header);
  out.flush();
}

/// SHA-256 of the voxel records ReachMap::write() writes after its two text lines.
std::string recordDigest(const ReachMap& map) {
  CacheDigest digest;
  int lines = 0;
  writeMapTo(map, "{}", [&](const char* data, std::size_t size) {
    std::size_t k = 0;
    while (lines < 2 && k < size) lines += data[k++] == '\n';
    digest.add(data + k, size - k);
  });
  return digest.hex();
}

/// The entry's header member `name`, which must be there with the type of `T`.
template <typename T>
T headerMember(const nlohmann::json& header, const char* name, const std::string& path) {
  if (!header.contains(name)) throw Error(path + ": the header has no '" + name + "'");
  try {
    return header.at(name).get<T>();
  } catch (const nlohmann::json::exception&) {
    throw Error(path + ": the header's '" + name + "' has the wrong type");
  }
}

/// Checks the entry's header line and the digest of what follows it (the stream at the records).
void checkEntry(std::istream& in, const std::string& json, const std::string& path,
                const std::string& key, std::uint64_t samples, CachedMapInfo* info) {
  const nlohmann::json header = nlohmann::json::parse(json, nullptr, false);
  if (!header.is_object()) throw Error(path + ": the header is not a JSON object");
  const int version = headerMember<int>(header, "cache_version", path);
  if (version != kMapCacheVersion) {
    throw Error(path + ": an entry of cache version " + std::to_string(version) + ", not " +
                std::to_string(kMapCacheVersion));
  }
  if (headerMember<std::string>(header, "cache_key", path) != key)
    throw Error(path + ": the entry's key is not the key of this run's map inputs");
  if (headerMember<std::uint64_t>(header, "samples", path) != samples)
    throw Error(path + ": the entry's sample count is not this run's");
  CacheDigest digest;
  std::vector<char> buffer(1u << 16);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    digest.add(buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw Error(path + ": cannot read the entry: " + std::strerror(errno));
  if (digest.hex() != headerMember<std::string>(header, "payload_sha256", path))
    throw Error(path + ": the voxel records do not match their SHA-256 (a damaged file)");
  if (info) {
    info->built_utc = headerMember<std::string>(header, "built_utc", path);
    info->build_seconds = headerMember<double>(header, "build_seconds", path);
    info->samples = samples;
    info->self_collision = headerMember<bool>(header, "self_collision", path);
  }
}

/// Whether `name` is an entry's file name: `<name>-<64 lowercase hex digits>.bin`.
bool isEntryName(const std::string& name) {
  constexpr std::size_t kKey = 64, kTail = kKey + 4;  // the key and ".bin"
  if (name.size() < kTail + 2 || name.compare(name.size() - 4, 4, ".bin") != 0) return false;
  const std::size_t key = name.size() - kTail;
  if (name[key - 1] != '-') return false;
  return std::all_of(name.begin() + key, name.begin() + key + kKey,
                     [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
}

/// A cache directory's entry: its file, size [bytes] and modification time.
struct Entry {
  std::filesystem::path path;
  std::uint64_t bytes{0};
  std::filesystem::file_time_type written;
};

/// The entries of `directory` (regular files named as entries; links and other files left out,
/// and a file gone while it is listed: another run trimmed it).
std::vector<Entry> entriesOf(const std::string& directory) {
  std::vector<Entry> entries;
  for (const auto& item : std::filesystem::directory_iterator(directory)) {
    if (!isEntryName(item.path().filename().string())) continue;
    std::error_code error;
    if (!std::filesystem::is_regular_file(item.symlink_status(error)) || error) continue;
    Entry entry{item.path(), item.file_size(error), {}};
    if (error) continue;
    entry.written = item.last_write_time(error);
    if (!error) entries.push_back(entry);
  }
  return entries;
}

std::string mebibytes(std::uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", static_cast<double>(bytes) / (1 << 20));
  return text;
}

}  // namespace

std::uint64_t mapCacheLimit() {
  const char* text = std::getenv("MCWS_MAP_CACHE_LIMIT_MB");
  if (!text) return kDefaultMapCacheLimit;
  const std::string value(text);
  constexpr std::uint64_t kLargest = std::uint64_t{1} << 40;  // MiB
  std::uint64_t mib = 0;
  bool whole = !value.empty() && value.size() <= 13;
  for (const char c : value) whole = whole && c >= '0' && c <= '9';
  if (whole) mib = std::stoull(value);
  if (!whole || mib > kLargest) {
    throw Error("MCWS_MAP_CACHE_LIMIT_MB: '" + value +
                "' is not a whole number of MiB (0: no limit) up to 2^40");
  }
  return mib << 20;
}

std::string defaultMapCacheDirectory() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg && xdg[0] == '/') return std::string(xdg) + "/mcws/reach-maps";
  const char* home = std::getenv("HOME");
  if (home && home[0] != '\0') return std::string(home) + "/.cache/mcws/reach-maps";
  return "";
}

std::string mapCacheKey(const Robot& robot, const ReachGrid& grid, const ReachSampling& sampling,
                        const CollisionModel* self_collision) {
  const io::CloudProvenance provenance = robotProvenance(robot);
  const nlohmann::json text{
      {"cache_version", kMapCacheVersion},
      {"map_format", kCacheMapFormat},
      // glibc's libmvec computes the sines and cosines of the samples' joint values: another
      // version may differ in a last bit, so a cache shared between machines does not mix them.
      {"libc", gnu_get_libc_version()},
      {"robot",
       {{"name", robot.name},
        {"length_unit", unitName(robot.length_unit)},
        {"file_sha256", provenance.sha256},
        {"base_link", robot.base_link},
        {"tip_link", robot.tip_link},
        {"kinematics", kinematicsJson(robot)}}},
      {"grid",
       {{"resolution", grid.resolution}, {"directions", grid.directions}, {"rolls", grid.rolls}}},
      {"sampling",
       {{"first", sampling.first},
        {"samples", sampling.samples},
        {"seed", sampling.seed},
        {"manipulability", sampling.manipulability ? qualitySummary(sampling.quality, robot)
                                                   : nlohmann::json(nullptr)}}},
      {"self_collision", self_collision ? nlohmann::json(collisionModelDigest(*self_collision))
                                        : nlohmann::json(nullptr)}};
  CacheDigest digest;
  const std::string text_dumped = dumped(text);
  digest.add(text_dumped.data(), text_dumped.size());
  return digest.hex();
}

ReachMapCache::ReachMapCache(std::string directory, const Robot& robot, const ReachGrid& grid,
                             const ReachSampling& sampling, const CollisionModel* self_collision)
    : directory_(std::move(directory)), grid_(grid), samples_(sampling.samples) {
  if (!enabled()) return;
  key_ = mapCacheKey(robot, grid, sampling, self_collision);
  path_ = (std::filesystem::path(directory_) / (fileNamePart(robot.name) + "-" + key_ + ".bin"))
              .string();
  const io::CloudProvenance provenance = robotProvenance(robot);
  const nlohmann::json summary{
      {"samples", sampling.samples},
      {"seed", sampling.seed},
      {"collision", false},  // the environment: never counted here (a map for placement)
      {"manipulability", sampling.manipulability ? qualitySummary(sampling.quality, robot)
                                                 : nlohmann::json(nullptr)}};
  nlohmann::json header =
      nlohmann::json::parse(mapFileHeader(robot, provenance.file, provenance.sha256, summary));
  header["self_collision"] = self_collision != nullptr;
  header["cache_version"] = kMapCacheVersion;
  header["cache_key"] = key_;
  header_ = dumped(header);
  limit_ = mapCacheLimit();
}

ReachMap ReachMapCache::read(const std::string& path, const std::string& key, const ReachGrid& grid,
                             std::uint64_t samples, CachedMapInfo* info) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the entry: " + std::strerror(errno));
  std::string magic, json;
  if (!std::getline(in, magic) || magic != kCacheMapFormat)
    throw Error(path + ": not a map of format '" + kCacheMapFormat + "'");
  if (!std::getline(in, json)) throw Error(path + ": the entry has no header");
  checkEntry(in, json, path, key, samples, info);
  in.clear();
  in.seekg(0);
  ReachMap map = ReachMap::read(in, path);
  const ReachGrid& got = map.grid();
  if (got.resolution != grid.resolution || got.directions != grid.directions ||
      got.rolls != grid.rolls) {
    throw Error(path + ": the entry's grid is not this run's");
  }
  return map;
}

std::optional<ReachMap> ReachMapCache::load(std::ostream& log, const std::string& tool,
                                            CachedMapInfo* info) const {
  if (!enabled()) return std::nullopt;
  struct stat status {};
  const bool found = ::stat(path_.c_str(), &status) == 0;
  const int stat_error = found ? 0 : errno;
  if (stat_error == ENOENT) return std::nullopt;
  try {
    if (!found) throw Error(path_ + ": " + std::strerror(stat_error));
    if (!S_ISREG(status.st_mode)) throw Error(path_ + ": not a regular file");
    return read(path_, key_, grid_, samples_, info);
  } catch (const std::exception& e) {  // mcws::Error, or std::bad_alloc for an absurd header
    log << tool << ": ignoring the cached map " << e.what() << "; building it again\n";
    return std::nullopt;
  }
}

bool ReachMapCache::store(const ReachMap& map, double build_seconds, std::ostream& log,
                          const std::string& tool) const {
  if (!enabled()) return false;
  try {
    std::error_code error;
    std::filesystem::create_directories(directory_, error);
    if (error) throw Error("cannot make the directory " + directory_ + ": " + error.message());
    nlohmann::json header = nlohmann::json::parse(header_);
    header["built_utc"] = utcNow();
    header["build_seconds"] = std::isfinite(build_seconds) ? build_seconds : 0.0;
    header["payload_sha256"] = recordDigest(map);
    io::AtomicFile file(path_);
    writeMapTo(map, dumped(header),
               [&](const char* data, std::size_t size) { file.write(data, size); });
    file.commit();
  } catch (const std::exception& e) {
    log << tool << ": cannot cache the map at " << path_ << ": " << e.what()
        << " (the run goes on)\n";
    return false;
  }
  trim(log, tool);
  return true;
}

void ReachMapCache::trim(std::ostream& log, const std::string& tool) const {
  if (limit_ == 0) return;
  try {
    std::vector<Entry> entries = entriesOf(directory_);
    std::uint64_t total = 0;
    for (const Entry& entry : entries) total += entry.bytes;
    if (total <= limit_) return;
    // Oldest first, then by name; the entry just written is never removed.
    std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
      return a.written != b.written ? a.written < b.written : a.path < b.path;
    });
    const std::filesystem::path own(path_);
    std::size_t removed = 0;
    std::uint64_t freed = 0;
    for (const Entry& entry : entries) {
      if (total <= limit_) break;
      if (entry.path.filename() == own.filename()) continue;
      std::error_code error;
      // Gone already (another run trimmed it): no longer counted either.
      if (!std::filesystem::remove(entry.path, error) && error) {
        throw Error("cannot remove " + entry.path.string() + ": " + error.message());
      }
      total -= entry.bytes;
      ++removed;
      freed += entry.bytes;
    }
    if (removed > 0) {
      log << tool << ": the map cache " << directory_ << " is over its limit of "
          << mebibytes(limit_) << " MiB: removed the " << removed << " oldest map"
          << (removed == 1 ? "" : "s") << " (" << mebibytes(freed) << " MiB)\n";
    }
  } catch (const std::exception& e) {  // mcws::Error, std::filesystem::filesystem_error
    log << tool << ": cannot trim the map cache " << directory_ << ": " << e.what()
        << " (the run goes on)\n";
  }
}

}  // namespace mcws
