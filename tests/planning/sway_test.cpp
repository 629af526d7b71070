// The maintenance-arm patent, step s20: base poses from a truncated Gaussian; chi-square and Wilson
// intervals.
#include "mcws/planning/sway.h"

#include <gtest/gtest.h>

#include <cmath>

#include "mcws/core/error.h"

namespace mcws {
namespace {

TEST(ChiSquareQuantile, MatchesTheTable) {
  // Abramowitz and Stegun, table 26.8 (upper 5 % and 1 % points).
  EXPECT_NEAR(chiSquareQuantile(0.95, 1), 3.841459, 1e-6);
  EXPECT_NEAR(chiSquareQuantile(0.95, 2), 5.991465, 1e-6);
  EXPECT_NEAR(chiSquareQuantile(0.95, 6), 12.591587, 1e-6);
  EXPECT_NEAR(chiSquareQuantile(0.99, 3), 11.344867, 1e-6);
  EXPECT_THROW(chiSquareQuantile(1.0, 2), Error);
  EXPECT_THROW(chiSquareQuantile(0.5, 0), Error);
}

TEST(WilsonInterval, MatchesNewcombesTable) {
  // Newcombe, "Two-sided confidence intervals for the single proportion", Stat. Med. 17 (1998),
  // Table I, method 3 (score interval without continuity correction).
  constexpr double kPrinted = 1e-4;  // the table's four decimals
  const struct {
    std::size_t k, n;
    double low, high;
  } rows[] = {{81, 263, 0.2553, 0.3662},
              {15, 148, 0.0624, 0.1605},
              {0, 20, 0.0, 0.1611},
              {1, 29, 0.0061, 0.1718}};
  for (const auto& row : rows) {
    const ProportionInterval interval = wilsonInterval(row.k, row.n);
    EXPECT_NEAR(interval.low, row.low, kPrinted) << row.k << "/" << row.n;
    EXPECT_NEAR(interval.high, row.high, kPrinted) << row.k << "/" << row.n;
  }
  EXPECT_THROW(wilsonInterval(0, 0), Error);
  EXPECT_THROW(wilsonInterval(3, 2), Error);
}

TEST(WilsonInterval, UpperEndsOfThePlannersAcceptanceRule) {
  // Closed form of the upper end for k of n at z = 1.959964 (95 %):
  // (k + z^2/2 + z sqrt(k (n - k) / n + z^2 / 4)) / (n + z^2), z^2 = 3.8414588.
  // k = 0, n = 100: z^2 / (n + z^2) = 3.8414588 / 103.8414588 = 0.0369935 (<= 0.05: accepted).
  // k = 2, n = 100: (2 + 1.9207294 + 1.959964 sqrt(1.96 + 0.9603647)) / 103.8414588
  //               = (3.9207294 + 3.3493971) / 103.8414588 = 0.0700118 (> 0.05: refused).
  // k = 1, n = 100: (1 + 1.9207294 + 1.959964 sqrt(0.99 + 0.9603647)) / 103.8414588 = 0.0544862.
  // k = 0, n = 72 and 73: 3.8414588 / 75.8414588 = 0.0506512, / 76.8414588 = 0.0499920: the
  // fewest poses with which a path can be accepted at 0.05.
  constexpr double kHand = 1e-6;  // the hand computation's seven decimals
  EXPECT_NEAR(wilsonInterval(0, 100).high, 0.0369935, kHand);
  EXPECT_NEAR(wilsonInterval(2, 100).high, 0.0700118, kHand);
  EXPECT_NEAR(wilsonInterval(1, 100).high, 0.0544862, kHand);
  EXPECT_NEAR(wilsonInterval(0, 72).high, 0.0506512, kHand);
  EXPECT_NEAR(wilsonInterval(0, 73).high, 0.0499920, kHand);
  // The other ends at k = 0 and k = n are exact (not 3e-18 off).
  EXPECT_EQ(wilsonInterval(0, 100).low, 0.0);
  EXPECT_EQ(wilsonInterval(100, 100).high, 1.0);
}

TEST(SwayDisplacement, RollSwingsTheBodyAboutTheLine) {
  SwayModel model;
  model.pivot = {0, 0, 25};
  model.line_direction = {2, 0, 0};
  const Eigen::Isometry3d T_world_sway = swayFrame(model);
  const double angle = 0.1;
  SwayVector xi = SwayVector::Zero();
  xi[3] = angle;                       // roll: about the line through the pivot
  xi[0] = 1.5;                         // slide along the line
  const Eigen::Vector3d p(7, 0, -20);  // 45 below the line
  const Eigen::Vector3d moved = swayDisplacement(T_world_sway, xi) * p;
  // Closed form: the point turns on a circle of radius 45 about the line x = t, z = 25. The
  // sway frame's z is up and y = z x x, so a positive roll moves a point below the line to +y.
  EXPECT_NEAR(moved.x(), 8.5, 1e-12);
  EXPECT_NEAR(moved.y(), 45 * std::sin(angle), 1e-12);
  EXPECT_NEAR(moved.z(), 25 - 45 * std::cos(angle), 1e-12);
}

TEST(SwaySampler, OneDirectionIsATruncatedNormal) {
  SwayModel model;
  const double sigma = 2.0;
  model.covariance(0, 0) = sigma * sigma;
  const SwaySampler sampler(model);
  EXPECT_EQ(sampler.rank(), 1);
  const double c = std::sqrt(chiSquareQuantile(0.95, 1));  // 1.959964
  const int n = 40000;
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const SwayVector xi = sampler.vector(7, i);
    ASSERT_LE(std::abs(xi[0]), c * sigma + 1e-12);
    for (int k = 1; k < 6; ++k) ASSERT_EQ(xi[k], 0.0);
    sum += xi[0];
    sum2 += xi[0] * xi[0];
  }
  // Variance of N(0, sigma^2) truncated to +-c sigma: sigma^2 (1 - 2 c phi(c) / (2 Phi(c) - 1)).
  const double phi = std::exp(-0.5 * c * c) / std::sqrt(2 * M_PI);
  const double variance = sigma * sigma * (1 - 2 * c * phi / 0.95);
  EXPECT_NEAR(sum / n, 0.0, 4 * std::sqrt(variance / n));
  // The sample variance's standard error is about variance * sqrt(2 / n) (0.7 %): 4 of them.
  EXPECT_NEAR(sum2 / n / variance, 1.0, 4 * std::sqrt(2.0 / n));
}

TEST(SwaySampler, MahalanobisRadiusFollowsTheTruncatedChiSquare) {
  SwayModel model;
  model.confidence = 0.9;
  model.covariance(0, 0) = 1.0;                                            // slide, 1 cm
  model.covariance(3, 3) = std::pow(3 * M_PI / 180, 2);                    // swing, 3 deg
  model.covariance(0, 3) = model.covariance(3, 0) = 0.5 * 3 * M_PI / 180;  // correlated
  const SwaySampler sampler(model);
  ASSERT_EQ(sampler.rank(), 2);
  EXPECT_NEAR(sampler.chiSquareRadius(), chiSquareQuantile(0.9, 2), 1e-12);
  // P(m^2 <= median of chi^2_2 | m^2 <= the 90 % point) = 0.5 / 0.9.
  const double median = chiSquareQuantile(0.5, 2);
  const int n = 20000;
  int inside = 0;
  for (int i = 0; i < n; ++i) {
    const double m2 = sampler.mahalanobisSquared(sampler.vector(3, i));
    ASSERT_LE(m2, sampler.chiSquareRadius() * (1 + 1e-9));
    inside += m2 <= median;
  }
  const double expected = 0.5 / 0.9;
  EXPECT_NEAR(double(inside) / n, expected, 4 * std::sqrt(expected * (1 - expected) / n));
}

TEST(SwaySampler, SampleDependsOnlyOnSeedAndIndex) {
  SwayModel model;
  model.covariance.diagonal() << 1, 2, 3, 0.01, 0.02, 0.03;
  const SwaySampler sampler(model);
  const std::vector<Eigen::Isometry3d> all = sampler.displacements(5, 50);
  for (int i : {0, 17, 49}) {
    const Eigen::Isometry3d one = swayDisplacement(sampler.frame(), sampler.vector(5, i));
    EXPECT_TRUE(one.matrix().isApprox(all[i].matrix(), 0.0));
  }
  EXPECT_FALSE(sampler.vector(5, 3).isApprox(sampler.vector(6, 3)));
}

TEST(SwaySampler, ZeroCovarianceKeepsTheMeasuredPose) {
  const SwaySampler sampler(SwayModel{});
  EXPECT_EQ(sampler.rank(), 0);
  EXPECT_TRUE(sampler.displacements(1, 3)[2].matrix().isIdentity(0.0));
}

TEST(SwaySampler, RejectsBadModels) {
  auto message = [](const SwayModel& model) {
    try {
      SwaySampler sampler(model);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  SwayModel model;
  model.covariance(0, 0) = 1.0;
  model.covariance(1, 1) = 1.0;
  model.covariance(0, 1) = model.covariance(1, 0) = 2.0;  // eigenvalues 3 and -1
  EXPECT_NE(message(model).find("not positive semi-definite (eigenvalue -1)"), std::string::npos)
      << message(model);
  model.covariance(0, 1) = 0.5;
  EXPECT_NE(message(model).find("not symmetric"), std::string::npos);
  model.covariance(0, 1) = 0.5;
  model.covariance(1, 0) = 0.5;
  model.confidence = 1.0;
  EXPECT_NE(message(model).find("confidence 1 is outside (0, 1)"), std::string::npos);
  model.confidence = 0.95;
  model.line_direction.setZero();
  EXPECT_NE(message(model).find("line direction"), std::string::npos);
}

}  // namespace
}  // namespace mcws
