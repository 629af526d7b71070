// The orthant boundary filter on grids and sampled shapes: exact rims, precision and recall, the
// hull-depth stage, thread counts and the grid search (small and degenerate clouds, settings and
// the sector prefilter are in orthant_boundary_cases_test.cpp).
#include "mcws/filters/orthant_boundary.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "filters/orthant_boundary_fixture.h"
#include "mcws/core/counter_rng.h"
#include "mcws/core/error.h"
#include "mcws/filters/impl/orthant_boundary.hpp"
#include "mcws/sampling/sampler.h"

namespace mcws {
namespace {

// The goals for boundary quality on the validation shapes.
constexpr double kMinPrecision = 0.99;
constexpr double kMinRecall = 0.97;

using test::kEveryFrameSet;
using test::paperTestOnly;

template <typename PointT>
typename pcl::PointCloud<PointT>::Ptr gridCloud(int n, int dimensions) {
  auto cloud = std::make_shared<pcl::PointCloud<PointT>>();
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      for (int k = 0; k < (dimensions == 3 ? n : 1); ++k) {
        PointT p;
        p.x = static_cast<float>(i);
        p.y = static_cast<float>(j);
        p.z = static_cast<float>(k);
        cloud->push_back(p);
      }
    }
  }
  return cloud;
}

bool onGridRim(const pcl::PointXYZ& p, int n, int dimensions) {
  auto edge = [&](float v) { return v == 0.0f || v == static_cast<float>(n - 1); };
  return edge(p.x) || edge(p.y) || (dimensions == 3 && edge(p.z));
}

template <typename PointT>
class OrthantBoundaryTyped : public ::testing::Test {};
using OrthantPointTypes = ::testing::Types<pcl::PointXYZ, WorkspacePoint>;
TYPED_TEST_SUITE(OrthantBoundaryTyped, OrthantPointTypes);

TYPED_TEST(OrthantBoundaryTyped, KeepsExactlyTheRimOfASquareGridInEveryFrame) {
  constexpr int n = 21;
  const auto cloud = gridCloud<TypeParam>(n, 2);
  for (const OrthantFrames frames : kEveryFrameSet) {
    OrthantBoundary<TypeParam> filter;
    paperTestOnly(filter);
    filter.setInputCloud(cloud);
    filter.setPlane(BoundaryPlane::kXY);
    filter.setRadiusSearch(1.5);  // the 8 grid neighbours
    filter.setFrames(frames);
    pcl::Indices kept;
    filter.filter(kept);
    EXPECT_EQ(kept.size(), static_cast<std::size_t>(4 * (n - 1))) << "frames " << frames.bits();
    for (const auto i : kept) {
      const auto& p = (*cloud)[i];
      EXPECT_TRUE(onGridRim(pcl::PointXYZ(p.x, p.y, p.z), n, 2)) << p.x << "," << p.y;
    }
  }
}

TYPED_TEST(OrthantBoundaryTyped, HullDepthKeepsExactlyTheRimOfASquareGrid) {
  // One row in, a point lies one spacing inside the hull of its neighbours, whose local spacing
  // sqrt(area / count) is below one (4 / 9 with radius 1.5; less than 1 with the adaptive
  // radius too, because a hull has fewer points on its edge than inside).
  constexpr int n = 21;
  const auto cloud = gridCloud<TypeParam>(n, 2);
  for (const double radius : {1.5, 0.0}) {
    OrthantBoundary<TypeParam> filter;
    filter.setMinimumGap(M_PI / 2);
    filter.setInputCloud(cloud);
    filter.setPlane(BoundaryPlane::kXY);
    if (radius > 0) {
      filter.setRadiusSearch(radius);
    } else {
      filter.setAdaptiveRadius(24, 2.0);
    }
    filter.setHullDepth(1.0);
    pcl::Indices kept;
    filter.filter(kept);
    EXPECT_EQ(kept.size(), static_cast<std::size_t>(4 * (n - 1))) << "radius " << radius;
    for (const auto i : kept) {
      const auto& p = (*cloud)[i];
      EXPECT_TRUE(onGridRim(pcl::PointXYZ(p.x, p.y, p.z), n, 2)) << p.x << "," << p.y;
    }
  }
}

