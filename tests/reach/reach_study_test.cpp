// mcws::ReachStudy, the free-roll inverse kinematics under it and base placement, against
// independent references: the planar 2R arm's closed-form annulus, elbow solutions and
// manipulability l1 l2 |sin q2|; its clearances from a hand-written 2-D distance (segment to
// rectangle, convex, minimised by ternary search) and from CollisionChecker::report(); the
// maintenance arm's cylindrical geometry worked by hand from robots/maintenance4.yaml; the
// base-placement interval of two targets in closed form. Free-roll IK, targets and options are in
// reach_study_inputs_test.cpp, base placement in base_placement_test.cpp.
#include "mcws/reach/reach_study.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "kinematics/random_joints.h"
#include "mcws/collision/collision_checker.h"
#include "mcws/collision/collision_model.h"
#include "mcws/core/error.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/inverse_kinematics.h"
#include "mcws/kinematics/robot_yaml.h"
#include "mcws/reach/base_placement.h"
#include "mcws/reach/orientation_bins.h"
#include "mcws/reach/reach_map.h"
#include "reach/planar2.h"
#include "reach/reach_study_fixture.h"
#include "test_support.h"

namespace mcws {
namespace {

using test::angleBetween;
using test::angleDifference;
using test::kDeg;
using test::kElbowLimit;
using test::kL1;
using test::kL2;
using test::kOuter;
using test::planar2;
using test::planarManipulability;
using test::planarManipulabilitySlope;
using test::planarOptions;
using test::translation;

/// robots/planar2.yaml: link capsule radius [cm], base sphere radius [cm].
constexpr double kLinkRadius = 2.5, kBaseRadius = 5.0;
/// Inner radius of planar2's annulus (the elbow bent to its limit).
const double kInner = std::sqrt(kL1 * kL1 + kL2 * kL2 + 2.0 * kL1 * kL2 * std::cos(kElbowLimit));

/// A study's manipulability m of planar2's solution q for a target r_target from its base: the
/// closed form at q's own tool point to 1e-9 relative, and at the target radius within what the
/// IK position tolerance (1e-6 cm) moves it.
void expectPlanarManipulability(double m, const Eigen::VectorXd& q, double r_target) {
  const double r = toolPose(loadRobot(test::robotPath("planar2")), q).translation().norm();
  EXPECT_NEAR(m, planarManipulability(r), 1e-9 * planarManipulability(r)) << "r " << r;
  EXPECT_NEAR(m, kL1 * kL2 * std::abs(std::sin(q[1])), 1e-9 * kL1 * kL2);
  EXPECT_NEAR(m, planarManipulability(r_target),
              1.01e-6 * planarManipulabilitySlope(r_target) + 1e-9 * kL1 * kL2)
      << "r " << r_target;
}

/// Both elbow solutions (q1, q2) of the planar arm for the point (x, y) [cm], within the elbow
/// limit.
std::vector<std::pair<double, double>> planarSolutions(double x, double y) {
  const double c = (x * x + y * y - kL1 * kL1 - kL2 * kL2) / (2.0 * kL1 * kL2);
  std::vector<std::pair<double, double>> out;
  if (std::abs(c) > 1.0) return out;
  for (const double sign : {1.0, -1.0}) {
    const double q2 = sign * std::acos(c);
    if (std::abs(q2) > kElbowLimit) continue;
    const double q1 = std::atan2(y, x) - std::atan2(kL2 * std::sin(q2), kL1 + kL2 * std::cos(q2));
    out.emplace_back(q1, q2);
  }
  return out;
}

/// A box of planar2's scene seen from above: centre and half sizes [cm]. The boxes are 40 cm tall
/// about z = 0 and the arm moves in z = 0, so distances are 2-D.
struct Rect {
  Eigen::Vector2d centre, half;
};
const Rect kPosts[] = {{{30, 38}, {5, 5}}, {{-32, 36}, {5, 5}}, {{0, -52}, {4, 4}}};

/// Distance from the segment ab to the rectangle: the point-to-rectangle distance is convex, so
/// along the segment it is a convex function of the parameter, minimised by ternary search.
double segmentRectDistance(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Rect& rect) {
  auto at = [&](double t) {
    const Eigen::Vector2d p = a + t * (b - a);
    const Eigen::Vector2d outside =
        ((p - rect.centre).cwiseAbs() - rect.half).cwiseMax(Eigen::Vector2d::Zero());
    return outside.norm();
  };
  double lo = 0.0, hi = 1.0;
  for (int k = 0; k < 200; ++k) {
    const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
    if (at(m1) < at(m2)) {
      hi = m2;
    } else {
      lo = m1;
    }
  }
  return std::min({at(0.0), at(1.0), at(0.5 * (lo + hi))});
}

/// Distance from a point to the segment ab.
double pointSegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                            const Eigen::Vector2d& b) {
  const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (a + t * (b - a) - p).norm();
}

/// planar2's clearance by hand at (q1, q2) with the robot moved by `move` (x, y) [cm]: the base
/// sphere against the forearm capsule (the one non-adjacent link pair), each link capsule against
/// each post (the base is not checked against the environment); negative when colliding.
double planarClearance(double q1, double q2,
                       const Eigen::Vector2d& move = Eigen::Vector2d::Zero()) {
  const Eigen::Vector2d base = move;
  const Eigen::Vector2d elbow = base + kL1 * Eigen::Vector2d(std::cos(q1), std::sin(q1));
  const Eigen::Vector2d tip = elbow + kL2 * Eigen::Vector2d(std::cos(q1 + q2), std::sin(q1 + q2));
  double d = pointSegmentDistance(base, elbow, tip) - kBaseRadius - kLinkRadius;
  for (const Rect& post : kPosts) {
    d = std::min(d, segmentRectDistance(base, elbow, post) - kLinkRadius);
    d = std::min(d, segmentRectDistance(elbow, tip, post) - kLinkRadius);
  }
  return d;
}

// ---- the planar arm against its closed form
// ------------------------------------------------------

// Targets in the arm's plane approached along +z (normal -z): reached iff r in [r_min, 70], with
// manipulability l1 l2 |sin q2|.
TEST(ReachStudy, PlanarAnnulusAndManipulabilityInClosedForm) {
  const Robot robot = planar2();
  const ReachStudy study(robot, nullptr, planarOptions());
  struct Case {
    double r;
    bool reached;
  };
  const Case cases[] = {{kInner + 1.0, true}, {30.0, true},          {50.0, true},
                        {69.0, true},         {kOuter + 1.0, false}, {kInner - 1.0, false},
                        {10.0, false},        {0.0, false},          {100.0, false}};
  std::vector<ReachTarget> targets;
  std::vector<bool> expected;
  for (const Case& c : cases) {
    for (const double t : {0.0, 1.0, 2.5, -2.0}) {
      targets.push_back(
          targetFromNormal({c.r * std::cos(t), c.r * std::sin(t), 0.0}, {0.0, 0.0, -1.0}));
      expected.push_back(c.reached);
    }
  }
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const TargetReach reach = study.evaluate(targets[i]);
    const Eigen::Vector3d p = targets[i].pose.translation();
    const double r = p.norm();
    ASSERT_EQ(reach.reached, expected[i]) << "r = " << r << " at " << p.transpose();
    EXPECT_EQ(reach.solved, expected[i]) << r;
    EXPECT_EQ(reach.label, kLabelFree);
    EXPECT_EQ(reach.clearance, std::numeric_limits<double>::infinity());  // no collision model
    if (!expected[i]) {
      EXPECT_EQ(reach.manipulability, 0.0) << r;
      EXPECT_EQ(reach.score(), 0.0) << r;
      continue;
    }
    ASSERT_EQ(reach.q.size(), 2);
    const Eigen::Isometry3d T = toolPose(robot, reach.q);
    EXPECT_LE((T.translation() - p).norm(), 1e-6 + 1e-9) << r;
    EXPECT_LE(reach.position_error, 1e-6) << r;
    EXPECT_LE(reach.orientation_error, 1e-6) << r;
    EXPECT_NEAR(std::cos(reach.q[1]), (r * r - kL1 * kL1 - kL2 * kL2) / (2.0 * kL1 * kL2), 1e-7)
        << r;
    EXPECT_LE(std::abs(reach.q[1]), kElbowLimit);
    {
      SCOPED_TRACE(r);
      expectPlanarManipulability(reach.manipulability, reach.q, r);
    }
    EXPECT_EQ(reach.score(), reach.manipulability);
  }

