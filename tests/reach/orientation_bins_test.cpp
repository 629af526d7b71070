// mcws::SpherePartition (Leopardi's EQ partition of S^2) and mcws::OrientationBins: areas from
// the bounds, Leopardi's published example, a brute-force lookup from the bounds, Monte Carlo
// shares, the poles and the longitude seam, and the roll about the approach.
#include "mcws/reach/orientation_bins.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "mcws/core/error.h"
#include "test_support.h"

namespace mcws {
namespace {

constexpr double kFullTurn = 2.0 * M_PI;
/// Areas from acos'd bounds (cos(acos(z)) loses about 1e-16 / sin(colatitude), at most ~1e-14 at
/// the smallest polar cap here): 1e-11 of a region's area.
constexpr double kAreaRelative = 1e-11;
/// Unit vectors built in code: rounding only.
constexpr double kBinRounding = 1e-12;
/// Monte Carlo shares: binomial standard deviations allowed per region.
constexpr double kSigmas = 5.0;

const int kSizes[] = {1, 2, 3, 7, 10, 12, 50, 200, 1000};

/// Uniform random directions (normalised Gaussian vectors).
Eigen::Vector3d randomDirection(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Eigen::Vector3d v;
  do {
    v = {normal(rng), normal(rng), normal(rng)};
  } while (v.norm() < 1e-6);
  return v.normalized();
}

struct Bounds {
  double theta0, theta1, phi0, phi1;
};

Bounds boundsOf(const SpherePartition& sphere, int region) {
  Bounds b;
  sphere.bounds(region, b.theta0, b.theta1, b.phi0, b.phi1);
  return b;
}

/// Area of a colatitude x longitude patch of the unit sphere.
double patchArea(const Bounds& b) {
  return (std::cos(b.theta0) - std::cos(b.theta1)) * (b.phi1 - b.phi0);
}

/// The region holding a direction, by trying every region's bounds (half-open: colatitude in
/// [theta0, theta1), longitude in [phi0, phi1); the south pole belongs to the last zone and a
/// longitude that rounds up to 2 pi to the last sector).
int bruteForceRegion(const SpherePartition& sphere, const Eigen::Vector3d& d) {
  const double theta = std::acos(std::clamp(d.z() / d.norm(), -1.0, 1.0));
  double phi = std::atan2(d.y(), d.x());
  if (phi < 0.0) phi += kFullTurn;
  for (int i = 0; i < sphere.regions(); ++i) {
    const Bounds b = boundsOf(sphere, i);
    const bool in_zone = theta >= b.theta0 && (theta < b.theta1 || b.theta1 == M_PI);
    const bool last_sector = std::abs(b.phi1 - kFullTurn) < kBinRounding;  // 2 pi k / k may round
    if (in_zone && phi >= b.phi0 && (phi < b.phi1 || last_sector)) return i;
  }
  return -1;
}

/// Regions per zone, read from the bounds (regions of a zone share their colatitude range).
std::vector<int> regionsPerZone(const SpherePartition& sphere) {
  std::vector<int> counts;
  double last_top = -1.0;
  for (int i = 0; i < sphere.regions(); ++i) {
    const Bounds b = boundsOf(sphere, i);
    if (counts.empty() || b.theta0 != last_top) counts.push_back(0);
    ++counts.back();
    last_top = b.theta0;
  }
  return counts;
}

TEST(SpherePartition, EveryRegionHasAreaFourPiOverN) {
  for (int n = 1; n <= 400; ++n) {
    SCOPED_TRACE(n);
    const SpherePartition sphere(n);
    ASSERT_EQ(sphere.regions(), n);
    const double area = 4.0 * M_PI / n;
    double total = 0.0;
    for (int i = 0; i < n; ++i) {
      const Bounds b = boundsOf(sphere, i);
      ASSERT_NEAR(patchArea(b), area, kAreaRelative * area) << "region " << i;
      ASSERT_LE(b.theta0, b.theta1);
      ASSERT_GE(b.phi0, 0.0);
      ASSERT_LE(b.phi1, kFullTurn + kBinRounding);
      total += patchArea(b);
    }
    ASSERT_NEAR(total, 4.0 * M_PI, 1e-9);
    // The zones tile the colatitudes: the first starts at the north pole, the last ends at the
    // south pole, and each zone's longitudes run 0 .. 2 pi.
    EXPECT_EQ(boundsOf(sphere, 0).theta0, 0.0);
    EXPECT_NEAR(boundsOf(sphere, n - 1).theta1, M_PI, kBinRounding);
    EXPECT_EQ(static_cast<int>(regionsPerZone(sphere).size()), sphere.zones());
  }
  for (int n : {1000, 4000}) {
    const SpherePartition sphere(n);
    for (int i = 0; i < n; ++i) {
      ASSERT_NEAR(patchArea(boundsOf(sphere, i)), 4.0 * M_PI / n, kAreaRelative * 4.0 * M_PI / n)
          << n << " " << i;
    }
  }
}

TEST(SpherePartition, RegionOfACentreIsThatRegion) {
  for (int n : kSizes) {
    const SpherePartition sphere(n);
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d c = sphere.centre(i);
      ASSERT_NEAR(c.norm(), 1.0, kBinRounding) << n << " " << i;
      ASSERT_EQ(sphere.region(c), i) << "N = " << n;
      // The centre lies inside its bounds (the poles are the caps' centres).
      ASSERT_EQ(bruteForceRegion(sphere, c), i) << "N = " << n;
    }
  }
}

TEST(SpherePartition, ZonesOfLeopardisPublishedExampleForTenRegions) {
  // Leopardi's EQ toolbox, eq_caps(2, 10): s_cap = 0.6435 1.5708 2.4981 3.1416,
  // n_regions = 1 4 4 1.
  const SpherePartition sphere(10);
  EXPECT_EQ(sphere.zones(), 4);
  EXPECT_EQ(regionsPerZone(sphere), (std::vector<int>{1, 4, 4, 1}));
  const double s_cap[] = {0.6435, 1.5708, 2.4981, 3.1416};
  const int last_of_zone[] = {0, 4, 8, 9};
  for (int z = 0; z < 4; ++z) {
    EXPECT_NEAR(boundsOf(sphere, last_of_zone[z]).theta1, s_cap[z], 5e-5) << z;
  }
}

TEST(SpherePartition, ZonesForTwoHundredRegionsFollowLeopardi) {
  // Leopardi 2006 by hand for N = 200: polar caps of colatitude c = acos(1 - 2/N) = acos(0.99)
  // = 0.141539 rad; the ideal collar angle is the side of a square of one region's area,
  // sqrt(4 pi / 200) = 0.250663 rad; (pi - 2c) / 0.250663 = 11.40 rounds to 11 collars of
  // 0.259865 rad each, so 13 zones. The ideal region counts of the collars (collar area /
  // region area) are 6.949 13.130 18.430 22.492 25.043 25.913 and back; rounding each with the
  // running remainder gives 7 13 19 22 25 26 25 22 19 13 7, which with the caps sums to 200.
  // (The header's "9 for N = 200" is not this count.)
  const SpherePartition sphere(200);
  EXPECT_EQ(sphere.zones(), 13);
  EXPECT_EQ(regionsPerZone(sphere),
            (std::vector<int>{1, 7, 13, 19, 22, 25, 26, 25, 22, 19, 13, 7, 1}));
  EXPECT_NEAR(boundsOf(sphere, 0).theta1, std::acos(0.99), 1e-12);
  EXPECT_NEAR(boundsOf(sphere, 199).theta0, M_PI - std::acos(0.99), 1e-12);
}

TEST(SpherePartition, SmallCountsAreCapsAndHemispheres) {
  const SpherePartition one(1);
  EXPECT_EQ(one.zones(), 1);
  const Bounds whole = boundsOf(one, 0);
  EXPECT_EQ(whole.theta0, 0.0);
  EXPECT_NEAR(whole.theta1, M_PI, kBinRounding);
  EXPECT_EQ(one.region({0.3, -0.2, -0.9}), 0);

  const SpherePartition two(2);  // hemispheres
  EXPECT_EQ(two.zones(), 2);
  EXPECT_NEAR(boundsOf(two, 0).theta1, M_PI / 2, kBinRounding);
  EXPECT_EQ(two.region({0.1, 0.2, 0.3}), 0);
  EXPECT_EQ(two.region({0.1, 0.2, -0.3}), 1);

  const SpherePartition three(3);  // two caps of area 4 pi / 3 and one collar between them
  EXPECT_EQ(regionsPerZone(three), (std::vector<int>{1, 1, 1}));
  EXPECT_NEAR(boundsOf(three, 0).theta1, std::acos(1.0 / 3.0), kBinRounding);
}

TEST(SpherePartition, RegionAgreesWithTheBoundsOnRandomDirections) {
  std::mt19937_64 rng(61);
  for (int n : kSizes) {
    const SpherePartition sphere(n);
    const int directions = n <= 200 ? 5000 : 1000;
    for (int k = 0; k < directions; ++k) {
      const Eigen::Vector3d d = randomDirection(rng);
      ASSERT_EQ(sphere.region(d), bruteForceRegion(sphere, d))
          << "N = " << n << ", d = " << d.transpose();
      // Length does not matter.
      ASSERT_EQ(sphere.region(37.5 * d), sphere.region(d));
    }
  }
}

TEST(SpherePartition, RegionsWithoutAtan2AreThoseWithIt) {
  // regions() finds most longitudes' sectors without atan2; regionsByAtan2() is its reference,
  // bit for bit: random directions, directions on and within 2e-5 .. 1e-15 rad of every sector
  // edge of every collar (where regions() must fall back, or decide by its rough longitude),
  // the axes and signed zeros, in batches of 1 to 16.
  std::mt19937_64 rng(64);
  for (int n : kSizes) {
    const SpherePartition sphere(n);
    std::vector<Eigen::Vector3d> directions;
    for (int i = 0; i < 4000; ++i) directions.push_back(randomDirection(rng));
    for (int region = 0; region < n; ++region) {
      double theta0, theta1, phi0, phi1;
      sphere.bounds(region, theta0, theta1, phi0, phi1);
      const double theta = 0.5 * (theta0 + theta1);
      // Near the edges too, where the rough longitude (within 8.2e-7 rad) decides or leaves it
      // to atan2 (within 2 pi 1e-6 rad of an edge), and at random up to 2e-5 rad off them.
      std::vector<double> offsets = {0.0,     1e-15,  -1e-15,  1e-12, -1e-12, 1e-9,  -1e-9,
                                     1e-7,    -1e-7,  1e-6,    -1e-6, 3e-6,   -3e-6, 6.2e-6,
                                     -6.2e-6, 6.4e-6, -6.4e-6, 7e-6,  -7e-6,  1e-5,  -1e-5};
      for (int i = 0; i < 8; ++i) {
        offsets.push_back(std::uniform_real_distribution<double>(-2e-5, 2e-5)(rng));
      }
      for (const double offset : offsets) {
        const double phi = phi0 + offset;
        directions.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                std::cos(theta));
      }
    }
    for (const double z : {0.0, -0.0, 0.6}) {
      for (const double x : {1.0, -1.0, 0.0, -0.0}) {
        for (const double y : {1.0, -1.0, 0.0, -0.0}) directions.emplace_back(x, y, z);
      }
    }
    // Not unit, but regions() is defined for them: x and y subnormal or near the largest double
    // (left to atan2), and infinite.
    const double huge = std::numeric_limits<double>::max();
    for (const double scale : {3e-320, 1e-310, 2.3e-308, 1e300, 0.2 * huge, 0.3 * huge, huge}) {
      for (const auto& [x, y] : std::vector<std::pair<double, double>>{
               {1.0, 0.9}, {-1.0, 0.3}, {0.2, -1.0}, {-0.7, -0.75}, {1.0, 0.0}}) {
        directions.emplace_back(scale * x, scale * y, 0.1);
      }
    }
    directions.emplace_back(std::numeric_limits<double>::infinity(), 1.0, 0.0);
    directions.emplace_back(-1.0, -std::numeric_limits<double>::infinity(), 0.0);
    for (std::size_t first = 0; first < directions.size();) {
      const int lanes =
          static_cast<int>(std::min<std::size_t>(1 + rng() % 16, directions.size() - first));
      double d[48];
      for (int k = 0; k < lanes; ++k) {
        for (int a = 0; a < 3; ++a) d[a * lanes + k] = directions[first + k][a];
      }
      int out[16], expected[16];
      sphere.regions(d, lanes, out);
      for (int k = 0; k < lanes; k += 8) {
        sphere.regionsByAtan2(d + k, lanes, std::min(8, lanes - k), expected + k);
      }
      for (int k = 0; k < lanes; ++k) {
        ASSERT_EQ(out[k], expected[k])
            << "N = " << n << ", d = " << directions[first + k].transpose();
      }
      first += static_cast<std::size_t>(lanes);
    }
  }
}

