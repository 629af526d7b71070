// mcws_plan through its command line: usage errors, bad scenarios, the three ways of finding no
// path, a real run on a tiny planar arm (CSV, JSON), determinism across threads, --plot, and
// input files left alone.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "apps/tool_paths.h"
#include "png_image.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

const std::string kScenarios = MCWS_SCENARIOS_DIR;

// CSV numbers have 12 significant digits; joint values here are at most 2 pi.
constexpr double kCsvTol = 1e-9;

// A two-joint planar arm in cm (robots/planar2.yaml with one post): upper arm 40 cm, forearm
// 30 cm, both capsules of radius 2.5 cm in the world x-y plane; a 10 x 10 cm post centred at
// (35, 45), at 57 cm from the base, so the straight arm collides with it at q1 = 52 deg
// (atan2(45, 35)). Its nearest corner, (30, 40), is 50 cm away: the upper arm (40 + 2.5 cm)
// never touches it, and folding the elbow gets past.
const char* const kArm = R"(name: arm2
units: {length: cm, angle: deg}
convention: standard
joints:
  - {name: q1, type: revolute, a: 40, alpha: 0, d: 0, theta: 0, limits: [-180, 180]}
  - {name: q2, type: revolute, a: 30, alpha: 0, d: 0, theta: 0, limits: [-160, 160]}
collision:
  links:
    q1:
      - {type: capsule, from: [0, 0, 0], to: [40, 0, 0], radius: 2.5}
    q2:
      - {type: capsule, from: [0, 0, 0], to: [30, 0, 0], radius: 2.5}
  environment:
    - {name: post, type: box, size: [10, 10, 40], xyz: [35, 45, 0]}
)";

// A small, fast scenario for the arm: the straight turn from 0 to 120 deg passes through the
// post, so the path must fold the elbow. @START@ and @GOAL@ are replaced.
const char* const kArmScenario = R"(name: tiny
robot: arm2.yaml
start: [@START@]
goal: [@GOAL@]
sway:
  pivot: [0 cm, 0 cm, 25 cm]
  line: [1, 0, 0]
  swing: 1 deg
  slide: 0.5 cm
  poses: 80    # at least 73: fewer cannot show a whole-path collision rate below 0.05
  seed: 1
planner:
  candidates: 3
  roadmap_nodes: 150
  max_roadmap_nodes: 600
  threshold: 0.5
validation: {poses: 200}
)";

// One prismatic joint moving a sphere (radius 2 cm) along world y from -20 to 20 cm (the base
// turned so that its z axis is world y); a wall 2 cm thick at y = 0, larger in x and z than
// anything the sphere can reach, parts y < 0 from y > 0.
const char* const kSlider = R"(name: slider
units: {length: cm, angle: deg}
convention: standard
base: {xyz: [0, 0, 0], rpy: [-90, 0, 0]}
joints:
  - {name: y, type: prismatic, a: 0, alpha: 0, d: 0, theta: 0, limits: [-20, 20]}
collision:
  links:
    y:
      - {type: sphere, center: [0, 0, 0], radius: 2}
  environment:
    - {name: wall, type: box, size: [200, 2, 200], xyz: [0, 0, 0]}
)";

const char* const kSliderScenario = R"(name: walled
robot: slider.yaml
start: [-10 cm]
goal: [10 cm]
sway:
  pivot: [0 cm, 0 cm, 25 cm]
  line: [1, 0, 0]
  slide: 0.5 cm
  poses: 20
planner:
  candidates: 3
  roadmap_nodes: 50
  max_roadmap_nodes: 100
validation: {poses: 100}
)";

// The slider past a post beside its way: the post (y from -4 to 4 cm) has its face at x = 3 cm,
// so the sphere (radius 2 cm, at x = the base's slide, sigma 1 cm) touches it for the poses that
// slide more than 1 cm toward it: about 13 % of them (P(X > 1 | |X| <= 1.96) for X ~ N(0, 1)). Only
// the segments beside the post lose those poses, so the patent's P stays high.
const char* const kBesideScenario = R"(name: beside
robot: slider_post.yaml
start: [-20 cm]
goal: [20 cm]
sway:
  pivot: [0 cm, 0 cm, 25 cm]
  line: [1, 0, 0]
  slide: 1 cm
  poses: 100