  // The vector form: the same results in the targets' order, whatever the threads; progress ends
  // with (all, all).
  ReachStudyOptions two_threads = planarOptions();
  two_threads.threads = 2;
  const ReachStudy parallel(robot, nullptr, two_threads);
  std::size_t last_done = 0, last_all = 0, calls = 0;
  const std::vector<TargetReach> all = parallel.evaluate(targets, Eigen::Isometry3d::Identity(),
                                                         [&](std::size_t done, std::size_t n) {
                                                           EXPECT_GE(done, last_done);
                                                           last_done = done;
                                                           last_all = n;
                                                           ++calls;
                                                         });
  ASSERT_EQ(all.size(), targets.size());
  EXPECT_GE(calls, 1u);
  EXPECT_EQ(last_done, targets.size());
  EXPECT_EQ(last_all, targets.size());
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const TargetReach one = study.evaluate(targets[i]);
    EXPECT_EQ(all[i].reached, one.reached) << i;
    EXPECT_EQ(all[i].q, one.q) << i;
    EXPECT_EQ(all[i].manipulability, one.manipulability) << i;
  }
  EXPECT_TRUE(study.evaluate(std::vector<ReachTarget>{}).empty());
}

// T_move moves the whole robot: target p is reached iff the robot in place reaches T_move^-1 p.
TEST(ReachStudy, MovedRobotReachesTheAnnulusAboutItsNewBase) {
  const Robot robot = planar2();
  ReachStudyOptions options = planarOptions();
  options.starts = 2;
  const ReachStudy study(robot, nullptr, options);
  const Eigen::Vector3d points[] = {{50, 0, 0}, {10, 40, 0}, {-30, -20, 0}};
  int reached = 0, missed = 0;
  for (const Eigen::Vector3d& p : points) {
    for (double dx = -90.0; dx <= 90.0; dx += 15.0) {
      const double r = (p - Eigen::Vector3d(dx, 0, 0)).norm();
      if (std::abs(r - kOuter) < 0.5 || std::abs(r - kInner) < 0.5) continue;  // on an edge
      const bool expected = r >= kInner && r <= kOuter;
      const TargetReach reach =
          study.evaluate(targetFromNormal(p, {0, 0, -1}), translation(dx, 0, 0));
      ASSERT_EQ(reach.reached, expected) << p.transpose() << " moved by " << dx << ": r " << r;
      if (!expected) {
        ++missed;
        continue;
      }
      ++reached;
      // The robot in place puts its tool at p - d.
      EXPECT_LE((toolPose(robot, reach.q).translation() + Eigen::Vector3d(dx, 0, 0) - p).norm(),
                1e-6 + 1e-9);
      expectPlanarManipulability(reach.manipulability, reach.q, r);
    }
  }
  EXPECT_GT(reached, 5);
  EXPECT_GT(missed, 5);

  // A rotating move turns the approach too: planar2 turned by 90 deg about x works in the world
  // x-z plane with its tool z along Rx(90) z = -y.
  Eigen::Isometry3d tilt = translation(5, 0, 0);
  tilt.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Vector3d p(45, 0, 30);  // robot frame (40, 30, 0), r = 50
  const TargetReach along = study.evaluate(targetFromNormal(p, {0, 1, 0}), tilt);
  ASSERT_TRUE(along.reached);
  EXPECT_LE((tilt * toolPose(robot, along.q).translation() - p).norm(), 1e-6 + 1e-9);
  expectPlanarManipulability(along.manipulability, along.q, 50.0);
  EXPECT_FALSE(study.evaluate(targetFromNormal(p, {0, 0, -1}), tilt).reached);
  EXPECT_FALSE(study.evaluate(targetFromNormal(p, {0, 1, 0})).reached);  // in place: off-plane
}

