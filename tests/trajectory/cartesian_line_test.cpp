#include "mcws/trajectory/cartesian_line.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "mcws/core/error.h"
#include "mcws/kinematics/forward_kinematics.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

// Planar two-link arm in the x-y plane: joint 1 at the origin, links of 1.0 m and 0.8 m.
constexpr double kL1 = 1.0, kL2 = 0.8;
// Closed-form IK and FK agree to rounding.
constexpr double kLineTolerance = 1e-9;

Robot planarArm() {
  Robot robot;
  robot.name = "planar2";
  Joint j1, j2;
  j1.name = "j1";
  j2.name = "j2";
  j1.lower = j2.lower = -M_PI;
  j1.upper = j2.upper = M_PI;
  j2.T_parent_joint.translation() = Eigen::Vector3d(kL1, 0, 0);
  robot.joints = {j1, j2};
  robot.T_last_flange.translation() = Eigen::Vector3d(kL2, 0, 0);
  return robot;
}

/// Position-only closed-form IK: elbow angle +-acos(c2); the branch given by `elbow` (+1, -1),
/// or, when elbow is 0, the branch whose elbow angle is nearer the seed's.
std::optional<Eigen::VectorXd> planarIk(const Eigen::Vector3d& p, const Eigen::VectorXd& seed,
                                        int elbow = 0) {
  const double c2 = (p.x() * p.x() + p.y() * p.y() - kL1 * kL1 - kL2 * kL2) / (2 * kL1 * kL2);
  if (std::abs(c2) > 1.0) return std::nullopt;
  double q2 = std::acos(c2);
  if (elbow < 0 || (elbow == 0 && std::abs(-q2 - seed[1]) < std::abs(q2 - seed[1]))) q2 = -q2;
  const double q1 =
      std::atan2(p.y(), p.x()) - std::atan2(kL2 * std::sin(q2), kL1 + kL2 * std::cos(q2));
  Eigen::VectorXd q(2);
  q << std::remainder(q1, 2 * M_PI), q2;
  return q;
}

IkFunction nearestBranchIk() {
  return [](const Eigen::Isometry3d& T, const Eigen::VectorXd& seed) {
    return planarIk(T.translation(), seed);
  };
}

Eigen::Isometry3d poseAt(const Robot& robot, double q1, double q2) {
  return toolPose(robot, Eigen::Vector2d(q1, q2));
}

TEST(CartesianLine, ToolFollowsTheStraightLineWithTheQuinticTiming) {
  const Robot robot = planarArm();
  const Eigen::VectorXd q_start = Eigen::Vector2d(0.2, 1.2);
  const Eigen::Isometry3d T_goal = poseAt(robot, 1.1, 0.6);
  CartesianLineOptions options;
  options.duration = 2.0;
  options.rate = 50.0;
  const CartesianLineResult r = cartesianLine(robot, q_start, T_goal, nearestBranchIk(), options);
  ASSERT_EQ(r.status, CartesianLineStatus::kSuccess) << r.message;
  const SampledTrajectory& tr = r.trajectory;
  ASSERT_EQ(tr.size(), 101);
  const Eigen::Vector3d p0 = toolPose(robot, q_start).translation(), p1 = T_goal.translation();
  const Eigen::Vector3d direction = (p1 - p0).normalized();
  for (int i = 0; i < tr.size(); ++i) {
    const Eigen::Vector3d p = toolPose(robot, tr.q.row(i).transpose()).translation();
    const Eigen::Vector3d along = p - p0;
    EXPECT_LT((along - along.dot(direction) * direction).norm(), kLineTolerance)
        << "off the line, " << i;
    const double u = tr.t[i] / options.duration;
    const double s = 10 * std::pow(u, 3) - 15 * std::pow(u, 4) + 6 * std::pow(u, 5);
    EXPECT_NEAR(along.norm() / (p1 - p0).norm(), s, kLineTolerance) << i;
  }
  EXPECT_LT((tr.q.row(tr.size() - 1).transpose() - Eigen::Vector2d(1.1, 0.6)).norm(),
            kLineTolerance);
}

