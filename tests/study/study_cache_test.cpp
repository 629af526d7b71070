// mcws_study --map-cache: the reach map of a second study run comes from the cache and the report
// is the same; the entry is mcws_place's for the same robot file and map flags (one cache for
// both tools).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "study/study_files.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

const std::string kStudyTool = MCWS_STUDY_EXE;
const std::string kPlaceTool = MCWS_PLACE_EXE;

/// The report without its wall times: every "seconds" and "*_seconds" member, and the view's
/// table of the stages' times.
nlohmann::json reportWithoutTimes(nlohmann::json json) {
  if (json.is_object() && json.contains("title") && json["title"] == "Time of each stage")
    return nlohmann::json();
  if (json.is_object()) {
    nlohmann::json out = nlohmann::json::object();
    for (auto& [key, value] : json.items()) {
      if (key == "seconds" || (key.size() > 8 && key.compare(key.size() - 8, 8, "_seconds") == 0))
        continue;
      out[key] = reportWithoutTimes(value);
    }
    return out;
  }
  if (json.is_array()) {
    for (auto& item : json) item = reportWithoutTimes(item);
  }
  return json;
}

std::size_t cacheEntryCount(const std::string& directory) {
  if (!std::filesystem::exists(directory)) return 0;
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(directory)) ++n;
  return n;
}

TEST(StudyMapCache, ASecondStudyReusesTheMapAndReportsTheSameAsMcwsPlaceShares) {
  const test::StudyFiles files;
  const std::string cache = files.file("cache");
  const auto study = [&](const std::string& out) {
    return test::run(kStudyTool + " --study " + files.file("study.yaml") + " --output " +
                     files.file(out) + " --json --threads 2 --map-cache " + cache);
  };
  const test::RunResult first = study("one");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_THAT(first.err, HasSubstr("mcws_study: building the reach map (will be cached at " +
                                   cache + "/maintenance4-"));
  ASSERT_EQ(cacheEntryCount(cache), 1u);
  const test::RunResult second = study("two");
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_THAT(second.err, HasSubstr("mcws_study: reusing the cached map " + cache));
  EXPECT_THAT(second.err, Not(HasSubstr("reach map samples")));
  EXPECT_EQ(reportWithoutTimes(nlohmann::json::parse(second.out)),
            reportWithoutTimes(nlohmann::json::parse(first.out)));
  // The files besides the report (whose times differ) are the same, byte for byte.
  std::size_t compared = 0;
  for (const auto& entry : std::filesystem::directory_iterator(files.file("one"))) {
    const std::string name = entry.path().filename().string();
    if (name == "report.json" || name == "report.html") continue;
    ASSERT_TRUE(std::filesystem::exists(files.file("two/" + name))) << name;
    EXPECT_EQ(test::readFile(files.file("two/" + name)), test::readFile(entry.path().string()))
        << name;
    ++compared;
  }
  EXPECT_GE(compared, 3u);  // samples, boundary, envelope at least
  EXPECT_EQ(cacheEntryCount(cache), 1u);

  // mcws_place with the study's map flags (study_app_test's PlacementIsMcwsPlaces...) finds the
  // study's map in the cache.
  const test::RunResult place =
      test::run(kPlaceTool + " --robot " + files.file("robot.yaml") + " --targets " +
                files.file("targets.csv") +
                " --along '20 40 10' --resolution 4 --samples 40000 --orientations 50 --seed 3"
                " --approach-tolerance 10deg --confirm all --threads 1 --json --output " +
                files.file("bases.pcd") + " --map-cache " + cache);
  ASSERT_EQ(place.exit_code, 0) << place.err;
  EXPECT_THAT(place.err, HasSubstr("mcws_place: reusing the cached map " + cache));
  EXPECT_EQ(nlohmann::json::parse(first.out)["placement"]["candidates"],
            nlohmann::json::parse(place.out)["candidates"]);
  EXPECT_EQ(cacheEntryCount(cache), 1u);
}

}  // namespace
}  // namespace mcws
