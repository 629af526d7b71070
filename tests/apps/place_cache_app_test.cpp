// mcws_place's map cache through its command line (planar2, a small map): a second run with the
// same map inputs reuses the map and places exactly as the first; another robot file,
// resolution or seed builds another; a damaged entry is rebuilt with one warning; off, an
// unwritable cache and a failed run store nothing; over MCWS_MAP_CACHE_LIMIT_MB the oldest entries
// go, and a bad limit stops the run before the map is built.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "apps/tool_paths.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

class PlaceCacheApp : public ::testing::Test {
 protected:
  PlaceCacheApp() {
    test::writeFile(dir_.file("targets.csv"),
                    "x,y,z,normal_x,normal_y,normal_z\n0,50,0,0,0,-1\n40,50,0,0,0,-1\n");
  }
  std::string file(const std::string& name) const { return dir_.file(name); }
  /// The cache directory of the tests (never the home's).
  std::string cache() const { return cache_.file("maps"); }
  /// mcws_place on planar2 building its own map (self-collision checked), with `extra` flags;
  /// `map` the resolution and seed.
  test::RunResult place(const std::string& extra, const std::string& output = "bases.pcd",
                        const std::string& robot = test::robotPath("planar2"),
                        const std::string& map = "--resolution 10cm --seed 3") const {
    return test::run(kPlace + " --robot " + robot + " --targets " + file("targets.csv") +
                     " --along \"-30 70 10\" --orientations 16 --samples 20000 --confirm all " +
                     map + " --output " + file(output) + " " + extra);
  }
  /// The entries in the cache directory.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    if (!std::filesystem::exists(cache())) return names;
    for (const auto& entry : std::filesystem::directory_iterator(cache()))
      names.push_back(entry.path().string());
    return names;
  }
  test::TempDir dir_, cache_, out_;
};

TEST_F(PlaceCacheApp, ASecondRunReusesTheMapAndPlacesByteForByteAsTheFirst) {
  const test::RunResult first =
      place("--map-cache " + cache() + " --json --plot " + file("first.png"));
  ASSERT_EQ(first.exit_code, 0) << first.err;
  ASSERT_EQ(entries().size(), 1u);
  const std::string entry = entries()[0];
  EXPECT_THAT(entry, ::testing::MatchesRegex(".*/planar2-[0-9a-f]{64}\\.bin"));
  EXPECT_THAT(first.err, HasSubstr("mcws_place: no --map: building a reachability map here from "
                                   "20000 samples, each checked for self-collision (will be "
                                   "cached at " +
                                   entry + ")\n"));
  const auto one = nlohmann::json::parse(first.out);
  EXPECT_EQ(one["map_cache"],
            (nlohmann::json{
                {"directory", cache()}, {"path", entry}, {"reused", false}, {"stored", true}}));
  EXPECT_EQ(one["map"]["about"]["source"], "built");

  const test::RunResult second = place(
      "--map-cache " + cache() + " --json --threads 1 --plot " + file("second.png"), "second.pcd");
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_THAT(second.err, HasSubstr("mcws_place: reusing the cached map " + entry + " (built "));
  EXPECT_THAT(second.err, HasSubstr(" from 20000 samples in "));
  EXPECT_THAT(second.err, Not(HasSubstr("building")));
  EXPECT_THAT(second.err, Not(HasSubstr("map samples")));  // no map progress
  const auto two = nlohmann::json::parse(second.out);
  EXPECT_EQ(two["map_cache"]["reused"], true);
  EXPECT_EQ(two["map_cache"]["stored"], false);
  EXPECT_EQ(two["map_cache"]["path"], entry);
  EXPECT_EQ(two["map"]["about"]["source"], "cache");
  EXPECT_EQ(two["map"]["about"]["self_collision"], true);
  EXPECT_EQ(two["map"]["about"]["samples"], 20000);
  for (const char* key : {"candidates", "best", "confirmation", "positions", "targets"})
    EXPECT_EQ(two[key], one[key]) << key;
  EXPECT_EQ(test::readFile(file("second.pcd")), test::readFile(file("bases.pcd")));
  EXPECT_EQ(test::readFile(file("second.png")), test::readFile(file("first.png")));
  EXPECT_EQ(entries().size(), 1u);

  // The entry is a map file: --map of it places the same.
  const test::RunResult as_map =
      test::run(kPlace + " --robot " + test::robotPath("planar2") + " --targets " +
                file("targets.csv") + " --along \"-30 70 10\" --seed 3 --confirm all --map " +
                entry + " --json --output " + file("third.pcd"));
  ASSERT_EQ(as_map.exit_code, 0) << as_map.err;
  EXPECT_EQ(nlohmann::json::parse(as_map.out)["candidates"], one["candidates"]);
  EXPECT_FALSE(nlohmann::json::parse(as_map.out).contains("map_cache"));
  EXPECT_EQ(test::readFile(file("third.pcd")), test::readFile(file("bases.pcd")));
}