// An approach the arm cannot take (-x; its tool z is always +z, 90 deg away): refused when
// exact, accepted by the point-only stage when the tolerance exceeds 90 deg.
TEST(ReachStudy, ApproachToleranceAcceptsThePointAloneWithinIt) {
  const Robot robot = planar2();
  const ReachTarget target = targetFromNormal({40, 30, 0}, {1, 0, 0});
  const auto evaluate = [&](double tolerance_deg) {
    ReachStudyOptions options = planarOptions();
    options.starts = 2;
    options.ik.restarts = 3;
    options.approach_tolerance = tolerance_deg * kDeg;
    return ReachStudy(robot, nullptr, options).evaluate(target);
  };
  const TargetReach exact = evaluate(0.0);
  EXPECT_FALSE(exact.reached);
  EXPECT_FALSE(exact.solved);
  EXPECT_EQ(exact.score(), 0.0);
  const TargetReach short_of = evaluate(80.0);
  EXPECT_FALSE(short_of.reached);
  EXPECT_FALSE(short_of.solved);
  for (const double tolerance : {100.0, 90.0 + 1e-4}) {
    const TargetReach loose = evaluate(tolerance);
    ASSERT_TRUE(loose.reached) << tolerance;
    EXPECT_TRUE(loose.solved);
    EXPECT_NEAR(loose.orientation_error, M_PI / 2, 1e-9) << tolerance;
    EXPECT_LE(loose.position_error, 1e-6);
    EXPECT_LE((toolPose(robot, loose.q).translation() - target.pose.translation()).norm(),
              1e-6 + 1e-9);
    expectPlanarManipulability(loose.manipulability, loose.q, 50.0);
  }
}

