// Scenario files of the maintenance-arm patent (mcws::parseScenario, loadScenario) and quantities
// with units (mcws::parseQuantity): every value converted by hand, every mistake one line naming
// the file, the line, the field and the bad value.
#include "mcws/planning/scenario.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <string>

#include "mcws/core/error.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

// Conversions are a product or quotient of two doubles: a few ulps.
constexpr double kTol = 1e-12;
constexpr double kDeg = M_PI / 180.0;

// ---------------------------------------------------------------------------------------------
// parseQuantity

using test::errorOf;

TEST(ParseQuantity, AnglesInRadiansWithPi) {
  const LengthUnit cm = LengthUnit::kCentimetre;
  EXPECT_DOUBLE_EQ(parseQuantity("pi rad", 'a', cm), M_PI);
  EXPECT_DOUBLE_EQ(parseQuantity("-pi/6 rad", 'a', cm), -M_PI / 6);
  EXPECT_DOUBLE_EQ(parseQuantity("2*pi rad", 'a', cm), 2 * M_PI);
  EXPECT_DOUBLE_EQ(parseQuantity("2pi rad", 'a', cm), 2 * M_PI);
  EXPECT_DOUBLE_EQ(parseQuantity("-3*pi/4 rad", 'a', cm), -0.75 * M_PI);
  EXPECT_DOUBLE_EQ(parseQuantity("0.5236 rad", 'a', cm), 0.5236);
  EXPECT_DOUBLE_EQ(parseQuantity("+1.5 rad", 'a', cm), 1.5);
}

TEST(ParseQuantity, DegreesBecomeRadians) {
  const LengthUnit cm = LengthUnit::kCentimetre;
  EXPECT_DOUBLE_EQ(parseQuantity("180 deg", 'a', cm), M_PI);
  EXPECT_DOUBLE_EQ(parseQuantity("90 deg", 'a', cm), M_PI / 2);
  EXPECT_DOUBLE_EQ(parseQuantity("-30 deg", 'a', cm), -M_PI / 6);
  EXPECT_DOUBLE_EQ(parseQuantity("0 deg", 'a', LengthUnit::kMetre), 0.0);
}

TEST(ParseQuantity, LengthsBecomeTheRobotsUnit) {
  const LengthUnit cm = LengthUnit::kCentimetre;
  EXPECT_DOUBLE_EQ(parseQuantity("10 cm", 'l', cm), 10.0);
  EXPECT_NEAR(parseQuantity("0.1 m", 'l', cm), 10.0, kTol);
  EXPECT_NEAR(parseQuantity("5 mm", 'l', cm), 0.5, kTol);
  EXPECT_NEAR(parseQuantity("10 cm", 'l', LengthUnit::kMetre), 0.1, kTol);
  EXPECT_NEAR(parseQuantity("0.1 m", 'l', LengthUnit::kMillimetre), 100.0, kTol);
  EXPECT_NEAR(parseQuantity("-2.5 cm", 'l', LengthUnit::kMillimetre), -25.0, kTol);
  // Surrounding and repeated blanks between value and unit are fine.
  EXPECT_DOUBLE_EQ(parseQuantity("  10   cm ", 'l', cm), 10.0);
}