TEST(OrthantBoundary, KeepsExactlyTheRimOfAnOffsetGridWithInexactCoordinates) {
  // Spacing 0.1: coordinates are not exact in float, so exactly collinear
  // directions must still be ordered exactly (a float pseudo-angle once misordered them).
  constexpr int n = 60;
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) cloud->push_back(pcl::PointXYZ(0.1f * i, 0.1f * j, 0));
  }
  for (double gap_degrees : {90.0, 92.0}) {
    OrthantBoundary<pcl::PointXYZ> filter;
    filter.setInputCloud(cloud);
    filter.setPlane(BoundaryPlane::kXY);
    filter.setAdaptiveRadius(24, 2.0);  // many collinear directions
    filter.setMinimumGap(gap_degrees * M_PI / 180.0);
    filter.setHullDepth(0.0);
    pcl::Indices kept;
    filter.filter(kept);
    EXPECT_EQ(kept.size(), static_cast<std::size_t>(4 * (n - 1))) << gap_degrees;
  }
}

TYPED_TEST(OrthantBoundaryTyped, KeepsExactlyTheSurfaceOfACubeGrid) {
  constexpr int n = 7;
  const auto cloud = gridCloud<TypeParam>(n, 3);
  OrthantBoundary<TypeParam> filter;
  filter.setInputCloud(cloud);
  filter.setRadiusSearch(1.8);  // the 26 grid neighbours
  pcl::Indices kept;
  filter.filter(kept);
  EXPECT_EQ(kept.size(), static_cast<std::size_t>(n * n * n - (n - 2) * (n - 2) * (n - 2)));
  for (const auto i : kept) {
    const auto& p = (*cloud)[i];
    EXPECT_TRUE(onGridRim(pcl::PointXYZ(p.x, p.y, p.z), n, 3));
  }
}

TYPED_TEST(OrthantBoundaryTyped, KeptAndRemovedPartitionTheInputAndNaNIsAlwaysRemoved) {
  auto cloud = std::make_shared<pcl::PointCloud<TypeParam>>();
  pcl::copyPointCloud(sampleCloud(ShapeSampler(Shape::kDisk, 3), 20000, 2), *cloud);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  (*cloud)[5].x = nan;
  (*cloud)[77].z = nan;
  pcl::Indices positive_removed;
  for (bool negative : {false, true}) {
    OrthantBoundary<TypeParam> filter(true);
    paperTestOnly(filter);
    filter.setInputCloud(cloud);
    filter.setPlane(BoundaryPlane::kXY);
    filter.setAdaptiveRadius(24, 2.0);
    filter.setNegative(negative);
    pcl::Indices kept;
    filter.filter(kept);
    const auto& removed = *filter.getRemovedIndices();
    EXPECT_EQ(kept.size() + removed.size(), cloud->size());
    pcl::Indices all = kept;
    all.insert(all.end(), removed.begin(), removed.end());
    std::sort(all.begin(), all.end());
    for (std::size_t i = 0; i < all.size(); ++i) ASSERT_EQ(all[i], static_cast<pcl::index_t>(i));
    EXPECT_EQ(std::count(kept.begin(), kept.end(), 5), 0);
    EXPECT_EQ(std::count(kept.begin(), kept.end(), 77), 0);
    if (negative) {
      // The interior is exactly what positive mode removed, less the two NaN points.
      pcl::Indices expected;
      for (const auto i : positive_removed) {
        if (i != 5 && i != 77) expected.push_back(i);
      }
      EXPECT_EQ(kept, expected);
      EXPECT_GT(kept.size(), 19000u);
    } else {
      EXPECT_LT(kept.size(), 1000u);  // the rim
      positive_removed = removed;
    }
  }
}

struct Quality {
  double precision, recall;
};

