// CollisionChecker against closed forms (segment distances, primitive pairs at known distance),
// hand-computed TA1400 configurations (see the comments for the arithmetic), the pair rules and
// determinism of labelled sampling.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <random>

#include "mcws/collision/collision_checker.h"
#include "mcws/collision/collision_sampler.h"
#include "mcws/collision/segment_distance.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/robot_yaml.h"
#include "test_support.h"

namespace mcws {
namespace {

constexpr double kDeg = M_PI / 180.0;
/// Exact arithmetic on short chains: agreement to rounding.
constexpr double kExact = 1e-9;
/// FCL's GJK/EPA (cylinder pairs) stops at a tolerance of about 1e-6 of the sizes here.
constexpr double kGjk = 1e-4;

/// Distance between segments by dense sampling of both (independent of Ericson's algorithm):
/// accurate to about the step times the segments' lengths.
double sampledSegmentDistance(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1,
                              const Eigen::Vector3d& p2, const Eigen::Vector3d& q2) {
  constexpr int kSteps = 400;
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= kSteps; ++i) {
    const Eigen::Vector3d a = p1 + (q1 - p1) * (double(i) / kSteps);
    // The distance from a point to a segment, in closed form.
    const Eigen::Vector3d d = q2 - p2;
    const double t =
        d.squaredNorm() > 0 ? std::clamp((a - p2).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    best = std::min(best, (a - (p2 + t * d)).norm());
  }
  return best;
}

TEST(SegmentDistance, ClosedFormCases) {
  using V = Eigen::Vector3d;
  // Skew perpendicular segments crossing over each other 2 apart.
  EXPECT_NEAR(segmentDistanceSquared(V(-1, 0, 0), V(1, 0, 0), V(0, -1, 2), V(0, 1, 2)), 4.0,
              kExact);
  // Parallel, overlapping in x, 3 apart.
  EXPECT_NEAR(segmentDistanceSquared(V(0, 0, 0), V(2, 0, 0), V(1, 3, 0), V(5, 3, 0)), 9.0, kExact);
  // Collinear with a gap of 1 between the ends.
  EXPECT_NEAR(segmentDistanceSquared(V(0, 0, 0), V(1, 0, 0), V(2, 0, 0), V(3, 0, 0)), 1.0, kExact);
  // A point against a segment: its end region (distance to the end (1, 0, 0) is sqrt(2)).
  EXPECT_NEAR(segmentDistanceSquared(V(2, 1, 0), V(2, 1, 0), V(0, 0, 0), V(1, 0, 0)), 2.0, kExact);
  // Two points.
  EXPECT_NEAR(segmentDistanceSquared(V(0, 0, 0), V(0, 0, 0), V(3, 4, 0), V(3, 4, 0)), 25.0, kExact);
  // Intersecting segments.
  EXPECT_NEAR(segmentDistanceSquared(V(-1, -1, 0), V(1, 1, 0), V(-1, 1, 0), V(1, -1, 0)), 0.0,
              kExact);
}

TEST(SegmentDistance, AgreesWithDenseSamplingOnRandomSegments) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto v = [&] { return Eigen::Vector3d(u(rng), u(rng), u(rng)); };
  for (int k = 0; k < 2000; ++k) {
    const Eigen::Vector3d p1 = v(), q1 = v(), p2 = v(), q2 = v();
    const double exact = std::sqrt(segmentDistanceSquared(p1, q1, p2, q2));
    const double sampled = sampledSegmentDistance(p1, q1, p2, q2);
    // Sampling only overestimates, by at most half a step along segment 1 (length <= 2*sqrt(3)).
    EXPECT_LE(exact, sampled + kExact);
    EXPECT_GE(exact, sampled - 3.5 / 400);
  }
}

/// Base fixed; joint 1 slides along x (no shape); link 2 rides on it. The base and link 2 are
/// not adjacent, so the pair base-hold is checked, its distance set by q[0].
class SlidingPair : public ::testing::Test {
 protected:
  SlidingPair() {
    Joint slide;
    slide.name = "slide";
    slide.type = JointType::kPrismatic;
    slide.axis = Eigen::Vector3d::UnitX();
    slide.lower = -10;
    slide.upper = 10;
    Joint hold;
    hold.name = "hold";
    hold.lower = -1;
    hold.upper = 1;
    robot_.name = "slider";
    robot_.joints = {slide, hold};
    model_.links.resize(3);
    model_.links[0].name = "base";
    model_.links[1].name = "slide";
    model_.links[2].name = "hold";
    model_.tool.name = "tool";
  }
  static ShapeSpec capsule(Eigen::Vector3d from, Eigen::Vector3d to, double radius) {
    ShapeSpec s;
    s.type = ShapeType::kCapsule;
    s.p_from = from;
    s.p_to = to;
    s.radius = radius;
    return s;
  }
  static ShapeSpec placed(ShapeType type, double radius, Eigen::Vector3d size, double length,
                          double yaw = 0.0) {
    ShapeSpec s;
    s.type = type;
    s.radius = radius;
    s.size = size;
    s.length = length;
    s.T_body_shape.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return s;
  }
  /// Label at slide position x.
  std::uint32_t labelAt(double x) const {
    const CollisionChecker checker(robot_, model_);
    return checker.label(Eigen::Vector2d(x, 0.0));
  }

