#include "mcws/trajectory/joint_trajectory.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mcws/core/error.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

// Polynomials evaluated in double: values agree with closed forms to rounding.
constexpr double kExact = 1e-12;
// Central differences with step kStep have error ~ kStep^2 * (third derivative) ~ 1e-8 here.
constexpr double kStep = 1e-5;
constexpr double kDifferenceTol = 1e-6;

// One revolute joint 'a' in [-1, 1] rad and one prismatic joint 'b' in [0, 50] cm.
Robot twoJointRobot() {
  Robot robot;
  robot.name = "two";
  robot.length_unit = LengthUnit::kCentimetre;
  Joint a;
  a.name = "a";
  a.lower = -1.0;
  a.upper = 1.0;
  Joint b;
  b.name = "b";
  b.type = JointType::kPrismatic;
  b.lower = 0.0;
  b.upper = 50.0;
  robot.joints = {a, b};
  return robot;
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

Eigen::VectorXd vec(std::initializer_list<double> values) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (double x : values) v[i++] = x;
  return v;
}

// Liu, Han, Xu & Li 2021, eq. (10).
TEST(Blend, QuinticIsThePapersEquationTen) {
  for (double u : {0.0, 0.1, 0.25, 0.5, 0.8, 1.0}) {
    const Blend b = blend(TimeProfile::kQuintic, u);
    EXPECT_NEAR(b.s, 10 * std::pow(u, 3) - 15 * std::pow(u, 4) + 6 * std::pow(u, 5), kExact);
    EXPECT_NEAR(b.ds, 30 * u * u - 60 * std::pow(u, 3) + 30 * std::pow(u, 4), kExact);
    EXPECT_NEAR(b.dds, 60 * u - 180 * u * u + 120 * std::pow(u, 3), kExact);
    const Blend c = blend(TimeProfile::kCubic, u);
    EXPECT_NEAR(c.s, 3 * u * u - 2 * u * u * u, kExact);
    EXPECT_NEAR(c.ds, 6 * u - 6 * u * u, kExact);
  }
}

TEST(PointToPoint, QuinticEndConditionsAndPeaks) {
  const Eigen::VectorXd q0 = vec({-0.5, 10.0}), qf = vec({0.7, 40.0});
  const double T = 10.0;
  const JointTrajectory traj = pointToPoint(q0, qf, T, TimeProfile::kQuintic);
  const Eigen::VectorXd D = qf - q0;
  EXPECT_LT((traj.position(0) - q0).norm(), kExact);
  EXPECT_LT((traj.position(T) - qf).norm(), kExact);
  for (double t : {0.0, T}) {
    EXPECT_LT(traj.velocity(t).norm(), kExact);
    EXPECT_LT(traj.acceleration(t).norm(), kExact);
  }
  EXPECT_LT((traj.position(T / 2) - (q0 + qf) / 2).norm(), kExact);
  // Peak velocity 30/16 D/T = 1.875 D/T at the middle; peak acceleration (10/sqrt(3)) D/T^2 at
  // u = (3 - sqrt(3))/6.
  EXPECT_LT((traj.velocity(T / 2) - 1.875 * D / T).norm(), kExact);
  const double u_acc = (3 - std::sqrt(3.0)) / 6;
  EXPECT_LT((traj.acceleration(u_acc * T) - 10 / std::sqrt(3.0) * D / (T * T)).norm(), kExact);
  // ... and no sample exceeds them.
  const SampledTrajectory s = sampleTrajectory(traj, 1000);
  for (int j = 0; j < 2; ++j) {
    EXPECT_NEAR(s.qd.col(j).cwiseAbs().maxCoeff(), 1.875 * std::abs(D[j]) / T, 1e-9);
    EXPECT_LE(s.qdd.col(j).cwiseAbs().maxCoeff(),
              10 / std::sqrt(3.0) * std::abs(D[j]) / (T * T) + 1e-12);
  }
}

