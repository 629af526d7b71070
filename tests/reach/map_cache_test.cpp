// The reach-map cache (mcws_place's own map): an entry read back is the map that was built, byte
// for byte; every map input changes the key (a mesh edited behind an unchanged robot file too);
// a damaged, truncated or foreign entry is reported in one line and not used; a cache that
// cannot be written says so and stores nothing; a store over the size limit removes the oldest
// entries only (never the new one, nor a file that is not an entry) and says so.
#include "mcws/reach/map_cache.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string>

#include "mcws/collision/robot_bodies.h"
#include "mcws/kinematics/robot_yaml.h"
#include "mcws/sampling/sampler.h"
#include "reach/planar2.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

/// The map file bytes of `map` with an empty header (the records decide them).
std::string recordBytes(const ReachMap& map) {
  std::ostringstream out;
  map.write(out, "{}");
  return out.str();
}

struct Planar2Map {
  Robot robot = test::planar2();
  CollisionModel self = robotBodiesOnly(loadCollisionModel(robot, robot.source));
  ReachGrid grid;
  ReachSampling sampling;
  Planar2Map() {
    grid.resolution = 10.0;
    grid.directions = 16;
    sampling.samples = 20000;
    sampling.seed = 3;
    sampling.threads = 2;
  }
  ReachMap build() const {
    const CollisionChecker checker(robot, self);
    ReachSampling with = sampling;
    with.collision = &checker;
    return buildReachMap(robot, grid, with);
  }
  ReachMapCache cache(const std::string& directory) const {
    return ReachMapCache(directory, robot, grid, sampling, &self);
  }
};

TEST(MapCache, AStoredMapIsReadBackTheSameWithWhatItSaysOfItself) {
  const test::TempDir dir;
  const Planar2Map inputs;
  const ReachMapCache cache = inputs.cache(dir.file("maps"));
  ASSERT_TRUE(cache.enabled());
  EXPECT_EQ(cache.key().size(), 64u);
  EXPECT_EQ(cache.path(), dir.file("maps") + "/planar2-" + cache.key() + ".bin");
  std::ostringstream log;
  EXPECT_FALSE(cache.load(log, "tool"));  // nothing there yet: a miss, silently
  EXPECT_EQ(log.str(), "");
  const ReachMap built = inputs.build();
  ASSERT_TRUE(cache.store(built, 1.25, log, "tool")) << log.str();
  EXPECT_EQ(log.str(), "");
  CachedMapInfo info;
  const std::optional<ReachMap> read = cache.load(log, "tool", &info);
  ASSERT_TRUE(read) << log.str();
  EXPECT_EQ(log.str(), "");
  EXPECT_EQ(recordBytes(*read), recordBytes(built));
  EXPECT_EQ(info.samples, 20000u);
  EXPECT_TRUE(info.self_collision);
  EXPECT_EQ(info.build_seconds, 1.25);
  EXPECT_EQ(info.built_utc.size(), 20u) << info.built_utc;  // 2026-11-29T00:41:07Z
  // The entry is a map file whose header mcws_place --map accepts for this robot.
  std::ifstream in(cache.path(), std::ios::binary);
  std::string header;
  ReachMap::read(in, cache.path(), &header);
  EXPECT_THAT(header, HasSubstr("\"robot\":\"planar2\""));
  EXPECT_THAT(header, HasSubstr("\"robot_sha256\":\"" +
                                io::sha256OfFile(test::robotPath("planar2")) + "\""));
  EXPECT_THAT(header, HasSubstr("\"collision\":false"));
  EXPECT_THAT(header, HasSubstr("\"cache_key\":\"" + cache.key() + "\""));
}