TEST(SpherePartition, BatchedRegionsAgreeWithRegion) {
  // regions() reads up to 8 unit directions laid out d[a * lanes + k]; a partial batch leaves the
  // lanes past `lanes` alone.
  std::mt19937_64 rng(63);
  for (int n : kSizes) {
    const SpherePartition sphere(n);
    for (int lanes = 1; lanes <= 8; ++lanes) {
      for (int batch = 0; batch < 200; ++batch) {
        std::vector<Eigen::Vector3d> directions(lanes);
        double d[24];
        for (int k = 0; k < lanes; ++k) {
          directions[k] = randomDirection(rng);
          if (batch == 0 && k == 0) directions[k] = Eigen::Vector3d::UnitZ();
          if (batch == 0 && k == 1) directions[k] = -Eigen::Vector3d::UnitZ();
          for (int a = 0; a < 3; ++a) d[a * lanes + k] = directions[k][a];
        }
        int out[9];
        std::fill(out, out + 9, -7);
        sphere.regions(d, lanes, out);
        for (int k = 0; k < lanes; ++k) {
          ASSERT_EQ(out[k], sphere.region(directions[k]))
              << "N = " << n << ", lanes " << lanes << ", d = " << directions[k].transpose();
        }
        for (int k = lanes; k < 9; ++k) ASSERT_EQ(out[k], -7) << "lane " << k << " written";
      }
    }
  }
}