TEST(PointToPoint, CubicEndConditionsAndPeak) {
  const Eigen::VectorXd q0 = vec({0.3, 5.0}), qf = vec({-0.9, 45.0});
  const double T = 4.0;
  const JointTrajectory traj = pointToPoint(q0, qf, T, TimeProfile::kCubic);
  const Eigen::VectorXd D = qf - q0;
  EXPECT_LT((traj.position(0) - q0).norm(), kExact);
  EXPECT_LT((traj.position(T) - qf).norm(), kExact);
  EXPECT_LT(traj.velocity(0).norm(), kExact);
  EXPECT_LT(traj.velocity(T).norm(), kExact);
  // The cubic starts and stops with acceleration +-6 D/T^2 (it cannot also zero those).
  EXPECT_LT((traj.acceleration(0) - 6 * D / (T * T)).norm(), kExact);
  EXPECT_LT((traj.acceleration(T) + 6 * D / (T * T)).norm(), kExact);
  EXPECT_LT((traj.velocity(T / 2) - 1.5 * D / T).norm(), kExact);
  const SampledTrajectory s = sampleTrajectory(traj, 1000);
  for (int j = 0; j < 2; ++j) {
    EXPECT_NEAR(s.qd.col(j).cwiseAbs().maxCoeff(), 1.5 * std::abs(D[j]) / T, 1e-9);
  }
}

TEST(CubicSpline, PassesTheViasWithContinuousVelocityAndAcceleration) {
  const std::vector<Eigen::VectorXd> points = {vec({0.0, 0.0}), vec({0.8, 10.0}), vec({-0.3, 30.0}),
                                               vec({0.1, 12.0}), vec({0.5, 40.0})};
  const std::vector<double> times = {0.0, 1.0, 2.5, 3.0, 5.0};  // uneven on purpose
  const JointTrajectory traj = cubicSpline(points, times);
  ASSERT_EQ(traj.segmentCount(), 4);
  for (std::size_t k = 0; k < points.size(); ++k) {
    EXPECT_LT((traj.position(times[k]) - points[k]).norm(), 1e-12) << "point " << k;
  }
  EXPECT_LT(traj.velocity(0).norm(), kExact);
  EXPECT_LT(traj.velocity(5.0).norm(), kExact);
  // Left and right limits at every via agree in position, velocity and acceleration; the third
  // derivative does jump (a C2, not C3, curve), so the check can tell.
  constexpr double eps = 1e-7;
  bool jerk_jumps = false;
  for (std::size_t k = 1; k + 1 < points.size(); ++k) {
    const double t = times[k];
    EXPECT_LT((traj.position(t - eps) - traj.position(t + eps)).norm(), 1e-5) << k;
    EXPECT_LT((traj.velocity(t - eps) - traj.velocity(t + eps)).norm(), 1e-4) << k;
    EXPECT_LT((traj.acceleration(t - eps) - traj.acceleration(t + eps)).norm(), 1e-4) << k;
    const Eigen::VectorXd jerk_left =
        (traj.acceleration(t - eps) - traj.acceleration(t - 2 * eps)) / eps;
    const Eigen::VectorXd jerk_right =
        (traj.acceleration(t + 2 * eps) - traj.acceleration(t + eps)) / eps;
    jerk_jumps |= (jerk_left - jerk_right).norm() > 1.0;
  }
  EXPECT_TRUE(jerk_jumps);
}

TEST(CubicSpline, ViaVelocityOfThreeEvenPointsIsClosedForm) {
  // h equal: v0 = v2 = 0 and v0 + 4 v1 + v2 = 3 (p2 - p0) / h  =>  v1 = 3 (p2 - p0) / (4 h).
  const double h = 2.0;
  const JointTrajectory traj = cubicSpline({vec({0.2}), vec({0.9}), vec({-0.4})}, {0.0, h, 2 * h});
  EXPECT_NEAR(traj.velocity(h)[0], 3 * (-0.4 - 0.2) / (4 * h), kExact);
}

TEST(CubicSpline, ThroughTwoPointsIsTheCubicMove) {
  const Eigen::VectorXd q0 = vec({0.1, 3.0}), qf = vec({-0.6, 33.0});
  const JointTrajectory spline = cubicSpline({q0, qf}, {0.0, 3.0});
  const JointTrajectory cubic = pointToPoint(q0, qf, 3.0, TimeProfile::kCubic);
  for (double t = 0; t <= 3.0; t += 0.25) {
    EXPECT_LT((spline.position(t) - cubic.position(t)).norm(), kExact);
    EXPECT_LT((spline.acceleration(t) - cubic.acceleration(t)).norm(), kExact);
  }
}