// ---- collisions and clearance
// --------------------------------------------------------------------

class ReachStudyCollision : public ::testing::Test {
 protected:
  ReachStudyCollision()
      : robot_(planar2()),
        checker_(robot_, loadCollisionModel(robot_, test::robotPath("planar2"))) {}
  ReachStudy study() const {
    ReachStudyOptions options = planarOptions();
    options.starts = 8;
    return ReachStudy(robot_, &checker_, options);
  }
  Robot robot_;
  CollisionChecker checker_;
};

// Targets with one elbow solution free and the other in a post: the free one is chosen; its
// clearance matches the hand-made 2-D distance and the minimum of report()'s.
TEST_F(ReachStudyCollision, ChoosesTheFreeElbowAndMeasuresItsClearance) {
  // My model of the pairs: base-forearm, and both links against three posts.
  ASSERT_EQ(checker_.pairs().size(), 7u);
  const ReachStudy s = study();
  const Eigen::Vector2d targets[] = {{50, 20}, {15, 50}, {-15, 50}, {45, 25}};
  for (const Eigen::Vector2d& p : targets) {
    const auto solutions = planarSolutions(p.x(), p.y());
    ASSERT_EQ(solutions.size(), 2u);
    const double c0 = planarClearance(solutions[0].first, solutions[0].second);
    const double c1 = planarClearance(solutions[1].first, solutions[1].second);
    ASSERT_TRUE((c0 > 0.5 && c1 < -0.5) || (c1 > 0.5 && c0 < -0.5)) << p.transpose();  // design
    const auto& free = c0 > 0.0 ? solutions[0] : solutions[1];
    const double free_clearance = std::max(c0, c1);

    const TargetReach reach = s.evaluate(targetFromNormal({p.x(), p.y(), 0.0}, {0, 0, -1}));
    ASSERT_TRUE(reach.reached) << p.transpose();
    EXPECT_EQ(reach.label, kLabelFree);
    EXPECT_EQ(checker_.label(reach.q), kLabelFree);
    EXPECT_NEAR(angleDifference(reach.q[0], free.first), 0.0, 1e-6) << p.transpose();
    EXPECT_NEAR(reach.q[1], free.second, 1e-6) << p.transpose();

    double report_min = std::numeric_limits<double>::infinity();
    for (const PairReport& pair : checker_.report(reach.q)) {
      EXPECT_FALSE(pair.colliding) << pair.body_a << "-" << pair.body_b;
      report_min = std::min(report_min, pair.distance);
    }
    // clearance() takes FCL's box distances 1e-6 short (collision_checker.h); report() does not.
    EXPECT_LE(reach.clearance, report_min + 1e-9) << p.transpose();
    EXPECT_GE(reach.clearance, report_min - 1e-6 - 1e-9) << p.transpose();
    // The exact distance: FCL's capsule-box GJK (libccd) is off by up to 6.5e-4 cm here (at
    // (-15, 50): 10.005884 against the exact 10.005231, an elbow 12.505 cm from post_a's face),
    // over the true distance although the checker documents a lower bound.
    EXPECT_NEAR(reach.clearance, free_clearance, 1e-3) << p.transpose();
    EXPECT_NEAR(report_min, free_clearance, 1e-3) << p.transpose();
  }
}

