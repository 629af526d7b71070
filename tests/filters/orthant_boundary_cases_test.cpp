// The orthant boundary filter on small and degenerate clouds, its settings and their checks, and
// the angular bins of its sector prefilter (the rest is in orthant_boundary_test.cpp).
#include "mcws/filters/orthant_boundary.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "filters/orthant_boundary_fixture.h"
#include "mcws/core/counter_rng.h"
#include "mcws/core/error.h"
#include "mcws/filters/impl/orthant_boundary.hpp"
#include "mcws/sampling/sampler.h"

namespace mcws {
namespace {

using test::kEveryFrameSet;
using test::paperTestOnly;
using ::testing::HasSubstr;

TEST(OrthantBoundary, AngleBinsFollowTheAngle) {
  // Brute force against atan2 in double: every direction's bin holds its angle, up to the error
  // the quick sector test allows for.
  const double width = 2 * M_PI / orthant::kAngleBins;
  for (int k = 0; k < 200000; ++k) {
    const double t = 2 * M_PI * (k + 0.37) / 200000.0;
    const float scale = k % 3 == 0 ? 1e-3f : (k % 3 == 1 ? 1.0f : 1e4f);
    const float x = scale * static_cast<float>(std::cos(t)),
                y = scale * static_cast<float>(std::sin(t));
    double angle = std::atan2(static_cast<double>(y), static_cast<double>(x));
    if (angle < 0) angle += 2 * M_PI;
    const unsigned bin = orthant::angleBin(x, y);
    ASSERT_LT(bin, static_cast<unsigned>(orthant::kAngleBins));
    const double lo = bin * width - orthant::kAngleError,
                 hi = (bin + 1) * width + orthant::kAngleError;
    const bool inside = (angle >= lo && angle <= hi) ||
                        (bin == 0 && angle >= 2 * M_PI - orthant::kAngleError) ||
                        (bin == orthant::kAngleBins - 1 && angle <= orthant::kAngleError);
    ASSERT_TRUE(inside) << "x " << x << " y " << y << " angle " << angle << " bin " << bin;
  }
  for (float x : {1.0f, -1.0f, 0.0f}) {  // the axes and diagonals
    for (float y : {1.0f, -1.0f, 0.0f}) {
      if (x == 0 && y == 0) continue;
      double angle = std::atan2(y, x);
      if (angle < 0) angle += 2 * M_PI;
      const double bin = orthant::angleBin(x, y);
      EXPECT_LE(std::fabs(bin * width - angle) - orthant::kAngleError, width + 1e-9)
          << x << "," << y;
    }
  }
}

TEST(OrthantBoundary, DegenerateClouds) {
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  OrthantBoundary<pcl::PointXYZ> filter;
  paperTestOnly(filter);
  filter.setPlane(BoundaryPlane::kXY);
  filter.setAutoRadius(0.0);
  filter.setInputCloud(cloud);
  pcl::Indices kept;
  filter.filter(kept);
  EXPECT_TRUE(kept.empty());  // empty in, empty out
  cloud->push_back(pcl::PointXYZ(1, 2, 3));
  filter.filter(kept);
  EXPECT_EQ(kept.size(), 1u);  // a lonely point is a boundary point
  cloud->resize(100, pcl::PointXYZ(1, 2, 3));
  filter.filter(kept);
  EXPECT_EQ(kept.size(), 100u);  // identical points: each is alone
}

TEST(OrthantBoundary, CopiesOfAPointGetItsAnswer) {
  const auto disk = sampleCloud(ShapeSampler(Shape::kDisk, 9), 5000, 0);
  auto once = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  pcl::copyPointCloud(disk, *once);
  auto thrice = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  for (int copy = 0; copy < 3; ++copy) *thrice += *once;
  pcl::Indices kept_once, kept_thrice;
  for (auto [cloud, kept] : {std::pair{once, &kept_once}, std::pair{thrice, &kept_thrice}}) {
    OrthantBoundary<pcl::PointXYZ> filter;
    filter.setInputCloud(cloud);
    filter.setPlane(BoundaryPlane::kXY);
    filter.setAdaptiveRadius(24, 2.0);  // copies must not shrink the k-th neighbour distance
    filter.filter(*kept);
  }
  ASSERT_EQ(kept_thrice.size(), 3 * kept_once.size());
  for (std::size_t k = 0; k < kept_once.size(); ++k) {
    EXPECT_EQ(kept_thrice[k], kept_once[k]);
    EXPECT_EQ(kept_thrice[2 * kept_once.size() + k], kept_once[k] + 10000);
  }
}

TEST(OrthantBoundary, ALonelyPointIsBoundaryInEveryFrame) {
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  cloud->push_back(pcl::PointXYZ(0, 0, 0));
  cloud->push_back(pcl::PointXYZ(10, 0, 0));
  for (const OrthantFrames frames : kEveryFrameSet) {
    OrthantBoundary<pcl::PointXYZ> filter;
    filter.setInputCloud(cloud);
    filter.setRadiusSearch(1.0);
    filter.setFrames(frames);
    pcl::Indices kept;
    filter.filter(kept);
    EXPECT_EQ(kept.size(), 2u) << "frames " << frames.bits();
  }
}

TEST(OrthantBoundary, DefaultConstructedFilterUsesTheRecommendedSettings) {
  // The documented recommendation, written out by hand, against what the filter does untouched.
  struct Case {
    Shape shape;
    BoundaryPlane plane;
    int k;
    double hull_depth;
  };
  for (const Case c : {Case{Shape::kAnnulus, BoundaryPlane::kXY, 24, 1.0},
                       Case{Shape::kBall, BoundaryPlane::k3D, 16, 0.0}}) {
    const auto cloud = std::make_shared<pcl::PointCloud<WorkspacePoint>>(
        sampleCloud(ShapeSampler(c.shape, 12), 20000, 0));
    OrthantBoundary<WorkspacePoint> untouched;
    untouched.setPlane(c.plane);
    EXPECT_EQ(untouched.getRadiusMode(), RadiusMode::kAdaptive);
    EXPECT_EQ(untouched.getAdaptiveNeighbours(), c.k);
    EXPECT_DOUBLE_EQ(untouched.getMinimumGap(), 92.0 * M_PI / 180.0);
    EXPECT_DOUBLE_EQ(untouched.getHullDepth(), c.hull_depth);
    EXPECT_TRUE(untouched.getFrames().empty());
    OrthantBoundary<WorkspacePoint> by_hand;
    by_hand.setPlane(c.plane);
    by_hand.setAdaptiveRadius(c.k, 2.0);
    by_hand.setMinimumGap(92.0 * M_PI / 180.0);
    by_hand.setHullDepth(c.hull_depth);
    by_hand.setFrames(c.plane == BoundaryPlane::k3D ? OrthantFrame::kAxis | OrthantFrame::kOutward
                                                    : OrthantFrame::kAnyRotation);
    pcl::Indices kept[2];
    untouched.setInputCloud(cloud);
    untouched.filter(kept[0]);
    by_hand.setInputCloud(cloud);
    by_hand.filter(kept[1]);
    EXPECT_EQ(kept[0], kept[1]);
    EXPECT_GT(kept[0].size(), 0u);
    EXPECT_DOUBLE_EQ(untouched.usedRadius(), by_hand.usedRadius());
  }
}

TEST(OrthantBoundary, RejectsBadParameters) {
  const auto cloud =
      std::make_shared<pcl::PointCloud<pcl::PointXYZ>>(10, 1, pcl::PointXYZ(0, 0, 0));
  auto message = [&](auto configure) {
    OrthantBoundary<pcl::PointXYZ> filter;
    filter.setInputCloud(cloud);
    configure(filter);
    pcl::Indices kept;
    try {
      filter.filter(kept);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(message([](auto& f) { f.setRadiusSearch(0.0); }),
              HasSubstr("radius 0 must be a positive number"));
  EXPECT_THAT(message([](auto& f) { f.setRadiusSearch(-1.0); }),
              HasSubstr("radius -1 must be a positive number"));
  EXPECT_THAT(message([](auto& f) {
                f.setRadiusSearch(2.0);
                f.setOuterRadius(1.0);
              }),
              HasSubstr("outer radius 1 is smaller than radius 2"));
  EXPECT_THAT(message([](auto& f) { f.setAutoRadius(-2.0); }),
              HasSubstr("radius factor -2 must be 0 (automatic) or a positive number"));
  EXPECT_THAT(message([](auto& f) { f.setAdaptiveRadius(0, 2.0); }),
              HasSubstr("adaptive k must be at least 1"));
  EXPECT_THAT(message([](auto& f) { f.setAdaptiveRadius(8, -2.0); }),
              HasSubstr("adaptive radius scale must be a positive number"));
  EXPECT_THAT(
      message([](auto& f) {
        f.setAdaptiveRadius(8, 2.0);
        f.setOuterRadius(0.5);
      }),
      HasSubstr("outer radius is a factor of each point's radius and must exceed 1, not 0.5"));
  EXPECT_THAT(message([](auto& f) {
                f.setPlane(BoundaryPlane::kXY);
                f.setAutoRadius(0.0);
                f.setHullDepth(-1.0);
              }),
              HasSubstr("hull depth must be 0 (off) or a positive number of spacings"));
  EXPECT_THAT(message([](auto& f) {
                f.setPlane(BoundaryPlane::kXY);
                f.setAutoRadius(0.0);
                f.setHullDepth(std::numeric_limits<double>::quiet_NaN());
              }),
              HasSubstr("hull depth must be 0 (off) or a positive number of spacings"));
  EXPECT_THAT(message([](auto& f) {
                f.setAutoRadius(0.0);
                f.setHullDepth(1.0);
              }),
              HasSubstr("the hull depth test works in a plane"));
  EXPECT_THROW(parseBoundaryPlane("xw"), Error);
}

/// The largest angle [rad] between circularly consecutive directions to the neighbours, from
/// their atan2 angles in double (2 pi when fewer than two directions).
double largestAngularGap(const std::vector<Neighbour>& neighbours) {
  std::vector<double> angles;
  for (const Neighbour& q : neighbours) {
    if (q.x != 0.0f || q.y != 0.0f) angles.push_back(std::atan2(double{q.y}, double{q.x}));
  }
  if (angles.size() < 2) return 2 * M_PI;
  std::sort(angles.begin(), angles.end());
  double largest = angles.front() + 2 * M_PI - angles.back();
  for (std::size_t k = 1; k < angles.size(); ++k) {
    largest = std::max(largest, angles[k] - angles[k - 1]);
  }
  return largest;
}

Neighbour neighbourAt(double angle, double radius) {
  return Neighbour(static_cast<float>(radius * std::cos(angle)),
                   static_cast<float>(radius * std::sin(angle)), 0.0f,
                   static_cast<float>(radius * radius), 0);
}

TEST(EmptySector, TheBinnedPrefilterAgreesWithTheAnglesOnRandomAndWorstCaseNeighbourhoods) {
  // The sector test first rejects points by 64 angular bins, then decides the rest exactly.
  // Whatever the bins reject must truly have no empty sector of the gap: compared with the
  // largest gap between the neighbours' atan2 angles, on random neighbourhoods and on ones
  // built with a single empty arc just wider or just narrower than the gap, at random rotations
  // (a bin's limit one too lenient rejects some of the wider ones).
  const CounterRng rng(5);
  std::uint64_t draw = 0;
  const auto uniform = [&] { return rng.uniform(draw++, 0); };
  std::vector<orthant::Direction> scratch;
  for (const double degrees : {90.0, 92.0, 100.0, 135.0}) {
    const double gap = degrees * M_PI / 180.0;
    const orthant::SectorGap sector = orthant::sectorGap(gap);
    int random_with_gap = 0;
    for (int trial = 0; trial < 3000; ++trial) {
      std::vector<Neighbour> neighbours;
      const int m = 2 + trial % 24;
      for (int k = 0; k < m; ++k) {
        neighbours.push_back(neighbourAt(2 * M_PI * uniform(), 0.5 + 1.5 * uniform()));
      }
      const double largest = largestAngularGap(neighbours);
      if (std::abs(largest - gap) < 1e-6) continue;  // too close to call in float directions
      random_with_gap += largest > gap;
      ASSERT_EQ(orthant::hasEmptySector(neighbours, sector, scratch), largest > gap)
          << degrees << " deg, trial " << trial << ", largest gap " << largest;
    }
    EXPECT_GT(random_with_gap, 100) << degrees;
    for (int trial = 0; trial < 2000; ++trial) {
      const double width =
          gap + (trial % 2 ? 1.0 : -1.0) * (0.05 + 0.45 * (trial % 5) / 4.0) * M_PI / 180.0;
      const double start = 2 * M_PI * uniform();
      std::vector<Neighbour> neighbours = {neighbourAt(start, 1.0),
                                           neighbourAt(start + width, 1.3)};
      for (double a = start + width + 0.035; a < start + 2 * M_PI - 0.02; a += 0.035) {
        neighbours.push_back(neighbourAt(a, 0.5 + uniform()));
      }
      ASSERT_EQ(orthant::hasEmptySector(neighbours, sector, scratch), width > gap)
          << degrees << " deg, empty arc " << width * 180.0 / M_PI << " deg at "
          << start * 180.0 / M_PI;
    }
  }
}

}  // namespace
}  // namespace mcws