TEST(JointTrajectory, VelocityAndAccelerationAreDerivativesOfPosition) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Eigen::VectorXd> points;
  for (int k = 0; k < 6; ++k) points.push_back(vec({value(rng), value(rng), value(rng)}));
  const std::vector<JointTrajectory> trajectories = {
      pointToPoint(points[0], points[1], 2.0, TimeProfile::kQuintic),
      pointToPoint(points[0], points[1], 2.0, TimeProfile::kCubic),
      cubicSpline(points, evenTimes(points.size(), 6.0))};
  for (const JointTrajectory& traj : trajectories) {
    for (int i = 0; i < 200; ++i) {
      const double t = kStep + (traj.duration() - 2 * kStep) * (i + 0.5) / 200;
      const Eigen::VectorXd v = (traj.position(t + kStep) - traj.position(t - kStep)) / (2 * kStep);
      const Eigen::VectorXd a = (traj.velocity(t + kStep) - traj.velocity(t - kStep)) / (2 * kStep);
      EXPECT_LT((v - traj.velocity(t)).norm(), kDifferenceTol) << t;
      EXPECT_LT((a - traj.acceleration(t)).norm(), kDifferenceTol) << t;
    }
  }
}

TEST(Sampling, TimesAreMultiplesOfThePeriodAndTheEnd) {
  EXPECT_EQ(sampleCount(10.0, 100.0), 1001u);
  EXPECT_EQ(sampleCount(1.0, 3.0), 4u);
  EXPECT_EQ(sampleCount(1.05, 10.0), 12u);
  EXPECT_EQ(sampleCount(0.01, 10.0), 2u);
  const JointTrajectory traj = pointToPoint(vec({0.0}), vec({1.0}), 1.05, TimeProfile::kQuintic);
  const SampledTrajectory s = sampleTrajectory(traj, 10.0);
  ASSERT_EQ(s.size(), 12);
  EXPECT_DOUBLE_EQ(s.t[3], 0.3);
  EXPECT_DOUBLE_EQ(s.t[10], 1.0);
  EXPECT_DOUBLE_EQ(s.t[11], 1.05);
  EXPECT_NEAR(s.q(11, 0), 1.0, kExact);
  EXPECT_DOUBLE_EQ(s.q(3, 0), traj.position(0.3)[0]);
  EXPECT_DOUBLE_EQ(s.qd(3, 0), traj.velocity(0.3)[0]);
}

TEST(Limits, SplineOvershootBetweenViasNamesJointValueAndTime) {
  // Joint a: 0 -> 1 -> 1 -> 0 at t = 0, 1, 2, 3. By symmetry v1 = 1, v2 = -1, and the middle
  // piece is 1 + tau - tau^2: it peaks at 1.25 at t = 1.5, above the limit 1.
  const Robot robot = twoJointRobot();
  const JointTrajectory traj = cubicSpline(
      {vec({0.0, 10.0}), vec({1.0, 10.0}), vec({1.0, 10.0}), vec({0.0, 10.0})}, {0, 1, 2, 3});
  EXPECT_EQ(errorOf([&] { checkTrajectoryLimits(robot, traj); }),
            "joint 'a' reaches 1.25 rad at t = 1.5 s, above its upper limit 1 rad");
}

TEST(Limits, VelocityLimitNamesJointValueAndTime) {
  const Robot robot = twoJointRobot();
  const JointTrajectory traj =
      pointToPoint(vec({-0.5, 0.0}), vec({0.5, 40.0}), 2.0, TimeProfile::kQuintic);
  // Peaks: a 1.875 * 1 / 2 = 0.9375 rad/s, b 1.875 * 40 / 2 = 37.5 cm/s, both at t = 1.
  EXPECT_NO_THROW(checkTrajectoryLimits(robot, traj, vec({0.94, 37.6})));
  EXPECT_EQ(errorOf([&] {
              checkTrajectoryLimits(robot, traj, vec({0.94, 37.4}));
            }),
            "velocity of joint 'b' reaches 37.5 cm/s at t = 1 s, above its upper limit 37.4 cm/s");
  const JointTrajectory back =
      pointToPoint(vec({0.5, 0.0}), vec({-0.5, 0.0}), 2.0, TimeProfile::kQuintic);
  EXPECT_EQ(errorOf([&] {
              checkTrajectoryLimits(robot, back, vec({0.9, 1.0}));
            }),
            "velocity of joint 'a' reaches -0.9375 rad/s at t = 1 s, below its lower limit -0.9 "
            "rad/s");
}