TEST(CartesianLine, FiniteDifferenceVelocitiesMatchTheJacobian) {
  const Robot robot = planarArm();
  const Eigen::VectorXd q_start = Eigen::Vector2d(-0.4, 1.5);
  const Eigen::Isometry3d T_goal = poseAt(robot, 0.5, 0.9);
  CartesianLineOptions options;
  options.duration = 4.0;
  options.rate = 200.0;
  const CartesianLineResult r = cartesianLine(robot, q_start, T_goal, nearestBranchIk(), options);
  ASSERT_EQ(r.status, CartesianLineStatus::kSuccess) << r.message;
  const Eigen::Vector3d dp = T_goal.translation() - toolPose(robot, q_start).translation();
  const SampledTrajectory& tr = r.trajectory;
  EXPECT_EQ(tr.qd.row(0).norm(), 0.0);
  EXPECT_EQ(tr.qd.row(tr.size() - 1).norm(), 0.0);
  for (int i = 1; i + 1 < tr.size(); ++i) {
    // qd = J^-1 pdot, pdot = dp * ds/du / T, J of the planar arm in closed form.
    const double q1 = tr.q(i, 0), q2 = tr.q(i, 1);
    Eigen::Matrix2d J;
    J << -kL1 * std::sin(q1) - kL2 * std::sin(q1 + q2), -kL2 * std::sin(q1 + q2),
        kL1 * std::cos(q1) + kL2 * std::cos(q1 + q2), kL2 * std::cos(q1 + q2);
    const Eigen::Vector2d pdot = dp.head<2>() *
                                 blend(TimeProfile::kQuintic, tr.t[i] / options.duration).ds /
                                 options.duration;
    const Eigen::Vector2d qd = J.inverse() * pdot;
    // Three-point differences at h = 5 ms: error ~ h^2 * third derivative, well below 1e-3.
    EXPECT_LT((tr.qd.row(i).transpose() - qd).norm(), 1e-3) << "t = " << tr.t[i];
  }
}

TEST(CartesianLine, SeedsEachStepWithThePreviousSolutionAndSlerpsOrientation) {
  const Robot robot = planarArm();
  const Eigen::VectorXd q_start = Eigen::Vector2d(0.0, 1.0);
  const Eigen::Isometry3d T_goal = poseAt(robot, 0.8, 0.6);
  std::vector<Eigen::VectorXd> seeds, answers;
  std::vector<Eigen::Isometry3d> targets;
  const IkFunction recording = [&](const Eigen::Isometry3d& T, const Eigen::VectorXd& seed) {
    seeds.push_back(seed);
    targets.push_back(T);
    auto q = planarIk(T.translation(), seed);
    answers.push_back(*q);
    return q;
  };
  CartesianLineOptions options;
  options.duration = 1.0;
  options.rate = 10.0;
  options.max_joint_step = Eigen::Vector2d(1.0, 1.0);  // ten big steps
  ASSERT_EQ(cartesianLine(robot, q_start, T_goal, recording, options).status,
            CartesianLineStatus::kSuccess);
  ASSERT_EQ(seeds.size(), 11u);
  EXPECT_EQ(seeds[0], q_start);
  for (std::size_t k = 1; k < seeds.size(); ++k) EXPECT_EQ(seeds[k], answers[k - 1]) << k;
  // At t = 0.5, s = 0.5: the tool's heading (q1 + q2) is halfway between 1.0 and 1.4.
  const Eigen::Matrix3d R = targets[5].linear();
  EXPECT_NEAR(std::atan2(R(1, 0), R(0, 0)), 1.2, kLineTolerance);
  EXPECT_NEAR(R(2, 2), 1.0, kLineTolerance);
}