TEST(MapCache, EveryMapInputChangesTheKeyAndTheThreadCountDoesNot) {
  const Planar2Map base;
  const std::string key = mapCacheKey(base.robot, base.grid, base.sampling, &base.self);
  EXPECT_EQ(mapCacheKey(base.robot, base.grid, base.sampling, &base.self), key);
  std::set<std::string> keys{key};
  const auto differs = [&](const Planar2Map& changed, const CollisionModel* self,
                           const std::string& what) {
    const std::string other = mapCacheKey(changed.robot, changed.grid, changed.sampling, self);
    EXPECT_TRUE(keys.insert(other).second) << what << " gives a key seen before";
  };
  Planar2Map m = base;
  m.grid.resolution = 10.000000001;
  differs(m, &m.self, "resolution");
  m = base, m.grid.directions = 17;
  differs(m, &m.self, "directions");
  m = base, m.grid.rolls = 2;
  differs(m, &m.self, "rolls");
  m = base, m.sampling.samples = 20001;
  differs(m, &m.self, "samples");
  m = base, m.sampling.seed = 4;
  differs(m, &m.self, "seed");
  m = base, m.sampling.first = 1;
  differs(m, &m.self, "first sample");
  m = base, m.sampling.manipulability = false;
  differs(m, &m.self, "no manipulability");
  m = base, m.sampling.quality.task = QualityTask::kPosition;
  differs(m, &m.self, "quality task");
  differs(base, nullptr, "no collision check");
  m = base, m.self.links[2].shapes[0].radius = 2.6;
  differs(m, &m.self, "a capsule's radius");
  m = base, m.self.allowed.emplace_back("base", "q2");
  differs(m, &m.self, "an allowed pair");
  m = base, m.robot.joints[1].upper -= 1e-9;
  differs(m, &m.self, "a joint limit");
  m = base, m.robot.T_world_base.translation().x() += 1.0;
  differs(m, &m.self, "the base pose");
  m = base, m.robot.T_flange_tool.translation().z() = 5.0;
  differs(m, &m.self, "the tool");
  m = base, m.robot.name = "arm-\xe9";  // Latin-1, not UTF-8: a key all the same, no exception
  differs(m, &m.self, "a name that is not UTF-8");
  m = base, m.sampling.threads = 1;
  EXPECT_EQ(mapCacheKey(m.robot, m.grid, m.sampling, &m.self), key) << "threads";
}

TEST(MapCache, AnEditedRobotFileOrMeshChangesTheKey) {
  // ta1400_mesh.yaml and its meshes copied, so that they can be edited.
  const test::TempDir dir;
  namespace fs = std::filesystem;
  const fs::path robots = fs::path(test::robotPath("ta1400_mesh")).parent_path();
  fs::create_directories(dir.file("meshes"));
  fs::copy(robots / "meshes" / "ta1400", dir.file("meshes/ta1400"));
  const std::string robot_file = dir.file("ta1400_mesh.yaml");
  fs::copy_file(robots / "ta1400_mesh.yaml", robot_file);
  const auto key = [&] {
    const Robot robot = loadRobot(robot_file);
    const CollisionModel self = robotBodiesOnly(loadCollisionModel(robot, robot_file));
    ReachGrid grid;
    grid.resolution = 50.0;
    ReachSampling sampling;
    sampling.samples = 1000;
    return mapCacheKey(robot, grid, sampling, &self);
  };
  const std::string original = key();
  // One vertex of the wrist's binary STL moved (its first triangle's first corner's x: bytes
  // 96..99), the robot file unchanged.
  const std::string stl = dir.file("meshes/ta1400/j5_wrist.stl");
  std::string bytes = test::readFile(stl);
  ASSERT_GT(bytes.size(), 100u);
  bytes[96] = static_cast<char>(bytes[96] ^ 0x10);
  test::writeFile(stl, bytes);
  const std::string mesh_edited = key();
  EXPECT_NE(mesh_edited, original);
  // A comment added to the robot file: another SHA-256, another key (the map header's check).
  test::writeFile(robot_file, test::readFile(robot_file) + "# edited\n");
  EXPECT_NE(key(), mesh_edited);
  EXPECT_NE(key(), original);
}

