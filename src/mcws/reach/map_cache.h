#pragma once
/// \file
/// \brief A cache of reachability maps built for base placement (mcws_place without --map): a
/// map is stored under a key that hashes everything the map is made from, and a later run with
/// the same inputs reads it instead of building it again.
///
/// Each entry is a map file in the format of docs/reach_map.md (so it is also a valid
/// `mcws_place --map` file), named `<robot>-<key>.bin`, whose header records, besides
/// mcws_reach's members, `self_collision`, `cache_version`, `cache_key`, `built_utc`,
/// `build_seconds` and `payload_sha256` (the SHA-256 of the voxel records). An entry is written
/// through io::AtomicFile (whole or not at all; concurrent writers: the last rename wins, and
/// both wrote the same map) and is trusted only when its key, version, grid, sample count and
/// record digest all match. After a store the directory's oldest entries are removed until the
/// entries take at most mapCacheLimit() bytes (ReachMapCache::store()).

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>

#include "mcws/collision/collision_model.h"
#include "mcws/kinematics/robot.h"
#include "mcws/reach/reach_map.h"

namespace mcws {

/// \brief Version of the cache's key and entries. Bump it whenever a map built from the same
/// inputs would come out different (the map builder's output, the map file format, what the key
/// hashes): entries of another version are then rebuilt, never read.
constexpr int kMapCacheVersion = 1;

/// \brief The size the entries of a cache directory may take by default [bytes]: 2 GiB (24 maps
/// of 85 MB: the mesh arm's at 2 cm from 5e6 samples).
constexpr std::uint64_t kDefaultMapCacheLimit = std::uint64_t{2} << 30;

/// \brief The size the entries of a cache directory may take [bytes]: the environment variable
/// MCWS_MAP_CACHE_LIMIT_MB when set (a whole number of MiB; 0: no limit), else
/// kDefaultMapCacheLimit. \throws mcws::Error naming the variable and its value when it is not a
/// whole number of at most 2^40.
std::uint64_t mapCacheLimit();

/// \brief The default cache directory: `$XDG_CACHE_HOME/mcws/reach-maps` when XDG_CACHE_HOME is
/// an absolute path (the XDG base directory rule), else `$HOME/.cache/mcws/reach-maps`; empty
/// when HOME is not set either (no cache).
std::string defaultMapCacheDirectory();

/// \brief The key of the map built by buildReachMap(robot, grid, sampling) with the self-collision
/// checker of `self_collision` (nullptr: no collision check): 64 lowercase hex digits, the SHA-256
/// of a text naming kMapCacheVersion, the map file format, the robot (name, length unit, the
/// SHA-256 of its file, a URDF chain's base and tip links, and every number of its kinematics:
/// base pose, joints with their limits, flange and tool, mimic joints), the grid (resolution,
/// directions, rolls), the sampling (first sample, samples, seed, whether manipulability is
/// computed and how it is measured) and the collision model's content (every body's shapes,
/// poses and mesh vertices and triangles, the allowed pairs): so an edited mesh or SRDF changes
/// the key even when the robot file does not. The thread count is not part of it (the map does
/// not depend on it). \throws mcws::Error naming the robot file when it cannot be read.
std::string mapCacheKey(const Robot& robot, const ReachGrid& grid, const ReachSampling& sampling,
                        const CollisionModel* self_collision);

/// \brief What a cache entry says of itself.
struct CachedMapInfo {
  std::string built_utc;       ///< when it was built, "2026-11-29T00:41:07Z"
  double build_seconds{0.0};   ///< how long the build took [s]
  std::uint64_t samples{0};    ///< joint samples of the map
  bool self_collision{false};  ///< whether only samples free of self-collision were counted
};

/// \brief One map's entry in a cache directory.
class ReachMapCache {
 public:
  /// \param directory the cache directory; empty: no cache (load() finds nothing, store() stores
  ///   nothing). Made on store() when missing.
  /// \param self_collision as for mapCacheKey(); nullptr: samples not checked.
  /// \throws mcws::Error as mapCacheKey(), or as mapCacheLimit() (read here, when enabled, so
  ///   that a bad limit stops the run before the map is built).
  ReachMapCache(std::string directory, const Robot& robot, const ReachGrid& grid,
                const ReachSampling& sampling, const CollisionModel* self_collision);

  /// \brief Whether there is a cache directory.
  bool enabled() const { return !directory_.empty(); }
  const std::string& directory() const { return directory_; }
  /// \brief The entry's file (empty when not enabled).
  const std::string& path() const { return path_; }
  const std::string& key() const { return key_; }
  /// \brief The size the directory's entries may take after store() [bytes]; 0: no limit.
  std::uint64_t limit() const { return limit_; }
  void setLimit(std::uint64_t bytes) { limit_ = bytes; }

  /// \brief The cached map, when the entry exists and is good. An entry that cannot be read or
  /// does not match (corrupt, truncated, another version or key, another grid) is reported as
  /// one line on `log`, "<tool>: ignoring the cached map <why>; building it again", and not
  /// used. \param info receives what the entry says of itself (may be nullptr).
  std::optional<ReachMap> load(std::ostream& log, const std::string& tool,
                               CachedMapInfo* info = nullptr) const;

  /// \brief Writes `map` (built from the inputs of the key, in `build_seconds` [s]) as the entry,
  /// through io::AtomicFile, making the directory if needed, then removes the directory's other
  /// entries (files named as entries are, `<name>-<64 hex digits>.bin`; nothing else is touched),
  /// the oldest written first (then by name), until all entries take at most limit() bytes; the
  /// new entry stays even when it alone is larger. Removals are reported as one line on `log`,
  /// "<tool>: the map cache <dir> is over its limit of <L> MiB: removed the <n> oldest maps
  /// (<m> MiB)". Nothing throws: a failure (a directory that cannot be made or written, an entry
  /// that cannot be removed) is reported as one line on `log`, "<tool>: cannot cache the map at
  /// <path>: <why> (the run goes on)" or "<tool>: cannot trim the map cache <dir>: <why> (the run
  /// goes on)". Call it with no io::OutputSet alive on the thread (the file would join that
  /// set). \return whether the entry was written.
  bool store(const ReachMap& map, double build_seconds, std::ostream& log,
             const std::string& tool) const;

  /// \brief Reads the entry at `path` for `key`. \throws mcws::Error naming the file and what
  /// does not match; used by load().
  static ReachMap read(const std::string& path, const std::string& key, const ReachGrid& grid,
                       std::uint64_t samples, CachedMapInfo* info);

 private:
  std::string directory_, path_, key_;
  std::string header_;  ///< the entry's header members but cache_key, built_* and the digest
  ReachGrid grid_;
  std::uint64_t samples_{0};
  std::uint64_t limit_{0};

  void trim(std::ostream& log, const std::string& tool) const;
};

}  // namespace mcws
