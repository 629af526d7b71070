#include "mcws/kinematics/forward_kinematics.h"

#include <gtest/gtest.h>

#include <kdl/chainfksolverpos_recursive.hpp>
#include <random>

#include "kinematics/kdl_chain.h"
#include "kinematics/random_joints.h"
#include "mcws/core/error.h"
#include "mcws/kinematics/point_kinematics.h"
#include "mcws/kinematics/robot_yaml.h"
#include "test_support.h"

namespace mcws {
namespace {

// Chains of up to ~2 m in mm: 1e-9 relative is far above double rounding (~1e-13 here) and far
// below any modelling error.
constexpr double kRelativeTolerance = 1e-9;
constexpr int kRandomVectors = 1000;

using test::randomJoints;

double reach(const Robot& robot) {  // a length scale for tolerances
  double sum = 1.0;
  Eigen::VectorXd q = robot.upperLimits();
  for (const auto& T : chainPoses(robot, q).T_world_link) sum += T.translation().norm();
  return sum;
}

// ---- Yin, Wang & Yu 2010, eq. (1) ---------------------------------------------------------------

TEST(ForwardKinematics, DeicingChainEqualsThePapersEquationOne) {
  const Robot robot = loadRobot(test::robotPath("deicing"));
  std::mt19937_64 rng(7);
  const double a1 = 50.0;
  for (int n = 0; n < kRandomVectors; ++n) {
    const Eigen::VectorXd q = randomJoints(robot, rng);  // theta3, theta1, theta2, a2
    const double t3 = q[0], t1 = q[1], t2 = q[2], a2 = q[3];
    const double r = a1 * std::cos(t1) + a2 * std::cos(t1 + t2);
    const Eigen::Vector3d expected(std::cos(t3) * r, std::sin(t3) * r,
                                   a1 * std::sin(t1) + a2 * std::sin(t1 + t2));
    const Eigen::Vector3d p = toolPose(robot, q).translation();
    ASSERT_NEAR((p - expected).norm(), 0.0, 1e-9) << "q = " << q.transpose();
  }
}

// ---- Liu, Han, Xu & Li 2021, the pose matrix of section 1.1 ------------------------------------

TEST(ForwardKinematics, InspectionArmReproducesThePapersPoseMatrix) {
  const Robot robot = loadRobot(test::robotPath("inspection6"));
  Eigen::VectorXd q(6);
  q << M_PI / 3, M_PI / 6, M_PI / 2, M_PI / 4, M_PI / 3, M_PI / 6;
  Eigen::Matrix<double, 3, 4> paper;            // as printed, 4 decimals
  paper << -0.9234, 0.3837, -0.0148, -39.3043,  //
      -0.0993, -0.2015, 0.9744, 731.9230,       //
      0.3709, 0.9012, 0.2241, -569.2371;
  const Eigen::Matrix4d T = toolPose(robot, q).matrix();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(T(r, c), paper(r, c), 0.5e-4) << r << "," << c;
  }
}

// ---- orocos-kdl as an independent oracle -------------------------------------------------------

/// Largest entry-wise difference, translations divided by `length` so the figure is relative.
double poseDifference(const Eigen::Matrix4d& A, const Eigen::Matrix4d& B, double length) {
  const Eigen::Matrix4d D = A - B;
  return std::max(D.topLeftCorner<3, 3>().cwiseAbs().maxCoeff(),
                  D.topRightCorner<3, 1>().cwiseAbs().maxCoeff() / length);
}

void expectMatchesKdl(const std::string& path) {
  const Robot robot = loadRobot(path);
  const KDL::Chain chain = test::kdlChainFromFile(path);
  ASSERT_EQ(static_cast<int>(chain.getNrOfJoints()), robot.dof());
  KDL::ChainFkSolverPos_recursive solver(chain);
  const double length = reach(robot);
  std::mt19937_64 rng(11);
  for (int n = 0; n < kRandomVectors; ++n) {
    const Eigen::VectorXd q = randomJoints(robot, rng);
    KDL::JntArray q_kdl(robot.dof());
    q_kdl.data = q;
    const ChainPoses poses = chainPoses(robot, q);
    KDL::Frame F;
    ASSERT_GE(solver.JntToCart(q_kdl, F), 0);
    ASSERT_LT(poseDifference(poses.T_world_tool.matrix(), test::toEigen(F), length),
              kRelativeTolerance)
        << path << " tool, q = " << q.transpose();
    ASSERT_NEAR((toolPose(robot, q).matrix() - poses.T_world_tool.matrix()).norm(), 0.0, 1e-9);
    for (int i = 0; i <= robot.dof(); ++i) {  // frame of joint i+1 = end of KDL segment i
      ASSERT_GE(solver.JntToCart(q_kdl, F, i + 1), 0);
      const Eigen::Isometry3d mine =
          i < robot.dof() ? poses.T_world_joint[i] : poses.T_world_flange;
      ASSERT_LT(poseDifference(mine.matrix(), test::toEigen(F), length), kRelativeTolerance)
          << path << " frame " << i << ", q = " << q.transpose();
    }
  }
}

TEST(ForwardKinematics, MatchesKdlOnEveryShippedRobot) {
  for (const char* name : test::kShippedRobots) {
    SCOPED_TRACE(name);
    expectMatchesKdl(test::robotPath(name));
  }
}

TEST(ForwardKinematics, ModifiedDhMatchesKdlCraig1989) {
  // PUMA 560 in Craig's table (m), with joint 3 made prismatic to cover that case too.
  test::TempDir dir;
  const std::string path = dir.file("puma_craig.yaml");
  test::writeFile(path, R"(name: puma_craig
units: {length: m, angle: deg}
convention: modified
base: {xyz: [0.1, -0.2, 0.6], rpy: [5, -10, 30]}
tool: {xyz: [0, 0.02, 0.15], rpy: [0, 90, 0]}
joints:
  - {name: j1, type: revolute,  a: 0,      alpha: 0,   d: 0,      limits: [-160, 160]}
  - {name: j2, type: revolute,  a: 0,      alpha: -90, d: 0.2435, limits: [-225, 45]}
  - {name: j3, type: prismatic, a: 0.4318, alpha: 0,   d: -0.0934, theta: 15, limits: [-0.1, 0.2]}
  - {name: j4, type: revolute,  a: -0.0203, alpha: -90, d: 0.4331, limits: [-110, 170]}
  - {name: j5, type: revolute,  a: 0,      alpha: 90,  d: 0,      limits: [-100, 100]}
  - {name: j6, type: revolute,  a: 0,      alpha: -90, d: 0,      theta: 10, limits: [-266, 266]}
)");
  expectMatchesKdl(path);
}

TEST(ForwardKinematics, RejectsWrongNumberOfJointValues) {
  const Robot robot = loadRobot(test::robotPath("ta1400"));
  try {
    toolPose(robot, Eigen::VectorXd::Zero(5));
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "robot 'ta1400' has 6 joints but 5 joint values were given");
  }
}

