#include "mcws/kinematics/inverse_kinematics.h"

#include <gtest/gtest.h>

#include <functional>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <limits>
#include <random>

#include "kinematics/kdl_chain.h"
#include "kinematics/random_joints.h"
#include "mcws/core/error.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/robot_yaml.h"
#include "test_support.h"

namespace mcws {
namespace {

/// Round trips per robot: enough to meet the poses that need restarts (a third of them on the
/// TA1400).
constexpr int kRoundTrips = 500;
/// The solver's default tolerances [length unit] and [rad]; the oracle's own FK rounding
/// (~1e-13 of a 2 m chain in mm) is far below.
constexpr double kTolerance = 1e-6;

using test::randomJoints;

Eigen::VectorXd inspectionExampleAngles() {
  Eigen::VectorXd q(6);
  q << M_PI / 3, M_PI / 6, M_PI / 2, M_PI / 4, M_PI / 3, M_PI / 6;
  return q;
}

Eigen::VectorXd inspectionExampleStart() {
  Eigen::VectorXd q(6);
  q << 1, 0.5, 1.5, 0.8, 1, 0.5;
  return q;
}

void expectWithinLimits(const Robot& robot, const Eigen::VectorXd& q) {
  for (int i = 0; i < robot.dof(); ++i) {
    EXPECT_GE(q[i], robot.joints[i].lower) << robot.joints[i].name;
    EXPECT_LE(q[i], robot.joints[i].upper) << robot.joints[i].name;
  }
}

// ---- Liu, Han, Xu & Li 2021, section 1.2 --------------------------------------------------------

TEST(NewtonPoseEntries, ReproducesThePapersExample) {
  // From q0 = [1, 0.5, 1.5, 0.8, 1, 0.5] to the pose at [pi/3, pi/6, pi/2, pi/4, pi/3, pi/6]
  // with the paper's tolerance 0.001: the paper needs 5 iterations and prints
  // q5 = [1.048, 0.524, 1.571, 0.786, 1.048, 0.523] (3 decimals).
  const Robot robot = loadRobot(test::robotPath("inspection6"));
  const Eigen::VectorXd expected = inspectionExampleAngles();
  const IkResult result =
      solveIkNewtonPoseEntries(robot, toolPose(robot, expected), inspectionExampleStart(), 0.001);
  ASSERT_TRUE(result.converged()) << ikStatusName(result.status);
  EXPECT_LE(result.iterations, 5);
  EXPECT_LT((result.q - expected).cwiseAbs().maxCoeff(), 2e-3);
  Eigen::VectorXd paper(6);
  paper << 1.048, 0.524, 1.571, 0.786, 1.048, 0.523;
  EXPECT_LT((result.q - paper).cwiseAbs().maxCoeff(), 1e-3 + 0.5e-3);  // its step + rounding
  // The result's errors are those of the full pose at q.
  const Eigen::Isometry3d T = toolPose(robot, result.q);
  EXPECT_NEAR(result.position_error,
              (T.translation() - toolPose(robot, expected).translation()).norm(), 1e-9);
}

TEST(NewtonPoseEntries, StopsOnTheStepNotTheResidual) {
  // One iteration from the paper's start is not enough: the budget runs out.
  const Robot robot = loadRobot(test::robotPath("inspection6"));
  const IkResult result = solveIkNewtonPoseEntries(
      robot, toolPose(robot, inspectionExampleAngles()), inspectionExampleStart(), 0.001, 1);
  EXPECT_EQ(result.status, IkStatus::kMaxIterations);
  EXPECT_EQ(result.iterations, 1);
  EXPECT_GT(result.position_error, 0.1);  // [mm]
}

TEST(NewtonPoseEntries, NeedsSixJoints) {
  const Robot robot = loadRobot(test::robotPath("deicing"));
  EXPECT_THROW(
      solveIkNewtonPoseEntries(robot, Eigen::Isometry3d::Identity(), Eigen::VectorXd::Zero(4)),
      Error);
}

TEST(InverseKinematics, SolvesTheInspectionArmExampleExactly) {
  const Robot robot = loadRobot(test::robotPath("inspection6"));
  const Eigen::VectorXd expected = inspectionExampleAngles();
  const IkResult result = solveIk(robot, toolPose(robot, expected), inspectionExampleStart());
  ASSERT_TRUE(result.converged());
  EXPECT_EQ(result.attempts, 1);
  EXPECT_LT((result.q - expected).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LE(result.position_error, kTolerance);
  EXPECT_LE(result.orientation_error, kTolerance);
}

// ---- round trips, checked with orocos-kdl's forward kinematics ----------------------------------

/// solveIk on the tool pose of random joint vectors from random first guesses: every solve
/// converges, stays within the limits and, by KDL's FK of the raw D-H rows, reaches the pose.
void expectRoundTrips(const std::string& name, bool position_only) {
  SCOPED_TRACE(name);
  const std::string path = test::robotPath(name);
  const Robot robot = loadRobot(path);
  const KDL::Chain chain = test::kdlChainFromFile(path);  // the solver keeps a reference
  KDL::ChainFkSolverPos_recursive kdl_fk(chain);
  IkOptions options;
  options.position_only = position_only;
  std::mt19937_64 rng(31);
  int converged = 0;
  for (int n = 0; n < kRoundTrips; ++n) {
    const Eigen::VectorXd q_target = randomJoints(robot, rng);
    const Eigen::VectorXd q_seed = randomJoints(robot, rng);
    const Eigen::Isometry3d T_target = toolPose(robot, q_target);
    const IkResult result = solveIk(robot, T_target, q_seed, options);
    expectWithinLimits(robot, result.q);
    if (!result.converged()) continue;
    ++converged;
    KDL::JntArray q_kdl(robot.dof());
    q_kdl.data = result.q;
    KDL::Frame F;
    ASSERT_GE(kdl_fk.JntToCart(q_kdl, F), 0);
    const Eigen::Matrix4d T = test::toEigen(F);
    const double position_error = (T.topRightCorner<3, 1>() - T_target.translation()).norm();
    EXPECT_LE(position_error, kTolerance * (1 + 1e-6)) << q_target.transpose();
    EXPECT_NEAR(position_error, result.position_error, 1e-9);
    if (!position_only) {
      const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
      const double angle = Eigen::AngleAxisd(T_target.linear() * R.transpose()).angle();
      EXPECT_LE(angle, kTolerance * (1 + 1e-6)) << q_target.transpose();
    }
  }
  // bench_ik measures >= 99.5 % on 10000 poses; 99 % of these leaves room for the sample.
  EXPECT_GE(converged, kRoundTrips * 99 / 100);
}

TEST(InverseKinematics, RoundTripInspectionArm) { expectRoundTrips("inspection6", false); }
TEST(InverseKinematics, RoundTripTa1400WithItsTightLimits) { expectRoundTrips("ta1400", false); }
TEST(InverseKinematics, RoundTripInsulatorCleanerWithPrismaticJoints) {
  expectRoundTrips("insulator_cleaner", false);
}
TEST(InverseKinematics, PositionOnlyDeicingArm) { expectRoundTrips("deicing", true); }
TEST(InverseKinematics, PositionOnlyMaintenanceArm) { expectRoundTrips("maintenance4", true); }

TEST(InverseKinematics, PositionOnlyDeicingArmMeetsTheClosedFormEndPoint) {
  // Yin, Wang & Yu 2010, eq. (1), an independent closed form of the arm's end point.
  const Robot robot = loadRobot(test::robotPath("deicing"));
  const Eigen::Vector3d target(60.0, 25.0, 20.0);  // [cm], inside the reach 50 + 25..70
  Eigen::Isometry3d T_target = Eigen::Isometry3d::Identity();
  T_target.translation() = target;
  IkOptions options;
  options.position_only = true;
  const IkResult result = solveIk(robot, T_target, Eigen::Vector4d(0, 0, 0, 40), options);
  ASSERT_TRUE(result.converged());
  const double t3 = result.q[0], t1 = result.q[1], t2 = result.q[2], a2 = result.q[3];
  const double r = 50 * std::cos(t1) + a2 * std::cos(t1 + t2);
  const Eigen::Vector3d p(std::cos(t3) * r, std::sin(t3) * r,
                          50 * std::sin(t1) + a2 * std::sin(t1 + t2));
  EXPECT_LT((p - target).norm(), kTolerance * (1 + 1e-6));
}

// ---- limits, unreachable poses, determinism -----------------------------------------------------

TEST(InverseKinematics, FirstGuessOutsideTheLimitsIsProjectedIntoThem) {
  const Robot robot = loadRobot(test::robotPath("ta1400"));
  Eigen::VectorXd q_target(6), q_seed(6);
  q_target << 0.3, -0.5, 0.2, 0.4, 0.6, -0.7;
  q_seed << 4.0, 2.0, -3.0, 0.0, -2.5, 9.0;  // j1, j2, j3, j5 beyond their limits; j6 >> pi
  const IkResult result = solveIk(robot, toolPose(robot, q_target), q_seed);
  EXPECT_TRUE(result.converged());
  expectWithinLimits(robot, result.q);
}

TEST(InverseKinematics, AJointLimitRulesOutTheFirstGuessesBranch) {
  // A first guess with the paper example's wrist flipped (q4 + pi, -q5, q6 - pi) leads to a
  // solution with q5 < 0 (the wrist offsets make it differ from the flip in q2 .. q4). Limit joint
  // 5 to [0.2, 1.5] rad and that branch is out: the solver must find another solution within the
  // limits.
  Robot robot = loadRobot(test::robotPath("inspection6"));
  const Eigen::VectorXd q_target = inspectionExampleAngles();  // q5 = pi/3
  Eigen::VectorXd q_flipped = q_target;
  q_flipped[3] += M_PI;
  q_flipped[4] = -q_flipped[4];
  q_flipped[5] -= M_PI;
  const Eigen::Isometry3d T = toolPose(robot, q_target);
  const IkResult free = solveIk(robot, T, q_flipped);
  ASSERT_TRUE(free.converged());
  EXPECT_EQ(free.attempts, 1);
  EXPECT_LT(free.q[4], 0.0);

  robot.joints[4].lower = 0.2;
  robot.joints[4].upper = 1.5;
  const IkResult limited = solveIk(robot, T, q_flipped);
  ASSERT_TRUE(limited.converged());
  expectWithinLimits(robot, limited.q);
}

TEST(InverseKinematics, UnreachablePoseReturnsAStatusWithoutThrowing) {
  const Robot robot = loadRobot(test::robotPath("inspection6"));
  Eigen::Isometry3d far = Eigen::Isometry3d::Identity();
  far.translation() << 3000, 0, 0;  // [mm], twice the reach
  IkResult result;
  ASSERT_NO_THROW(result = solveIk(robot, far, Eigen::VectorXd::Zero(6)));
  EXPECT_FALSE(result.converged());
  EXPECT_NE(result.status, IkStatus::kConverged);
  EXPECT_EQ(result.attempts, 21);  // the seed and every restart
  // The closest point of the sphere of reach 1513.7 around the shoulder (0, 0, 50).
  EXPECT_GT(result.position_error, 3000 - 1513.7 - 1.0);
  expectWithinLimits(robot, result.q);
}

TEST(InverseKinematics, FourJointArmCannotMatchAFullPose) {
  // The de-icing arm reaches the point but cannot also turn its end to an arbitrary orientation.
  const Robot robot = loadRobot(test::robotPath("deicing"));
  Eigen::Isometry3d T = toolPose(robot, Eigen::Vector4d(0.2, 0.1, -0.3, 40));
  T.linear() = (Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitX()) * T.linear()).eval();
  IkOptions options;
  options.restarts = 3;
  const IkResult result = solveIk(robot, T, Eigen::Vector4d(0, 0, 0, 30), options);
  EXPECT_FALSE(result.converged());
  EXPECT_GT(result.orientation_error, 0.1);
  options.position_only = true;
  EXPECT_TRUE(solveIk(robot, T, Eigen::Vector4d(0, 0, 0, 30), options).converged());
}

TEST(InverseKinematics, TooSmallBudgetSaysMaxIterations) {
  const Robot robot = loadRobot(test::robotPath("inspection6"));
  IkOptions options;
  options.max_iterations = 2;
  options.restarts = 0;
  const IkResult result =
      solveIk(robot, toolPose(robot, inspectionExampleAngles()), Eigen::VectorXd::Zero(6), options);
  EXPECT_EQ(result.status, IkStatus::kMaxIterations);
  EXPECT_EQ(result.iterations, 2);
}

TEST(InverseKinematics, SameSeedSameResultOtherSeedOtherRestarts) {
  const Robot robot = loadRobot(test::robotPath("ta1400"));
  std::mt19937_64 rng(37);
  int restarted = 0;
  for (int n = 0; n < 200; ++n) {
    const Eigen::VectorXd q_target = randomJoints(robot, rng);
    const Eigen::VectorXd q_seed = randomJoints(robot, rng);
    const Eigen::Isometry3d T = toolPose(robot, q_target);
    IkOptions options;
    options.seed = 5;
    const IkResult a = solveIk(robot, T, q_seed, options);
    const IkResult b = solveIk(robot, T, q_seed, options);
    ASSERT_EQ(a.q, b.q);  // bit for bit
    ASSERT_EQ(a.iterations, b.iterations);
    ASSERT_EQ(a.attempts, b.attempts);
    if (a.attempts > 1) {
      ++restarted;
      options.seed = 6;
      const IkResult c = solveIk(robot, T, q_seed, options);
      EXPECT_NE(c.q, a.q);  // other restarts, another path (and often another solution)
    }
  }
  EXPECT_GT(restarted, 10);  // the case above was exercised
}

TEST(InverseKinematics, PreparedSolverGivesSolveIksResults) {
  const Robot robot = loadRobot(test::robotPath("insulator_cleaner"));
  const IkSolver solver(robot);
  std::mt19937_64 rng(41);
  for (int n = 0; n < 50; ++n) {
    const Eigen::Isometry3d T = toolPose(robot, randomJoints(robot, rng));
    const Eigen::VectorXd q_seed = randomJoints(robot, rng);
    const IkResult a = solver.solve(T, q_seed), b = solveIk(robot, T, q_seed);
    ASSERT_EQ(a.q, b.q);
    ASSERT_EQ(a.iterations, b.iterations);
  }
}

// ---- misuse throws ------------------------------------------------------------------------------

TEST(InverseKinematics, MisuseThrowsNamingTheProblem) {
  const Robot robot = loadRobot(test::robotPath("inspection6"));
  const Eigen::VectorXd q0 = Eigen::VectorXd::Zero(6);
  Eigen::Isometry3d nan_target = Eigen::Isometry3d::Identity();
  nan_target.translation().x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(test::errorOf([&] { solveIk(robot, nan_target, q0); }),
            "solveIk: target pose entry (0, 3) is nan, not a finite number");

  Eigen::Isometry3d skewed = Eigen::Isometry3d::Identity();
  skewed.linear()(0, 1) = 0.1;
  EXPECT_EQ(test::errorOf([&] {
              solveIk(robot, skewed, q0);
            }).rfind("solveIk: target rotation is not orthonormal (|R^T R - I| = 0.1", 0),
            0u);
  Eigen::Isometry3d mirrored = Eigen::Isometry3d::Identity();
  mirrored.linear()(2, 2) = -1;
  EXPECT_NE(test::errorOf([&] { solveIk(robot, mirrored, q0); }).find("det R = -1"),
            std::string::npos);
  Eigen::Isometry3d projective = Eigen::Isometry3d::Identity();
  projective.matrix()(3, 0) = 0.5;
  EXPECT_EQ(test::errorOf([&] { solveIk(robot, projective, q0); }),
            "solveIk: target pose's last row is not 0 0 0 1");

  EXPECT_EQ(
      test::errorOf([&] { solveIk(robot, Eigen::Isometry3d::Identity(), Eigen::VectorXd(5)); }),
      "robot 'inspection6' has 6 joints but 5 joint values were given");
  Eigen::VectorXd q_inf = q0;
  q_inf[2] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(test::errorOf([&] { solveIk(robot, Eigen::Isometry3d::Identity(), q_inf); }),
            "IK seed value of joint 'j3' is inf, not a finite number");

  IkOptions options;
  options.position_tolerance = 0;
  EXPECT_EQ(test::errorOf([&] { solveIk(robot, Eigen::Isometry3d::Identity(), q0, options); }),
            "IK position tolerance 0 is not a positive number");
  options = {};
  options.restarts = -1;
  EXPECT_EQ(test::errorOf([&] { solveIk(robot, Eigen::Isometry3d::Identity(), q0, options); }),
            "IK restarts -1 is negative");
  EXPECT_EQ(test::errorOf([&] { solveIkNewtonPoseEntries(robot, nan_target, q0); }),
            "solveIkNewtonPoseEntries: target pose entry (0, 3) is nan, not a finite number");
  const Robot deicing = loadRobot(test::robotPath("deicing"));
  EXPECT_EQ(test::errorOf([&] {
              solveIkNewtonPoseEntries(deicing, Eigen::Isometry3d::Identity(),
                                       Eigen::VectorXd::Zero(4));
            }),
            "solveIkNewtonPoseEntries: robot 'deicing' has 4 joints, not 6");
  EXPECT_EQ(
      test::errorOf([&] { solveIkNewtonPoseEntries(robot, Eigen::Isometry3d::Identity(), q0, 0); }),
      "solveIkNewtonPoseEntries: step tolerance 0 is not a positive number");
  EXPECT_EQ(test::errorOf([&] {
              solveIkNewtonPoseEntries(robot, Eigen::Isometry3d::Identity(), q0, 1e-3, 0);
            }),
            "solveIkNewtonPoseEntries: max_iterations 0 is not at least 1");
}

}  // namespace
}  // namespace mcws
