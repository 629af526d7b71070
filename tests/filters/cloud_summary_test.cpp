// The summary the boundary and measure tools check a cloud with (summarizeCloud): counts, extents
// and distinct positions against a brute-force count, the cap on counting, and the spacing only
// when asked for.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <set>

#include "mcws/core/error.h"
#include "mcws/filters/boundary_geometry.h"

namespace mcws {
namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

/// Distinct finite positions of `cloud` in `plane`, by a std::set of the projected coordinates.
std::size_t bruteForceDistinct(const Cloud& cloud, BoundaryPlane plane) {
  std::set<std::array<float, 3>> seen;
  for (const auto& p : cloud) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
    const std::array<float, 3> xyz{p.x + 0.0f, p.y + 0.0f, p.z + 0.0f};
    if (plane == BoundaryPlane::k3D) {
      seen.insert(xyz);
    } else {
      const std::array<int, 2> axes = planeAxes(plane);
      seen.insert({xyz[axes[0]], xyz[axes[1]], 0.0f});
    }
  }
  return seen.size();
}

TEST(CloudSummary, CountsFinitePointsAndDistinctPositionsInThePlane) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  Cloud cloud;
  cloud.emplace_back(0.0f, 0.0f, 0.0f);
  cloud.emplace_back(-0.0f, 5.0f, 0.0f);  // the same x-z position as the first (-0 is 0)
  cloud.emplace_back(1.0f, 2.0f, 3.0f);
  cloud.emplace_back(1.0f, 2.0f, 3.0f);  // a copy
  cloud.emplace_back(nan, 0.0f, 0.0f);
  cloud.emplace_back(2.0f, -1.0f, 0.5f);
  for (const BoundaryPlane plane :
       {BoundaryPlane::k3D, BoundaryPlane::kXY, BoundaryPlane::kXZ, BoundaryPlane::kYZ}) {
    const CloudSummary s = summarizeCloud(cloud, plane);
    EXPECT_EQ(s.points, 6u);
    EXPECT_EQ(s.finite, 5u);
    EXPECT_EQ(s.distinct, bruteForceDistinct(cloud, plane)) << boundaryPlaneName(plane);
    EXPECT_EQ(s.extent, Eigen::Vector3d(2.0, 6.0, 3.0));
    EXPECT_FALSE(s.spacing.has_value());
  }
  // By hand: x-z positions (0, 0), (1, 3), (2, 0.5); x-y: (0, 0), (0, 5), (1, 2), (2, -1).
  EXPECT_EQ(summarizeCloud(cloud, BoundaryPlane::kXZ).distinct, 3u);
  EXPECT_EQ(summarizeCloud(cloud, BoundaryPlane::kXY).distinct, 4u);
  EXPECT_EQ(summarizeCloud(cloud, BoundaryPlane::kXZ).largest, 3.0);  // z; y is not in the plane
  EXPECT_EQ(summarizeCloud(cloud, BoundaryPlane::k3D).largest, 6.0);
}

TEST(CloudSummary, StopsCountingDistinctPositionsAtTheCap) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  Cloud cloud;
  for (int i = 0; i < 5000; ++i) cloud.emplace_back(u(rng), u(rng), u(rng));
  ASSERT_EQ(bruteForceDistinct(cloud, BoundaryPlane::k3D), 5000u);
  EXPECT_EQ(summarizeCloud(cloud, BoundaryPlane::k3D).distinct, kDistinctCounted);
  // Below the cap the count is exact: 1000 positions, each five times.
  Cloud copies;
  for (int k = 0; k < 5; ++k) {
    for (int i = 0; i < 1000; ++i) copies.push_back(cloud[i]);
  }
  EXPECT_EQ(summarizeCloud(copies, BoundaryPlane::k3D).distinct, 1000u);
}

TEST(CloudSummary, SpacingOnlyWhenAskedForAndThatOfTheDistinctPositions) {
  // A 100 x 100 grid of spacing 0.5 in the x-z plane, every point twice: spacing 0.5 (the copies
  // do not halve the area per point), within meanSpacing's few % of occupied-cell estimate.
  Cloud cloud;
  for (int copy = 0; copy < 2; ++copy) {
    for (int i = 0; i < 100; ++i) {
      for (int j = 0; j < 100; ++j) cloud.emplace_back(0.5f * i, 1.0f, 0.5f * j);
    }
  }
  const CloudSummary counts = summarizeCloud(cloud, BoundaryPlane::kXZ);
  EXPECT_FALSE(counts.spacing.has_value());
  EXPECT_THROW(parameterLengths(counts), Error);
  const CloudSummary full = summarizeCloud(cloud, BoundaryPlane::kXZ, SummaryDetail::kSpacing);
  ASSERT_TRUE(full.spacing.has_value());
  EXPECT_NEAR(*full.spacing, 0.5, 0.05 * 0.5);
  EXPECT_DOUBLE_EQ(parameterLengths(full).min, kShortestLengthSpacings * *full.spacing);
  EXPECT_DOUBLE_EQ(parameterLengths(full).max, 49.5);
}

}  // namespace
}  // namespace mcws