// The tool point inside a post: kinematically solved, not reached, labelled environment.
TEST_F(ReachStudyCollision, TargetInsideAPostIsSolvedButNotReached) {
  const ReachStudy s = study();
  for (const Eigen::Vector2d& p :
       {Eigen::Vector2d(30, 38), Eigen::Vector2d(-32, 36), Eigen::Vector2d(0, -52)}) {
    for (const auto& [q1, q2] : planarSolutions(p.x(), p.y())) {
      ASSERT_LT(planarClearance(q1, q2), 0.0);  // design: both elbows collide
    }
    const TargetReach reach = s.evaluate(targetFromNormal({p.x(), p.y(), 0.0}, {0, 0, -1}));
    EXPECT_TRUE(reach.solved) << p.transpose();
    EXPECT_FALSE(reach.reached) << p.transpose();
    EXPECT_EQ(reach.label, kLabelEnvironment) << p.transpose();
    EXPECT_EQ(reach.clearance, 0.0);
    EXPECT_EQ(reach.score(), 0.0);
    expectPlanarManipulability(reach.manipulability, reach.q, p.norm());
    EXPECT_LE((toolPose(robot_, reach.q).translation() - Eigen::Vector3d(p.x(), p.y(), 0)).norm(),
              1e-6 + 1e-9);
  }
}

// The moved robot is checked at its new base against the scene that stays: the clearance is the
// hand-made distance to the posts seen from the moved base.
TEST_F(ReachStudyCollision, MovedRobotIsCheckedAgainstTheFixedScene) {
  const ReachStudy s = study();
  // Robot moved by (10, 10): world (50, 20) is (40, 10) for it; elbow +109.5 deg free, -109.5 in
  // post_a.
  {
    const Eigen::Vector2d move(10, 10), p(50, 20);
    const auto solutions = planarSolutions(p.x() - move.x(), p.y() - move.y());
    ASSERT_EQ(solutions.size(), 2u);
    const double c0 = planarClearance(solutions[0].first, solutions[0].second, move);
    const double c1 = planarClearance(solutions[1].first, solutions[1].second, move);
    ASSERT_TRUE(c0 > 0.5 && c1 < -0.5) << c0 << " " << c1;
    const TargetReach reach =
        s.evaluate(targetFromNormal({p.x(), p.y(), 0}, {0, 0, -1}), translation(10, 10, 0));
    ASSERT_TRUE(reach.reached);
    EXPECT_NEAR(angleDifference(reach.q[0], solutions[0].first), 0.0, 1e-6);
    EXPECT_NEAR(reach.q[1], solutions[0].second, 1e-6);
    EXPECT_NEAR(reach.clearance, c0, 1e-3);  // FCL's capsule-box accuracy, as above
  }
  // Robot moved by (-20, 18): world post_a's centre (30, 38) is (50, 20) for it, which the robot
  // in place reaches; moved, its tool is inside the post.
  {
    const ReachTarget target = targetFromNormal({30, 38, 0}, {0, 0, -1});
    const TargetReach moved = s.evaluate(target, translation(-20, 18, 0));
    EXPECT_TRUE(moved.solved);
    EXPECT_FALSE(moved.reached);
    EXPECT_EQ(moved.label, kLabelEnvironment);
    const TargetReach in_place = s.evaluate(targetFromNormal({50, 20, 0}, {0, 0, -1}));
    EXPECT_TRUE(in_place.reached);
  }
  // A cap: clearances at or above it are the cap.
  ReachStudyOptions options = planarOptions();
  options.starts = 8;
  options.clearance_cap = 5.0;
  const ReachStudy capped(robot_, &checker_, options);
  const TargetReach far = capped.evaluate(targetFromNormal({50, 20, 0}, {0, 0, -1}));
  ASSERT_TRUE(far.reached);
  EXPECT_EQ(far.clearance, 5.0);
}

// ---- the maintenance arm's geometry by hand
// ------------------------------------------------------