/// Precision and recall as the issue defines them: reported points within two mean spacings of
/// the true boundary, points within half a spacing that are reported.
Quality quality(Shape shape, std::size_t n, const pcl::Indices& kept,
                const pcl::PointCloud<WorkspacePoint>& cloud) {
  const double h = std::pow(shapeMeasure(shape) / n, shapeIsPlanar(shape) ? 0.5 : 1.0 / 3.0);
  std::vector<char> reported(cloud.size(), 0);
  std::size_t close = 0;
  for (const auto i : kept) {
    reported[i] = 1;
    close += shapeBoundaryDistance(shape, cloud[i].getVector3fMap().cast<double>()) <= 2.0 * h;
  }
  std::size_t near = 0, found = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (shapeBoundaryDistance(shape, cloud[i].getVector3fMap().cast<double>()) <= 0.5 * h) {
      ++near;
      found += reported[i];
    }
  }
  return {static_cast<double>(close) / kept.size(), static_cast<double>(found) / near};
}

/// The recommended settings without the hull-depth stage: the sector (2-D) or octant (3-D) test.
Quality runOnShape(Shape shape, std::size_t n, std::uint64_t seed) {
  const auto cloud = std::make_shared<pcl::PointCloud<WorkspacePoint>>(
      sampleCloud(ShapeSampler(shape, seed), n, 0));
  OrthantBoundary<WorkspacePoint> filter;
  filter.setInputCloud(cloud);
  filter.setPlane(shapeIsPlanar(shape) ? BoundaryPlane::kXY : BoundaryPlane::k3D);
  filter.setHullDepth(0.0);
  pcl::Indices kept;
  filter.filter(kept);
  return quality(shape, n, kept, *cloud);
}

TEST(OrthantBoundary, MeetsPrecisionAndRecallOnDiskAnnulusAndBall) {
  for (std::uint64_t seed : {1, 2}) {
    const Quality disk = runOnShape(Shape::kDisk, 100000, seed);
    EXPECT_GE(disk.precision, kMinPrecision);
    EXPECT_GE(disk.recall, kMinRecall);
    const Quality annulus = runOnShape(Shape::kAnnulus, 100000, seed);
    EXPECT_GE(annulus.precision, kMinPrecision);
    EXPECT_GE(annulus.recall, kMinRecall);
    const Quality ball = runOnShape(Shape::kBall, 50000, seed);
    EXPECT_GE(ball.precision, kMinPrecision);
    EXPECT_GE(ball.recall, kMinRecall);
  }
}

TEST(OrthantBoundary, HullDepthFindsEveryPointNearTheBoundaryAndNoneDeeper) {
  // The peers on a 1e6 disk reach precision 0.998 (plain quadrant test) and recall 0.984
  // (pcl::BoundaryEstimation); with the hull depth both are 1 on these clouds (BENCHMARKS.md).
  for (const Shape shape : {Shape::kDisk, Shape::kAnnulus}) {
    constexpr std::size_t n = 100000;
    const auto cloud = std::make_shared<pcl::PointCloud<WorkspacePoint>>(
        sampleCloud(ShapeSampler(shape, 3), n, 0));
    OrthantBoundary<WorkspacePoint> filter;  // the recommended settings: hull depth 1
    filter.setInputCloud(cloud);
    filter.setPlane(BoundaryPlane::kXY);
    pcl::Indices kept;
    filter.filter(kept);
    const Quality q = quality(shape, n, kept, *cloud);
    EXPECT_GE(q.precision, 0.999) << static_cast<int>(shape);
    EXPECT_GE(q.recall, 0.999) << static_cast<int>(shape);
  }
}