planner:
  candidates: 2
  roadmap_nodes: 30
  max_roadmap_nodes: 60
  segment_length: 4
  threshold: 0.9
validation: {poses: 200}
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

/// Lines of stderr that are not progress lines ("mcws_plan: 40% (2/5 segments)", printed when a
/// stage takes more than a second, as it may in a sanitizer build).
std::vector<std::string> messageLines(const std::string& err) {
  std::vector<std::string> lines;
  std::istringstream in(err);
  for (std::string line; std::getline(in, line);) {
    const std::size_t percent = line.find("% (");
    const bool progress = line.rfind("mcws_plan: ", 0) == 0 && percent != std::string::npos &&
                          line.find_first_not_of("0123456789", 11) == percent;
    if (!progress) lines.push_back(line);
  }
  return lines;
}

/// `json` without any key (at any depth) that ends in "seconds": wall times differ between runs.
nlohmann::json withoutTimes(const nlohmann::json& json) {
  if (json.is_object()) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [key, value] : json.items()) {
      const std::string suffix = "seconds";
      if (key.size() >= suffix.size() &&
          key.compare(key.size() - suffix.size(), suffix.size(), suffix) == 0)
        continue;
      out[key] = withoutTimes(value);
    }
    return out;
  }
  if (json.is_array()) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& value : json) out.push_back(withoutTimes(value));
    return out;
  }
  return json;
}

class McwsPlan : public ::testing::Test {
 protected:
  void SetUp() override {
    test::writeFile(inputs_.file("arm2.yaml"), kArm);
    test::writeFile(inputs_.file("slider.yaml"), kSlider);
    test::writeFile(inputs_.file("walled.yaml"), kSliderScenario);
    test::writeFile(
        inputs_.file("slider_post.yaml"),
        replaced(kSlider, "{name: wall, type: box, size: [200, 2, 200], xyz: [0, 0, 0]}",
                 "{name: post, type: box, size: [2, 8, 200], xyz: [4, 0, 0]}"));
    test::writeFile(inputs_.file("beside.yaml"), kBesideScenario);
    writeArmScenario("ok.yaml", "0 deg, 0 deg", "120 deg, 0 deg");
  }

  /// An arm scenario in the inputs directory; returns its path.
  std::string writeArmScenario(const std::string& name, const std::string& start,
                               const std::string& goal) const {
    const std::string path = inputs_.file(name);
    test::writeFile(path, replaced(replaced(kArmScenario, "@START@", start), "@GOAL@", goal));
    return path;
  }

  std::string okScenario() const { return inputs_.file("ok.yaml"); }

  /// A run that must find no path: exit 1, one message line naming the status, the report on
  /// stdout and nothing written.
  void expectNoPath(const std::string& scenario, const std::string& status) const {
    const std::string out = outputs_.file("path.csv");
    const test::RunResult r = test::run(kPlan + " --scenario " + scenario + " --output " + out);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    const std::vector<std::string> lines = messageLines(r.err);
    ASSERT_EQ(lines.size(), 1u) << r.err;
    EXPECT_THAT(lines[0], StartsWith("mcws_plan: no path"));
    EXPECT_THAT(lines[0], HasSubstr(status));
    EXPECT_THAT(lines[0], HasSubstr("nothing written"));
    EXPECT_THAT(r.out, HasSubstr(status));  // the report
    EXPECT_EQ(outputs_.fileCount(), 0u);

    // --json says the same.
    const test::RunResult json =
        test::run(kPlan + " --scenario " + scenario + " --json --output " + out);
    EXPECT_EQ(json.exit_code, 1) << json.err;
    EXPECT_EQ(nlohmann::json::parse(json.out)["status"], status);
    EXPECT_EQ(outputs_.fileCount(), 0u);
  }

  test::TempDir inputs_, outputs_;
};