  Robot robot_;
  CollisionModel model_;
};

TEST_F(SlidingPair, TwoCapsulesCollideExactlyWithinTheSumOfTheirRadii) {
  // Vertical capsule at the origin, radius 0.3; a horizontal one along y at height 0.5, radius
  // 0.2, x away: the segments are x apart, so the capsules meet at x = 0.5.
  model_.links[0].shapes = {capsule({0, 0, -1}, {0, 0, 1}, 0.3)};
  model_.links[2].shapes = {capsule({0, -1, 0.5}, {0, 1, 0.5}, 0.2)};
  EXPECT_EQ(labelAt(0.5 - 1e-9), kLabelLinkLink);
  EXPECT_EQ(labelAt(0.5 + 1e-9), kLabelFree);
  EXPECT_EQ(labelAt(-0.5 + 1e-9), kLabelLinkLink);
  const CollisionChecker checker(robot_, model_);
  const auto report = checker.report(Eigen::Vector2d(2.0, 0.0));
  ASSERT_EQ(report.size(), 1u);
  EXPECT_EQ(report[0].body_a, "base");
  EXPECT_EQ(report[0].body_b, "hold");
  EXPECT_NEAR(report[0].distance, 1.5, kExact);
  EXPECT_NEAR(checker.report(Eigen::Vector2d(0.1, 0.0))[0].distance, -0.4, kExact);  // depth
}

TEST_F(SlidingPair, SphereAgainstBoxThroughFcl) {
  // Unit cube at the origin, sphere of radius 0.25: they meet at x = 0.5 + 0.25.
  model_.links[0].shapes = {placed(ShapeType::kBox, 0, {1, 1, 1}, 0)};
  ShapeSpec sphere = capsule({0, 0, 0}, {0, 0, 0}, 0.25);
  sphere.type = ShapeType::kSphere;
  model_.links[2].shapes = {sphere};
  EXPECT_EQ(labelAt(0.75 - 1e-6), kLabelLinkLink);
  EXPECT_EQ(labelAt(0.75 + 1e-6), kLabelFree);
  const CollisionChecker checker(robot_, model_);
  EXPECT_NEAR(checker.report(Eigen::Vector2d(2.0, 0.0))[0].distance, 1.25, kGjk);
}

TEST_F(SlidingPair, BoxAgainstABoxTurnedByFortyFiveDegrees) {
  // The turned cube reaches sqrt(2)/2 towards the other, whose face is at 0.5.
  model_.links[0].shapes = {placed(ShapeType::kBox, 0, {1, 1, 1}, 0)};
  model_.links[2].shapes = {placed(ShapeType::kBox, 0, {1, 1, 1}, 0, 45 * kDeg)};
  const double touch = 0.5 + std::sqrt(0.5);
  EXPECT_EQ(labelAt(touch - 1e-6), kLabelLinkLink);
  EXPECT_EQ(labelAt(touch + 1e-6), kLabelFree);
}

TEST_F(SlidingPair, CylinderAgainstCapsule) {
  // Cylinder radius 0.5 along z, capsule radius 0.2 parallel to it: they meet at x = 0.7.
  model_.links[0].shapes = {placed(ShapeType::kCylinder, 0.5, {0, 0, 0}, 2.0)};
  model_.links[2].shapes = {capsule({0, 0, -0.5}, {0, 0, 0.5}, 0.2)};
  EXPECT_EQ(labelAt(0.7 - kGjk), kLabelLinkLink);
  EXPECT_EQ(labelAt(0.7 + kGjk), kLabelFree);
}

TEST_F(SlidingPair, AdjacentLinksAndAllowedPairsAreNotChecked) {
  model_.links[0].shapes = {capsule({0, 0, -1}, {0, 0, 1}, 0.3)};
  model_.links[1].shapes = {capsule({0, 0, -1}, {0, 0, 1}, 0.3)};  // always inside the base
  model_.links[2].shapes = {capsule({0, 0, -1}, {0, 0, 1}, 0.3)};  // always inside slide
  EXPECT_EQ(labelAt(5.0), kLabelFree);
  EXPECT_EQ(labelAt(0.0), kLabelLinkLink);  // base - hold
  model_.allowed = {{"hold", "base"}};
  EXPECT_EQ(labelAt(0.0), kLabelFree);
}

TEST_F(SlidingPair, ToolAndEnvironmentLabelsAndTheLowestCodeRule) {
  // The tool rides on the last link (hold); a wall stands at x = 3.
  model_.links[0].shapes = {capsule({0, 0, -1}, {0, 0, 1}, 0.3)};
  model_.tool.shapes = {capsule({0, 0, 0}, {0, 0, 0}, 0.5)};
  BodySpec wall;
  wall.name = "wall";
  wall.shapes = {placed(ShapeType::kBox, 0, {0.2, 4, 4}, 0)};
  wall.shapes[0].T_body_shape.translation() = Eigen::Vector3d(3, 0, 0);
  model_.environment = {wall};
  EXPECT_EQ(labelAt(0.8 - 1e-9), kLabelToolLink);  // tool (0.5) against the base (0.3)
  EXPECT_EQ(labelAt(0.8 + 1e-9), kLabelFree);
  EXPECT_EQ(labelAt(2.4 + 1e-6), kLabelEnvironment);  // tool reaches the wall's face at 2.9
  EXPECT_EQ(labelAt(2.4 - 1e-6), kLabelFree);
  model_.links[2].shapes = {capsule({0, 0, 0}, {0, 0, 0}, 0.1)};
  EXPECT_EQ(labelAt(0.3), kLabelLinkLink);  // hold and tool both hit the base: lowest code
}

class Ta1400 : public ::testing::Test {
 protected:
  Ta1400()
      : robot_(loadRobot(test::robotPath("ta1400"))),
        checker_(robot_, loadCollisionModel(robot_, test::robotPath("ta1400"))) {}
  static Eigen::VectorXd degrees(std::initializer_list<double> values) {
    Eigen::VectorXd q(values.size());
    int i = 0;
    for (double v : values) q[i++] = v * kDeg;
    return q;
  }
  PairReport pair(const Eigen::VectorXd& q, const std::string& a, const std::string& b) const {
    for (const PairReport& r : checker_.report(q))
      if (r.body_a == a && r.body_b == b) return r;
    ADD_FAILURE() << "no pair " << a << " - " << b;
    return {};
  }
  Robot robot_;
  CollisionChecker checker_;
};

TEST_F(Ta1400, PairsAreTheNonAdjacentLinksAndTheToolAgainstAllButTheLastLink) {
  std::vector<std::string> names;
  for (const CollisionPair& p : checker_.pairs())
    names.push_back(checker_.bodyName(p.body_a) + "-" + checker_.bodyName(p.body_b));
  // The tool is mounted on j6, the last link.
  EXPECT_THAT(names, ::testing::ElementsAre("base-j2", "base-j3", "base-j4", "base-j5", "base-j6",
                                            "j1-j3", "j1-j4", "j1-j5", "j1-j6", "j2-j4", "j2-j5",
                                            "j2-j6", "j3-j5", "j3-j6", "j4-j6", "base-tool",
                                            "j1-tool", "j2-tool", "j3-tool", "j4-tool", "j5-tool"));
}

TEST_F(Ta1400, ZeroPoseIsFreeWithTheTorchTwentyFiveMillimetresFromTheWrist) {
  // q = 0: upper arm along x, forearm hanging down from the elbow at (840, 0, 0), torch along the
  // forearm. Nearest pair: the torch body starts 120 mm out along the flange axis, the wrist
  // housing (radius 65) lies on the perpendicular j5 axis through the wrist centre:
  // 120 - 30 - 65 = 25 mm.
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(6);
  EXPECT_EQ(checker_.label(q), kLabelFree);
  EXPECT_NEAR(pair(q, "j5", "tool").distance, 25.0, kExact);
}

TEST_F(Ta1400, ElbowFoldedIntoTheBaseCollides) {
  // q2 = 50, q3 = 60 deg: the upper arm points 50 deg down, the forearm back towards the robot.
  // By hand: O3 = (465.5, 0, -551.1), forearm direction (-0.9397, 0, 0.3420), so the flange
  // (wrist centre) is at (-98.3, 0, -345.9) (mcws_fk --frame flange agrees). Link j4's segment,
  // 330..560 mm along the forearm, crosses the base axis x = 0 at z = -381.6, inside the base
  // segment z in [-420, -330]: distance 0, penetration 180 + 70 = 250 mm.
  const Eigen::VectorXd q = degrees({0, 50, 60, 0, 0, 0});
  EXPECT_TRUE(
      flangePose(robot_, q).translation().isApprox(Eigen::Vector3d(-98.317, 0, -345.933), 1e-5));
  EXPECT_EQ(checker_.label(q), kLabelLinkLink);
  const PairReport base_j4 = pair(q, "base", "j4");
  EXPECT_TRUE(base_j4.colliding);
  EXPECT_NEAR(base_j4.distance, -250.0, kExact);
}

TEST_F(Ta1400, TorchDrivenIntoTheBaseCollidesAsToolLink) {
  // q2 = 50, q3 = 20 deg: the forearm points back and down, (-0.940, 0, -0.342); the wrist
  // centre is at (-9.39, 0, -756.36) (mcws_fk --frame flange). q5 = 90 deg turns the torch up
  // and back, (-0.342, 0, 0.940): its body ends 230 mm out at (-88.05, 0, -540.23), 149.02 mm
  // from the base segment's lower end (0, 0, -420): penetration 180 + 30 - 149.02 = 60.98 mm.
  // Nothing else touches (the flange housing is 12.7 mm from the base).
  const Eigen::VectorXd q = degrees({0, 50, 20, 0, 90, 0});
  EXPECT_TRUE(
      flangePose(robot_, q).translation().isApprox(Eigen::Vector3d(-9.392, 0, -756.357), 1e-5));
  EXPECT_EQ(checker_.label(q), kLabelToolLink);
  const Eigen::Vector3d end = flangePose(robot_, q).translation() +
                              230 * Eigen::Vector3d(-std::sin(20 * kDeg), 0, std::cos(20 * kDeg));
  const double gap = (end - Eigen::Vector3d(0, 0, -420)).norm();
  EXPECT_NEAR(gap, 149.02, 0.01);
  EXPECT_NEAR(pair(q, "base", "tool").distance, gap - 180 - 30, 1e-6);
  EXPECT_FALSE(pair(q, "base", "j6").colliding);
}

TEST_F(Ta1400, WristBentBackHitsTheForearmWithFlangeAndTorch) {
  // q5 = 150 deg at q = 0 otherwise: the flange axis points back at 30 deg to the forearm.
  // The flange housing (radius 45, 85..110 mm out) passes 100 sin 30 = 50 mm from the end of
  // link j4 (radius 70, 100 mm back from the wrist): penetration 45 + 70 - 50 = 65 mm, a
  // link-link collision. The torch body (radius 30) starts 120 mm out, 120 sin 30 = 60 mm off the
  // forearm axis, beside j4: penetration 30 + 70 - 60 = 40 mm; the lowest code is link-link.
  const Eigen::VectorXd q = degrees({0, 0, 0, 0, 150 - 1e-7, 0});
  EXPECT_EQ(checker_.label(q), kLabelLinkLink);
  EXPECT_NEAR(pair(q, "j4", "j6").distance, -65.0, 1e-4);
  EXPECT_NEAR(pair(q, "j4", "tool").distance, -40.0, 1e-4);
  EXPECT_FALSE(pair(q, "j3", "tool").colliding);
}

TEST_F(Ta1400, TorchDrivenIntoLinkThreeCollides) {
  // As above with q6 = 180 deg: the neck now bends towards the forearm. In the plane of the
  // forearm (back distance from the wrist, offset from the axis) the flange z axis is
  // (cos 30, sin 30) and its x axis (sin 30, -cos 30); the neck's end (82.5, 0, 317) lies at
  // (315.8, 87.05): beside link j3's rear forearm (back distance 280..600, radius 85), so the
  // distance is 87.05 - 85 - 14 = -11.95 mm. The flange hits j4 as above: label link-link.
  const Eigen::VectorXd q = degrees({0, 0, 0, 0, 150 - 1e-7, 180});
  EXPECT_EQ(checker_.label(q), kLabelLinkLink);
  const PairReport j3 = pair(q, "j3", "tool");
  EXPECT_TRUE(j3.colliding);
  const double offset = 317 * std::sin(30 * kDeg) - 82.5 * std::cos(30 * kDeg);
  EXPECT_NEAR(j3.distance, offset - 85 - 14, 1e-4);
}

TEST_F(Ta1400, FoldedElbowHitsLinksAndTorchAndGivesTheLowestCode) {
  // q3 = 90 deg folds the forearm back parallel to the upper arm, 130 mm beside it: j2 (90) and
  // j4 (70) overlap by 30 mm, and the torch hits the turret too.
  const Eigen::VectorXd q = degrees({0, 0, 90 - 1e-7, 0, 0, 0});
  EXPECT_NEAR(pair(q, "j2", "j4").distance, -30.0, 1e-4);
  EXPECT_TRUE(pair(q, "j1", "tool").colliding);
  EXPECT_EQ(checker_.label(q), kLabelLinkLink);
}

TEST_F(Ta1400, LabelAgreesWithTheReportOnRandomConfigurations) {
  RobotSamplerOptions options;
  options.seed = 3;
  const RobotSampler sampler(robot_, options);
  CollisionChecker::Scratch scratch;
  int collisions = 0;
  for (int i = 0; i < 2000; ++i) {
    Eigen::VectorXd q(6);
    sampler.jointValues(i, q.data());
    std::uint32_t lowest = kLabelFree;
    for (const PairReport& r : checker_.report(q)) {
      if (r.colliding && (lowest == kLabelFree || r.label < lowest)) lowest = r.label;
      // Capsule pairs only: the distance's sign is the decision.
      EXPECT_EQ(r.colliding, r.distance < 0.0);
    }
    EXPECT_EQ(checker_.label(q.data(), scratch), lowest) << i;
    collisions += lowest != kLabelFree;
  }
  EXPECT_GT(collisions, 200);  // the test sees both outcomes
  EXPECT_LT(collisions, 1800);
}

TEST_F(Ta1400, LabelledCloudIsTheSameForOneAndTwoThreads) {
  RobotSamplerOptions options;
  options.seed = 11;
  const LabelledRobotSampler sampler(robot_, options, checker_);
  const auto one = sampleCloud(sampler, 50000, 1);
  const auto two = sampleCloud(sampler, 50000, 2);
  std::size_t labelled = 0;
  for (std::size_t i = 0; i < one.size(); ++i) {
    ASSERT_EQ(one[i].label, two[i].label) << i;
    ASSERT_EQ(one[i].x, two[i].x) << i;
    labelled += one[i].label != kLabelFree;
  }
  EXPECT_GT(labelled, 5000u);
  // Each label is the checker's for the sample's exact joint values.
  const RobotSampler plain(robot_, options);
  for (std::size_t i = 0; i < 1000; ++i) {
    double q[6];
    plain.jointValues(i, q);
    EXPECT_EQ(one[i].label, checker_.label(Eigen::Map<Eigen::VectorXd>(q, 6)));
    EXPECT_EQ(one[i].q1, static_cast<float>(q[0]));
  }
}

TEST(CollisionChecker, LineRobotsAreFreeAtTheirStartAndHitTheirLine) {
  // deicing at q = 0: arm straight along x at the shoulder's height, 60 cm under the conductor.
  // Raised (theta1 = 45, theta2 = 45 deg), the 45 cm outer forearm tube stands vertical at
  // x = 50 cos 45 = 35.4 cm from z = 35.4 to 80.4 cm: through the conductor at z = 60.
  const Robot deicing = loadRobot(test::robotPath("deicing"));
  const CollisionChecker line(deicing, loadCollisionModel(deicing, test::robotPath("deicing")));
  EXPECT_EQ(line.label(Eigen::Vector4d(0, 0, 0, 25)), kLabelFree);
  EXPECT_EQ(line.label(Eigen::Vector4d(0, 45 * kDeg, 45 * kDeg, 70)), kLabelEnvironment);
  // Turned 30 deg about the vertical, the tube passes z = 60 at y = 35.4 sin 30 = 17.7 cm from
  // the conductor's axis: free.
  EXPECT_EQ(line.label(Eigen::Vector4d(30 * kDeg, 45 * kDeg, 45 * kDeg, 70)), kLabelFree);

  // maintenance4: gripper on the forearm at q = 0 lies 0.5 cm from link j2's end (the 6 cm
  // fixed forearm ends at 6 + 3, the inner tube starts at 6 with radius 2.5).
  const Robot arm = loadRobot(test::robotPath("maintenance4"));
  const CollisionChecker checker(arm, loadCollisionModel(arm, test::robotPath("maintenance4")));
  EXPECT_EQ(checker.label(Eigen::Vector4d(0, 0, 0, 0)), kLabelFree);
  // Turned towards the twin bundle (j1 = 90 deg puts the link along -y under the flipped base,
  // where the bundle is), lowered 10 cm and stretched: forearm at z = -20 - 25 = -45 cm
  // (j2 = 10: column 15 + 10 below the mount at -20), the height of conductor C at y = -35.
  const Eigen::Vector4d towards_c(90 * kDeg, 10, 0, 30);
  const Eigen::Vector3d p = toolPose(arm, towards_c).translation();
  EXPECT_NEAR(p.z(), -45.0, kExact);
  EXPECT_LT(p.y(), -35.0);  // the arm reaches past the conductor
  EXPECT_EQ(checker.label(towards_c), kLabelEnvironment);
}

}  // namespace
}  // namespace mcws