TEST(SpherePartition, UniformDirectionsFillEveryRegionEqually) {
  constexpr int kDirections = 400000;
  std::mt19937_64 rng(67);
  std::vector<Eigen::Vector3d> directions(kDirections);
  for (Eigen::Vector3d& d : directions) d = randomDirection(rng);
  for (int n : kSizes) {
    SCOPED_TRACE(n);
    const SpherePartition sphere(n);
    std::vector<int> counts(n, 0);
    for (const Eigen::Vector3d& d : directions) {
      const int region = sphere.region(d);
      ASSERT_GE(region, 0);
      ASSERT_LT(region, n);
      ++counts[region];
    }
    const double p = 1.0 / n, mean = kDirections * p;
    const double sigma = std::sqrt(kDirections * p * (1.0 - p));
    for (int i = 0; i < n; ++i) {
      ASSERT_NEAR(counts[i], mean, kSigmas * sigma + 0.5) << "region " << i;
    }
  }
}

TEST(SpherePartition, PolesAndTheLongitudeSeam) {
  for (int n : kSizes) {
    SCOPED_TRACE(n);
    const SpherePartition sphere(n);
    EXPECT_EQ(sphere.region(Eigen::Vector3d::UnitZ()), 0);
    EXPECT_EQ(sphere.region(-Eigen::Vector3d::UnitZ()), n - 1);
    EXPECT_EQ(sphere.region({0.0, 0.0, 1e-3}), sphere.region(Eigen::Vector3d::UnitZ()));
    if (n >= 2) {
      EXPECT_EQ(sphere.centre(0), Eigen::Vector3d::UnitZ());
      EXPECT_EQ(sphere.centre(n - 1), -Eigen::Vector3d::UnitZ());
    }
    // On the seam (longitude 0, +x side) a direction is in the first region of its zone; just
    // below it (longitude 2 pi - tiny) in the last one. (Colatitudes off the zone edges: pi / 2
    // is one for every even N, where acos in bruteForceRegion() cannot tell the side.)
    for (double theta : {0.3, 1.0, 1.4, 2.0, 2.9}) {
      const Eigen::Vector3d on_seam(std::sin(theta), 0.0, std::cos(theta));
      const Eigen::Vector3d negative_zero(std::sin(theta), -0.0, std::cos(theta));
      const Eigen::Vector3d below(std::sin(theta), -1e-300, std::cos(theta));
      const int region = sphere.region(on_seam);
      const Bounds b = boundsOf(sphere, region);
      EXPECT_EQ(b.phi0, 0.0) << theta;
      EXPECT_EQ(sphere.region(negative_zero), region) << theta;
      EXPECT_NEAR(boundsOf(sphere, sphere.region(below)).phi1, kFullTurn, kBinRounding) << theta;
      EXPECT_EQ(sphere.region(below), bruteForceRegion(sphere, below)) << theta;
    }
  }
}