TEST_F(McwsPlan, HelpExitsZero) {
  const test::RunResult r = test::run(kPlan + " --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* flag : {"--scenario", "--output", "--json", "--plot", "--plot-offsets",
                           "--cells", "--seed", "--validation-poses", "--threads"}) {
    EXPECT_THAT(r.out, HasSubstr(flag));
  }
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST_F(McwsPlan, BadCommandLinesExitTwo) {
  const std::string scenario = " --scenario " + okScenario();
  const std::string output = " --output " + outputs_.file("path.csv");
  test::expectToolFailure(kPlan, "--bogus 1" + scenario + output, 2, "bogus", outputs_);
  test::expectToolFailure(kPlan, output, 2, "missing --scenario", outputs_);
  test::expectToolFailure(kPlan, scenario, 2, "missing --output", outputs_);
  test::expectToolFailure(kPlan, scenario + output + " --threads 0", 2,
                          "--threads: 0 is less than 1", outputs_);
  test::expectToolFailure(kPlan, scenario + output + " --threads 257", 2,
                          "--threads: 257 is more than 256", outputs_);
  test::expectToolFailure(kPlan, scenario + output + " --seed=-1", 2, "--seed: -1 is less than 0",
                          outputs_);
  test::expectToolFailure(kPlan, scenario + output + " --seed x", 2,
                          "--seed: 'x' is not a whole number", outputs_);
  test::expectToolFailure(kPlan, scenario + output + " --cells 3", 2, "--cells: 3 is less than 4",
                          outputs_);
  test::expectToolFailure(kPlan, scenario + output + " --validation-poses -1", 2,
                          "--validation-poses", outputs_);
  test::expectToolFailure(kPlan, scenario + output + " --plot " + outputs_.file("path.csv"), 2,
                          "--plot: must differ from --output", outputs_);
}

TEST_F(McwsPlan, BadScenarioExitsOneNamingTheField) {
  const std::string bad = inputs_.file("bad.yaml");
  test::writeFile(bad, replaced(test::readFile(okScenario()), "swing: 1 deg", "swing: -1 deg"));
  test::expectToolFailure(kPlan, "--scenario " + bad + " --output " + outputs_.file("path.csv"), 1,
                          bad + ":8: sway: swing: sigma -1 deg must be >= 0", outputs_);
  test::expectToolFailure(
      kPlan, "--scenario " + inputs_.file("none.yaml") + " --output " + outputs_.file("p.csv"), 1,
      "none.yaml: scenario file does not exist", outputs_);
}

TEST_F(McwsPlan, PlotOfAFourJointRobotIsAUsageError) {
  // Fails after loading the scenario and before planning: fast even for maintenance4.
  test::expectToolFailure(kPlan,
                          "--scenario " + kScenarios + "/maintenance4.yaml --output " +
                              outputs_.file("path.csv") + " --plot " + outputs_.file("c.png"),
                          2, "--plot: draws a two-joint configuration space", outputs_);
}

TEST_F(McwsPlan, GoalInCollision) {
  // The straight arm at 52 deg passes through the post.
  expectNoPath(writeArmScenario("goal.yaml", "0 deg, 0 deg", "52 deg, 0 deg"), "goal_in_collision");
}

TEST_F(McwsPlan, StartInCollision) {
  expectNoPath(writeArmScenario("start.yaml", "52 deg, 0 deg", "120 deg, 0 deg"),
               "start_in_collision");
}

TEST_F(McwsPlan, WallBetweenStartAndGoalIsNotConnected) {
  expectNoPath(inputs_.file("walled.yaml"), "not_connected");
}

