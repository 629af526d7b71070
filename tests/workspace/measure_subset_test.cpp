// delaunayMeasureSubset: a subset of a cloud (the collision-free samples of a cloud sampled with
// collision checking) measured within the whole cloud's triangulation never exceeds the whole
// cloud's measure, where measuring it on its own can.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/sampling/sampler.h"
#include "mcws/workspace/measure.h"
#include "workspace/shape_cloud.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

/// Every `keep`-th of `n` points flagged: a thinning spread evenly over the region, as collisions
/// thin an arm's reach inside.
std::vector<char> everyKth(std::size_t n, std::size_t keep) {
  std::vector<char> flags(n, 0);
  for (std::size_t i = 0; i < n; i += keep) flags[i] = 1;
  return flags;
}

pcl::PointCloud<pcl::PointXYZ> subsetOf(const pcl::PointCloud<pcl::PointXYZ>& cloud,
                                        const std::vector<char>& flags) {
  pcl::PointCloud<pcl::PointXYZ> out;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (flags[i]) out.push_back(cloud[i]);
  }
  return out;
}

constexpr float kGap = 0.2f;

/// Two unit squares side by side, kGap apart ([0, 1] and [1.2, 2.2] along x, [0, 1] along y),
/// sampled uniformly: area 2.
pcl::PointCloud<pcl::PointXYZ> twoSquares(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  pcl::PointCloud<pcl::PointXYZ> cloud;
  for (std::size_t i = 0; i < n; ++i) {
    const float x = unit(random), y = unit(random);
    cloud.push_back(pcl::PointXYZ(i % 2 ? x + 1.0f + kGap : x, y, 0.f));
  }
  return cloud;
}

// The bug: two squares 0.2 apart, 20000 points (spacing 0.01: the alpha limit, 3 local spacings,
// bridges no gap of 0.2) and every ninth of them (spacing 0.03: its alpha limit bridges the gap).
// Measured on its own the subset's area comes out above the whole's, by the gap it bridges.
// Measured within the whole cloud's triangulation it is at most the whole's, and still the two
// squares' area.
TEST(DelaunayMeasureSubset, ASparseSubsetNoLongerBridgesWhatTheWholeCloudDoesNot) {
  const pcl::PointCloud<pcl::PointXYZ> cloud = twoSquares(20000, 7);
  const std::vector<char> flags = everyKth(cloud.size(), 9);
  const double alone = delaunayMeasure(subsetOf(cloud, flags), 2).measure;
  const double whole = delaunayMeasure(cloud, 2).measure;
  EXPECT_GT(alone, whole * 1.05);  // the old way: the subset bridges the gap (2.2 against 2.0)
  EXPECT_NEAR(whole, 2.0, 0.004);

  const SubsetMeasure m = delaunayMeasureSubset(cloud, flags, 2, MeasureOptions());
  EXPECT_LE(m.measure, m.all.measure);
  EXPECT_NEAR(m.all.measure, whole, 1e-9 * whole);  // every point triangulated: the same
  EXPECT_NEAR(m.measure, 2.0, 0.016);  // 0.5 % low with a ninth of the points: their band
  EXPECT_EQ(m.points, 2223u);
  EXPECT_GT(m.outside, 0.0);
  EXPECT_LE(m.outside, static_cast<double>(m.all.outside));
  EXPECT_NEAR(m.unit_share, m.all.measure / m.all.points, 1e-12 * m.unit_share);
}

// A ball thinned evenly (as collisions thin an arm's reach inside): the subset samples the whole
// ball, so its measure is the ball's, at most the whole cloud's; the subset of every point is the
// whole cloud, to the last bit.
TEST(DelaunayMeasureSubset, AnEvenlyThinnedBallMeasuresTheBall) {
  const pcl::PointCloud<pcl::PointXYZ> cloud = test::shapeCloud(Shape::kBall, 20000, 3);
  const SubsetMeasure thinned =
      delaunayMeasureSubset(cloud, everyKth(cloud.size(), 3), 3, MeasureOptions());
  EXPECT_LE(thinned.measure, thinned.all.measure);
  EXPECT_NEAR(thinned.all.measure / shapeMeasure(Shape::kBall), 1.0, 0.006);
  EXPECT_NEAR(thinned.measure / shapeMeasure(Shape::kBall), 1.0, 0.01);

  const SubsetMeasure every =
      delaunayMeasureSubset(cloud, std::vector<char>(cloud.size(), 1), 3, MeasureOptions());
  EXPECT_EQ(every.measure, every.all.measure);
  EXPECT_EQ(every.outside, static_cast<double>(every.all.outside));
  EXPECT_EQ(every.points, every.all.points);
}

// A subset that ends inside the whole cloud: the half disk x < 0 of a uniform disk. Its edge
// along the cut is counted by the straddling triangles' shares; the result is the half disk's
// area within a percent, never above the whole's.
TEST(DelaunayMeasureSubset, HalfADiskMeasuresHalfTheArea) {
  const pcl::PointCloud<pcl::PointXYZ> cloud = test::shapeCloud(Shape::kDisk, 20000, 5);
  std::vector<char> left(cloud.size(), 0);
  for (std::size_t i = 0; i < cloud.size(); ++i) left[i] = cloud[i].x < 0.f;
  const SubsetMeasure m = delaunayMeasureSubset(cloud, left, 2, MeasureOptions());
  EXPECT_NEAR(m.measure / (M_PI / 2.0), 1.0, 0.01);
  EXPECT_LE(m.measure, m.all.measure);
  // Without the edge correction: the kept triangles' shares only.
  MeasureOptions raw;
  raw.edge_correction = false;
  const SubsetMeasure r = delaunayMeasureSubset(cloud, left, 2, raw);
  EXPECT_EQ(r.measure, r.uncorrected);
  EXPECT_EQ(r.all.measure, r.all.uncorrected);
  EXPECT_EQ(r.outside, 0.0);
  EXPECT_LT(r.measure, m.measure);
}

TEST(DelaunayMeasureSubset, RejectsBadFlagsAndTooSmallSubsets) {
  const pcl::PointCloud<pcl::PointXYZ> cloud = test::shapeCloud(Shape::kDisk, 1000, 1);
  try {
    delaunayMeasureSubset(cloud, std::vector<char>(999, 1), 2, MeasureOptions());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("subset flags: 999 for 1000 points"));
  }
  std::vector<char> few(cloud.size(), 0);
  for (std::size_t i = 0; i < 5; ++i) few[i] = 1;
  try {
    delaunayMeasureSubset(cloud, few, 2, MeasureOptions());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("the subset has 5 distinct points, too few to measure"));
  }
}

}  // namespace
}  // namespace mcws