TEST_F(PlaceCacheApp, AnotherRobotFileResolutionOrSeedBuildsAnotherMap) {
  const std::string robot = file("planar2.yaml");
  std::filesystem::copy_file(test::robotPath("planar2"), robot);
  const std::string flags = "--map-cache " + cache();
  ASSERT_EQ(place(flags, "a.pcd", robot).exit_code, 0);
  ASSERT_EQ(entries().size(), 1u);
  test::writeFile(robot, test::readFile(robot) + "# edited: another SHA-256\n");
  const test::RunResult edited = place(flags, "b.pcd", robot);
  ASSERT_EQ(edited.exit_code, 0) << edited.err;
  EXPECT_THAT(edited.err, HasSubstr("(will be cached at "));
  EXPECT_EQ(entries().size(), 2u);
  ASSERT_EQ(place(flags, "c.pcd", robot, "--resolution 12cm --seed 3").exit_code, 0);
  EXPECT_EQ(entries().size(), 3u);
  ASSERT_EQ(place(flags, "d.pcd", robot, "--resolution 10cm --seed 4").exit_code, 0);
  EXPECT_EQ(entries().size(), 4u);
  const test::RunResult no_collision = place(flags + " --no-collision", "e.pcd", robot);
  ASSERT_EQ(no_collision.exit_code, 0);
  EXPECT_EQ(entries().size(), 5u);
  // Each again: all five reused.
  for (const auto& [extra, map] : std::vector<std::pair<std::string, std::string>>{
           {"", "--resolution 10cm --seed 3"},
           {"", "--resolution 12cm --seed 3"},
           {"", "--resolution 10cm --seed 4"},
           {" --no-collision", "--resolution 10cm --seed 3"}}) {
    const test::RunResult again = place(flags + extra, "f.pcd", robot, map);
    ASSERT_EQ(again.exit_code, 0) << again.err;
    EXPECT_THAT(again.err, HasSubstr("reusing the cached map")) << extra << map;
  }
  EXPECT_EQ(entries().size(), 5u);
}

TEST_F(PlaceCacheApp, ADamagedEntryIsRebuiltWithAOneLineWarning) {
  ASSERT_EQ(place("--map-cache " + cache(), "a.pcd").exit_code, 0);
  ASSERT_EQ(entries().size(), 1u);
  const std::string entry = entries()[0];
  std::string bytes = test::readFile(entry);
  bytes.resize(bytes.size() - 3);  // truncated
  test::writeFile(entry, bytes);
  const test::RunResult r = place("--map-cache " + cache() + " --json", "b.pcd");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("mcws_place: ignoring the cached map " + entry +
                               ": the voxel records do not match their SHA-256 (a damaged "
                               "file); building it again\n"));
  EXPECT_THAT(r.err, HasSubstr("(will be cached at " + entry + ")"));
  EXPECT_EQ(nlohmann::json::parse(r.out)["map_cache"]["stored"], true);
  EXPECT_EQ(test::readFile(file("b.pcd")), test::readFile(file("a.pcd")));
  // Rebuilt: the next run reuses it.
  const test::RunResult next = place("--map-cache " + cache(), "c.pcd");
  EXPECT_THAT(next.err, HasSubstr("reusing the cached map " + entry));
  EXPECT_EQ(test::readFile(file("c.pcd")), test::readFile(file("a.pcd")));
}

TEST_F(PlaceCacheApp, TwoRunsAtOnceLeaveOneGoodEntry) {
  const std::string one = kPlace + " --robot " + test::robotPath("planar2") + " --targets " +
                          file("targets.csv") +
                          " --along \"-30 70 10\" --orientations 16 --samples 20000 --confirm all "
                          "--resolution 10cm --seed 3 --map-cache " +
                          cache() + " --output ";
  const test::RunResult both = test::run("(" + one + file("a.pcd") + " & p=$!; " + one +
                                         file("b.pcd") + " & q=$!; wait $p && wait $q)");
  ASSERT_EQ(both.exit_code, 0) << both.err;
  ASSERT_EQ(entries().size(), 1u);
  const test::RunResult after = place("--map-cache " + cache(), "c.pcd");
  EXPECT_THAT(after.err, HasSubstr("reusing the cached map " + entries()[0]));
  EXPECT_EQ(test::readFile(file("a.pcd")), test::readFile(file("c.pcd")));
  EXPECT_EQ(test::readFile(file("b.pcd")), test::readFile(file("c.pcd")));
}

/// Sets the environment variable `name` to `value` for the object's life, then puts it back.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    const char* was = std::getenv(name);
    if (was) saved_ = was;
    had_ = was != nullptr;
    ::setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (had_) {
      ::setenv(name_, saved_.c_str(), 1);
    } else {
      ::unsetenv(name_);
    }
  }

 private:
  const char* name_;
  std::string saved_;
  bool had_{false};
};

