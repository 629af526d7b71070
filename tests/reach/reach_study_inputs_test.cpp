// The parts under mcws::ReachStudy: free-roll inverse kinematics against the full-pose solver and
// the planar arm's elbow solutions, targets from a surface normal, and the options' checks (the
// studies are in reach_study_test.cpp).
#include "mcws/reach/reach_study.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "kinematics/random_joints.h"
#include "mcws/core/error.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/inverse_kinematics.h"
#include "mcws/kinematics/robot_yaml.h"
#include "mcws/reach/orientation_bins.h"
#include "reach/planar2.h"
#include "reach/reach_study_fixture.h"
#include "test_support.h"

namespace mcws {
namespace {

using test::angleBetween;
using test::angleDifference;
using test::kDeg;
using test::planar2;
using test::translation;

// ---- free-roll inverse kinematics
// ----------------------------------------------------------------

// A pose rolled about its own z axis keeps the tool point and the approach: free-roll IK must meet
// both exactly while the roll comes out wherever the solver lands; full-pose IK must meet the roll.
TEST(FreeRollIk, InspectionArmMeetsPointAndApproachOfRolledPoses) {
  const Robot robot = loadRobot(test::robotPath("inspection6"));
  const IkSolver solver(robot);
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> roll(-M_PI, M_PI);
  const Eigen::VectorXd seed = Eigen::VectorXd::Zero(robot.dof());
  int roll_differs = 0;
  for (int i = 0; i < 20; ++i) {
    const Eigen::VectorXd q = test::randomJoints(robot, rng);
    const double phi = roll(rng);
    const Eigen::Isometry3d target =
        toolPose(robot, q) * Eigen::AngleAxisd(phi, Eigen::Vector3d::UnitZ());
    IkOptions options;
    options.free_roll = true;
    const IkResult free = solver.solve(target, seed, options);
    ASSERT_TRUE(free.converged()) << i << ": " << ikStatusName(free.status);
    const Eigen::Isometry3d T = toolPose(robot, free.q);
    EXPECT_LE((T.translation() - target.translation()).norm(), 1e-6 + 1e-9) << i;
    const double approach_error = angleBetween(T.linear().col(2), target.linear().col(2));
    EXPECT_LT(approach_error, 1e-6) << i;
    EXPECT_NEAR(free.orientation_error, approach_error, 1e-9) << i;
    for (int j = 0; j < robot.dof(); ++j) {
      EXPECT_GE(free.q[j], robot.joints[j].lower) << i;
      EXPECT_LE(free.q[j], robot.joints[j].upper) << i;
    }
    // The roll left over: the angle between the tool's x axis and the target's.
    if (angleBetween(T.linear().col(0), target.linear().col(0)) > 1e-3) ++roll_differs;

    // The full pose, roll included.
    const IkResult full = solver.solve(target, seed, IkOptions{});
    ASSERT_TRUE(full.converged()) << i;
    const Eigen::Isometry3d T_full = toolPose(robot, full.q);
    EXPECT_LE((T_full.translation() - target.translation()).norm(), 1e-6 + 1e-9) << i;
    EXPECT_LT(Eigen::AngleAxisd(target.linear() * T_full.linear().transpose()).angle(), 1e-6) << i;
  }
  // Were the roll matched too, free roll would be the full pose.
  EXPECT_GE(roll_differs, 10);
}

// planar2's tool z is always +z and its roll is q1 + q2: a point with a roll the elbow solutions
// do not have is unreachable as a full pose and reachable with the roll free.
TEST(FreeRollIk, PlanarArmReachesPointWhoseRollItCannotMatch) {
  const Robot robot = planar2();
  const IkSolver solver(robot);
  // r = 50: q2 = +-90 deg, q1 + q2 = +-(90 - atan2(30, 40)) = +-53.13 deg; ask for 17 deg.
  Eigen::Isometry3d target = translation(50, 0, 0);
  target.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::VectorXd seed = Eigen::VectorXd::Zero(2);
  IkOptions options;
  options.restarts = 5;
  EXPECT_FALSE(solver.solve(target, seed, options).converged());
  options.free_roll = true;
  const IkResult free = solver.solve(target, seed, options);
  ASSERT_TRUE(free.converged());
  EXPECT_NEAR(std::abs(free.q[1]), 90.0 * kDeg, 1e-6);
  EXPECT_NEAR(std::abs(angleDifference(free.q[0] + free.q[1], 0.0)),
              (90.0 - std::atan2(30.0, 40.0) / kDeg) * kDeg, 1e-6);
  // position_only wins over free_roll.
  options.position_only = true;
  const IkResult point = solver.solve(target, seed, options);
  ASSERT_TRUE(point.converged());
  EXPECT_NEAR((toolPose(robot, point.q).translation() - target.translation()).norm(), 0.0, 1e-6);
}

// ---- targetFromNormal, options ------------------------------------------------------------------

TEST(ReachStudyTarget, FromNormalApproachesAgainstTheNormal) {
  const std::vector<Eigen::Vector3d> normals = {{0, 0, -1},   {0, 0, 3},        {1, 0, 0},
                                                {-2, 0.1, 0}, {0.3, -0.4, 0.5}, {0, 1e-3, 0}};
  for (const Eigen::Vector3d& n : normals) {
    const Eigen::Vector3d point(1.5, -2.0, 7.0);
    const ReachTarget target = targetFromNormal(point, n);
    EXPECT_TRUE(target.free_roll);
    EXPECT_EQ(target.pose.translation(), point);
    const Eigen::Matrix3d R = target.pose.linear();
    EXPECT_NEAR((R.col(2) + n / n.norm()).norm(), 0.0, 1e-15) << n.transpose();
    EXPECT_NEAR((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 0.0, 1e-14)
        << n.transpose();
    EXPECT_NEAR(R.determinant(), 1.0, 1e-14) << n.transpose();
    EXPECT_NEAR((R.col(0) - OrientationBins::rollReference(R.col(2))).norm(), 0.0, 1e-15);
    EXPECT_EQ(target.pose.matrix().row(3), Eigen::RowVector4d(0, 0, 0, 1));
  }
  // The world x axis projected, or y for approaches near +-x (rollReference's rule), by hand.
  EXPECT_NEAR(
      (targetFromNormal({0, 0, 0}, {0, 0, -1}).pose.linear().col(0) - Eigen::Vector3d::UnitX())
          .norm(),
      0.0, 1e-15);
  EXPECT_NEAR(
      (targetFromNormal({0, 0, 0}, {1, 0, 0}).pose.linear().col(0) - Eigen::Vector3d::UnitY())
          .norm(),
      0.0, 1e-15);
}

TEST(ReachStudyTarget, FromNormalRejectsBadInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d p(1, 2, 3);
  EXPECT_NE(test::errorOf([&] { targetFromNormal(p, Eigen::Vector3d::Zero()); }).find("normal"),
            std::string::npos);
  EXPECT_NE(test::errorOf([&] {
              targetFromNormal(p, {nan, 0, 1});
            }).find("normal"),
            std::string::npos);
  EXPECT_NE(test::errorOf([&] {
              targetFromNormal(p, {inf, 0, 0});
            }).find("normal"),
            std::string::npos);
  EXPECT_NE(test::errorOf([&] {
              targetFromNormal({0, nan, 0}, {0, 0, 1});
            }).find("point"),
            std::string::npos);
  EXPECT_NE(test::errorOf([&] {
              targetFromNormal({inf, 0, 0}, {0, 0, 1});
            }).find("point"),
            std::string::npos);
}

TEST(ReachStudyOptionsCheck, RejectsBadValues) {
  const Robot robot = planar2();
  auto bad = [&](auto edit, const char* words) {
    ReachStudyOptions options;
    edit(options);
    EXPECT_THROW(options.check(), Error) << words;
    EXPECT_NE(test::errorOf([&] { (void)ReachStudy(robot, nullptr, options); }).find(words),
              std::string::npos);
  };
  bad([](ReachStudyOptions& o) { o.approach_tolerance = -0.1; }, "approach tolerance");
  bad([](ReachStudyOptions& o) { o.approach_tolerance = std::nan(""); }, "approach tolerance");
  bad([](ReachStudyOptions& o) { o.approach_tolerance = INFINITY; }, "approach tolerance");
  bad([](ReachStudyOptions& o) { o.starts = 0; }, "starts");
  bad([](ReachStudyOptions& o) { o.clearance_cap = 0.0; }, "clearance cap");
  bad([](ReachStudyOptions& o) { o.clearance_cap = std::nan(""); }, "clearance cap");
  bad([](ReachStudyOptions& o) { o.quality.characteristic_length = 0.0; }, "characteristic");
  EXPECT_NO_THROW(ReachStudyOptions{}.check());
}

}  // namespace
}  // namespace mcws