TEST(ParseQuantity, BadTextNamesTheText) {
  const LengthUnit cm = LengthUnit::kCentimetre;
  const struct {
    const char* text;
    char want;
    const char* message;
  } cases[] = {
      {"10", 'a', "'10' is not a value and a unit (e.g. 'pi rad', '30 deg', '10 cm')"},
      {"", 'l', "'' is not a value and a unit"},
      {"10 cm cm", 'l', "'10 cm cm' is not a value and a unit"},
      {"10 cm", 'a', "'10 cm' is a length; an angle is needed (rad, deg)"},
      {"pi rad", 'l', "'pi rad' is an angle; a length is needed (m, cm, mm)"},
      {"3 deg", 'l', "'3 deg' is an angle; a length is needed (m, cm, mm)"},
      {"3 inch", 'l', "unknown unit 'inch' in '3 inch' (rad, deg, m, cm, mm)"},
      {"3 Cm", 'l', "unknown unit 'Cm' in '3 Cm'"},
      {"abc rad", 'a', "'abc' is not a number (or pi)"},
      {"1/0 rad", 'a', "'1/0' is not a number (or pi)"},
      {"pi/0 rad", 'a', "'pi/0' is not a number (or pi)"},
      {"2/pi rad", 'a', "'2/pi' is not a number (or pi)"},
      {"10x cm", 'l', "'10x' is not a number (or pi)"},
      {"nan cm", 'l', "'nan' is not a number (or pi)"},
      {"inf cm", 'l', "'inf' is not a number (or pi)"},
      {"1e400 cm", 'l', "'1e400' is not a number (or pi)"},
      {"- cm", 'l', "'-' is not a number (or pi)"},
  };
  for (const auto& c : cases) {
    const std::string message = errorOf([&] { parseQuantity(c.text, c.want, cm); });
    EXPECT_THAT(message, HasSubstr(c.message)) << "text: '" << c.text << "'";
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(ParseQuantity, MalformedSignsAndProductsAreErrors) {
  // A second sign ("--1 rad" once read as +1 rad: a typo that flips a joint value), a bare '*'
  // ("*pi rad" once read as pi) and hexadecimal ("0x10 rad" once read as 16 rad) are errors.
  const LengthUnit cm = LengthUnit::kCentimetre;
  std::string accepted;
  for (const char* text : {"--1 rad", "+-1 rad", "-+1 rad", "*pi rad", "2**pi rad", "0x10 rad"}) {
    try {
      const double value = parseQuantity(text, 'a', cm);
      accepted +=
          std::string(accepted.empty() ? "" : ", ") + "'" + text + "' -> " + std::to_string(value);
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("is not a number (or pi)")) << text;
    }
  }
  EXPECT_TRUE(accepted.empty()) << "accepted: " << accepted;
}

// ---------------------------------------------------------------------------------------------
// Scenario files

// A revolute joint (deg limits) and a prismatic one in cm, a base pose of its own and one
// obstacle.
const char* const kRobot = R"(name: rp2
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
const char* const kScenario = R"(name: good
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
const char* const kMinimal = R"(name: minimal
robot: arm.yaml
start: [0 rad, 0 cm]
goal: [1 rad, 10 cm]
sway:
  pivot: [0 cm, 0 cm, 0 cm]
  line: [0, 1, 0]
)";

/// `text` with its first `from` replaced by `to` (which must be there).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "no '" << from << "' in the scenario";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

class ScenarioFile : public ::testing::Test {
 protected:
  void SetUp() override { test::writeFile(dir_.file("arm.yaml"), kRobot); }

  /// Writes `text` to s.yaml next to arm.yaml and loads it.
  mcws::Scenario load(const std::string& text) const {
    test::writeFile(path(), text);
    return loadScenario(path());
  }

  std::string path() const { return dir_.file("s.yaml"); }

  /// Loading `text` fails with one line "s.yaml:<line>: ..." holding every part.
  void expectError(const std::string& text, int line,
                   std::initializer_list<std::string> parts) const {
    test::writeFile(path(), text);
    const std::string message = errorOf([&] { loadScenario(path()); });
    EXPECT_EQ(message.rfind(path() + ":" + std::to_string(line) + ": ", 0), 0u)
        << "wanted " << path() << ":" << line << ": ...\ngot: " << message;
    for (const std::string& part : parts) EXPECT_THAT(message, HasSubstr(part));
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }

  test::TempDir dir_;
};