TEST(SpherePartition, ZoneEdgesSplitDirectionsJustAboveAndBelow) {
  // A direction exactly on an edge belongs to the zone below it, as one on the seam belongs to
  // the sector east of it (half-open [theta0, theta1) x [phi0, phi1)): the equator is an edge for
  // N = 2 (hemispheres) and N = 10 (Leopardi's 1 4 4 1, so its first region below is 5).
  EXPECT_EQ(SpherePartition(2).region(Eigen::Vector3d::UnitX()), 1);
  EXPECT_EQ(SpherePartition(10).region(Eigen::Vector3d::UnitX()), 5);
  EXPECT_EQ(SpherePartition(10).region(Eigen::Vector3d(1.0, 0.0, 1e-9)), 1);

  const SpherePartition sphere(200);
  for (int i = 0; i + 1 < sphere.regions(); ++i) {
    const Bounds b = boundsOf(sphere, i), next = boundsOf(sphere, i + 1);
    if (next.theta0 == b.theta0) continue;  // same zone
    // Directions at the edge's colatitude +- 1e-9 rad, mid-longitude of the zones' first regions.
    const Eigen::Vector3d above(std::sin(b.theta1 - 1e-9), 0.0, std::cos(b.theta1 - 1e-9));
    const Eigen::Vector3d beyond(std::sin(b.theta1 + 1e-9), 0.0, std::cos(b.theta1 + 1e-9));
    EXPECT_EQ(boundsOf(sphere, sphere.region(above)).theta1, b.theta1) << i;
    EXPECT_EQ(boundsOf(sphere, sphere.region(beyond)).theta0, b.theta1) << i;
  }
}

