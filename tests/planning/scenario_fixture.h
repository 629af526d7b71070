#pragma once
// The scenario-file tests' robot, scenarios and fixture (scenario_test.cpp and
// scenario_errors_test.cpp).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <initializer_list>
#include <string>

#include "mcws/planning/scenario.h"
#include "test_support.h"

namespace mcws::test {

// A revolute joint (deg limits) and a prismatic one in cm, a base pose of its own and one
// obstacle.
inline const char* const kRobot = R"(name: rp2
units: {length: cm, angle: deg}
convention: standard
base: {xyz: [1, 2, 3], rpy: [0, 0, 0]}
joints:
  - {name: q1, type: revolute, a: 20, alpha: 0, d: 0, theta: 0, limits: [-180, 180]}
  - {name: s2, type: prismatic, a: 0, alpha: 0, d: 5, theta: 0, limits: [0, 30]}
collision:
  links:
    q1:
      - {type: capsule, from: [-20, 0, 0], to: [0, 0, 0], radius: 2}
    s2:
      - {type: sphere, center: [0, 0, 0], radius: 2}
  environment:
    - {name: post, type: box, size: [4, 4, 4], xyz: [60, 0, 0]}
)";

// Line numbers of the fields, for the messages: name 1, robot 2, start 3, goal 4,
// joint_scale 5, sway 6 (pivot 7, line 8, swing 9, slide 10, confidence 11, poses 12, seed 13),
// planner 14 (candidates 15, diversity 16, roadmap_nodes 17, max_roadmap_nodes 18,
// neighbours 19, roadmap_seed 20, segment_length 21, rule 22, weight 23, threshold 24,
// base_step 25, base_range 26, padding 27), validation 28.
inline const char* const kScenario = R"(name: good
robot: arm.yaml
start: [90 deg, 100 mm]
goal: [-pi/6 rad, 0.2 m]
joint_scale: [1, 0.5]
sway:
  pivot: [0 cm, 10 mm, 0.25 m]
  line: [1, 0, 0]
  swing: 3 deg
  slide: 1 cm
  confidence: 0.9
  poses: 40
  seed: 7
planner:
  candidates: 4
  diversity: 0.25
  roadmap_nodes: 120
  max_roadmap_nodes: 480
  neighbours: 6
  roadmap_seed: 3
  segment_length: 0.25
  rule: literal
  weight: 2
  threshold: 0.8
  base_step: 20 mm
  base_range: 0.1 m
  padding: auto
validation: {poses: 500}
)";

// The smallest scenario: no joint_scale, base, planner or validation.
inline const char* const kMinimal = R"(name: minimal
robot: arm.yaml
start: [0 rad, 0 cm]
goal: [1 rad, 10 cm]
sway:
  pivot: [0 cm, 0 cm, 0 cm]
  line: [0, 1, 0]
)";

/// `text` with its first `from` replaced by `to` (which must be there).
inline std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "no '" << from << "' in the scenario";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

class ScenarioFile : public ::testing::Test {
 protected:
  void SetUp() override { writeFile(dir_.file("arm.yaml"), kRobot); }

  /// Writes `text` to s.yaml next to arm.yaml and loads it.
  mcws::Scenario load(const std::string& text) const {
    writeFile(path(), text);
    return loadScenario(path());
  }

  std::string path() const { return dir_.file("s.yaml"); }

  /// Loading `text` fails with one line "s.yaml:<line>: ..." holding every part.
  void expectError(const std::string& text, int line,
                   std::initializer_list<std::string> parts) const {
    writeFile(path(), text);
    const std::string message = errorOf([&] { loadScenario(path()); });
    EXPECT_EQ(message.rfind(path() + ":" + std::to_string(line) + ": ", 0), 0u)
        << "wanted " << path() << ":" << line << ": ...\ngot: " << message;
    for (const std::string& part : parts) EXPECT_THAT(message, ::testing::HasSubstr(part));
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }

  TempDir dir_;
};

}  // namespace mcws::test