/// Stores the planar map in a fresh cache, damages the entry with `damage` and expects load() to
/// refuse it in one line naming `why`.
void expectRefused(const std::function<void(std::string&)>& damage, const std::string& why) {
  const test::TempDir dir;
  const Planar2Map inputs;
  const ReachMapCache cache = inputs.cache(dir.file("maps"));
  std::ostringstream log;
  ASSERT_TRUE(cache.store(inputs.build(), 0.5, log, "tool")) << log.str();
  std::string bytes = test::readFile(cache.path());
  damage(bytes);
  test::writeFile(cache.path(), bytes);
  EXPECT_FALSE(cache.load(log, "tool")) << why;
  EXPECT_THAT(log.str(), StartsWith("tool: ignoring the cached map " + cache.path() + ": "));
  EXPECT_THAT(log.str(), HasSubstr(why));
  EXPECT_THAT(log.str(), ::testing::EndsWith("; building it again\n"));
  EXPECT_EQ(test::lineCount(log.str()), 1) << log.str();
}

TEST(MapCache, ADamagedTruncatedOrForeignEntryIsReportedInOneLineAndNotUsed) {
  // A bit flipped in the last voxel's records: still a well-formed map, but not the one built.
  expectRefused([](std::string& b) { b[b.size() - 1] = static_cast<char>(b.back() ^ 1); },
                "do not match their SHA-256");
  expectRefused([](std::string& b) { b.resize(b.size() - 7); }, "do not match their SHA-256");
  expectRefused([](std::string& b) { b.resize(10); }, "not a map of format");
  expectRefused([](std::string& b) { b = ""; }, "not a map of format");
  expectRefused(
      [](std::string& b) {
        const std::string from = "\"cache_version\":1", to = "\"cache_version\":0";
        b.replace(b.find(from), from.size(), to);
      },
      "an entry of cache version 0, not 1");
  expectRefused(
      [](std::string& b) {
        const std::size_t at = b.find("\"cache_key\":\"") + 13;
        b[at] = b[at] == 'a' ? 'b' : 'a';
      },
      "key is not the key of this run's map inputs");
  expectRefused(
      [](std::string& b) {
        const std::string from = "\"resolution\":10,";
        b.replace(b.find(from), from.size(), "\"resolution\":20,");
      },
      "the entry's grid is not this run's");
  // A map file of mcws_reach's put there by hand: no cache members.
  expectRefused(
      [](std::string& b) {
        const std::size_t end = b.find('\n', b.find('\n') + 1);
        b = b.substr(0, b.find('\n') + 1) + "{\"resolution\":10}" + b.substr(end);
      },
      "the header has no 'cache_version'");
}

TEST(MapCache, AnUnwritableCacheSaysSoInOneLineAndStoresNothing) {
  const test::TempDir dir;
  test::writeFile(dir.file("file"), "x");  // a file where the directory would be: also as root
  const Planar2Map inputs;
  const ReachMapCache cache = inputs.cache(dir.file("file") + "/maps");
  std::ostringstream log;
  EXPECT_FALSE(cache.store(inputs.build(), 0.5, log, "tool"));
  EXPECT_THAT(log.str(), StartsWith("tool: cannot cache the map at " + cache.path() + ": "));
  EXPECT_THAT(log.str(), ::testing::EndsWith(" (the run goes on)\n"));
  EXPECT_EQ(test::lineCount(log.str()), 1) << log.str();
  EXPECT_FALSE(cache.load(log, "tool"));
}

/// `bytes` in MiB with one decimal, as the cache's message gives it.
std::string mebibytes(std::uint64_t bytes) {
  std::ostringstream text;
  text.setf(std::ios::fixed);
  text.precision(1);
  text << static_cast<double>(bytes) / (1 << 20);
  return text.str();
}

/// An entry's file name for `key_digit` repeated (a name the cache would give a map).
std::string entryName(const std::string& robot, char key_digit) {
  return robot + "-" + std::string(64, key_digit) + ".bin";
}

