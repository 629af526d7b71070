#pragma once
// What the tests of the output rules (outputs_app_test.cpp, output_set_app_test.cpp) share: the
// inputs they give the tools, and the listing of a folder the tools wrote into.

#include <filesystem>
#include <set>
#include <string>

#include "test_support.h"

namespace mcws::test {

inline const std::string kPlanar2Robot = robotPath("planar2");
inline const std::string kAnnulusCloud = std::string(MCWS_CLOUDS_DIR) + "/annulus_2000_seed1.pcd";
inline const std::string kCleanerBehaviors =
    std::string(MCWS_ROBOTS_DIR) + "/insulator_cleaner_behaviors.yaml";
inline const std::string kPlanar2Scenario = std::string(MCWS_SCENARIOS_DIR) + "/planar2.yaml";
/// planar2.yaml made light (tests/apps/data/): for tests of files, not of numbers.
inline const std::string kPlanar2QuickScenario =
    std::string(MCWS_SCENARIOS_DIR) + "/../tests/apps/data/planar2_quick.yaml";

/// The names of the entries of folder `dir`.
inline std::set<std::string> listing(const std::string& dir) {
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    names.insert(entry.path().filename());
  return names;
}

}  // namespace mcws::test