TEST_F(McwsPlan, APathThatCollidesForSomePlanningPosesIsRefusedByDefault) {
  // P stays above the threshold 0.9, but the whole path collides for some of the 100 poses.
  expectNoPath(inputs_.file("beside.yaml"), "above_max_collision_probability");
  const test::RunResult r = test::run(kPlan + " --scenario " + inputs_.file("beside.yaml") +
                                      " --json --output " + outputs_.file("path.csv"));
  ASSERT_EQ(r.exit_code, 1) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["acceptance"], "whole_path");
  EXPECT_EQ(json["max_collision_probability"], 0.05);
  EXPECT_FALSE(json.contains("chosen"));
  EXPECT_FALSE(json.contains("accepted_round"));
  const auto& best = json["rounds"][0]["best"];
  EXPECT_FALSE(best["accepted"].get<bool>());
  EXPECT_GE(best["probability"].get<double>(), 0.9);  // the patent's reading would take it
  const std::size_t colliding = best["whole_path_colliding_poses"];
  EXPECT_GT(colliding, 0u);
  EXPECT_EQ(best["whole_path_free_poses"].get<std::size_t>() + colliding, 100u);
  EXPECT_DOUBLE_EQ(best["whole_path_collision_rate"].get<double>(), colliding / 100.0);
  // Wilson's upper end, computed here from its closed form.
  const double z = 1.959964, k = static_cast<double>(colliding), n = 100.0;
  const double upper = (k + z * z / 2 + z * std::sqrt(k * (n - k) / n + z * z / 4)) / (n + z * z);
  EXPECT_NEAR(best["whole_path_collision_interval_95"][1].get<double>(), upper, 1e-6);
  EXPECT_GT(upper, 0.05);
  // The refused path is still validated, and the report says it was refused.
  EXPECT_EQ(json["validated_round"], 0);
  EXPECT_EQ(json["validation"]["rows"][0]["name"], "chosen");

  // With the patent's literal reading the same path is accepted (and written).
  const std::string patent = inputs_.file("patent.yaml");
  test::writeFile(patent, replaced(kBesideScenario, "threshold: 0.9",
                                   "threshold: 0.9\n  acceptance: patent_p"));
  const test::RunResult accepted =
      test::run(kPlan + " --scenario " + patent + " --json --output " + outputs_.file("path.csv"));
  ASSERT_EQ(accepted.exit_code, 0) << accepted.err;
  const auto patent_json = nlohmann::json::parse(accepted.out);
  EXPECT_EQ(patent_json["acceptance"], "patent_p");
  EXPECT_EQ(patent_json["chosen"]["whole_path_colliding_poses"], colliding);

  // 72 poses cannot accept even a path free for all of them (upper end 3.8415 / 75.8415 =
  // 0.0507); the message says how many can (73: 0.0500).
  const std::string few = inputs_.file("few.yaml");
  test::writeFile(few, replaced(test::readFile(okScenario()), "poses: 80", "poses: 72"));
  const test::RunResult refused = test::run(
      kPlan + " --scenario " + few + " --validation-poses 0 --output " + outputs_.file("path.csv"));
  EXPECT_EQ(refused.exit_code, 1) << refused.err;
  EXPECT_THAT(refused.err, HasSubstr("above_max_collision_probability"));
  EXPECT_THAT(refused.err, HasSubstr("(lowest 0.0507, 0 of 72 poses colliding); with n = 72 poses "
                                     "not even a path free for all of them can pass: sway: poses "
                                     "must be at least 73; nothing written"));
  // At 0.001: 3.8415 / (3838 + 3.8415) = 0.00099990, / (3837 + 3.8415) = 0.00100010.
  const std::string strict = inputs_.file("strict.yaml");
  test::writeFile(strict, replaced(test::readFile(okScenario()), "threshold: 0.5",
                                   "max_collision_probability: 0.001"));
  const test::RunResult strict_run =
      test::run(kPlan + " --scenario " + strict + " --validation-poses 0 --output " +
                outputs_.file("path.csv"));
  EXPECT_EQ(strict_run.exit_code, 1) << strict_run.err;
  EXPECT_THAT(strict_run.err, HasSubstr("with n = 80 poses not even a path free for all of them "
                                        "can pass: sway: poses must be at least 3838"));
}