/// Writes `bytes` bytes at `path`, last written `hours_ago` hours ago.
void writeAged(const std::string& path, std::size_t bytes, int hours_ago) {
  test::writeFile(path, std::string(bytes, 'x'));
  std::filesystem::last_write_time(
      path, std::filesystem::file_time_type::clock::now() - std::chrono::hours(hours_ago));
}

TEST(MapCache, AStoreOverTheLimitRemovesTheOldestEntriesOnlyAndSaysSo) {
  const test::TempDir dir;
  const Planar2Map inputs;
  const ReachMap built = inputs.build();
  // The new entry's size, from a store into a cache of its own.
  const ReachMapCache probe = inputs.cache(dir.file("probe"));
  std::ostringstream log;
  ASSERT_TRUE(probe.store(built, 0.5, log, "tool")) << log.str();
  const std::uint64_t own = std::filesystem::file_size(probe.path());

  const std::string maps = dir.file("maps");
  std::filesystem::create_directories(maps);
  writeAged(maps + "/" + entryName("arm", 'a'), 1000, 30);  // oldest: removed
  writeAged(maps + "/" + entryName("arm", 'b'), 1000, 20);  // removed
  writeAged(maps + "/" + entryName("arm", 'c'), 1000, 10);  // stays: the limit is met
  writeAged(maps + "/notes.txt", 5000, 40);                 // not an entry: never removed
  writeAged(maps + "/arm-short.bin", 5000, 40);             // not an entry's name
  writeAged(maps + "/" + entryName("arm", 'A'), 5000, 40);  // upper-case key: not an entry
  // A link named as an entry: not one (removing it would not free the space it points to).
  std::filesystem::create_symlink(maps + "/notes.txt", maps + "/" + entryName("arm", '0'));
  ReachMapCache cache = inputs.cache(maps);
  EXPECT_EQ(cache.limit(), kDefaultMapCacheLimit);
  cache.setLimit(own + 1500);
  ASSERT_TRUE(cache.store(built, 0.5, log, "tool")) << log.str();
  EXPECT_EQ(log.str(), "tool: the map cache " + maps + " is over its limit of " +
                           mebibytes(own + 1500) + " MiB: removed the 2 oldest maps (0.0 MiB)\n");
  EXPECT_FALSE(std::filesystem::exists(maps + "/" + entryName("arm", 'a')));
  EXPECT_FALSE(std::filesystem::exists(maps + "/" + entryName("arm", 'b')));
  for (const std::string& kept :
       {entryName("arm", 'c'), std::string("notes.txt"), std::string("arm-short.bin"),
        entryName("arm", 'A'), entryName("arm", '0')}) {
    EXPECT_TRUE(std::filesystem::exists(maps + "/" + kept)) << kept;
  }
  const std::optional<ReachMap> read = cache.load(log, "tool");
  ASSERT_TRUE(read) << log.str();
  EXPECT_EQ(recordBytes(*read), recordBytes(built));

  // Under the limit: nothing removed, nothing said.
  std::ostringstream quiet;
  ASSERT_TRUE(cache.store(built, 0.5, quiet, "tool"));
  EXPECT_EQ(quiet.str(), "");
  EXPECT_TRUE(std::filesystem::exists(maps + "/" + entryName("arm", 'c')));
}

TEST(MapCache, TheNewEntryStaysWhenItAloneIsOverTheLimitAndNoLimitRemovesNothing) {
  const test::TempDir dir;
  const Planar2Map inputs;
  const ReachMap built = inputs.build();
  const std::string maps = dir.file("maps");
  std::filesystem::create_directories(maps);
  writeAged(maps + "/" + entryName("arm", 'd'), 3 << 20, 5);  // 3 MiB
  ReachMapCache cache = inputs.cache(maps);
  cache.setLimit(0);  // no limit
  std::ostringstream log;
  ASSERT_TRUE(cache.store(built, 0.5, log, "tool"));
  EXPECT_EQ(log.str(), "");
  EXPECT_TRUE(std::filesystem::exists(maps + "/" + entryName("arm", 'd')));
  cache.setLimit(1);  // one byte
  ASSERT_TRUE(cache.store(built, 0.5, log, "tool"));
  EXPECT_EQ(log.str(), "tool: the map cache " + maps +
                           " is over its limit of 0.0 MiB: removed the 1 oldest map (3.0 MiB)\n");
  EXPECT_FALSE(std::filesystem::exists(maps + "/" + entryName("arm", 'd')));
  EXPECT_TRUE(cache.load(log, "tool"));
}

