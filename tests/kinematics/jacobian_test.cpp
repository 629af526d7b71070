#include "mcws/kinematics/jacobian.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <kdl/chainjnttojacsolver.hpp>
#include <kdl/jacobian.hpp>
#include <random>
#include <set>

#include "kinematics/kdl_chain.h"
#include "kinematics/random_joints.h"
#include "kinematics/test_chains.h"
#include "mcws/core/error.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/robot_yaml.h"
#include "test_support.h"

namespace mcws {
namespace {

using test::differenceJacobian;
using test::shippedRobotFiles;
using test::tiltedAxesRobot;

constexpr int kRandomJointVectors = 1000;
/// Central differences with step h: truncation error ~ h^2 |q'''| ~ 1e-10 reach, rounding error
/// ~ 1e-16 reach / h ~ 1e-11 reach; 1e-8 of the reach leaves a margin of 100.
constexpr double kDifferenceTolerance = 1e-8;
/// KDL builds the same columns in another order of operations: rounding only.
constexpr double kKdlTolerance = 1e-12;

using test::randomJoints;

/// A length scale: the sum of the chain's fixed offsets and prismatic strokes, at least 1.
double lengthScale(const Robot& robot) {
  double sum =
      1.0 + robot.T_last_flange.translation().norm() + robot.T_flange_tool.translation().norm();
  for (const Joint& joint : robot.joints) {
    sum +=
        joint.T_parent_joint.translation().norm() +
        (joint.type == JointType::kPrismatic ? std::abs(joint.upper) + std::abs(joint.lower) : 0.0);
  }
  return sum;
}

/// Largest difference, linear rows divided by `length`.
double jacobianDifference(const Jacobian& A, const Jacobian& B, double length) {
  return std::max((A.topRows<3>() - B.topRows<3>()).cwiseAbs().maxCoeff() / length,
                  (A.bottomRows<3>() - B.bottomRows<3>()).cwiseAbs().maxCoeff());
}

TEST(Jacobian, MatchesCentralDifferencesOnEveryShippedRobot) {
  const std::vector<std::string> files = shippedRobotFiles();
  ASSERT_GE(files.size(), 5u);
  for (const std::string& path : files) {
    SCOPED_TRACE(path);
    const Robot robot = loadRobot(path);
    const double length = lengthScale(robot);
    std::mt19937_64 rng(17);
    for (int n = 0; n < kRandomJointVectors; ++n) {
      const Eigen::VectorXd q = randomJoints(robot, rng);
      ASSERT_LT(jacobianDifference(toolJacobian(robot, q), differenceJacobian(robot, q), length),
                kDifferenceTolerance)
          << "q = " << q.transpose();
    }
  }
}

TEST(Jacobian, MatchesKdlChainJntToJacSolverOnEveryShippedRobot) {
  for (const std::string& path : shippedRobotFiles()) {
    SCOPED_TRACE(path);
    const Robot robot = loadRobot(path);
    const KDL::Chain chain = test::kdlChainFromFile(path);
    ASSERT_EQ(static_cast<int>(chain.getNrOfJoints()), robot.dof());
    KDL::ChainJntToJacSolver solver(chain);
    KDL::Jacobian kdl_jacobian(robot.dof());
    const double length = lengthScale(robot);
    std::mt19937_64 rng(19);
    for (int n = 0; n < kRandomJointVectors; ++n) {
      const Eigen::VectorXd q = randomJoints(robot, rng);
      KDL::JntArray q_kdl(robot.dof());
      q_kdl.data = q;
      // KDL: twist of the chain's last segment (the tool), reference point at its origin,
      // expressed in the chain's base (the world): the same convention.
      ASSERT_GE(solver.JntToJac(q_kdl, kdl_jacobian), 0);
      ASSERT_LT(jacobianDifference(toolJacobian(robot, q), kdl_jacobian.data, length),
                kKdlTolerance)
          << "q = " << q.transpose();
    }
  }
}

TEST(Jacobian, TiltedAxesMatchCentralDifferences) {
  const Robot robot = tiltedAxesRobot();
  const KinematicChain chain(robot);
  std::mt19937_64 rng(23);
  for (int n = 0; n < kRandomJointVectors; ++n) {
    const Eigen::VectorXd q = randomJoints(robot, rng);
    ASSERT_LT(jacobianDifference(toolJacobian(robot, q), differenceJacobian(robot, q), 1.0),
              kDifferenceTolerance);
    // The prepared chain's pose is the robot's pose.
    ASSERT_LT((chain.toolPose(q.data()).matrix() - toolPose(robot, q).matrix()).norm(), 1e-12);
  }
}

TEST(Jacobian, PoseOfThePreparedChainIsTheToolPose) {
  for (const std::string& path : shippedRobotFiles()) {
    const Robot robot = loadRobot(path);
    const KinematicChain chain(robot);
    std::mt19937_64 rng(29);
    for (int n = 0; n < 100; ++n) {
      const Eigen::VectorXd q = randomJoints(robot, rng);
      const Eigen::Matrix4d expected = toolPose(robot, q).matrix();
      Eigen::Matrix3d R;
      Eigen::Vector3d p;
      Jacobian J(6, robot.dof());
      chain.toolPoseAndJacobian(q.data(), R, p, J.data());
      ASSERT_LT((chain.toolPose(q.data()).matrix() - expected).norm(), 1e-9 * lengthScale(robot));
      ASSERT_LT((R - expected.topLeftCorner<3, 3>()).norm(), 1e-12);
      ASSERT_LT((p - expected.topRightCorner<3, 1>()).norm(), 1e-9 * lengthScale(robot));
    }
  }
}

TEST(Jacobian, PlanarTwoLinkArmClosedForm) {
  // Two revolute joints about z, links 0.7 and 0.4 (standard D-H, alpha = 0): the textbook
  // J = [-l1 s1 - l2 s12, -l2 s12; l1 c1 + l2 c12, l2 c12] in the linear rows, ones in row 5.
  test::TempDir dir;
  const std::string path = dir.file("planar.yaml");
  test::writeFile(path, R"(name: planar
units: {length: m, angle: deg}
convention: standard
joints:
  - {name: j1, type: revolute, a: 0.7, alpha: 0, d: 0, limits: [-180, 180]}
  - {name: j2, type: revolute, a: 0.4, alpha: 0, d: 0, limits: [-180, 180]}
)");
  const Robot robot = loadRobot(path);
  const double q1 = 0.4, q2 = -1.1;
  const Jacobian J = toolJacobian(robot, Eigen::Vector2d(q1, q2));
  Jacobian expected = Jacobian::Zero(6, 2);
  expected(0, 0) = -0.7 * std::sin(q1) - 0.4 * std::sin(q1 + q2);
  expected(0, 1) = -0.4 * std::sin(q1 + q2);
  expected(1, 0) = 0.7 * std::cos(q1) + 0.4 * std::cos(q1 + q2);
  expected(1, 1) = 0.4 * std::cos(q1 + q2);
  expected(5, 0) = expected(5, 1) = 1.0;
  EXPECT_LT((J - expected).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(Jacobian, RejectsWrongNumberOfJointValues) {
  const Robot robot = loadRobot(test::robotPath("inspection6"));
  try {
    toolJacobian(robot, Eigen::VectorXd::Zero(7));
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "robot 'inspection6' has 6 joints but 7 joint values were given");
  }
}

}  // namespace
}  // namespace mcws
