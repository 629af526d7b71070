// The reach-map cache (mcws_place's own map): an entry read back is the map that was built, byte
// for byte; every map input changes the key (a mesh edited behind an unchanged robot file too);
// a damaged, truncated or foreign entry is reported in one line and not used; a cache that
// cannot be written says so and stores nothing.
#include "mcws/reach/map_cache.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
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