TEST_F(ScenarioFile, GoodFileConvertsEveryField) {
  const mcws::Scenario s = load(kScenario);
  EXPECT_EQ(s.name, "good");
  EXPECT_EQ(s.source, path());
  EXPECT_EQ(std::filesystem::weakly_canonical(s.robot_path),
            std::filesystem::weakly_canonical(dir_.file("arm.yaml")));
  const SwayPlanningProblem& p = s.problem;
  ASSERT_EQ(p.robot.dof(), 2);
  EXPECT_EQ(p.robot.length_unit, LengthUnit::kCentimetre);
  EXPECT_TRUE(hasGeometry(p.collision));

  // Joint values: 90 deg = pi/2 rad, 100 mm = 10 cm; -pi/6 rad, 0.2 m = 20 cm.
  ASSERT_EQ(p.start.size(), 2);
  ASSERT_EQ(p.goal.size(), 2);
  EXPECT_NEAR(p.start[0], M_PI / 2, kTol);
  EXPECT_NEAR(p.start[1], 10.0, kTol);
  EXPECT_NEAR(p.goal[0], -M_PI / 6, kTol);
  EXPECT_NEAR(p.goal[1], 20.0, kTol);
  ASSERT_EQ(p.roadmap.joint_scale.size(), 2);
  EXPECT_EQ(p.roadmap.joint_scale[0], 1.0);
  EXPECT_EQ(p.roadmap.joint_scale[1], 0.5);
  EXPECT_EQ(s.distance_unit, "sqrt(sum (s_i dq_i)^2) with s = 1/rad, 0.5/cm");

  // Sway: pivot (0, 10 mm, 0.25 m) = (0, 1, 25) cm; the sigmas squared on the diagonal.
  EXPECT_NEAR(p.sway.pivot.x(), 0.0, kTol);
  EXPECT_NEAR(p.sway.pivot.y(), 1.0, kTol);
  EXPECT_NEAR(p.sway.pivot.z(), 25.0, kTol);
  EXPECT_TRUE(p.sway.line_direction == Eigen::Vector3d(1, 0, 0));
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
  covariance(0, 0) = 1.0;                                  // slide 1 cm, squared [cm^2]
  covariance(3, 3) = (3 * M_PI / 180) * (3 * M_PI / 180);  // swing 3 deg, squared [rad^2]
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c)
      EXPECT_NEAR(p.sway.covariance(r, c), covariance(r, c), kTol) << r << ", " << c;
  EXPECT_EQ(p.sway.confidence, 0.9);
  EXPECT_EQ(p.base_poses, 40u);
  EXPECT_EQ(p.seed, 7u);

  // Planner.
  EXPECT_EQ(p.candidates, 4u);
  EXPECT_EQ(p.diversity, 0.25);
  EXPECT_EQ(p.roadmap.nodes, 120u);
  EXPECT_EQ(p.roadmap.max_nodes, 480u);
  EXPECT_EQ(p.roadmap.neighbours, 6u);
  EXPECT_EQ(p.roadmap.seed, 3u);
  EXPECT_EQ(p.segment_length, 0.25);
  EXPECT_EQ(p.score.rule, ScoreRule::kLiteral);
  EXPECT_EQ(p.score.weight, 2.0);
  EXPECT_EQ(p.threshold, 0.8);
  EXPECT_NEAR(p.base_step, 2.0, kTol);    // 20 mm
  EXPECT_NEAR(p.base_range, 10.0, kTol);  // 0.1 m
  EXPECT_LT(p.padding, 0.0);              // auto
  EXPECT_EQ(p.validation_poses, 500u);

  // No base: the robot file's own T_world_base, (1, 2, 3) cm.
  EXPECT_TRUE(
      p.robot.T_world_base.isApprox(Eigen::Isometry3d(Eigen::Translation3d(1, 2, 3)), kTol));
}

TEST_F(ScenarioFile, ParseScenarioFindsTheRobotNextToTheSource) {
  const mcws::Scenario s = parseScenario(kScenario, dir_.file("not_written.yaml"));
  EXPECT_EQ(s.source, dir_.file("not_written.yaml"));
  EXPECT_EQ(s.problem.robot.name, "rp2");
  EXPECT_NEAR(s.problem.goal[1], 20.0, kTol);
  // An absolute robot path is taken as it is, wherever the scenario is.
  test::TempDir elsewhere;
  const mcws::Scenario absolute =
      parseScenario(replaced(kScenario, "robot: arm.yaml", "robot: " + dir_.file("arm.yaml")),
                    elsewhere.file("s.yaml"));
  EXPECT_EQ(absolute.robot_path, dir_.file("arm.yaml"));
}

