// Bad scenario files (mcws::loadScenario): every mistake one line naming the file, the line, the
// field and the bad value (the good files are in scenario_test.cpp).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "mcws/core/error.h"
#include "mcws/planning/scenario.h"
#include "planning/scenario_fixture.h"
#include "test_support.h"

namespace mcws {
namespace {

using test::errorOf;
using test::kRobot;
using test::kScenario;
using test::replaced;
using test::ScenarioFile;
using ::testing::HasSubstr;

// ---------------------------------------------------------------------------------------------
// Bad scenarios: one line "s.yaml:<line>: <field>: ..." with the bad value.

TEST_F(ScenarioFile, NegativeSigma) {
  expectError(replaced(kScenario, "swing: 3 deg", "swing: -1 deg"), 9,
              {"sway: swing: sigma -1 deg must be >= 0"});
  expectError(replaced(kScenario, "slide: 1 cm", "slide: -2 mm"), 10,
              {"sway: slide: sigma -2 mm must be >= 0"});
}

TEST_F(ScenarioFile, SigmaOfTheWrongKind) {
  expectError(replaced(kScenario, "swing: 3 deg", "swing: 3 cm"), 9,
              {"sway: swing: ", "'3 cm' is a length; an angle is needed"});
  expectError(replaced(kScenario, "slide: 1 cm", "slide: 1"), 10,
              {"sway: slide: ", "'1' is not a value and a unit"});
}

// The covariance key on line 11, its map from line 12 (where yaml-cpp marks a block map: its
// first key, so messages about the whole matrix name line 12), its rows on lines 15 to 20.
const char* const kCovarianceAt11 =
    "  slide: 1 cm\n"
    "  covariance:\n"
    "    length: cm\n"
    "    angle: rad\n"
    "    matrix:\n"
    "      - [1, 0, 0, 0, 0, 0]\n"
    "      - [0, 1, 0, 0, 0, 0]\n"
    "      - [0, 0, 1, 0, 0, 0]\n"
    "      - [0, 0, 0, 1, 0, 0]\n"
    "      - [0, 0, 0, 0, 1, 0]\n"
    "      - [0, 0, 0, 0, 0, 1]\n";

TEST_F(ScenarioFile, CovarianceNotPositiveSemiDefinite) {
  // [[1, 2], [2, 1]] in the (x, y) block: eigenvalues 3 and -1.
  const std::string text =
      replaced(replaced(replaced(kScenario, "  slide: 1 cm\n", kCovarianceAt11),
                        "[1, 0, 0, 0, 0, 0]", "[1, 2, 0, 0, 0, 0]"),
               "[0, 1, 0, 0, 0, 0]", "[2, 1, 0, 0, 0, 0]");
  // The slide adds 1 cm^2 to (x, x): [[2, 2], [2, 1]], eigenvalues (3 -+ sqrt(17)) / 2.
  expectError(text, 12, {"sway: covariance is not positive semi-definite (eigenvalue -0.56"});
}

TEST_F(ScenarioFile, CovarianceNotSymmetric) {
  const std::string text = replaced(replaced(kScenario, "  slide: 1 cm\n", kCovarianceAt11),
                                    "[0, 0, 1, 0, 0, 0]", "[0, 0.5, 1, 0, 0, 0]");
  expectError(text, 12, {"sway: covariance is not symmetric"});
}

TEST_F(ScenarioFile, CovarianceRowOfFiveNumbers) {
  const std::string text = replaced(replaced(kScenario, "  slide: 1 cm\n", kCovarianceAt11),
                                    "[0, 0, 0, 1, 0, 0]", "[0, 0, 0, 1, 0]");
  expectError(text, 18, {"sway: covariance: row 4 must have 6 numbers"});
}

TEST_F(ScenarioFile, CovarianceOfFiveRows) {
  const std::string text = replaced(replaced(kScenario, "  slide: 1 cm\n", kCovarianceAt11),
                                    "      - [0, 0, 0, 0, 0, 1]\n", "");
  expectError(text, 15, {"sway: covariance: matrix must have 6 rows"});
}

TEST_F(ScenarioFile, CovarianceNegativeVariance) {
  const std::string text = replaced(replaced(kScenario, "  slide: 1 cm\n", kCovarianceAt11),
                                    "[0, 0, 0, 0, 1, 0]", "[0, 0, 0, 0, -1, 0]");
  expectError(text, 19, {"sway: covariance: variance -1", "of row 5 is negative"});
}

TEST_F(ScenarioFile, CovarianceUnknownUnit) {
  const std::string text =
      replaced(replaced(kScenario, "  slide: 1 cm\n", kCovarianceAt11), "length: cm", "length: ft");
  expectError(text, 12, {"sway: covariance: ", "unknown unit 'ft'"});
}

TEST_F(ScenarioFile, ConfidenceOutsideZeroOne) {
  expectError(replaced(kScenario, "confidence: 0.9", "confidence: 0"), 11,
              {"sway: confidence 0 is outside (0, 1)"});
  expectError(replaced(kScenario, "confidence: 0.9", "confidence: 1.5"), 11,
              {"sway: confidence 1.5 is outside (0, 1)"});
  expectError(replaced(kScenario, "confidence: 0.9", "confidence: 1"), 11,
              {"sway: confidence 1 is outside (0, 1)"});
}

/// The reader's words for a count out of its range: "FIELD: VALUE must be a whole number from 1
/// to 1000000000".
std::string countOutOfRange(const std::string& field_value) {
  return field_value + " must be a whole number from 1 to 1000000000";
}

TEST_F(ScenarioFile, PosesAndCandidatesZero) {
  expectError(replaced(kScenario, "poses: 40", "poses: 0"), 12,
              {countOutOfRange("sway: poses: 0")});
  expectError(replaced(kScenario, "poses: 40", "poses: 2.5"), 12,
              {countOutOfRange("sway: poses: 2.5")});
  expectError(replaced(kScenario, "candidates: 4", "candidates: 0"), 15,
              {countOutOfRange("planner: candidates: 0")});
  expectError(replaced(kScenario, "validation: {poses: 500}", "validation: {poses: 0}"), 28,
              {countOutOfRange("validation: poses: 0")});
}

// Counts above 10^9 are refused with the limit they break, not a rule they meet.
TEST_F(ScenarioFile, CountsAboveTheLimitNameTheLimit) {
  for (const char* value : {"2000000000", "4294967297", "1000000001"}) {
    expectError(replaced(kScenario, "candidates: 4", std::string("candidates: ") + value), 15,
                {countOutOfRange(std::string("planner: candidates: ") + value)});
  }
  expectError(replaced(kScenario, "poses: 40", "poses: 2000000000"), 12,
              {countOutOfRange("sway: poses: 2000000000")});
}

TEST_F(ScenarioFile, StartOutsideTheJointLimits) {
  expectError(replaced(kScenario, "start: [90 deg, 100 mm]", "start: [200 deg, 100 mm]"), 3,
              {"start: joint 'q1' value 200 deg is outside its limits", "([-180, 180] deg)"});
  expectError(replaced(kScenario, "goal: [-pi/6 rad, 0.2 m]", "goal: [-pi/6 rad, 0.4 m]"), 4,
              {"goal: joint 's2' value 0.4 m is outside its limits [0, 30] cm"});
}

TEST_F(ScenarioFile, GoalOfTheWrongLength) {
  expectError(replaced(kScenario, "goal: [-pi/6 rad, 0.2 m]", "goal: [0 rad, 0 cm, 0 cm]"), 4,
              {"goal: has 3 values; robot 'rp2' has 2 joints"});
  expectError(replaced(kScenario, "start: [90 deg, 100 mm]", "start: 0 rad"), 3,
              {"start: must be a list of joint values with units"});
}

TEST_F(ScenarioFile, JointValueWithoutUnit) {
  expectError(replaced(kScenario, "start: [90 deg, 100 mm]", "start: [1.5, 100 mm]"), 3,
              {"start[1] (joint 'q1', revolute): '1.5' is not a value and a unit"});
}

TEST_F(ScenarioFile, AngleUnitOnAPrismaticJoint) {
  expectError(replaced(kScenario, "goal: [-pi/6 rad, 0.2 m]", "goal: [-pi/6 rad, 1 rad]"), 4,
              {"goal[2] (joint 's2', prismatic): '1 rad' is an angle; a length is needed"});
  expectError(replaced(kScenario, "goal: [-pi/6 rad, 0.2 m]", "goal: [5 cm, 0.2 m]"), 4,
              {"goal[1] (joint 'q1', revolute): '5 cm' is a length; an angle is needed"});
}

TEST_F(ScenarioFile, UnknownFields) {
  expectError(replaced(kScenario, "joint_scale:", "speed: 3\njoint_scale:"), 5,
              {"scenario: unknown key 'speed'"});
  expectError(replaced(kScenario, "  candidates: 4", "  candidates: 4\n  iterations: 9"), 16,
              {"planner: unknown key 'iterations'"});
  expectError(replaced(kScenario, "  seed: 7", "  seed: 7\n  gust: 1 deg"), 14,
              {"sway: unknown key 'gust'"});
  expectError(replaced(kScenario, "validation: {poses: 500}", "validation: {samples: 500}"), 28,
              {"validation: unknown key 'samples'"});
}

TEST_F(ScenarioFile, DuplicateFields) {
  // The robot parser refuses a key given twice ("key 'x' given twice"); a scenario with two
  // goals must not silently plan to one of them.
  const std::string text = replaced(kScenario, "joint_scale:", "goal: [0 rad, 0 cm]\njoint_scale:");
  test::writeFile(path(), text);
  try {
    const mcws::Scenario s = loadScenario(path());
    ADD_FAILURE() << "a scenario with 'goal:' on lines 4 and 5 loads, goal = ["
                  << s.problem.goal.transpose() << "]";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr(path() + ":5: "));
    EXPECT_THAT(e.what(), HasSubstr("goal"));
  }
}

TEST_F(ScenarioFile, MissingFields) {
  expectError(replaced(kScenario, "goal: [-pi/6 rad, 0.2 m]\n", ""), 1,
              {"scenario: missing field 'goal'"});
}

TEST_F(ScenarioFile, UnknownRule) {
  expectError(replaced(kScenario, "rule: literal", "rule: greedy"), 22,
              {"planner: rule 'greedy' is not literal or weighted"});
}

TEST_F(ScenarioFile, BadPlannerNumbers) {
  expectError(replaced(kScenario, "segment_length: 0.25", "segment_length: 0"), 21,
              {"planner: segment_length 0 must be > 0"});
  expectError(replaced(kScenario, "weight: 2", "weight: -1"), 23,
              {"planner: weight: -1 must be >= 0"});
  expectError(replaced(kScenario, "padding: auto", "padding: -3 cm"), 27,
              {"planner: padding: -3 cm must be >= 0"});
  expectError(replaced(kScenario, "threshold: 0.8", "threshold: high"), 24,
              {"planner: threshold: 'high' is not a number"});
  expectError(replaced(kScenario, "threshold: 0.8", "threshold: 1.5"), 24,
              {"planner: threshold 1.5 is outside [0, 1]"});
  expectError(replaced(kScenario, "base_step: 20 mm", "base_step: -2 cm"), 25,
              {"planner: base_step: -2 cm must be >= 0"});
  expectError(replaced(kScenario, "joint_scale: [1, 0.5]", "joint_scale: [1, 0]"), 5,
              {"joint_scale[2]: 0 must be > 0"});
  expectError(replaced(kScenario, "joint_scale: [1, 0.5]", "joint_scale: [1]"), 5,
              {"joint_scale: must list 2 numbers, one per joint"});
  expectError(replaced(kScenario, "line: [1, 0, 0]", "line: [0, 0, 0]"), 8,
              {"sway: line: must not be zero"});
}

TEST_F(ScenarioFile, UnknownObstacleTypeInTheRobotFile) {
  // The collision parser reports it with the robot file's name and line.
  std::string robot = kRobot;
  robot = replaced(robot, "{name: post, type: box, size: [4, 4, 4],",
                   "{name: post, type: cone, size: [4, 4, 4],");
  test::writeFile(dir_.file("arm.yaml"), robot);
  test::writeFile(path(), kScenario);
  const std::string message = errorOf([&] { loadScenario(path()); });
  EXPECT_EQ(message.rfind(dir_.file("arm.yaml") + ":15: ", 0), 0u) << message;
  EXPECT_THAT(message, HasSubstr("collision: environment"));
  EXPECT_THAT(message, HasSubstr("type 'cone' is not capsule, sphere, box, cylinder or mesh"));
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST_F(ScenarioFile, RobotFileThatDoesNotExist) {
  expectError(
      replaced(kScenario, "robot: arm.yaml", "robot: nowhere.yaml"), 2,
      {"robot: 'nowhere.yaml' does not exist (looked for " + dir_.file("nowhere.yaml") + ")"});
}

TEST_F(ScenarioFile, RobotFileNameTooLongForTheFileSystem) {
  // Found by the scenario fuzzer: std::filesystem::exists threw (ENAMETOOLONG) past the loader.
  const std::string name(5000, 'r');
  expectError(replaced(kScenario, "robot: arm.yaml", "robot: " + name), 2,
              {"robot: '" + name + "' cannot be looked up: File name too long"});
}

TEST_F(ScenarioFile, AKeyThatIsAMapOrAList) {
  // Found by the scenario fuzzer: YAML's "? key" form made the key reading throw past the loader.
  const std::string text = kScenario;
  const int next = test::lineCount(text) + 1;  // the line after the scenario's last
  expectError(text + "? {poses: 101}\n: 1\n", next, {"scenario: a key must be a plain name"});
  expectError(text + "? [a, b]\n: 1\n", next, {"scenario: a key must be a plain name"});
}

TEST_F(ScenarioFile, RobotFileWithoutCollisionSection) {
  std::string robot = kRobot;
  robot.erase(robot.find("collision:"));
  test::writeFile(dir_.file("bare.yaml"), robot);
  expectError(replaced(kScenario, "robot: arm.yaml", "robot: bare.yaml"), 2,
              {"robot: 'bare.yaml' has no collision geometry (collision: key)"});
}

TEST_F(ScenarioFile, MalformedYaml) {
  // An unclosed flow sequence: yaml-cpp stops at the end of the document.
  expectError(replaced(kScenario, "goal: [-pi/6 rad, 0.2 m]", "goal: [-pi/6 rad, 0.2 m"), 5,
              {"end of sequence"});
  expectError("- just\n- a list\n", 1, {"the document must be a map of scenario fields"});
}

TEST_F(ScenarioFile, ScenarioFileThatCannotBeRead) {
  const std::string missing = dir_.file("missing.yaml");
  const std::string message = errorOf([&] { loadScenario(missing); });
  EXPECT_EQ(message, missing + ": scenario file does not exist");
  // A FIFO nobody writes would block the read for ever: refused before it is opened.
  const std::string fifo = dir_.file("fifo.yaml");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  EXPECT_EQ(errorOf([&] { loadScenario(fifo); }),
            fifo + ": scenario file is not a regular file (a FIFO)");
}

}  // namespace
}  // namespace mcws
