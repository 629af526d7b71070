// Scenario files of the maintenance-arm patent (mcws::parseScenario, loadScenario) and quantities
// with units (mcws::parseQuantity): every value converted by hand, every mistake one line naming
// the file, the line, the field and the bad value (bad scenario files are in
// scenario_errors_test.cpp).
#include "mcws/planning/scenario.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <string>

#include "mcws/core/error.h"
#include "planning/scenario_fixture.h"
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
using test::kMinimal;
using test::kScenario;
using test::replaced;
using test::ScenarioFile;

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
}  // namespace
}  // namespace mcws