TEST_F(McwsPlan, ABaseShiftReportsHowFarTheToolEndsFromTheTarget) {
  // The post refuses offset 0; +5 cm puts the sphere's way through the post (no path); -5 cm
  // leaves 8 - 2 = 6 cm between its face and the sphere, more than any slide (1.96 cm).
  const std::string shifted = inputs_.file("shifted.yaml");
  test::writeFile(shifted, replaced(kBesideScenario, "threshold: 0.9",
                                    "threshold: 0.9\n  base_step: 5 cm\n  base_range: 5 cm"));
  const std::string out = outputs_.file("path.csv");
  const test::RunResult r = test::run(kPlan + " --scenario " + shifted + " --json --output " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["status"], "ok");
  ASSERT_EQ(json["accepted_round"], 2);
  EXPECT_EQ(json["rounds"][2]["base_offset"], -5.0);
  ASSERT_TRUE(json.contains("goal_displacement")) << r.out;
  // A 5 cm shift along the line moves every point of the arm by 5 cm.
  EXPECT_NEAR(json["goal_displacement"]["value"].get<double>(), 5.0, 1e-9);
  EXPECT_EQ(json["goal_displacement"]["unit"], "cm");
  EXPECT_EQ(json["chosen"]["whole_path_colliding_poses"], 0);

  const test::RunResult text = test::run(kPlan + " --scenario " + shifted + " --output " + out);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("\nstatus: ok: round 3's best path is accepted (whole_path); the "
                                  "base is shifted -5 cm along the line, so the tool ends 5 cm "
                                  "from the target"));
  // Without a shift, no goal_displacement.
  const test::RunResult plain = test::run(kPlan + " --scenario " + okScenario() +
                                          " --json --validation-poses 0 --output " + out);
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_FALSE(nlohmann::json::parse(plain.out).contains("goal_displacement"));
}

TEST_F(McwsPlan, APaddedPlannerWithoutAPathHasAStatusAndNoProbability) {
  // Obstacles padded by 40 cm swallow the straight arm at the start (37.5 cm from the post).
  const std::string padded = inputs_.file("padded.yaml");
  test::writeFile(padded, replaced(test::readFile(okScenario()), "threshold: 0.5",
                                   "threshold: 0.5\n  padding: 40 cm"));
  const std::string out = outputs_.file("path.csv");
  const test::RunResult r = test::run(kPlan + " --scenario " + padded + " --json --output " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  bool found = false;
  for (const auto& row : json["validation"]["rows"]) {
    if (row["name"] != "padded") continue;
    found = true;
    EXPECT_FALSE(row["planned"].get<bool>());
    EXPECT_EQ(row["status"], "no_path");
    EXPECT_EQ(row["roadmap_status"], "start_in_collision");
    for (const char* key : {"collision_probability", "length", "colliding_poses", "interval_95"})
      EXPECT_FALSE(row.contains(key)) << key << " in " << row;
    EXPECT_EQ(row["padding"], 40.0);
  }
  EXPECT_TRUE(found);
  EXPECT_FALSE(json["validation"].contains("padded_collision_probability"));
  const test::RunResult text = test::run(kPlan + " --scenario " + padded + " --output " + out);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("padded    no path (roadmap start_in_collision)"));
}