TEST_F(ScenarioFile, DefaultsWithoutPlannerJointScaleOrValidation) {
  const mcws::Scenario s = load(kMinimal);
  const SwayPlanningProblem& p = s.problem;
  const SwayPlanningProblem defaults;
  const RoadmapOptions roadmap;
  EXPECT_TRUE(p.roadmap.joint_scale == Eigen::VectorXd::Ones(2)) << p.roadmap.joint_scale;
  EXPECT_TRUE(p.sway.covariance.isZero(0.0)) << p.sway.covariance;  // no swing, no slide
  EXPECT_EQ(p.sway.confidence, 0.95);
  EXPECT_TRUE(p.sway.line_direction == Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(p.base_poses, 100u);
  EXPECT_EQ(p.seed, 1u);
  EXPECT_EQ(p.candidates, 10u);
  EXPECT_EQ(p.diversity, 0.5);
  EXPECT_EQ(p.roadmap.nodes, 400u);
  EXPECT_EQ(p.roadmap.max_nodes, 3200u);
  EXPECT_EQ(p.roadmap.neighbours, 10u);
  EXPECT_EQ(p.roadmap.seed, 1u);
  EXPECT_EQ(p.segment_length, 0.5);
  EXPECT_EQ(p.score.rule, ScoreRule::kWeighted);
  EXPECT_EQ(p.score.weight, 1.0);
  EXPECT_EQ(p.threshold, 0.9);
  EXPECT_EQ(p.acceptance, Acceptance::kWholePath);
  EXPECT_EQ(p.max_collision_probability, 0.05);
  EXPECT_FALSE(p.allow_goal_shift);
  EXPECT_EQ(p.base_step, 0.0);
  EXPECT_EQ(p.base_range, 0.0);
  EXPECT_LT(p.padding, 0.0);
  EXPECT_EQ(p.validation_poses, 10000u);
  // ... which are the structs' own defaults.
  EXPECT_EQ(p.base_poses, defaults.base_poses);
  EXPECT_EQ(p.candidates, defaults.candidates);
  EXPECT_EQ(p.threshold, defaults.threshold);
  EXPECT_EQ(p.roadmap.nodes, roadmap.nodes);
  EXPECT_EQ(p.roadmap.max_nodes, roadmap.max_nodes);
  EXPECT_EQ(s.distance_unit, "sqrt(sum (s_i dq_i)^2) with s = 1/rad, 1/cm");
}

TEST_F(ScenarioFile, AcceptanceFields) {
  const SwayPlanningProblem defaults = load(kScenario).problem;
  EXPECT_EQ(defaults.acceptance, Acceptance::kWholePath);
  EXPECT_EQ(defaults.max_collision_probability, 0.05);
  EXPECT_FALSE(defaults.allow_goal_shift);
  const std::string fields =
      "threshold: 0.8\n  acceptance: patent_p\n  max_collision_probability: 0.1\n"
      "  allow_goal_shift: true";
  const SwayPlanningProblem set = load(replaced(kScenario, "threshold: 0.8", fields)).problem;
  EXPECT_EQ(set.acceptance, Acceptance::kPatentP);
  EXPECT_EQ(set.max_collision_probability, 0.1);
  EXPECT_TRUE(set.allow_goal_shift);
  EXPECT_EQ(set.threshold, 0.8);
  EXPECT_EQ(
      load(replaced(kScenario, "threshold: 0.8", "acceptance: whole_path")).problem.acceptance,
      Acceptance::kWholePath);
}

TEST_F(ScenarioFile, BadAcceptanceFields) {
  // Each replaces the threshold on line 24.
  auto with = [](const std::string& field) { return replaced(kScenario, "threshold: 0.8", field); };
  expectError(with("acceptance: P"), 24, {"planner: acceptance 'P' is not whole_path or patent_p"});
  expectError(with("acceptance: [whole_path]"), 24,
              {"planner: acceptance: must be a single value"});
  for (const char* bad : {"0", "1", "1.5", "-0.05"}) {
    expectError(with(std::string("max_collision_probability: ") + bad), 24,
                {std::string("planner: max_collision_probability ") + bad + " is outside (0, 1)"});
  }
  expectError(with("max_collision_probability: 5%"), 24,
              {"planner: max_collision_probability: '5%' is not a number"});
  expectError(with("allow_goal_shift: maybe"), 24,
              {"planner: allow_goal_shift 'maybe' is not true or false"});
  expectError(with("allow_goal_shift: 1"), 24,
              {"planner: allow_goal_shift '1' is not true or false"});
  // The old switch is refused with what replaced it, not silently ignored.
  expectError(with("threshold_on: whole_path"), 24,
              {"planner: threshold_on is no longer read", "acceptance: whole_path",
               "max_collision_probability", "patent_p"});
}

TEST_F(ScenarioFile, PaddingAsALength) {
  EXPECT_NEAR(load(replaced(kScenario, "padding: auto", "padding: 3 cm")).problem.padding, 3.0,
              kTol);
  EXPECT_NEAR(load(replaced(kScenario, "padding: auto", "padding: 15 mm")).problem.padding, 1.5,
              kTol);
  EXPECT_EQ(load(replaced(kScenario, "padding: auto", "padding: 0 cm")).problem.padding, 0.0);
}

TEST_F(ScenarioFile, MaxRoadmapNodesIsAtLeastRoadmapNodes) {
  const mcws::Scenario s =
      load(replaced(kScenario, "max_roadmap_nodes: 480", "max_roadmap_nodes: 60"));
  EXPECT_EQ(s.problem.roadmap.nodes, 120u);
  EXPECT_EQ(s.problem.roadmap.max_nodes, 120u);
}

TEST_F(ScenarioFile, CovarianceBlockConvertsItsUnits) {
  // Entries in mm and deg: (x, x) 4 mm^2 = 0.04 cm^2 (plus the slide's 1 cm^2),
  // (roll, roll) 9 deg^2 (plus the swing's (3 deg)^2), (x, roll) 2 mm deg =
  // 2 * (0.1 cm) * (pi/180 rad), (y, y) 100 mm^2 = 1 cm^2, (yaw, yaw) 1 deg^2.
  const std::string text = replaced(kScenario, "  slide: 1 cm\n",
                                    "  slide: 1 cm\n"
                                    "  covariance:\n"
                                    "    length: mm\n"
                                    "    angle: deg\n"
                                    "    matrix:\n"
                                    "      - [4, 0, 0, 2, 0, 0]\n"
                                    "      - [0, 100, 0, 0, 0, 0]\n"
                                    "      - [0, 0, 0, 0, 0, 0]\n"
                                    "      - [2, 0, 0, 9, 0, 0]\n"
                                    "      - [0, 0, 0, 0, 0, 0]\n"
                                    "      - [0, 0, 0, 0, 0, 1]\n");
  const Eigen::Matrix<double, 6, 6> C = load(text).problem.sway.covariance;
  EXPECT_NEAR(C(0, 0), 0.04 + 1.0, kTol);
  EXPECT_NEAR(C(1, 1), 1.0, kTol);
  EXPECT_NEAR(C(3, 3), 9 * kDeg * kDeg + std::pow(3 * kDeg, 2), kTol);
  EXPECT_NEAR(C(0, 3), 2 * 0.1 * kDeg, kTol);
  EXPECT_NEAR(C(3, 0), 2 * 0.1 * kDeg, kTol);
  EXPECT_NEAR(C(5, 5), kDeg * kDeg, kTol);
  EXPECT_EQ(C(2, 2), 0.0);
  EXPECT_EQ(C(4, 4), 0.0);
  EXPECT_EQ(C(1, 0), 0.0);

  // In m and rad: (x, x) 1e-4 m^2 = 1 cm^2 (plus the slide's), (x, roll) 0.001 m rad =
  // 0.1 cm rad, (roll, roll) 0.04 rad^2 (plus the swing's).
  const std::string metres = replaced(kScenario, "  slide: 1 cm\n",
                                      "  slide: 1 cm\n"
                                      "  covariance:\n"
                                      "    length: m\n"
                                      "    angle: rad\n"
                                      "    matrix:\n"
                                      "      - [1e-4, 0, 0, 0.001, 0, 0]\n"
                                      "      - [0, 0, 0, 0, 0, 0]\n"
                                      "      - [0, 0, 0, 0, 0, 0]\n"
                                      "      - [0.001, 0, 0, 0.04, 0, 0]\n"
                                      "      - [0, 0, 0, 0, 0, 0]\n"
                                      "      - [0, 0, 0, 0, 0, 0]\n");
  const Eigen::Matrix<double, 6, 6> M = load(metres).problem.sway.covariance;
  EXPECT_NEAR(M(0, 0), 1.0 + 1.0, kTol);
  EXPECT_NEAR(M(0, 3), 0.1, kTol);
  EXPECT_NEAR(M(3, 0), 0.1, kTol);
  EXPECT_NEAR(M(3, 3), 0.04 + std::pow(3 * kDeg, 2), kTol);
  EXPECT_EQ(M(1, 1), 0.0);
}

TEST_F(ScenarioFile, BaseOverridesTheRobotsPose) {
  // xyz (10 mm, 0 cm, -0.2 m) = (1, 0, -20) cm; R = Rz(90 deg) Ry(0) Rx(180 deg).
  const mcws::Scenario s = load(replaced(
      kScenario, "joint_scale:",
      "base: {xyz: [10 mm, 0 cm, -0.2 m], rpy: [180 deg, 0 rad, pi/2 rad]}\njoint_scale:"));
  const Eigen::Isometry3d& T = s.problem.robot.T_world_base;
  EXPECT_TRUE(T.translation().isApprox(Eigen::Vector3d(1, 0, -20), kTol)) << T.translation();
  Eigen::Matrix3d R;
  R << 0, 1, 0,  //
      1, 0, 0,   //
      0, 0, -1;
  EXPECT_TRUE(T.linear().isApprox(R, kTol)) << T.linear();
  // Only xyz: no rotation.
  const mcws::Scenario shifted =
      load(replaced(kScenario, "joint_scale:", "base: {xyz: [0 cm, 5 cm, 0 cm]}\njoint_scale:"));
  EXPECT_TRUE(shifted.problem.robot.T_world_base.isApprox(
      Eigen::Isometry3d(Eigen::Translation3d(0, 5, 0)), kTol));
}

TEST_F(ScenarioFile, ShippedMaintenance4) {
  const std::string file = std::string(MCWS_ROBOTS_DIR) + "/../scenarios/maintenance4.yaml";
  const mcws::Scenario s = loadScenario(file);
  EXPECT_EQ(s.name, "maintenance4");
  const SwayPlanningProblem& p = s.problem;
  ASSERT_EQ(p.robot.dof(), 4);
  EXPECT_EQ(p.robot.length_unit, LengthUnit::kCentimetre);
  const double start[] = {0, 0, 0, 0};
  const double goal[] = {M_PI, 10, 0.5236, 10};  // the patent's example, rad and cm
  for (int j = 0; j < 4; ++j) {
    EXPECT_NEAR(p.start[j], start[j], kTol) << j;
    EXPECT_NEAR(p.goal[j], goal[j], kTol) << j;
  }
  EXPECT_TRUE(hasGeometry(p.collision));
  EXPECT_GT(p.sway.covariance(3, 3), 0.0);  // it swings about the line
  EXPECT_GE(p.base_poses, 1u);
  EXPECT_GE(p.candidates, 1u);
}

TEST_F(ScenarioFile, ShippedPlanar2) {
  const std::string file = std::string(MCWS_ROBOTS_DIR) + "/../scenarios/planar2.yaml";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " is not there yet";
  const mcws::Scenario s = loadScenario(file);
  ASSERT_EQ(s.problem.robot.dof(), 2);
  EXPECT_EQ(s.problem.start.size(), 2);
  EXPECT_EQ(s.problem.goal.size(), 2);
  EXPECT_TRUE(hasGeometry(s.problem.collision));
}

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

TEST_F(ScenarioFile, PosesAndCandidatesZero) {
  expectError(replaced(kScenario, "poses: 40", "poses: 0"), 12,
              {"sway: poses: 0 must be a whole number of at least 1"});
  expectError(replaced(kScenario, "poses: 40", "poses: 2.5"), 12,
              {"sway: poses: 2.5 must be a whole number of at least 1"});
  expectError(replaced(kScenario, "candidates: 4", "candidates: 0"), 15,
              {"planner: candidates: 0 must be a whole number of at least 1"});
  expectError(replaced(kScenario, "validation: {poses: 500}", "validation: {poses: 0}"), 28,
              {"validation: poses: 0 must be a whole number of at least 1"});
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
