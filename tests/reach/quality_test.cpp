// mcws::jacobianQuality and mcws::manipulability against closed forms (the planar 2R arm),
// determinants, a Jacobian built by central differences of the tool pose, and a wrist
// singularity of the inspection arm.
#include "mcws/reach/quality.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <random>

#include "kinematics/random_joints.h"
#include "kinematics/test_chains.h"
#include "mcws/core/error.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/jacobian.h"
#include "mcws/kinematics/robot_yaml.h"
#include "reach/planar2.h"
#include "test_support.h"

namespace mcws {
namespace {

using test::kDeg;
using test::kL1;
using test::kL2;
using test::planar2;

using test::differenceJacobian;

/// A closed form against an SVD of the same numbers: rounding only.
constexpr double kRounding = 1e-12;
/// The Cholesky path against the SVD, relative: the header promises about 1e-12 away from
/// singularities (inverse condition >= 1e-2 here; observed at most 1e-12 over 1e5 vectors of
/// inspection6 and ta1400). Nearer, the Gram matrix's condition number 1 / inverse_condition^2
/// multiplies the rounding: relative error <= k eps / inverse_condition^2 with k the size
/// (observed k <= 15 over those vectors; 64 leaves a margin). At inverse condition 1e-4 that is
/// 1.4e-7: a random vector of inspection6 with q5 = 0.037 rad differs by 3.4e-8.
constexpr double kFastPathRelative = 1e-12;
constexpr double kFastPathRegular = 1e-2;
constexpr double kFastPathGramFactor = 64.0;

/// Tolerance of manipulability() against the SVD's value w with inverse condition ic.
double fastPathTolerance(double w, double ic) {
  if (ic >= kFastPathRegular) return kFastPathRelative * w;
  return kFastPathGramFactor * std::numeric_limits<double>::epsilon() / (ic * ic) * w;
}
/// Central differences with step h = 1e-5 rad: truncation ~ h^2 * reach ~ 1e-10 * 1.7e3 mm and
/// rounding ~ 1e-16 * 1.7e3 mm / h ~ 2e-8 mm in the linear rows, about 1e-11 after division by
/// L = 1655 mm; the singular values move by at most that (Weyl), so the quality by about
/// 1e-11 / sigma_min relative. 1e-6 allows sigma_min down to 1e-5.
constexpr double kDifferenceRelative = 1e-6;
constexpr int kRandomVectors = 500;

Robot inspection6() { return loadRobot(test::robotPath("inspection6")); }

QualityOptions positionOnly() {
  QualityOptions options;
  options.task = QualityTask::kPosition;
  return options;
}

QualityOptions fullTwist(const Robot& robot) {
  QualityOptions options;
  options.task = QualityTask::kFull;
  options.characteristic_length = chainLengthScale(robot);
  return options;
}

/// The textbook Jacobian of a planar 2R arm: d(x, y) / d(q1, q2).
Eigen::Matrix2d planarJacobian(double q1, double q2) {
  const double s1 = std::sin(q1), c1 = std::cos(q1);
  const double s12 = std::sin(q1 + q2), c12 = std::cos(q1 + q2);
  Eigen::Matrix2d J;
  J << -kL1 * s1 - kL2 * s12, -kL2 * s12, kL1 * c1 + kL2 * c12, kL2 * c12;
  return J;
}

/// Singular values of a 2 x 2 matrix in closed form: the roots of s^4 - T s^2 + D^2 = 0 with
/// T = ||M||_F^2 and D = det M (the eigenvalues of M^T M). Largest first.
Eigen::Vector2d singularValues2x2(const Eigen::Matrix2d& M) {
  const double T = M.squaredNorm(), D = M.determinant();
  const double root = std::sqrt(std::max(0.0, T * T - 4.0 * D * D));
  const double big = std::sqrt(0.5 * (T + root));
  return {big, big > 0.0 ? std::abs(D) / big : 0.0};  // s1 s2 = |D|, no cancellation
}

/// J_s = [J_v / L; J_w], square for a 6-joint arm.
Eigen::Matrix<double, 6, 6> scaledSquare(const Jacobian& J, double L) {
  Eigen::Matrix<double, 6, 6> J_s = J;
  J_s.topRows<3>() /= L;
  return J_s;
}

TEST(Quality, PlanarTwoLinkManipulabilityIsL1L2SinQ2) {
  const Robot robot = planar2();
  const QualityOptions options = positionOnly();
  // Elbow angles of both signs, near and far from the stretched arm; q1 must not matter.
  const double q1s[] = {0.0, 0.7, -2.5};
  const double q2s[] = {90.0, -90.0, 30.0, -150.0, 5.0, 160.0, 120.0};
  for (double q1 : q1s) {
    for (double q2_deg : q2s) {
      const double q2 = q2_deg * kDeg;
      SCOPED_TRACE(testing::Message() << "q1 = " << q1 << " rad, q2 = " << q2_deg << " deg");
      const Jacobian J = toolJacobian(robot, Eigen::Vector2d(q1, q2));
      const Quality quality = jacobianQuality(J, options);
      const double expected = kL1 * kL2 * std::abs(std::sin(q2));  // [cm^2]
      EXPECT_NEAR(quality.manipulability, expected, kRounding * kL1 * kL2);
      EXPECT_NEAR(manipulability(J.data(), 2, options), expected, kRounding * kL1 * kL2);

      const Eigen::Vector2d sigma = singularValues2x2(planarJacobian(q1, q2));
      EXPECT_NEAR(quality.inverse_condition, sigma[1] / sigma[0], kRounding);
      EXPECT_NEAR(sigma[0] * sigma[1], expected, kRounding * kL1 * kL2);  // the helper itself
    }
  }
  // A hand-worked value: q2 = 90 deg, q1 = 0 gives J = [[-30, -30], [40, 0]], so J^T J =
  // [[2500, 900], [900, 900]], trace 3400, det 1440000: s^2 = 1700 +- sqrt(1700^2 - 1440000)
  // = 1700 +- 1204.159, s = 53.8903 and 22.2675 (product 1200), ratio 0.413200.
  const Quality q90 =
      jacobianQuality(toolJacobian(robot, Eigen::Vector2d(0.0, 90 * kDeg)), options);
  EXPECT_NEAR(q90.manipulability, 1200.0, 1e-9);
  EXPECT_NEAR(q90.inverse_condition, 0.413200, 1e-6);
}

TEST(Quality, PlanarTwoLinkStretchedArmIsSingular) {
  const Robot robot = planar2();
  const QualityOptions options = positionOnly();
  for (double q2 : {0.0, M_PI}) {  // stretched and folded: J's columns are parallel
    const Jacobian J = toolJacobian(robot, Eigen::Vector2d(0.4, q2));
    const Quality quality = jacobianQuality(J, options);
    EXPECT_NEAR(quality.manipulability, 0.0, kRounding * kL1 * kL2) << q2;
    EXPECT_NEAR(quality.inverse_condition, 0.0, kRounding) << q2;
    EXPECT_NEAR(manipulability(J.data(), 2, options), 0.0, 1e-6 * kL1 * kL2) << q2;
  }
}

TEST(Quality, FastPathAgreesWithSvdOnRandomJointVectors) {
  const Robot robot = inspection6();
  std::mt19937_64 rng(41);
  // kFull: the 6 x 6 Gram matrix J^T J; kPosition: 3 x 6, the 3 x 3 Gram matrix J J^T.
  for (const QualityOptions& options : {fullTwist(robot), positionOnly()}) {
    SCOPED_TRACE(qualityTaskName(options.task));
    for (int n = 0; n < kRandomVectors; ++n) {
      const Eigen::VectorXd q = test::randomJoints(robot, rng);
      const Jacobian J = toolJacobian(robot, q);
      const Quality svd = jacobianQuality(J, options);
      const double fast = manipulability(J.data(), robot.dof(), options);
      ASSERT_GT(svd.manipulability, 0.0) << q.transpose();
      ASSERT_NEAR(fast, svd.manipulability,
                  fastPathTolerance(svd.manipulability, svd.inverse_condition))
          << q.transpose();
    }
  }
}

TEST(Quality, FastPathAgreesWithSvdForFewerJointsThanRows) {
  // planar2 with the full twist: 6 x 2, the 2 x 2 Gram matrix J^T J.
  const Robot robot = planar2();
  std::mt19937_64 rng(43);
  QualityOptions options = fullTwist(robot);
  for (int n = 0; n < kRandomVectors; ++n) {
    const Eigen::VectorXd q = test::randomJoints(robot, rng);
    const Jacobian J = toolJacobian(robot, q);
    const Quality quality = jacobianQuality(J, options);
    const double svd = quality.manipulability;
    ASSERT_NEAR(manipulability(J.data(), 2, options), svd,
                fastPathTolerance(svd, quality.inverse_condition));
    // By hand: J^T J = J_v^T J_v / L^2 + [1 1; 1 1] (both angular columns are z).
    const Eigen::Matrix2d A = planarJacobian(q[0], q[1]) / options.characteristic_length;
    const Eigen::Matrix2d gram = A.transpose() * A + Eigen::Matrix2d::Ones();
    ASSERT_NEAR(svd, std::sqrt(gram.determinant()), 1e-9 * svd);
  }
}

TEST(Quality, SixJointFullManipulabilityIsTheDeterminantOfTheScaledJacobian) {
  const Robot robot = inspection6();
  const QualityOptions options = fullTwist(robot);
  std::mt19937_64 rng(47);
  for (int n = 0; n < kRandomVectors; ++n) {
    const Eigen::VectorXd q = test::randomJoints(robot, rng);
    const Jacobian J = toolJacobian(robot, q);
    const double det = std::abs(scaledSquare(J, options.characteristic_length).determinant());
    ASSERT_NEAR(jacobianQuality(J, options).manipulability, det, 1e-9 * det) << q.transpose();
  }
}

TEST(Quality, ScalingTheLengthScalesTheFullManipulabilityByItsCube) {
  // det [J_v / L; J_w] = det [J_v; J_w] / L^3: doubling L divides the manipulability by 8.
  const Robot robot = inspection6();
  QualityOptions options = fullTwist(robot);
  const Jacobian J =
      toolJacobian(robot, (Eigen::VectorXd(6) << 0.3, -0.8, 1.1, 0.4, 0.9, -0.2).finished());
  const double w = jacobianQuality(J, options).manipulability;
  options.characteristic_length *= 2.0;
  EXPECT_NEAR(jacobianQuality(J, options).manipulability, w / 8.0, 1e-12 * w);
}

TEST(Quality, AnalyticJacobianQualityMatchesCentralDifferences) {
  for (const char* name : {"inspection6", "planar2", "ta1400"}) {
    SCOPED_TRACE(name);
    const Robot robot = loadRobot(test::robotPath(name));
    const QualityOptions options = robot.dof() >= 6 ? fullTwist(robot) : positionOnly();
    std::mt19937_64 rng(53);
    for (int n = 0; n < 200; ++n) {
      const Eigen::VectorXd q = test::randomJoints(robot, rng);
      const Quality analytic = jacobianQuality(toolJacobian(robot, q), options);
      const Quality numeric = jacobianQuality(differenceJacobian(robot, q), options);
      ASSERT_NEAR(numeric.manipulability, analytic.manipulability,
                  kDifferenceRelative * analytic.manipulability)
          << q.transpose();
      ASSERT_NEAR(numeric.inverse_condition, analytic.inverse_condition,
                  kDifferenceRelative * analytic.inverse_condition)
          << q.transpose();
    }
  }
}

TEST(Quality, InspectionArmIsSingularWithTheWristStraight) {
  // inspection6 (standard D-H): alpha_2 = alpha_3 = 0, so the axes of joints 2, 3 and 4 are
  // parallel (z_1 || z_2 || z_3); their columns span the planar motions normal to that axis (two
  // translations and the turn about it), three dimensions. With q5 = 0, alpha_4 = 90 deg and
  // alpha_5 = -90 deg turn z_5 back onto z_3: joint 6 is parallel to joint 4, offset by d5 = 50 mm
  // along z_4, so J_6 = J_4 - [d5 z_3 x z_4; 0], J_4 less a translation normal to z_3, which
  // joints 2-4 already make: J_6 lies in the span of J_2, J_3, J_4 and the rank is 5. (q5 = pi
  // likewise; q5 = 0.5 rad is regular.)
  const Robot robot = inspection6();
  const QualityOptions options = fullTwist(robot);
  std::mt19937_64 rng(59);
  for (int n = 0; n < 20; ++n) {
    Eigen::VectorXd q = test::randomJoints(robot, rng);
    for (double q5 : {0.0, M_PI, 0.5}) {
      q[4] = q5;
      SCOPED_TRACE(testing::Message() << "q = " << q.transpose());
      const Jacobian J = toolJacobian(robot, q);
      const Eigen::Matrix<double, 6, 6> J_s = scaledSquare(J, options.characteristic_length);
      const Quality quality = jacobianQuality(J, options);
      // The witness, independent of the SVD: J_6 lies in the span of J_2, J_3, J_4 (least
      // squares residual ~ 0) when the wrist is straight.
      Eigen::Matrix<double, 6, 3> span;
      span << J_s.col(1), J_s.col(2), J_s.col(3);
      const Eigen::Matrix<double, 6, 1> J_6 = J_s.col(5);
      const Eigen::Vector3d c = span.colPivHouseholderQr().solve(J_6);
      const double residual = (span * c - J_6).norm();
      if (q5 != 0.5) {
        EXPECT_LT(residual, 1e-12);
        EXPECT_LT(std::abs(J_s.determinant()), 1e-12);
        EXPECT_LT(quality.manipulability, 1e-12);
        EXPECT_LT(quality.inverse_condition, 1e-12);
        // The Cholesky path squares the condition number: at a singularity it gives 0 or about
        // sqrt(machine epsilon) times the other singular values, never more than 1e-6 here.
        EXPECT_LT(manipulability(J.data(), 6, options), 1e-6);
      } else {
        EXPECT_GT(residual, 1e-3);
        EXPECT_GT(quality.manipulability, 1e-5);
        EXPECT_GT(quality.inverse_condition, 1e-4);
      }
    }
  }
}

TEST(Quality, InverseConditionIsOneForAnIsotropicJacobian) {
  // A Jacobian whose measured rows are orthonormal columns times 2: every singular value 2.
  Jacobian J = Jacobian::Zero(6, 3);
  J(0, 0) = J(1, 1) = J(2, 2) = 2.0;
  const Quality quality = jacobianQuality(J, positionOnly());
  EXPECT_NEAR(quality.manipulability, 8.0, kRounding);
  EXPECT_NEAR(quality.inverse_condition, 1.0, kRounding);
  // The full twist of the same matrix with L = 4: velocity rows / 4 -> singular values 0.5.
  QualityOptions full;
  full.characteristic_length = 4.0;
  EXPECT_NEAR(jacobianQuality(J, full).manipulability, 0.125, kRounding);
  EXPECT_NEAR(manipulability(J.data(), 3, full), 0.125, kRounding);
  // A zero Jacobian: no motion at all.
  const Quality zero = jacobianQuality(Jacobian::Zero(6, 2), full);
  EXPECT_EQ(zero.manipulability, 0.0);
  EXPECT_EQ(zero.inverse_condition, 0.0);
}

TEST(Quality, RejectsABadCharacteristicLength) {
  const Jacobian J = Jacobian::Identity(6, 6);
  for (double L : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                   std::numeric_limits<double>::infinity()}) {
    QualityOptions options;
    options.characteristic_length = L;
    const std::string message = test::errorOf([&] { jacobianQuality(J, options); });
    EXPECT_NE(message.find("characteristic length"), std::string::npos) << message;
  }
  QualityOptions options;
  options.characteristic_length = -2.5;
  EXPECT_NE(test::errorOf([&] { jacobianQuality(J, options); }).find("-2.5"), std::string::npos);
}

TEST(Quality, RejectsAJacobianWithoutColumnsOrWithTooMany) {
  EXPECT_NE(test::errorOf([] {
              jacobianQuality(Jacobian(6, 0), QualityOptions{});
            }).find("1 to 8 columns"),
            std::string::npos);
  EXPECT_NE(test::errorOf([] {
              jacobianQuality(Jacobian::Zero(6, 9), QualityOptions{});
            }).find("1 to 8 columns"),
            std::string::npos);
}

TEST(Quality, DefaultOptionsFollowTheNumberOfJoints) {
  const QualityOptions planar = defaultQualityOptions(planar2());
  EXPECT_EQ(planar.task, QualityTask::kPosition);
  EXPECT_DOUBLE_EQ(planar.characteristic_length, kL1 + kL2);
  // inspection6: offsets |(0, 0, 50)|, |(500, 0, 50)| twice, 50, 50, 500 mm.
  const QualityOptions inspection = defaultQualityOptions(inspection6());
  EXPECT_EQ(inspection.task, QualityTask::kFull);
  EXPECT_NEAR(inspection.characteristic_length, 650.0 + 2.0 * std::sqrt(252500.0), 1e-9);
}

TEST(Quality, TaskNamesRoundTrip) {
  for (QualityTask task : {QualityTask::kPosition, QualityTask::kFull}) {
    EXPECT_EQ(parseQualityTask(qualityTaskName(task)), task);
  }
  EXPECT_STREQ(qualityTaskName(QualityTask::kPosition), "position");
  EXPECT_STREQ(qualityTaskName(QualityTask::kFull), "full");
  const std::string message = test::errorOf([] { parseQualityTask("twist"); });
  EXPECT_NE(message.find("'twist'"), std::string::npos) << message;
  EXPECT_NE(message.find("position, full"), std::string::npos) << message;
  EXPECT_NE(test::errorOf([] { parseQualityTask("Full"); }).find("'Full'"), std::string::npos);
  EXPECT_NE(test::errorOf([] { parseQualityTask(""); }).find("''"), std::string::npos);
}

}  // namespace
}  // namespace mcws