TEST_F(McwsPlan, PlansAPathAndWritesItAsCsv) {
  const std::string out = outputs_.file("path.csv");
  const test::RunResult r = test::run(kPlan + " --scenario " + okScenario() + " --output " + out +
                                      " --validation-poses 200 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(messageLines(r.err).empty()) << r.err;
  EXPECT_EQ(outputs_.fileCount(), 1u);

  const test::Csv csv = test::parseCsv(test::readFile(out));
  ASSERT_EQ(csv.header, (std::vector<std::string>{"D", "q1_rad", "q2_rad"}));
  ASSERT_GE(csv.rows.size(), 2u);
  EXPECT_EQ(csv.rows.front()[0], 0.0);
  EXPECT_NEAR(csv.rows.front()[1], 0.0, kCsvTol);
  EXPECT_NEAR(csv.rows.front()[2], 0.0, kCsvTol);
  EXPECT_NEAR(csv.last()[1], 120 * M_PI / 180, kCsvTol);
  EXPECT_NEAR(csv.last()[2], 0.0, kCsvTol);
  for (std::size_t k = 1; k < csv.rows.size(); ++k) {
    EXPECT_GT(csv.rows[k][0], csv.rows[k - 1][0]) << "row " << k;
    // D is the joint-space distance (scales 1/rad), row by row.
    const double step =
        std::hypot(csv.rows[k][1] - csv.rows[k - 1][1], csv.rows[k][2] - csv.rows[k - 1][2]);
    EXPECT_NEAR(csv.rows[k][0] - csv.rows[k - 1][0], step, 1e-9) << "row " << k;
  }
  // The post stands in the way: the path is longer than the straight turn of 2 pi / 3.
  EXPECT_GT(csv.last()[0], 2 * M_PI / 3);

  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["status"], "ok");
  EXPECT_EQ(json["units"]["length"], "cm");
  EXPECT_EQ(json["units"]["angle"], "rad");
  ASSERT_FALSE(json["rounds"].empty());
  const auto& candidates = json["rounds"][0]["candidates"];
  ASSERT_TRUE(candidates.is_array());
  EXPECT_GE(candidates.size(), 1u);
  EXPECT_LE(candidates.size(), 3u);
  EXPECT_EQ(json["rounds"][0]["roadmap_status"], "connected");
  // The CSV is the chosen path.
  const auto& chosen = json["chosen"];
  ASSERT_EQ(chosen["waypoints"].size(), csv.rows.size());
  for (std::size_t k = 0; k < csv.rows.size(); ++k) {
    for (int j = 0; j < 2; ++j)
      EXPECT_NEAR(chosen["waypoints"][k][j].get<double>(), csv.rows[k][1 + j], kCsvTol);
  }
  EXPECT_NEAR(chosen["length"].get<double>(), csv.last()[0], 1e-9);
  // Accepted by the default criterion: the upper end of the whole-path collision rate's 95 %
  // interval over the 80 planning poses is at most 0.05 (so none of them collides: 0 of 80
  // gives 3.8415 / 83.8415 = 0.0458, 1 of 80 more than 0.05).
  EXPECT_EQ(json["acceptance"], "whole_path");
  EXPECT_LE(chosen["whole_path_collision_interval_95"][1].get<double>(), 0.05);
  EXPECT_EQ(chosen["whole_path_colliding_poses"], 0);

  const auto& validation = json["validation"];
  EXPECT_EQ(validation["poses"], 200);
  for (const char* key : {"chosen_collision_probability", "shortest_collision_probability"}) {
    ASSERT_TRUE(validation.contains(key)) << key;
    const double p = validation[key];
    EXPECT_GE(p, 0.0) << key;
    EXPECT_LE(p, 1.0) << key;
  }
  bool padded_planned = false;
  for (const auto& row : validation["rows"]) {
    if (row["name"] == "padded") padded_planned = row["planned"].get<bool>();
    EXPECT_GE(row["collision_probability"].get<double>(), 0.0);
    EXPECT_LE(row["collision_probability"].get<double>(), 1.0);
    EXPECT_EQ(row["colliding_poses"].get<std::size_t>() / 200.0,
              row["collision_probability"].get<double>());
  }
  EXPECT_EQ(validation.contains("padded_collision_probability"), padded_planned);
  if (padded_planned) {
    const double p = validation["padded_collision_probability"];
    EXPECT_GE(p, 0.0);
    EXPECT_LE(p, 1.0);
  }
}

TEST_F(McwsPlan, TextReportWithoutJson) {
  const test::RunResult r = test::run(kPlan + " --scenario " + okScenario() + " --output " +
                                      outputs_.file("path.csv") + " --validation-poses 100");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("scenario tiny"));
  EXPECT_THAT(r.out, HasSubstr("round 1"));
  EXPECT_FALSE(nlohmann::json::accept(r.out));
}

TEST_F(McwsPlan, SameResultForOneAndTwoThreads) {
  const std::string one = outputs_.file("one.csv"), two = outputs_.file("two.csv");
  const std::string common =
      kPlan + " --scenario " + okScenario() + " --validation-poses 200 --json";
  const test::RunResult a = test::run(common + " --threads 1 --output " + one);
  const test::RunResult b = test::run(common + " --threads 2 --output " + two);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_TRUE(test::readFile(one) == test::readFile(two));
  EXPECT_EQ(withoutTimes(nlohmann::json::parse(a.out)), withoutTimes(nlohmann::json::parse(b.out)));
}