TEST_F(PlaceCacheApp, OverTheLimitTheOldestEntriesGoAndABadLimitStopsTheRun) {
  std::filesystem::create_directories(cache());
  const std::string old = cache() + "/arm-" + std::string(64, '7') + ".bin";
  test::writeFile(old, std::string(std::size_t{2} << 20, 'x'));  // 2 MiB, written long ago
  std::filesystem::last_write_time(
      old, std::filesystem::file_time_type::clock::now() - std::chrono::hours(48));
  {
    const ScopedEnv limit("MCWS_MAP_CACHE_LIMIT_MB", "1");
    const test::RunResult run = place("--map-cache " + cache() + " --json");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_THAT(run.err, HasSubstr("mcws_place: the map cache " + cache() +
                                   " is over its limit of 1.0 MiB: removed the 1 oldest map "
                                   "(2.0 MiB)\n"));
    EXPECT_FALSE(std::filesystem::exists(old));
    ASSERT_EQ(entries().size(), 1u);
    EXPECT_EQ(nlohmann::json::parse(run.out)["map_cache"]["stored"], true);
  }
  const ScopedEnv bad("MCWS_MAP_CACHE_LIMIT_MB", "1GB");
  const test::RunResult run = place("--map-cache " + cache(), "bad.pcd");
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_EQ(run.err,
            "mcws_place: MCWS_MAP_CACHE_LIMIT_MB: '1GB' is not a whole number of MiB (0: no "
            "limit) up to 2^40\n");
  EXPECT_FALSE(std::filesystem::exists(file("bad.pcd")));
}

TEST_F(PlaceCacheApp, OffUnwritableAndFailedRunsStoreNothing) {
  // off: no cache, as before it existed.
  const test::RunResult off = place("--map-cache off --json", "a.pcd");
  ASSERT_EQ(off.exit_code, 0) << off.err;
  EXPECT_THAT(off.err, HasSubstr("(mcws_reach --map MAP.bin builds one to pass as --map)"));
  EXPECT_EQ(nlohmann::json::parse(off.out)["map_cache"],
            (nlohmann::json{
                {"directory", nullptr}, {"path", nullptr}, {"reused", false}, {"stored", false}}));
  EXPECT_TRUE(entries().empty());
  // A cache that cannot be made (a file where its folder would be): one warning, the run goes on.
  test::writeFile(file("plain"), "x");
  const test::RunResult unwritable = place("--map-cache " + file("plain") + "/maps", "b.pcd");
  ASSERT_EQ(unwritable.exit_code, 0) << unwritable.err;
  EXPECT_THAT(unwritable.err, ::testing::ContainsRegex(
                                  "mcws_place: cannot cache the map at [^\n]*/plain/maps/"
                                  "planar2-[0-9a-f]{64}\\.bin: [^\n]* \\(the run goes on\\)\n"));
  EXPECT_EQ(test::readFile(file("b.pcd")), test::readFile(file("a.pcd")));
  // A run that fails while building the map (a tool point beyond the index range of a tiny
  // voxel) and one that fails before (bad targets) store nothing.
  const test::RunResult tiny =
      place("--map-cache " + cache(), "c.pcd", test::robotPath("planar2"), "--resolution 0.00001");
  EXPECT_EQ(tiny.exit_code, 1) << tiny.err;
  test::writeFile(file("targets.csv"), "x,y,z\n1,2,3\n");
  EXPECT_NE(place("--map-cache " + cache(), "d.pcd").exit_code, 0);
  EXPECT_TRUE(entries().empty());
  // A run killed while it builds its map leaves nothing in the cache.
  test::writeFile(file("targets.csv"), "x,y,z,normal_x,normal_y,normal_z\n0,50,0,0,0,-1\n");
  const test::RunResult killed =
      test::run("timeout -s KILL 2 " + kPlace + " --robot " + test::robotPath("planar2") +
                " --targets " + file("targets.csv") + " --along \"0 10 10\" --resolution 1cm " +
                "--samples 100000000000 --map-cache " + cache() + " --output " + file("e.pcd"));
  EXPECT_NE(killed.exit_code, 0);
  EXPECT_TRUE(entries().empty());
  const test::RunResult help = test::run(kPlace + " --help");
  EXPECT_THAT(help.out, HasSubstr("--map-cache"));
  EXPECT_THAT(help.out, HasSubstr("~/.cache/mcws/reach-maps"));
  // With --map, --map-cache is refused.
  test::expectToolFailure(kPlace,
                          "--robot " + test::robotPath("planar2") + " --targets " +
                              file("targets.csv") + " --along \"0 10 10\" --map " + file("m.bin") +
                              " --map-cache " + cache() + " --output " + out_.file("o.pcd"),
                          2, "--map-cache is for a map built here, not with --map", out_);
}

}  // namespace
}  // namespace mcws