TEST(OrthantBoundary, HullDepthOfARegularPolygonIsItsApothem) {
  // p at (a, 0) inside a regular 12-gon of circumradius 2 with an edge at x = 2 cos(pi / 12):
  // depth 2 cos(pi / 12) - a, area 6 * 2^2 sin(pi / 6) = 12, 13 positions with p.
  constexpr int corners = 12;
  const double apothem = 2.0 * std::cos(M_PI / corners);
  for (const double a : {0.0, 0.5, 1.5, apothem}) {
    std::vector<Neighbour> nn;
    nn.emplace_back(0.0f, 0.0f, 0.0f, 0.0f, 0);
    for (int k = 0; k < corners; ++k) {
      const double angle = (2 * k + 1) * M_PI / corners;
      const auto x = static_cast<float>(2.0 * std::cos(angle) - a);
      const auto y = static_cast<float>(2.0 * std::sin(angle));
      nn.emplace_back(x, y, 0.0f, x * x + y * y, k + 1);
    }
    orthant::HullScratch scratch;
    const double spacing = std::sqrt(12.0 / 13.0);
    EXPECT_NEAR(orthant::hullDepthInSpacings(nn, scratch), (apothem - a) / spacing, 1e-6)
        << "a = " << a;
  }
}

TEST(OrthantBoundary, HullDepthAgreesWithBruteForceOverEveryPairOfPoints) {
  // Brute force: (i, j) is a counter-clockwise hull edge when every other point lies strictly
  // to its left; the hull's area is the sum of the triangles (p, i, j) and p's depth the
  // smallest distance to such an edge. Random positions are never collinear.
  const CounterRng rng(11);
  std::uint64_t draws = 0;
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * rng.uniform(draws++, 0); };
  for (int trial = 0; trial < 200; ++trial) {
    const int m = 3 + trial % 40;
    std::vector<Neighbour> nn;
    nn.emplace_back(0.0f, 0.0f, 0.0f, 0.0f, 0);
    const double shift = trial % 3 == 0 ? 1.5 : 0.0;  // p outside the others' hull: depth 0
    for (int k = 0; k < m; ++k) {
      const auto x = static_cast<float>(uniform(-1.0, 1.0) + shift);
      const auto y = static_cast<float>(uniform(-1.0, 1.0));
      nn.emplace_back(x, y, 0.0f, x * x + y * y, k + 1);
    }
    auto turn = [&](int i, int j, double x, double y) {
      const double xi = nn[i].x, yi = nn[i].y, xj = nn[j].x, yj = nn[j].y;
      return (xj - xi) * (y - yi) - (yj - yi) * (x - xi);
    };
    double area = 0.0, depth = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= m; ++i) {
      for (int j = 0; j <= m; ++j) {
        bool edge = i != j;
        for (int k = 0; k <= m && edge; ++k) {
          if (k != i && k != j) edge = turn(i, j, nn[k].x, nn[k].y) > 0.0;
        }
        if (!edge) continue;
        area += 0.5 * turn(i, j, 0.0, 0.0);
        const double length = std::hypot(double{nn[j].x} - nn[i].x, double{nn[j].y} - nn[i].y);
        depth = std::min(depth, std::max(0.0, turn(i, j, 0.0, 0.0) / length));
      }
    }
    orthant::HullScratch scratch;
    const double expected = depth / std::sqrt(area / (m + 1));
    EXPECT_NEAR(orthant::hullDepthInSpacings(nn, scratch), expected, 1e-9 * (1.0 + expected))
        << "trial " << trial;
  }
}

TEST(OrthantBoundary, FindsTheInnerCircleOfTheAnnulus) {
  constexpr std::size_t n = 50000;
  const auto cloud = std::make_shared<pcl::PointCloud<WorkspacePoint>>(
      sampleCloud(ShapeSampler(Shape::kAnnulus, 4), n, 0));
  OrthantBoundary<WorkspacePoint> filter;
  paperTestOnly(filter);
  filter.setInputCloud(cloud);
  filter.setPlane(BoundaryPlane::kXY);
  filter.setAdaptiveRadius(24, 2.0);
  pcl::Indices kept;
  filter.filter(kept);
  const double h = std::sqrt(shapeMeasure(Shape::kAnnulus) / n);
  std::size_t inner = 0, inner_near = 0;
  for (const auto i : kept) inner += (*cloud)[i].getVector3fMap().norm() < 0.5 + 2 * h;
  for (const auto& p : *cloud) inner_near += p.getVector3fMap().norm() < 0.5 + 0.5 * h;
  // The inner circle is half as long as the outer: about a third of the boundary points.
  EXPECT_GT(inner, kept.size() / 4);
  EXPECT_GE(static_cast<double>(inner) / inner_near, kMinRecall);
}