TEST(Robot, CheckJointVectorNamesJointValueAndLimits) {
  const Robot robot = loadRobot(test::robotPath("deicing"));
  Eigen::VectorXd q(4);
  q << 0, 0, 0, 80;
  try {
    robot.checkJointVector(q);
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "joint 'a2' value 80 is outside its limits [25, 70] cm");
  }
  q[3] = std::nan("");
  EXPECT_THROW(robot.checkJointVector(q), Error);
}

// ---- the sampling kernel against the general chain ---------------------------------------------

TEST(PointKinematics, AgreesWithChainPosesForToolAndFlange) {
  for (const char* name : test::kShippedRobots) {
    SCOPED_TRACE(name);
    const Robot robot = loadRobot(test::robotPath(name));
    const PointKinematics tool(robot, robot.T_flange_tool.translation());
    const PointKinematics flange(robot, Eigen::Vector3d::Zero());
    const double length = reach(robot);
    std::mt19937_64 rng(3);
    constexpr int L = PointKinematics::kLanes;
    std::vector<double> batch(robot.dof() * L);
    std::vector<Eigen::VectorXd> qs;
    for (int n = 0; n < kRandomVectors; ++n) {
      const Eigen::VectorXd q = randomJoints(robot, rng);
      const ChainPoses poses = chainPoses(robot, q);
      ASSERT_LT((tool.position(q.data()) - poses.T_world_tool.translation()).norm() / length,
                kRelativeTolerance);
      ASSERT_LT((flange.position(q.data()) - poses.T_world_flange.translation()).norm() / length,
                kRelativeTolerance);
      // The vectorised batch gives the same positions.
      const int lane = n % L;
      for (int j = 0; j < robot.dof(); ++j) batch[j * L + lane] = q[j];
      qs.push_back(q);
      if (lane == L - 1) {
        double x[L], y[L], z[L];
        tool.positions(batch.data(), x, y, z);
        for (int k = 0; k < L; ++k) {
          const Eigen::Vector3d expected = chainPoses(robot, qs[k]).T_world_tool.translation();
          ASSERT_LT((Eigen::Vector3d(x[k], y[k], z[k]) - expected).norm() / length,
                    kRelativeTolerance);
        }
        qs.clear();
      }
    }
  }
}

}  // namespace
}  // namespace mcws