TEST(CartesianLine, ReportsTheTimeWhereIkFails) {
  // From (1.4, 0.05) straight through the unreachable hole r < 0.2 around the base.
  const Robot robot = planarArm();
  const Eigen::VectorXd q_start = *planarIk({1.4, 0.05, 0}, Eigen::Vector2d(0, 1), 1);
  Eigen::Isometry3d T_goal = Eigen::Isometry3d::Identity();
  T_goal.translation() = Eigen::Vector3d(-1.4, 0.05, 0);
  CartesianLineOptions options;
  options.duration = 2.0;
  options.rate = 100.0;
  options.max_joint_step = Eigen::Vector2d(10, 10);  // the elbow whips near the hole
  const CartesianLineResult r = cartesianLine(robot, q_start, T_goal, nearestBranchIk(), options);
  ASSERT_EQ(r.status, CartesianLineStatus::kIkFailed);
  // First sample with |x| < sqrt(0.2^2 - 0.05^2): x = 1.4 - 2.8 s(t / 2).
  const double x_hole = std::sqrt(0.04 - 0.0025);
  int first = 0;
  while (1.4 - 2.8 * blend(TimeProfile::kQuintic, first / 200.0).s >= x_hole) ++first;
  EXPECT_DOUBLE_EQ(r.failure_time, first / 100.0);
  EXPECT_EQ(r.trajectory.size(), first);
  EXPECT_THAT(r.message, StartsWith("IK found no solution at t = " +
                                    std::to_string(first / 100.0).substr(0, 4)));
  EXPECT_THAT(r.message, HasSubstr(" m"));
}

TEST(CartesianLine, ReportsAJointJumpWithJointAndTime) {
  // An IK that picks the elbow branch by the sign of y flips the elbow where the line crosses
  // y = 0: from (1.2, 0.4) to (1.2, -0.4), at the first sample with y < 0 (t = 0.51 s: at
  // t = 0.5 s the tool is on y = 0 and keeps the first branch).
  const Robot robot = planarArm();
  const IkFunction flipping = [](const Eigen::Isometry3d& T, const Eigen::VectorXd& seed) {
    return planarIk(T.translation(), seed, T.translation().y() >= 0 ? 1 : -1);
  };
  const Eigen::VectorXd q_start = *planarIk({1.2, 0.4, 0}, Eigen::Vector2d(0, 1), 1);
  Eigen::Isometry3d T_goal = Eigen::Isometry3d::Identity();
  T_goal.translation() = Eigen::Vector3d(1.2, -0.4, 0);
  CartesianLineOptions options;
  options.duration = 1.0;
  options.rate = 100.0;
  const CartesianLineResult r = cartesianLine(robot, q_start, T_goal, flipping, options);
  ASSERT_EQ(r.status, CartesianLineStatus::kJointJump);
  int first = 0;
  while (0.4 - 0.8 * blend(TimeProfile::kQuintic, first / 100.0).s >= 0) ++first;
  EXPECT_DOUBLE_EQ(r.failure_time, first / 100.0);
  EXPECT_THAT(r.message, StartsWith("joint 'j1' jumps by "));
  EXPECT_THAT(r.message, HasSubstr(" rad at t = 0.51 s (at most 0.1 per sample)"));
  EXPECT_EQ(first, 51);
}

TEST(CartesianLine, ReportsBadOptions) {
  const Robot robot = planarArm();
  const Eigen::Isometry3d T_goal = poseAt(robot, 0.3, 0.3);
  CartesianLineOptions options;
  options.duration = 0.01;
  options.rate = 100.0;
  auto error = [&](const Eigen::VectorXd& q) -> std::string {
    try {
      cartesianLine(robot, q, T_goal, nearestBranchIk(), options);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(error(Eigen::Vector2d(0, 1)),
            "cartesian line: 2 samples are too few; raise the rate or the duration");
  options.duration = -1.0;
  EXPECT_EQ(error(Eigen::Vector2d(0, 1)), "sampling: duration -1 s is not a positive number");
  options.duration = 1.0;
  EXPECT_EQ(error(Eigen::Vector3d(0, 1, 2)),
            "robot 'planar2' has 2 joints but 3 joint values were given");
  options.max_joint_step = Eigen::Vector2d(0.1, 0.0);
  EXPECT_EQ(error(Eigen::Vector2d(0, 1)), "cartesian line: joint step limits must be positive");
}

}  // namespace
}  // namespace mcws