TEST(OrthantBoundary, SameResultForAnyThreadCount) {
  const auto cloud = std::make_shared<pcl::PointCloud<WorkspacePoint>>(
      sampleCloud(ShapeSampler(Shape::kBall, 5), 30000, 0));
  pcl::Indices kept[2];
  for (int threads : {1, 2}) {
    OrthantBoundary<WorkspacePoint> filter;  // the recommended settings
    filter.setInputCloud(cloud);
    filter.setNumberOfThreads(threads);
    filter.filter(kept[threads - 1]);
  }
  EXPECT_EQ(kept[0], kept[1]);
  const auto disk = std::make_shared<pcl::PointCloud<WorkspacePoint>>(
      sampleCloud(ShapeSampler(Shape::kAnnulus, 5), 30000, 0));
  pcl::Indices rim[2];
  for (int threads : {1, 2}) {
    OrthantBoundary<WorkspacePoint> filter;
    filter.setInputCloud(disk);
    filter.setPlane(BoundaryPlane::kXY);
    filter.setNumberOfThreads(threads);
    filter.filter(rim[threads - 1]);
  }
  EXPECT_EQ(rim[0], rim[1]);
  EXPECT_GT(rim[0].size(), 0u);
}

TEST(OrthantBoundary, TwoStageTestEqualsOneTestAtTheOuterRadius) {
  const auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  pcl::copyPointCloud(sampleCloud(ShapeSampler(Shape::kDisk, 6), 20000, 0), *cloud);
  auto run = [&](double r, double R) {
    OrthantBoundary<pcl::PointXYZ> filter;
    paperTestOnly(filter);
    filter.setInputCloud(cloud);
    filter.setPlane(BoundaryPlane::kXY);
    filter.setFrames(OrthantFrame::kAxis);  // the paper's own test
    filter.setRadiusSearch(r);
    filter.setOuterRadius(R);
    pcl::Indices kept;
    filter.filter(kept);
    return kept;
  };
  const pcl::Indices two_stage = run(0.02, 0.05), single = run(0.05, 0.0);
  EXPECT_EQ(two_stage, single);
  EXPECT_LT(single.size(), run(0.02, 0.0).size());  // R removes false points of r (Fig. 12)
}

/// A cloud whose density varies by orders of magnitude, as joint-space sampling gives: radius
/// u^3 of a uniform u (dense centre, sparse rim), plus a tight cluster of copies and near-copies.
pcl::PointCloud<pcl::PointXYZ>::Ptr unevenCloud(std::size_t n, int dimensions) {
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  const auto uniform =
      sampleCloud(ShapeSampler(dimensions == 2 ? Shape::kDisk : Shape::kBall, 9), n, 2);
  for (const auto& p : uniform) {
    const Eigen::Vector3f v = p.getVector3fMap();
    const float r = v.norm();
    const Eigen::Vector3f w = r > 0 ? Eigen::Vector3f(v * (r * r)) : v;
    cloud->push_back(pcl::PointXYZ(w.x(), w.y(), w.z()));
  }
  for (int k = 0; k < 200; ++k) cloud->push_back(pcl::PointXYZ(0.5f + 1e-6f * (k % 7), 0.5f, 0));
  return cloud;
}