TEST(SpherePartition, RejectsBadCountsAndRegions) {
  EXPECT_NE(test::errorOf([] { SpherePartition(0); }).find("not 0"), std::string::npos);
  EXPECT_NE(test::errorOf([] { SpherePartition(-4); }).find("-4"), std::string::npos);
  const SpherePartition sphere(12);
  EXPECT_NE(test::errorOf([&] { sphere.centre(12); }).find("no region 12 of 12"),
            std::string::npos);
  EXPECT_NE(test::errorOf([&] { sphere.centre(-1); }).find("no region -1"), std::string::npos);
  double a, b, c, d;
  EXPECT_NE(test::errorOf([&] { sphere.bounds(99, a, b, c, d); }).find("99"), std::string::npos);
}

/// A tool rotation with approach `a` and roll `roll` [rad] from the reference: x = the reference
/// turned by `roll` about a (Eigen's AngleAxis, right-handed).
Eigen::Matrix3d toolFrame(const Eigen::Vector3d& a, const Eigen::Vector3d& reference, double roll) {
  Eigen::Matrix3d R;
  R.col(2) = a;
  R.col(0) = Eigen::AngleAxisd(roll, a) * reference;
  R.col(1) = a.cross(R.col(0));
  return R;
}

TEST(OrientationBins, BinOfABinCentreIsThatBin) {
  const std::pair<int, int> kBinSizes[] = {{1, 1}, {1, 4}, {7, 3}, {50, 8}, {200, 6}, {12, 1}};
  for (const auto& [directions, rolls] : kBinSizes) {
    const OrientationBins bins(directions, rolls);
    ASSERT_EQ(bins.size(), directions * rolls);
    for (int b = 0; b < bins.size(); ++b) {
      const Eigen::Matrix3d R = bins.centre(b);
      // A rotation: orthonormal, right-handed.
      ASSERT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), kBinRounding);
      ASSERT_NEAR(R.determinant(), 1.0, kBinRounding);
      ASSERT_EQ(bins.bin(R.col(2), R.col(0)), b) << directions << " x " << rolls;
      ASSERT_EQ(b / rolls, bins.sphere().region(R.col(2)));
    }
  }
}

