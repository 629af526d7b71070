// mcws_ik through its command line: the pose of Liu, Han, Xu & Li 2021, position-only arms,
// unreachable poses and bad input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>

#include "apps/tool_paths.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/robot_yaml.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

// The pose matrix of Liu, Han, Xu & Li 2021 as printed (section 1.1, 4 decimals), at
// q = [pi/3, pi/6, pi/2, pi/4, pi/3, pi/6].
const std::string kPapersMatrix =
    " --matrix '-0.9234 0.3837 -0.0148 -39.3043  -0.0993 -0.2015 0.9744 731.9230  "
    "0.3709 0.9012 0.2241 -569.2371  0 0 0 1'";

Eigen::VectorXd papersAngles() {
  Eigen::VectorXd q(6);
  q << M_PI / 3, M_PI / 6, M_PI / 2, M_PI / 4, M_PI / 3, M_PI / 6;
  return q;
}

Eigen::VectorXd jsonQ(const nlohmann::json& json) {
  const std::vector<double> q = json["q"].get<std::vector<double>>();
  return Eigen::Map<const Eigen::VectorXd>(q.data(), static_cast<Eigen::Index>(q.size()));
}

TEST(IkApp, HelpExitsZeroAndStatesUnits) {
  const test::RunResult r = test::run(kIk + " --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* text : {"--robot", "--pose", "--matrix", "--q0", "--position-only",
                           "--tolerance", "--json", "length unit", "rad"}) {
    EXPECT_THAT(r.out, HasSubstr(text));
  }
}