// robots/maintenance4.yaml: base at z = -20, axis 1 down; the column (15 + q2) puts axis 3 at
// z = -35 - q2, 25 cm from axis 1; the forearm and tool are
// horizontal, tool point s = 20 + q4 (q4 in [0, 40]) beyond axis 3 along the tool z. A target
// approached along -y at (dx, -30.5, -51): axis 3 at c = p + s (0, 1, 0) with
// dx^2 + (s - 30.5)^2 = 25^2; s = 30.5 + sqrt(625 - dx^2) always fits, s = 30.5 - sqrt(...)
// needs |dx| >= 22.69; the elbow angle between the link (c / 25) and the forearm (0, -1) is at
// most 150 deg: c_y <= 25 cos 30 deg, so |dx| >= 12.5 on the first branch. Reached iff
// 12.5 <= |dx| <= 25.
TEST(ReachStudy, MaintenanceArmCylindricalGeometryByHand) {
  const Robot robot = loadRobot(test::robotPath("maintenance4"));
  ASSERT_EQ(robot.dof(), 4);
  ReachStudyOptions options;
  options.starts = 3;
  const ReachStudy study(robot, nullptr, options);
  const double y = -30.5, z = -51.0;
  for (const double dx : {18.0, 22.0, -20.0, 14.0}) {
    const TargetReach reach = study.evaluate(targetFromNormal({dx, y, z}, {0, 1, 0}));
    ASSERT_TRUE(reach.reached) << dx;
    const double s = 30.5 + std::sqrt(625.0 - dx * dx);
    const Eigen::Vector2d c(dx, y + s);  // axis 3 in the world xy plane
    EXPECT_NEAR(c.norm(), 25.0, 1e-12);
    const double elbow = std::acos(c.dot(Eigen::Vector2d(0, -1)) / 25.0);
    EXPECT_NEAR(reach.q[1], -z - 35.0, 1e-5) << dx;  // column: z = -35 - q2
    EXPECT_NEAR(reach.q[3], s - 20.0, 1e-5) << dx;
    EXPECT_NEAR(std::abs(reach.q[2]), elbow, 1e-5) << dx;
    const Eigen::Isometry3d T = toolPose(robot, reach.q);
    EXPECT_LE((T.translation() - Eigen::Vector3d(dx, y, z)).norm(), 1e-6 + 1e-9) << dx;
    EXPECT_LT(angleBetween(T.linear().col(2), Eigen::Vector3d(0, -1, 0)), 1e-6) << dx;
  }
  for (const double dx : {0.0, 5.0, 10.0, -10.0, 26.0, 30.0}) {
    const TargetReach reach = study.evaluate(targetFromNormal({dx, y, z}, {0, 1, 0}));
    EXPECT_FALSE(reach.reached) << dx;
    EXPECT_FALSE(reach.solved) << dx;
  }
  // Out of the column's travel (axis 3 between z = -65 and -35): below and above it.
  EXPECT_FALSE(study.evaluate(targetFromNormal({18, y, -70}, {0, 1, 0})).reached);
  EXPECT_FALSE(study.evaluate(targetFromNormal({18, y, -30}, {0, 1, 0})).reached);
  // A vertical approach: the tool is always horizontal.
  EXPECT_FALSE(study.evaluate(targetFromNormal({18, y, z}, {0, 0, 1})).reached);
}

// ---- summaries and heat-map points
// ----------------------------------------------------------------