TEST(OrthantBoundary, GridSearchGivesTheTreesResult) {
  // The tree (KdTreeFLANN everywhere) is the reference; the grid must reproduce it exactly,
  // in every mode, on uniform and very uneven clouds, and on a lattice full of exact ties.
  struct Case {
    const char* name;
    pcl::PointCloud<pcl::PointXYZ>::Ptr cloud;
    BoundaryPlane plane;
    std::function<void(OrthantBoundary<pcl::PointXYZ>&)> configure;
  };
  auto disk = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  pcl::copyPointCloud(sampleCloud(ShapeSampler(Shape::kAnnulus, 4), 20000, 2), *disk);
  auto ball = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  pcl::copyPointCloud(sampleCloud(ShapeSampler(Shape::kBall, 5), 20000, 2), *ball);
  auto lattice = gridCloud<pcl::PointXYZ>(40, 2);
  auto cube = gridCloud<pcl::PointXYZ>(12, 3);
  const std::vector<Case> cases = {
      {"annulus adaptive", disk, BoundaryPlane::kXY, [](auto& f) { f.setAdaptiveRadius(24, 2); }},
      {"annulus auto", disk, BoundaryPlane::kXY, [](auto& f) { f.setAutoRadius(0); }},
      {"annulus fixed axis", disk, BoundaryPlane::kXY,
       [](auto& f) { f.setRadiusSearch(0.03), f.setFrames(OrthantFrame::kAxis); }},
      {"annulus two-stage outward", disk, BoundaryPlane::kXY,
       [](auto& f) {
         f.setRadiusSearch(0.02), f.setOuterRadius(0.04), f.setFrames(OrthantFrame::kOutward);
       }},
      {"annulus adaptive outer", disk, BoundaryPlane::kXY,
       [](auto& f) { f.setAdaptiveRadius(12, 1.5), f.setOuterRadius(1.6); }},
      {"ball adaptive", ball, BoundaryPlane::k3D, [](auto& f) { f.setAdaptiveRadius(16, 2); }},
      {"ball axis", ball, BoundaryPlane::k3D,
       [](auto& f) { f.setAdaptiveRadius(16, 2), f.setFrames(OrthantFrame::kAxis); }},
      {"uneven disk", unevenCloud(30000, 2), BoundaryPlane::kXY,
       [](auto& f) { f.setAdaptiveRadius(24, 2); }},
      {"annulus hull depth", disk, BoundaryPlane::kXY,
       [](auto& f) { f.setAdaptiveRadius(24, 2), f.setHullDepth(1.0); }},
      {"uneven disk hull depth", unevenCloud(30000, 2), BoundaryPlane::kXY,
       [](auto& f) { f.setAdaptiveRadius(24, 2), f.setHullDepth(1.0); }},
      {"annulus fixed hull depth", disk, BoundaryPlane::kXY,
       [](auto& f) { f.setRadiusSearch(0.04), f.setHullDepth(0.75); }},
      {"uneven ball", unevenCloud(30000, 3), BoundaryPlane::k3D,
       [](auto& f) { f.setAdaptiveRadius(16, 2); }},
      {"lattice adaptive", lattice, BoundaryPlane::kXY,
       [](auto& f) { f.setAdaptiveRadius(24, 2); }},
      {"lattice fixed", lattice, BoundaryPlane::kXY, [](auto& f) { f.setRadiusSearch(2.0); }},
      // Radius 1 on a unit lattice: the 4 nearest neighbours sit exactly on the sphere and the
      // tree's strict d^2 < r^2 leaves them out, so every point is alone.
      {"lattice at the tie", lattice, BoundaryPlane::kXY,
       [](auto& f) { f.setRadiusSearch(1.0), f.setFrames(OrthantFrame::kAxis); }},
      {"cube lattice", cube, BoundaryPlane::k3D, [](auto& f) { f.setAdaptiveRadius(16, 2); }},
  };
  for (const auto& c : cases) {
    pcl::Indices kept[2];
    for (int grid = 0; grid < 2; ++grid) {
      OrthantBoundary<pcl::PointXYZ> filter;
      paperTestOnly(filter);
      filter.setInputCloud(c.cloud);
      filter.setPlane(c.plane);
      c.configure(filter);
      filter.setGridSearch(grid == 1);
      filter.filter(kept[grid]);
    }
    EXPECT_EQ(kept[0], kept[1]) << c.name;
    EXPECT_GT(kept[0].size(), 0u) << c.name;
  }
}

}  // namespace
}  // namespace mcws