TEST(OrientationBins, RollBinIsTheAngleFromTheReferenceAboutTheApproach) {
  constexpr int kRolls = 8;
  const OrientationBins bins(50, kRolls);
  std::mt19937_64 rng(71);
  std::uniform_real_distribution<double> angle(0.0, kFullTurn);
  for (int k = 0; k < 5000; ++k) {
    const Eigen::Vector3d a = randomDirection(rng);
    const double roll = angle(rng);
    const Eigen::Matrix3d R = toolFrame(a, OrientationBins::rollReference(a), roll);
    const int expected_roll = static_cast<int>(std::floor(roll / (kFullTurn / kRolls)));
    ASSERT_EQ(bins.bin(R.col(2), R.col(0)), bins.sphere().region(a) * kRolls + expected_roll)
        << "roll " << roll;
  }
}

TEST(OrientationBins, TurningAboutTheApproachByOneBinMovesToTheNextRollBin) {
  std::mt19937_64 rng(73);
  for (int rolls : {2, 3, 6, 12}) {
    const OrientationBins bins(100, rolls);
    const Eigen::AngleAxisd step_about_z(kFullTurn / rolls, Eigen::Vector3d::UnitZ());
    for (int k = 0; k < 2000; ++k) {
      // A random rotation: a random approach, then a random roll.
      const Eigen::Vector3d a = randomDirection(rng);
      const Eigen::Matrix3d R =
          toolFrame(a, OrientationBins::rollReference(a),
                    std::uniform_real_distribution<double>(0, kFullTurn)(rng));
      const int b = bins.bin(R.col(2), R.col(0));
      // Turning the tool about its own approach: R * Rz(2 pi / rolls) (= Rot(a, step) * R).
      const Eigen::Matrix3d turned = R * step_about_z.toRotationMatrix();
      ASSERT_LT((turned.col(2) - a).norm(), kBinRounding);
      const int expected = (b / rolls) * rolls + (b % rolls + 1) % rolls;
      ASSERT_EQ(bins.bin(turned.col(2), turned.col(0)), expected) << "rolls " << rolls;
    }
  }
}

TEST(OrientationBins, BatchedBinsAgreeWithBin) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> angle(0.0, kFullTurn);
  for (int rolls : {1, 5}) {
    const OrientationBins bins(200, rolls);
    for (int lanes = 1; lanes <= 8; ++lanes) {
      for (int batch = 0; batch < 300; ++batch) {
        std::vector<Eigen::Matrix3d> frames(lanes);
        double approach[24], x_axis[24];
        for (int k = 0; k < lanes; ++k) {
          const Eigen::Vector3d a = randomDirection(rng);
          frames[k] = toolFrame(a, OrientationBins::rollReference(a), angle(rng));
          for (int c = 0; c < 3; ++c) {
            approach[c * lanes + k] = frames[k](c, 2);
            x_axis[c * lanes + k] = frames[k](c, 0);
          }
        }
        int out[8];
        bins.bins(approach, x_axis, lanes, out);
        for (int k = 0; k < lanes; ++k) {
          ASSERT_EQ(out[k], bins.bin(frames[k].col(2), frames[k].col(0))) << rolls << " " << lanes;
        }
      }
    }
  }
}