TEST_F(McwsPlan, SeedChangesTheRoadmapNotTheEnds) {
  const std::string out = outputs_.file("path.csv");
  const test::RunResult r = test::run(kPlan + " --scenario " + okScenario() + " --output " + out +
                                      " --seed 5 --validation-poses 0 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_FALSE(json.contains("validation"));  // --validation-poses 0 skips it
  const test::Csv csv = test::parseCsv(test::readFile(out));
  ASSERT_GE(csv.rows.size(), 2u);
  EXPECT_NEAR(csv.last()[1], 120 * M_PI / 180, kCsvTol);
}

TEST_F(McwsPlan, PlotOfTheTwoJointArmShowsTheChosenPath) {
  if (test::run("command -v gnuplot").exit_code != 0) GTEST_SKIP() << "gnuplot is not installed";
  const std::string png = outputs_.file("cspace.png");
  const test::RunResult r =
      test::run(kPlan + " --scenario " + okScenario() + " --output " + outputs_.file("path.csv") +
                " --validation-poses 100 --cells 16 --plot " + png);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(outputs_.fileCount(), 2u);
  // The configuration space q1 x q2 over the joint limits [-180, 180] x [-160, 160] deg fills
  // the frame; the chosen path (#08519c, 4 pixels wide) starts at (0, 0) and ends at (120, 0)
  // (within 8 pixels: a shared-node mark may cover its end).
  const test::PngImage picture(png);
  ASSERT_EQ(picture.width(), 1000);
  ASSERT_EQ(picture.height(), 900);
  const test::PixelBox frame = picture.frame();
  ASSERT_FALSE(frame.empty());
  auto pixel = [&](double q1_deg, double q2_deg) {
    return std::pair<int, int>{
        static_cast<int>(std::lround(frame.x0 + (q1_deg + 180.0) / 360.0 * frame.width())),
        static_cast<int>(std::lround(frame.y1 - (q2_deg + 160.0) / 320.0 * frame.height()))};
  };
  for (const auto& [q1, q2] : {std::pair{0.0, 0.0}, std::pair{120.0, 0.0}}) {
    const auto [x, y] = pixel(q1, q2);
    EXPECT_FALSE(picture.box(0x08519c, 0, {x - 8, x + 8, y - 8, y + 8}).empty())
        << "no chosen path at (" << q1 << ", " << q2 << ") deg, pixel " << x << ", " << y;
  }
  // and nowhere near q1 = -90 deg (it does not turn the long way round).
  const auto [x, y] = pixel(-90.0, 0.0);
  EXPECT_TRUE(picture.box(0x08519c, 0, {x - 4, x + 4, frame.y0, frame.y1}).empty());
}

TEST_F(McwsPlan, InputFilesAreNeverModified) {
  const std::string scenario = test::readFile(okScenario());
  const std::string robot = test::readFile(inputs_.file("arm2.yaml"));
  ASSERT_EQ(test::run(kPlan + " --scenario " + okScenario() + " --output " +
                      outputs_.file("path.csv") + " --validation-poses 100")
                .exit_code,
            0);
  // Asked to write over its own input: refused as a usage error before any planning.
  const std::string goal = writeArmScenario("goal.yaml", "0 deg, 0 deg", "52 deg, 0 deg");
  const std::string goal_text = test::readFile(goal);
  EXPECT_EQ(test::run(kPlan + " --scenario " + goal + " --output " + goal).exit_code, 2);
  EXPECT_EQ(test::readFile(goal), goal_text);
  EXPECT_EQ(test::readFile(okScenario()), scenario);
  EXPECT_EQ(test::readFile(inputs_.file("arm2.yaml")), robot);
}

TEST_F(McwsPlan, OutputOverAnInputIsRefused) {
  // A successful run told to write its path over its own scenario or robot file.
  std::string overwritten;
  for (const char* input : {"copy.yaml", "arm2.yaml"}) {
    const std::string scenario = inputs_.file("copy.yaml");
    test::writeFile(scenario, test::readFile(okScenario()));
    const std::string target = inputs_.file(input);
    const std::string before = test::readFile(target);
    const test::RunResult r = test::run(kPlan + " --scenario " + scenario + " --output " + target +
                                        " --validation-poses 100");
    if (test::readFile(target) != before) {
      overwritten += std::string(overwritten.empty() ? "" : ", ") + input + " (exit " +
                     std::to_string(r.exit_code) + ")";
      test::writeFile(target, before);
      continue;
    }
    EXPECT_EQ(r.exit_code, 2) << input << ": " << r.err;
  }
  EXPECT_TRUE(overwritten.empty()) << "--output replaced an input with the CSV: " << overwritten;
}

}  // namespace
}  // namespace mcws