TEST(Limits, ReportsTheEarliestViolationOfASegment) {
  // a(t) = 0.6 t peaks at 1.2 at t = 2; b(t) = 200 t - 100 t^2 peaks at 100 cm at t = 1.
  Eigen::MatrixXd c(2, 3);
  c << 0.0, 0.6, 0.0, 0.0, 200.0, -100.0;
  const JointTrajectory traj({0.0, 2.0}, std::vector<Eigen::MatrixXd>(1, c));
  EXPECT_EQ(errorOf([&] { checkTrajectoryLimits(twoJointRobot(), traj); }),
            "joint 'b' reaches 100 cm at t = 1 s, above its upper limit 50 cm");
}

TEST(Limits, MovesOntoTheLimitsPass) {
  const Robot robot = twoJointRobot();
  EXPECT_NO_THROW(checkTrajectoryLimits(
      robot, pointToPoint(vec({-1.0, 0.0}), vec({1.0, 50.0}), 3.0, TimeProfile::kQuintic)));
  EXPECT_NO_THROW(checkTrajectoryLimits(
      robot, cubicSpline({vec({-1.0, 0.0}), vec({0.0, 25.0}), vec({1.0, 50.0})}, {0, 1, 2})));
}

TEST(Limits, ReportsMismatchedSizes) {
  const Robot robot = twoJointRobot();
  const JointTrajectory one = pointToPoint(vec({0.0}), vec({1.0}), 1.0, TimeProfile::kCubic);
  EXPECT_EQ(errorOf([&] { checkTrajectoryLimits(robot, one); }),
            "trajectory has 1 joints but robot 'two' has 2");
  const JointTrajectory two =
      pointToPoint(vec({0.0, 0.0}), vec({0.1, 1.0}), 1.0, TimeProfile::kCubic);
  EXPECT_EQ(errorOf([&] { checkTrajectoryLimits(robot, two, vec({1.0})); }),
            "velocity limits: 1 values for robot 'two' with 2 joints");
  EXPECT_EQ(errorOf([&] {
              checkTrajectoryLimits(robot, two, vec({1.0, 0.0}));
            }),
            "velocity limit of joint 'b' must be positive");
}

TEST(JointTrajectory, ReportsBadInput) {
  const Eigen::VectorXd a = vec({0.0, 1.0}), b = vec({1.0, 2.0});
  EXPECT_EQ(errorOf([&] { pointToPoint(a, b, 0.0, TimeProfile::kQuintic); }),
            "point-to-point move: duration 0 s is not a positive number");
  EXPECT_EQ(errorOf([&] { pointToPoint(a, b, -2.0, TimeProfile::kQuintic); }),
            "point-to-point move: duration -2 s is not a positive number");
  EXPECT_EQ(errorOf([&] { pointToPoint(a, vec({1.0}), 1.0, TimeProfile::kQuintic); }),
            "point-to-point move: start has 2 joint values but goal has 1");
  EXPECT_EQ(errorOf([&] {
              pointToPoint(a, vec({1.0, NAN}), 1.0, TimeProfile::kQuintic);
            }),
            "point-to-point move: goal has a value that is not a finite number");
  EXPECT_EQ(errorOf([&] {
              cubicSpline({a, b, a}, {0.0, 1.0, 1.0});
            }),
            "spline: times must increase");
  EXPECT_EQ(errorOf([&] {
              cubicSpline({a, vec({1.0}), a}, {0.0, 1.0, 2.0});
            }),
            "spline: point 2 has 1 joint values, point 1 has 2");
  EXPECT_EQ(errorOf([&] { cubicSpline({a}, {0.0}); }), "spline: needs at least two points, got 1");
  EXPECT_EQ(errorOf([&] { sampleCount(1.0, 0.0); }),
            "sampling: rate 0 Hz is not a positive number");
  EXPECT_EQ(errorOf([&] { sampleCount(1.0, -5.0); }),
            "sampling: rate -5 Hz is not a positive number");
  EXPECT_EQ(errorOf([&] { sampleCount(1e6, 1e3); }),
            "sampling: 1e+06 s at 1000 Hz gives more than 1e8 samples");
  EXPECT_EQ(errorOf([&] { profileFromName("linear"); }),
            "profile 'linear' is not quintic or cubic");
}

}  // namespace
}  // namespace mcws