TEST(OrientationBins, RollsOfOneIgnoreTheRoll) {
  const OrientationBins bins(30, 1);
  const Eigen::Vector3d a = Eigen::Vector3d(0.2, -0.5, 0.7).normalized();
  for (double roll = 0.0; roll < kFullTurn; roll += 0.1) {
    const Eigen::Matrix3d R = toolFrame(a, OrientationBins::rollReference(a), roll);
    EXPECT_EQ(bins.bin(R.col(2), R.col(0)), bins.sphere().region(a));
  }
}

TEST(OrientationBins, RollReferenceIsUnitAndNormalToTheApproach) {
  const double c30 = std::cos(M_PI / 6);
  std::vector<Eigen::Vector3d> approaches = {
      Eigen::Vector3d::UnitX(),
      -Eigen::Vector3d::UnitX(),
      Eigen::Vector3d::UnitY(),
      -Eigen::Vector3d::UnitY(),
      Eigen::Vector3d::UnitZ(),
      -Eigen::Vector3d::UnitZ(),
      Eigen::Vector3d(1.0, 1e-9, -1e-9).normalized(),
      Eigen::Vector3d(-1.0, 1e-12, 0.0).normalized(),
      // 29 and 31 deg from +x, and 29 deg from -x, on both sides of the switch.
      {std::cos(29 * M_PI / 180), std::sin(29 * M_PI / 180), 0.0},
      {std::cos(31 * M_PI / 180), 0.0, std::sin(31 * M_PI / 180)},
      {-std::cos(29 * M_PI / 180), 0.0, -std::sin(29 * M_PI / 180)}};
  std::mt19937_64 rng(79);
  for (int k = 0; k < 2000; ++k) approaches.push_back(randomDirection(rng));
  for (const Eigen::Vector3d& a : approaches) {
    const Eigen::Vector3d r = OrientationBins::rollReference(a);
    ASSERT_NEAR(r.norm(), 1.0, kBinRounding) << a.transpose();
    ASSERT_NEAR(r.dot(a), 0.0, kBinRounding) << a.transpose();
    // The documented rule: world x projected onto the plane normal to a, or world y within
    // 30 deg of +-x; the projection keeps the positive side of that axis.
    const Eigen::Vector3d axis =
        std::abs(a.x()) > c30 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX();
    const Eigen::Vector3d projected = axis - axis.dot(a) * a;
    ASSERT_GT(projected.norm(), 0.49) << a.transpose();  // never degenerate
    ASSERT_LT((r - projected.normalized()).norm(), kBinRounding) << a.transpose();
  }
  // Hand-worked: approach +z -> reference +x; approach +x -> reference +y; approach
  // (1, 0, 1)/sqrt 2 (45 deg from x) -> x projected: (1/2, 0, -1/2), normalised (1, 0, -1)/sqrt 2.
  EXPECT_LT(
      (OrientationBins::rollReference(Eigen::Vector3d::UnitZ()) - Eigen::Vector3d::UnitX()).norm(),
      kBinRounding);
  EXPECT_LT(
      (OrientationBins::rollReference(Eigen::Vector3d::UnitX()) - Eigen::Vector3d::UnitY()).norm(),
      kBinRounding);
  EXPECT_LT((OrientationBins::rollReference(Eigen::Vector3d(1, 0, 1).normalized()) -
             Eigen::Vector3d(1, 0, -1).normalized())
                .norm(),
            kBinRounding);
}

TEST(OrientationBins, RejectsBadCountsAndBins) {
  EXPECT_NE(test::errorOf([] { OrientationBins(0, 1); }).find("not 0"), std::string::npos);
  const std::string rolls = test::errorOf([] { OrientationBins(10, 0); });
  EXPECT_NE(rolls.find("roll"), std::string::npos) << rolls;
  EXPECT_NE(rolls.find("not 0"), std::string::npos) << rolls;
  EXPECT_NE(test::errorOf([] { OrientationBins(10, -3); }).find("-3"), std::string::npos);
  const OrientationBins bins(10, 3);
  EXPECT_NE(test::errorOf([&] { bins.centre(30); }).find("no bin 30 of 30"), std::string::npos);
  EXPECT_NE(test::errorOf([&] { bins.centre(-1); }).find("no bin -1"), std::string::npos);
}

}  // namespace
}  // namespace mcws
