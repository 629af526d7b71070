// Exact motion checks: nothing between two checked configurations is missed.
#include "mcws/planning/motion_certifier.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kinematics/random_joints.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/robot_yaml.h"
#include "test_support.h"

namespace mcws {
namespace {

/// A 50 cm stick turning about z, and one sphere obstacle of radius 1 at `post` (world, cm).
struct Stick {
  Robot robot;
  CollisionModel model;
  explicit Stick(const std::string& post) {
    const std::string text = R"(name: stick
units: {length: cm, angle: deg}
convention: standard
joints:
  - {name: q1, type: revolute, a: 50, alpha: 0, d: 0, theta: 0, limits: [-180, 180]}
collision:
  links:
    q1: [{type: capsule, from: [0, 0, 0], to: [50, 0, 0], radius: 1}]
  environment:
    - {name: post, type: sphere, center: )" +
                             post + R"(, radius: 1}
)";
    robot = parseRobotYaml(text, "stick.yaml");
    model = parseCollisionYaml(robot, text, "stick.yaml");
  }
};

/// The arm of the maintenance-arm patent in its scene.
struct MaintenanceArm {
  Robot robot = loadRobot(test::robotPath("maintenance4"));
  CollisionChecker checker{robot, loadCollisionModel(robot, test::robotPath("maintenance4"))};
  MotionCertifier certifier{robot, checker};
  CollisionChecker::Scratch scratch;
};

Eigen::VectorXd one(double degrees) { return Eigen::VectorXd::Constant(1, degrees * M_PI / 180); }

TEST(MotionCertifier, FindsAPostBetweenTwoFreeEnds) {
  const Stick stick("[40, 0, 0]");
  const CollisionChecker checker(stick.robot, stick.model);
  const MotionCertifier certifier(stick.robot, checker);
  CollisionChecker::Scratch scratch;
  const Eigen::Isometry3d base = stick.robot.T_world_base;
  // Both ends are 40 sin(30 deg) = 20 cm from the post: a check of the ends alone sees no
  // collision; the stick passes through the post at 0 deg.
  EXPECT_TRUE(certifier.configurationFree(one(-30), base, scratch));
  EXPECT_TRUE(certifier.configurationFree(one(30), base, scratch));
  EXPECT_FALSE(certifier.motionFree(one(-30), one(30), base, PairSet::kAll, scratch));
  // Swinging the other way round misses it.
  EXPECT_TRUE(certifier.motionFree(one(30), one(179), base, PairSet::kAll, scratch));
  // The post just beyond the tip (clearance 0.5 cm) never touches the stick.
  const Stick far("[52.5, 0, 0]");
  const CollisionChecker far_checker(far.robot, far.model);
  const MotionCertifier far_certifier(far.robot, far_checker);
  EXPECT_TRUE(far_certifier.motionFree(one(-30), one(30), base, PairSet::kAll, scratch));
  // ... unless the obstacles are padded by more than that clearance.
  MotionCertifierOptions padded;
  padded.environment_margin = 0.6;
  const MotionCertifier padded_certifier(far.robot, far_checker, padded);
  EXPECT_FALSE(padded_certifier.motionFree(one(-30), one(30), base, PairSet::kAll, scratch));
  EXPECT_TRUE(padded_certifier.motionFree(one(30), one(90), base, PairSet::kAll, scratch));
}

TEST(MotionCertifier, ReachBoundsHoldOverRandomConfigurations) {
  MaintenanceArm arm;
  const Robot& robot = arm.robot;
  const CollisionChecker& checker = arm.checker;
  const MotionCertifier& certifier = arm.certifier;
  CollisionChecker::Scratch& scratch = arm.scratch;
  std::mt19937_64 random(11);
  for (int trial = 0; trial < 500; ++trial) {
    const Eigen::VectorXd q = test::randomJoints(robot, random);
    const ChainPoses chain = chainPoses(robot, q);
    checker.place(q.data(), robot.T_world_base, scratch);
    for (int i = 0; i < robot.dof(); ++i) {
      if (robot.joints[i].type != JointType::kRevolute) continue;
      const Eigen::Vector3d origin = chain.T_world_joint[i].translation();
      const Eigen::Vector3d axis = chain.T_world_joint[i].linear() * robot.joints[i].axis;
      for (int body = i + 1; body <= checker.toolBody(); ++body) {
        const CollisionChecker::BodySphere sphere = checker.bodySphere(body);
        const Eigen::Vector3d c = checker.bodyPose(body, scratch) * sphere.center - origin;
        const double from_axis = (c - c.dot(axis) * axis).norm() + sphere.radius;
        ASSERT_LE(from_axis, certifier.reach(i, body) + 1e-9) << "joint " << i << " body " << body;
      }
    }
  }
}

/// A motion's collisions by brute force: `steps` + 1 evenly spaced configurations.
bool denseFree(const CollisionChecker& checker, const Eigen::VectorXd& a, const Eigen::VectorXd& b,
               const Eigen::Isometry3d& base, int steps, CollisionChecker::Scratch& scratch) {
  for (int k = 0; k <= steps; ++k) {
    const Eigen::VectorXd q = a + (b - a) * (double(k) / steps);
    if (checker.label(q.data(), base, scratch) != kLabelFree) return false;
  }
  return true;
}

TEST(MotionCertifier, NeverCallsFreeWhatDenseSamplingFindsColliding) {
  MaintenanceArm arm;
  const Robot& robot = arm.robot;
  const CollisionChecker& checker = arm.checker;
  const MotionCertifier& certifier = arm.certifier;
  CollisionChecker::Scratch& scratch = arm.scratch;
  std::mt19937_64 random(5);
  int free = 0, colliding = 0, only_certifier = 0;
  const int trials = 300 / test::kSanitizerShrink;
  for (int trial = 0; trial < trials; ++trial) {
    Eigen::VectorXd a(robot.dof()), b(robot.dof());
    for (int j = 0; j < robot.dof(); ++j) {
      const Joint& joint = robot.joints[j];
      std::uniform_real_distribution<double> within(joint.lower, joint.upper);
      a[j] = within(random);
      // Moves of up to a fifth of the range, clamped: many end free and cross an obstacle.
      b[j] = std::clamp(a[j] + 0.2 * (within(random) - 0.5 * (joint.lower + joint.upper)),
                        joint.lower, joint.upper);
    }
    Eigen::Isometry3d base = robot.T_world_base;
    if (trial % 2) {  // a displaced base: a roll about conductor A and a slide
      Eigen::Isometry3d sway = Eigen::Isometry3d::Identity();
      sway.translation() =
          Eigen::Vector3d(std::uniform_real_distribution<double>(-2, 2)(random), 0, 25);
      sway.rotate(Eigen::AngleAxisd(std::uniform_real_distribution<double>(-0.1, 0.1)(random),
                                    Eigen::Vector3d::UnitX()));
      sway.translate(Eigen::Vector3d(0, 0, -25));
      base = sway * base;
    }
    const bool certified = certifier.motionFree(a, b, base, PairSet::kAll, scratch);
    const bool dense = denseFree(checker, a, b, base, 2000, scratch);
    ASSERT_FALSE(certified && !dense) << "trial " << trial;  // soundness: the whole point
    (certified ? free : colliding)++;
    only_certifier += !certified && dense;
  }
  // Both outcomes occur, and a collision found only by the exact check is rare (thin contacts
  // between dense samples, or grazing within the resolution).
  EXPECT_GT(free, trials / 10);
  EXPECT_GT(colliding, trials / 10);
  EXPECT_LE(only_certifier, trials / 20);
}

TEST(MotionCertifier, DisplacementBoundsTheClearanceChange) {
  MaintenanceArm arm;
  const Robot& robot = arm.robot;
  const CollisionChecker& checker = arm.checker;
  const MotionCertifier& certifier = arm.certifier;
  CollisionChecker::Scratch& scratch = arm.scratch;
  std::mt19937_64 random(3);
  const Eigen::Vector3d pivot(0, 0, 25);
  constexpr double kCap = 1e9;  // uncapped
  int compared = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::VectorXd q = test::randomJoints(robot, random);
    Eigen::Isometry3d d = Eigen::Isometry3d::Identity();
    d.translation() =
        pivot + Eigen::Vector3d(std::uniform_real_distribution<double>(-3, 3)(random), 0, 0);
    d.rotate(Eigen::AngleAxisd(std::uniform_real_distribution<double>(-0.2, 0.2)(random),
                               Eigen::Vector3d::UnitX()));
    d.translate(-pivot);
    std::vector<double> nominal, moved;
    certifier.clearances(q, robot.T_world_base, PairSet::kEnvironment, kCap, scratch, nominal);
    checker.place(q.data(), robot.T_world_base, scratch);
    const MotionCertifier::DisplacementBound bound = MotionCertifier::displacementBound(d, pivot);
    std::vector<double> reach(nominal.size());
    for (std::size_t e = 0; e < nominal.size(); ++e) {
      const int body = certifier.environmentBody(e);
      const CollisionChecker::BodySphere s = checker.bodySphere(body);
      reach[e] = (checker.bodyPose(body, scratch) * s.center - pivot).norm() + s.radius;
    }
    certifier.clearances(q, d * robot.T_world_base, PairSet::kEnvironment, kCap, scratch, moved);
    for (std::size_t e = 0; e < nominal.size(); ++e) {
      if (nominal[e] <= 0.0) continue;
      ++compared;
      ASSERT_GE(moved[e], nominal[e] - bound.sin_term * reach[e] - bound.shift - 1e-6);
    }
  }
  EXPECT_GT(compared, 1000);
}

}  // namespace
}  // namespace mcws