TEST(IkApp, ThePapersPrintedMatrixGivesItsAngles) {
  const test::RunResult r =
      test::run(kIk + kInspection + kPapersMatrix + " --q0 '1 0.5 1.5 0.8 1 0.5' --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["status"], "converged");
  EXPECT_EQ(json["q"].size(), 6u);
  // The printed matrix is the pose at the seed angles rounded to 4 decimals (0.5e-4 mm in the
  // translation, 0.5e-4 in each rotation entry): the angles come back to about 1e-4.
  EXPECT_LT((jsonQ(json) - papersAngles()).cwiseAbs().maxCoeff(), 1e-3);
  EXPECT_LE(json["position_error"].get<double>(), 1e-6);
  EXPECT_LE(json["orientation_error"].get<double>(), 1e-6);
  EXPECT_GE(json["iterations"].get<int>(), 1);
}

TEST(IkApp, PoseFlagRoundTrip) {
  // The tool pose of a joint vector as x y z roll pitch yaw, solved back and checked by FK.
  const Robot robot = loadRobot(test::robotPath("ta1400"));
  Eigen::VectorXd q(6);
  q << 0.3, -0.8, 0.4, 1.0, 0.7, -0.5;
  const Eigen::Isometry3d T = toolPose(robot, q);
  const Eigen::Vector3d ypr = T.linear().eulerAngles(2, 1, 0);  // R = Rz Ry Rx
  char pose[256];
  std::snprintf(pose, sizeof pose, " --pose '%.17g %.17g %.17g %.17g %.17g %.17g'",
                T.translation().x(), T.translation().y(), T.translation().z(), ypr[2], ypr[1],
                ypr[0]);
  const test::RunResult r =
      test::run(kIk + " --robot " + test::robotPath("ta1400") + pose + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Eigen::Isometry3d T_solved = toolPose(robot, jsonQ(nlohmann::json::parse(r.out)));
  EXPECT_LT((T_solved.translation() - T.translation()).norm(), 1e-6);
  EXPECT_LT(Eigen::AngleAxisd(T_solved.linear() * T.linear().transpose()).angle(), 1e-6);
}

TEST(IkApp, TextOutputNamesUnits) {
  const test::RunResult r = test::run(kIk + kInspection + kPapersMatrix);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The joint values under a '#' line naming their unit (as mcws_fk's matrix).
  EXPECT_EQ(r.out.rfind("# joint values q in rad\nq: ", 0), 0u) << r.out;
  EXPECT_THAT(r.out, HasSubstr("iterations: "));
  EXPECT_THAT(r.out, HasSubstr(" mm\n"));
  EXPECT_THAT(r.out, HasSubstr("orientation error: "));
}

TEST(IkApp, PositionOnlyDeicingArmMeetsTheClosedFormEndPoint) {
  const test::RunResult r = test::run(kIk + " --robot " + test::robotPath("deicing") +
                                      " --pose '60 25 20 0 0 0' --position-only --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Eigen::VectorXd q = jsonQ(nlohmann::json::parse(r.out));  // theta3 theta1 theta2 a2
  const double radial = 50 * std::cos(q[1]) + q[3] * std::cos(q[1] + q[2]);
  EXPECT_NEAR(std::cos(q[0]) * radial, 60.0, 1e-6);
  EXPECT_NEAR(std::sin(q[0]) * radial, 25.0, 1e-6);
  EXPECT_NEAR(50 * std::sin(q[1]) + q[3] * std::sin(q[1] + q[2]), 20.0, 1e-6);
}

TEST(IkApp, PositionOnlyMaintenanceArm) {
  const Robot robot = loadRobot(test::robotPath("maintenance4"));
  Eigen::VectorXd q(4);
  q << 2.0, 10.0, 0.5236, 10.0;  // near the patent's goal [pi, 10, 0.5236, 10]
  const Eigen::Vector3d p = toolPose(robot, q).translation();
  char pose[200];
  std::snprintf(pose, sizeof pose, " --pose '%.17g %.17g %.17g 0 0 0'", p.x(), p.y(), p.z());
  const test::RunResult r = test::run(kIk + " --robot " + test::robotPath("maintenance4") + pose +
                                      " --position-only --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Eigen::VectorXd solved = jsonQ(nlohmann::json::parse(r.out));
  EXPECT_LT((toolPose(robot, solved).translation() - p).norm(), 1e-6);
}

/// The planar arm's tool z axis is always world z: a pose with a yaw other than the two its
/// elbows give is out of reach as a full pose, but reached with the roll free.
TEST(IkApp, FreeRollPlanarArmMeetsPointAndApproach) {
  const std::string args = " --robot " + test::robotPath("planar2") + " --pose '50 0 0 0 0 0.3'";
  const test::RunResult full = test::run(kIk + args);
  EXPECT_EQ(full.exit_code, 1);
  EXPECT_THAT(full.err, HasSubstr("try --position-only or --free-roll"));
  const test::RunResult r = test::run(kIk + args + " --free-roll --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Eigen::VectorXd q = jsonQ(nlohmann::json::parse(r.out));
  // l1 = 40, l2 = 30 at r = 50: cos q2 = (50^2 - 40^2 - 30^2) / (2 40 30) = 0.
  EXPECT_NEAR(std::abs(q[1]), M_PI / 2, 1e-6);
  const Robot robot = loadRobot(test::robotPath("planar2"));
  EXPECT_LT((toolPose(robot, q).translation() - Eigen::Vector3d(50, 0, 0)).norm(), 1e-6);
  const test::RunResult text = test::run(kIk + args + " --free-roll");
  EXPECT_THAT(text.out, HasSubstr("approach (z axis) error: "));
  const test::RunResult both = test::run(kIk + args + " --free-roll --position-only");
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_THAT(both.err, HasSubstr("--position-only and --free-roll exclude each other"));
}

TEST(IkApp, FailuresAndBadInput) {
  test::TempDir nothing_written;
  struct Case {
    std::string args;
    int exit_code;
    std::string message;
  };
  const std::string deicing = " --robot " + test::robotPath("deicing");
  const Case cases[] = {
      {kInspection + " --pose '3000 0 0 0 0 0'", 1,
       "no solution (no_solution): the best pose found is "},
      {deicing + " --pose '60 25 20 0 0 0'", 1,
       "the robot has 4 joints, try --position-only or --free-roll"},
      {kInspection + " --pose '1 2 3 nan 0 0'", 2, "--pose: 'nan' is not a finite number"},
      {kInspection + " --pose '1 2 inf 0 0 0'", 2, "--pose: 'inf' is not a finite number"},
      {kInspection + " --pose '1 2 3 0 0'", 2,
       "--pose: 5 values given, 6 wanted (x y z roll pitch yaw)"},
      {kInspection + " --matrix '1 0 0 0 0 1 0 0 0 0 1 -inf 0 0 0 1'", 2,
       "--matrix: '-inf' is not a finite number"},
      {kInspection + " --matrix '1 0 0 0 0 1 0 0 0 0 1 0'", 2,
       "--matrix: 12 values given, 16 wanted (a 4x4 matrix, row by row)"},
      {kInspection + " --matrix '1 0 0 0 0 2 0 0 0 0 1 0 0 0 0 1'", 2,
       "--matrix: the rotation is not orthonormal (|R^T R - I| = 3, at most 0.001 accepted)"},
      {kInspection + " --matrix '1 0 0 0 0 1 0 0 0 0 -1 0 0 0 0 1'", 2,
       "--matrix: the rotation is a reflection (det R = -1"},
      {kInspection + " --matrix '1 0 0 0 0 1 0 0 0 0 1 0 0 0 0.5 1'", 2,
       "--matrix: last row is 0 0 0.5 1, not 0 0 0 1"},
      {kInspection + " --pose '0 0 0 0 0 0' --matrix '1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1'", 2,
       "--pose and --matrix exclude each other"},
      {kInspection, 2, "missing --pose or --matrix"},
      {kInspection + " --pose '500 0 500 0 0 0' --q0 '1 2 3'", 2,
       "--q0: robot 'inspection6' has 6 joints but 3 joint values were given"},
      {kInspection + " --pose '500 0 500 0 0 0' --q0 '1 2 3 4 5 x'", 2,
       "--q0: 'x' is not a finite number"},
      {kInspection + " --pose '500 0 500 0 0 0' --tolerance -1", 2,
       "--tolerance: -1 is not a positive number"},
      {kInspection + " --pose '500 0 500 0 0 0' --angle-tolerance 0", 2,
       "--angle-tolerance: 0 is not a positive number"},
      {kInspection + " --pose '500 0 500 0 0 0' --seed -1", 2, "--seed: -1 is less than 0"},
      {kInspection + " --pose '500 0 500 0 0 0' --seed 1.5", 2,
       "--seed: '1.5' is not a whole number"},
      {kInspection + " --pose '500 0 500 0 0 0' --restarts -2", 2, "--restarts: -2 is less than 0"},
      {" --robot /nonexistent.yaml --pose '0 0 0 0 0 0'", 1,
       "--robot: /nonexistent.yaml: robot file does not exist"},
      {" --pose '0 0 0 0 0 0'", 2, "missing --robot"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    test::expectToolFailure(kIk, c.args, c.exit_code, c.message, nothing_written);
  }
}

}  // namespace
}  // namespace mcws