TEST(ReachStudySummary, HandMadeResults) {
  std::vector<TargetReach> results(5);
  results[0].reached = results[0].solved = true;
  results[0].manipulability = 2.0;
  results[0].clearance = 3.0;
  results[1].reached = results[1].solved = true;
  results[1].manipulability = 4.0;
  results[1].clearance = 1.5;
  results[2].solved = true;  // in a collision
  results[2].label = kLabelEnvironment;
  results[2].manipulability = 50.0;
  results[2].clearance = 0.0;
  results[3].manipulability = 7.0;  // not solved (a value that must not count)
  results[4].reached = results[4].solved = true;
  results[4].manipulability = 9.0;
  results[4].clearance = 8.0;
  const ReachSummary s = summarize(results);
  EXPECT_EQ(s.targets, 5u);
  EXPECT_EQ(s.reached, 3u);
  EXPECT_EQ(s.solved, 4u);
  EXPECT_DOUBLE_EQ(s.share_reached, 3.0 / 5.0);
  EXPECT_DOUBLE_EQ(s.mean_score, (2.0 + 4.0 + 9.0) / 5.0);
  EXPECT_DOUBLE_EQ(s.mean_manipulability_reached, (2.0 + 4.0 + 9.0) / 3.0);
  EXPECT_EQ(s.min_clearance_reached, 1.5);

  const ReachSummary none = summarize({});
  EXPECT_EQ(none.targets, 0u);
  EXPECT_EQ(none.share_reached, 0.0);
  EXPECT_EQ(none.mean_score, 0.0);
  EXPECT_EQ(none.mean_manipulability_reached, 0.0);
  EXPECT_EQ(none.min_clearance_reached, std::numeric_limits<double>::infinity());
  const ReachSummary missed = summarize({results[2], results[3]});
  EXPECT_EQ(missed.reached, 0u);
  EXPECT_EQ(missed.solved, 1u);
  EXPECT_EQ(missed.share_reached, 0.0);
  EXPECT_EQ(missed.mean_score, 0.0);
  EXPECT_EQ(missed.mean_manipulability_reached, 0.0);
  EXPECT_EQ(missed.min_clearance_reached, std::numeric_limits<double>::infinity());
}

TEST(ReachStudySummary, TargetPointCarriesTheResult) {
  const ReachTarget target = targetFromNormal({1, 2, 3}, {0, 0.6, 0.8});
  TargetReach reach;
  reach.reached = reach.solved = true;
  reach.q = Eigen::Vector3d(0.5, -1.25, 2.0);
  reach.manipulability = 12.5;
  reach.clearance = 4.25;
  reach.orientation_error = 0.125;
  ReachTargetPoint point = reachTargetPoint(target, reach);
  EXPECT_EQ(point.x, 1.f);
  EXPECT_EQ(point.y, 2.f);
  EXPECT_EQ(point.z, 3.f);
  EXPECT_NEAR(point.normal_x, 0.0, 1e-7);
  EXPECT_NEAR(point.normal_y, 0.6, 1e-7);
  EXPECT_NEAR(point.normal_z, 0.8, 1e-7);
  EXPECT_EQ(point.q1, 0.5f);
  EXPECT_EQ(point.q2, -1.25f);
  EXPECT_EQ(point.q3, 2.0f);
  for (int j = 3; j < kMaxJoints; ++j) EXPECT_EQ(point.q[j], 0.f) << j;
  EXPECT_EQ(point.label, kLabelFree);
  EXPECT_EQ(point.reached, 1.f);
  EXPECT_EQ(point.score, 12.5f);
  EXPECT_EQ(point.manipulability, 12.5f);
  EXPECT_EQ(point.clearance, 4.25f);
  EXPECT_EQ(point.orientation_error, 0.125f);

  // In a collision: score 0, clearance 0; without a collision model: clearance -1.
  reach.reached = false;
  reach.label = kLabelEnvironment;
  reach.clearance = 0.0;
  point = reachTargetPoint(target, reach);
  EXPECT_EQ(point.reached, 0.f);
  EXPECT_EQ(point.score, 0.f);
  EXPECT_EQ(point.manipulability, 12.5f);
  EXPECT_EQ(point.label, kLabelEnvironment);
  EXPECT_EQ(point.clearance, 0.f);
  reach.reached = true;
  reach.label = kLabelFree;
  reach.clearance = std::numeric_limits<double>::infinity();
  EXPECT_EQ(reachTargetPoint(target, reach).clearance, -1.f);
  // Not solved: no joint values, no clearance.
  TargetReach missed;
  missed.q = Eigen::Vector3d(0.5, 0.5, 0.5);
  missed.orientation_error = 0.5;
  point = reachTargetPoint(target, missed);
  for (int j = 0; j < kMaxJoints; ++j) EXPECT_EQ(point.q[j], 0.f) << j;
  EXPECT_EQ(point.clearance, -1.f);
  EXPECT_EQ(point.reached, 0.f);
  EXPECT_EQ(point.orientation_error, 0.5f);
}
}  // namespace
}  // namespace mcws