TEST(MapCache, TheLimitComesFromTheEnvironmentAndABadOneStopsTheRunBeforeTheBuild) {
  const char* saved = std::getenv("MCWS_MAP_CACHE_LIMIT_MB");
  const std::string saved_value = saved ? saved : "";
  ::unsetenv("MCWS_MAP_CACHE_LIMIT_MB");
  EXPECT_EQ(mapCacheLimit(), std::uint64_t{2048} << 20);
  ::setenv("MCWS_MAP_CACHE_LIMIT_MB", "512", 1);
  EXPECT_EQ(mapCacheLimit(), std::uint64_t{512} << 20);
  ::setenv("MCWS_MAP_CACHE_LIMIT_MB", "0", 1);
  EXPECT_EQ(mapCacheLimit(), 0u);
  for (const char* bad : {"", "-1", "1.5", "2G", " 5", "99999999999999"}) {
    ::setenv("MCWS_MAP_CACHE_LIMIT_MB", bad, 1);
    EXPECT_EQ(test::errorOf([] { mapCacheLimit(); }),
              "MCWS_MAP_CACHE_LIMIT_MB: '" + std::string(bad) +
                  "' is not a whole number of MiB (0: no limit) up to 2^40");
  }
  const Planar2Map inputs;
  const test::TempDir dir;
  ::setenv("MCWS_MAP_CACHE_LIMIT_MB", "lots", 1);
  EXPECT_THAT(test::errorOf([&] { inputs.cache(dir.file("maps")); }),
              StartsWith("MCWS_MAP_CACHE_LIMIT_MB: 'lots'"));
  EXPECT_NO_THROW(inputs.cache(""));  // no cache: no limit read
  if (saved) {
    ::setenv("MCWS_MAP_CACHE_LIMIT_MB", saved_value.c_str(), 1);
  } else {
    ::unsetenv("MCWS_MAP_CACHE_LIMIT_MB");
  }
}

TEST(MapCache, NoDirectoryIsNoCache) {
  const Planar2Map inputs;
  const ReachMapCache cache = inputs.cache("");
  EXPECT_FALSE(cache.enabled());
  std::ostringstream log;
  EXPECT_FALSE(cache.load(log, "tool"));
  EXPECT_FALSE(cache.store(inputs.build(), 0.5, log, "tool"));
  EXPECT_EQ(log.str(), "");
}

TEST(MapCache, TheDefaultDirectoryFollowsXdgCacheHomeThenHome) {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  const char* home = std::getenv("HOME");
  const std::string saved_xdg = xdg ? xdg : "", saved_home = home ? home : "";
  ::setenv("XDG_CACHE_HOME", "/x/cache", 1);
  ::setenv("HOME", "/h", 1);
  EXPECT_EQ(defaultMapCacheDirectory(), "/x/cache/mcws/reach-maps");
  ::setenv("XDG_CACHE_HOME", "relative", 1);  // not absolute: ignored, as the XDG rule says
  EXPECT_EQ(defaultMapCacheDirectory(), "/h/.cache/mcws/reach-maps");
  ::unsetenv("XDG_CACHE_HOME");
  EXPECT_EQ(defaultMapCacheDirectory(), "/h/.cache/mcws/reach-maps");
  ::unsetenv("HOME");
  EXPECT_EQ(defaultMapCacheDirectory(), "");
  if (xdg) ::setenv("XDG_CACHE_HOME", saved_xdg.c_str(), 1);
  if (home) ::setenv("HOME", saved_home.c_str(), 1);
}

}  // namespace
}  // namespace mcws
