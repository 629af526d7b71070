// The baselines of Yin, Wang & Yu 2010: the grid method (GridBoundary) and the extremum method
// (ExtremumBoundary), on grids with known answers and on the validation shapes.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <set>
#include <utility>

#include "mcws/core/error.h"
#include "mcws/filters/extremum_boundary.h"
#include "mcws/filters/grid_boundary.h"
#include "mcws/sampling/sampler.h"
#include "mcws/workspace/measure.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;
using Cell = std::pair<float, float>;

/// An n x n grid of unit spacing at integer coordinates in the x-y plane; point (x, y) has index
/// x n + y. Points with x and y both in [hole_begin, hole_end] are left out.
template <typename PointT>
typename pcl::PointCloud<PointT>::Ptr squareGrid(int n, int hole_begin = 1, int hole_end = 0) {
  auto cloud = std::make_shared<pcl::PointCloud<PointT>>();
  for (int x = 0; x < n; ++x) {
    for (int y = 0; y < n; ++y) {
      if (x >= hole_begin && x <= hole_end && y >= hole_begin && y <= hole_end) continue;
      PointT p;
      p.x = static_cast<float>(x);
      p.y = static_cast<float>(y);
      p.z = 0.0f;
      cloud->push_back(p);
    }
  }
  return cloud;
}

template <typename PointT>
std::set<Cell> positions(const pcl::PointCloud<PointT>& cloud, const pcl::Indices& indices) {
  std::set<Cell> result;
  for (const auto i : indices) result.emplace(cloud[i].x, cloud[i].y);
  return result;
}

template <typename PointT>
typename pcl::PointCloud<PointT>::Ptr shapeCloud(Shape shape, std::size_t n, std::uint64_t seed) {
  auto cloud = std::make_shared<pcl::PointCloud<PointT>>();
  pcl::copyPointCloud(sampleCloud(ShapeSampler(shape, seed), n, 2), *cloud);
  return cloud;
}

/// The indices `filter` keeps of `cloud`, its points projected to `plane`.
template <typename Filter>
pcl::Indices boundaryOf(Filter& filter, const typename Filter::PointCloudConstPtr& cloud,
                        BoundaryPlane plane = BoundaryPlane::kXY) {
  filter.setInputCloud(cloud);
  filter.setPlane(plane);
  pcl::Indices kept;
  filter.filter(kept);
  return kept;
}

/// The message of the mcws::Error boundaryOf() throws, or "no error".
template <typename Filter>
std::string errorOf(Filter& filter, const typename Filter::PointCloudConstPtr& cloud,
                    BoundaryPlane plane = BoundaryPlane::kXY) {
  try {
    boundaryOf(filter, cloud, plane);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

template <typename PointT>
class BaselineTyped : public ::testing::Test {};
using BaselinePointTypes = ::testing::Types<pcl::PointXYZ, pcl::PointXYZL, WorkspacePoint>;
TYPED_TEST_SUITE(BaselineTyped, BaselinePointTypes);

// ---------------------------------------------------------------------------------------------
// GridBoundary

TYPED_TEST(BaselineTyped, GridWithUnitCellsKeepsExactlyTheRimOfASquareGrid) {
  constexpr int n = 20;
  const auto cloud = squareGrid<TypeParam>(n);
  GridBoundary<TypeParam> grid;
  grid.setCellSize(1.0);  // one point per cell
  const pcl::Indices kept = boundaryOf(grid, cloud);
  std::set<Cell> rim;
  for (float k = 0; k < n; ++k) rim.insert({{0.0f, k}, {n - 1.0f, k}, {k, 0.0f}, {k, n - 1.0f}});
  EXPECT_EQ(kept.size(), rim.size());
  EXPECT_EQ(positions(*cloud, kept), rim);
  EXPECT_EQ(grid.occupiedCells(), static_cast<std::size_t>(n * n));
  EXPECT_EQ(grid.boundaryCells(), rim.size());
  std::set<Cell> means;
  for (const auto& p : grid.cellMeans()) means.emplace(p.x, p.y);
  EXPECT_EQ(means, rim);  // one point per cell: the means are the points
}

TEST(GridBoundary, CellsOfFourPointsGiveTheirMeansAndTheLowestIndexNearestToIt) {
  // 20 x 20 points, cells of 2 x 2 points: 10 x 10 cells, the 36 on the rim are boundary cells.
  // The mean of cell (i, j) is (2i + 0.5, 2j + 0.5); its 4 points are equally near, and the
  // lowest index, (2i, 2j), is kept.
  const auto cloud = squareGrid<pcl::PointXYZ>(20);
  GridBoundary<pcl::PointXYZ> grid;
  grid.setCellSize(2.0);
  const pcl::Indices kept = boundaryOf(grid, cloud);
  std::set<Cell> corners, means;
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) {
      if (i == 0 || i == 9 || j == 0 || j == 9) {
        corners.emplace(2.0f * i, 2.0f * j);
        means.emplace(2.0f * i + 0.5f, 2.0f * j + 0.5f);
      }
    }
  }
  EXPECT_EQ(positions(*cloud, kept), corners);
  EXPECT_EQ(kept.size(), 36u);
  std::set<Cell> got_means;
  for (const auto& p : grid.cellMeans()) got_means.emplace(p.x, p.y);
  EXPECT_EQ(got_means, means);
}

TEST(GridBoundary, ThreeDimensionalCellsKeepTheSurfaceOfACubeGrid) {
  constexpr int n = 7;
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  for (int x = 0; x < n; ++x) {
    for (int y = 0; y < n; ++y) {
      for (int z = 0; z < n; ++z) cloud->push_back(pcl::PointXYZ(x, y, z));
    }
  }
  GridBoundary<pcl::PointXYZ> grid;  // 3-D by default
  grid.setInputCloud(cloud);
  grid.setCellSize(1.0);
  pcl::Indices kept;
  grid.filter(kept);
  EXPECT_EQ(kept.size(), static_cast<std::size_t>(n * n * n - (n - 2) * (n - 2) * (n - 2)));
  for (const auto i : kept) {
    const auto& p = (*cloud)[i];
    auto edge = [&](float v) { return v == 0.0f || v == n - 1.0f; };
    EXPECT_TRUE(edge(p.x) || edge(p.y) || edge(p.z)) << p;
  }
}

TEST(GridBoundary, AutomaticCellsFindBothCirclesOfTheAnnulusAndNothingBetween) {
  const auto cloud = shapeCloud<pcl::PointXYZ>(Shape::kAnnulus, 20000, 4);
  GridBoundary<pcl::PointXYZ> grid;
  const pcl::Indices kept = boundaryOf(grid, cloud);
  // The automatic rule: h sqrt(m), m = ln(2 n / m) = 7.84 for n = 20000 (by hand), and the
  // annulus's spacing sqrt(0.75 pi / n) (meanSpacing estimates it within a few %).
  const double h = std::sqrt(0.75 * M_PI / 20000);
  EXPECT_NEAR(grid.usedCellSize() / (h * std::sqrt(7.84)), 1.0, 0.05);
  const double cell = grid.usedCellSize();
  std::size_t inner = 0, outer = 0, between = 0;
  for (const auto i : kept) {
    const double r = std::hypot((*cloud)[i].x, (*cloud)[i].y);
    // A boundary cell touches an empty cell, so its points lie within 2 cell diagonals of the
    // rim unless an interior cell happened to be empty (each such cell makes at most 8).
    if (std::abs(r - 0.5) <= 2 * M_SQRT2 * cell) {
      ++inner;
    } else if (std::abs(r - 1.0) <= 2 * M_SQRT2 * cell) {
      ++outer;
    } else {
      ++between;
    }
  }
  EXPECT_LE(between, 8u);
  // Each circle crosses at least (circumference / cell) cells.
  EXPECT_GT(inner, static_cast<std::size_t>(M_PI / cell));
  EXPECT_GT(outer, static_cast<std::size_t>(2 * M_PI / cell));
  EXPECT_EQ(kept.size(), grid.boundaryCells());  // one point per boundary cell
  EXPECT_EQ(grid.cellMeans().size(), kept.size());
}

TEST(GridBoundary, TheColumnAreaOfItsMeansIsBelowTheDiskAsThePaperSays) {
  // Yin, Wang & Yu 2010, section 5: grid boundary points lie inside the region (its Fig. 8), so the
  // area computed from them by its column method is a little low (its Table 2: 0.7 % to 7 %).
  const auto cloud = shapeCloud<pcl::PointXYZ>(Shape::kDisk, 100000, 1);
  GridBoundary<pcl::PointXYZ> grid;
  boundaryOf(grid, cloud);
  const double area = columnArea(grid.cellMeans()).area;
  EXPECT_LT(area, M_PI);
  EXPECT_GT(area, 0.95 * M_PI);
}

TEST(GridBoundary, DegenerateClouds) {
  GridBoundary<pcl::PointXYZ> grid;
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  EXPECT_TRUE(boundaryOf(grid, cloud).empty());  // empty: nothing kept, no error
  cloud->push_back(pcl::PointXYZ(1, 2, 3));
  EXPECT_EQ(boundaryOf(grid, cloud), pcl::Indices({0}));  // one point: its own boundary cell
  for (int k = 0; k < 4; ++k) cloud->push_back(pcl::PointXYZ(1, 2, 3));
  // Identical points: one cell, the first point.
  EXPECT_EQ(boundaryOf(grid, cloud), pcl::Indices({0}));
}

TEST(GridBoundary, RejectsBadParameters) {
  const auto cloud = shapeCloud<pcl::PointXYZ>(Shape::kDisk, 1000, 1);
  auto message = [&](double cell) {
    GridBoundary<pcl::PointXYZ> grid;
    grid.setCellSize(cell);
    return errorOf(grid, cloud);
  };
  EXPECT_EQ(message(0.0), "GridBoundary: cell size 0 must be a positive number");
  EXPECT_EQ(message(-0.5), "GridBoundary: cell size -0.5 must be a positive number");
  EXPECT_EQ(message(std::numeric_limits<double>::infinity()),
            "GridBoundary: cell size inf must be a positive number");
  EXPECT_THAT(message(1e-7),
              HasSubstr("GridBoundary: cell size 1e-07 is too small for the extent"));
  EXPECT_THROW(parseBoundaryPlane("xw"), Error);
}

// ---------------------------------------------------------------------------------------------
// ExtremumBoundary

TYPED_TEST(BaselineTyped, ExtremumKeepsTheLowestAndHighestPointOfEachColumn) {
  constexpr int n = 20;
  const auto cloud = squareGrid<TypeParam>(n);
  ExtremumBoundary<TypeParam> extremum;
  extremum.setColumnWidth(1.0);   // one grid column per column
  extremum.setGapThreshold(1.5);  // the grid's spacing 1 is no gap
  const pcl::Indices kept = boundaryOf(extremum, cloud);
  std::set<Cell> expected;
  for (float x = 0; x < n; ++x) expected.insert({{x, 0.0f}, {x, n - 1.0f}});
  EXPECT_EQ(positions(*cloud, kept), expected);
  EXPECT_EQ(kept.size(), expected.size());
  EXPECT_EQ(extremum.columns(), static_cast<std::size_t>(n));
}

TEST(ExtremumBoundary, WideColumnsKeepTheFirstOfPointsAtTheSameExtreme) {
  // Columns of 2 grid columns: x = 2i and 2i + 1 tie at y = 0 and y = 19; the lower index wins.
  const auto cloud = squareGrid<pcl::PointXYZ>(20);
  ExtremumBoundary<pcl::PointXYZ> extremum;
  extremum.setColumnWidth(2.0);
  extremum.setGapThreshold(1.5);
  const pcl::Indices kept = boundaryOf(extremum, cloud);
  std::set<Cell> expected;
  for (int i = 0; i < 10; ++i) expected.insert({{2.0f * i, 0.0f}, {2.0f * i, 19.0f}});
  EXPECT_EQ(positions(*cloud, kept), expected);
}

TEST(ExtremumBoundary, GapsAboveTheThresholdGiveInnerBoundaryPoints) {
  // A 20 x 20 grid with a 10 x 10 hole (x, y in [5, 14]): columns x = 5 .. 14 jump from y = 4
  // to y = 15, a gap of 11.
  const auto cloud = squareGrid<pcl::PointXYZ>(20, 5, 14);
  ExtremumBoundary<pcl::PointXYZ> extremum;
  extremum.setColumnWidth(1.0);
  for (double threshold : {1.5, 10.9}) {
    extremum.setGapThreshold(threshold);
    const pcl::Indices kept = boundaryOf(extremum, cloud);
    std::set<Cell> expected;
    for (float x = 0; x < 20; ++x) expected.insert({{x, 0.0f}, {x, 19.0f}});
    for (float x = 5; x <= 14; ++x) expected.insert({{x, 4.0f}, {x, 15.0f}});
    EXPECT_EQ(positions(*cloud, kept), expected) << threshold;
  }
  extremum.setGapThreshold(11.0);  // not above the threshold: the hole is missed
  EXPECT_EQ(boundaryOf(extremum, cloud).size(), 40u);
}

TEST(ExtremumBoundary, FindsTheHoleOfTheAnnulusWithAutomaticParameters) {
  const auto cloud = shapeCloud<pcl::PointXYZ>(Shape::kAnnulus, 20000, 4);
  ExtremumBoundary<pcl::PointXYZ> extremum;
  const pcl::Indices kept = boundaryOf(extremum, cloud);
  const double width = extremum.usedColumnWidth();
  // The rule: t = ln(2 n) h^2 / dL with dL = h sqrt(m) as for the grid.
  EXPECT_NEAR(extremum.usedGapThreshold(),
              std::log(40000.0) * std::pow(extremum.usedSpacing(), 2) / width, 1e-12);
  std::size_t inner = 0, between = 0;
  for (const auto i : kept) {
    const double r = std::hypot((*cloud)[i].x, (*cloud)[i].y);
    if (r < 0.5 + extremum.usedGapThreshold()) {
      ++inner;
    } else if (r < 1.0 - 2 * width) {
      ++between;  // extremes of columns at the annulus's sides lie on the outer circle
    }
  }
  // Columns crossing the hole well inside (|x| < 0.45) each give two inner points.
  EXPECT_GE(inner, static_cast<std::size_t>(2 * 0.9 / width) - 2);
  EXPECT_LE(between, 2u);
}

TEST(ExtremumBoundary, ColumnsRunAlongTheFirstAxisOfThePlane) {
  // A 3 x 10 block in the x-z plane: columns along x, extremes along z (Fig. 9 of
  // Yin, Wang & Yu 2010).
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  for (int x = 0; x < 3; ++x) {
    for (int z = 0; z < 10; ++z) cloud->push_back(pcl::PointXYZ(x, 5.0f, z));
  }
  ExtremumBoundary<pcl::PointXYZ> extremum;
  extremum.setColumnWidth(1.0);
  extremum.setGapThreshold(1.5);
  const pcl::Indices kept = boundaryOf(extremum, cloud, BoundaryPlane::kXZ);
  std::set<Cell> got;
  for (const auto i : kept) got.emplace((*cloud)[i].x, (*cloud)[i].z);
  EXPECT_EQ(got, std::set<Cell>({{0, 0}, {0, 9}, {1, 0}, {1, 9}, {2, 0}, {2, 9}}));
}

TEST(ExtremumBoundary, DegenerateClouds) {
  ExtremumBoundary<pcl::PointXYZ> extremum;
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  EXPECT_TRUE(boundaryOf(extremum, cloud).empty());
  cloud->push_back(pcl::PointXYZ(1, 2, 3));
  EXPECT_EQ(boundaryOf(extremum, cloud), pcl::Indices({0}));
  for (int k = 0; k < 4; ++k) cloud->push_back(pcl::PointXYZ(1, 2, 3));
  // The lowest and highest are the same, first, point.
  EXPECT_EQ(boundaryOf(extremum, cloud), pcl::Indices({0}));
}

TEST(ExtremumBoundary, RejectsBadParameters) {
  const auto cloud = shapeCloud<pcl::PointXYZ>(Shape::kDisk, 1000, 1);
  auto message = [&](const std::function<void(ExtremumBoundary<pcl::PointXYZ>&)>& set,
                     BoundaryPlane plane = BoundaryPlane::kXY) {
    ExtremumBoundary<pcl::PointXYZ> extremum;
    set(extremum);
    return errorOf(extremum, cloud, plane);
  };
  EXPECT_EQ(message([](auto& f) { f.setColumnWidth(0.0); }),
            "ExtremumBoundary: column width 0 must be a positive number");
  EXPECT_EQ(message([](auto& f) { f.setColumnWidth(-2.0); }),
            "ExtremumBoundary: column width -2 must be a positive number");
  EXPECT_EQ(message([](auto& f) { f.setGapThreshold(0.0); }),
            "ExtremumBoundary: gap threshold 0 must be a positive number");
  EXPECT_EQ(message([](auto& f) { f.setGapThreshold(-1.0); }),
            "ExtremumBoundary: gap threshold -1 must be a positive number");
  EXPECT_EQ(message([](auto&) {}, BoundaryPlane::k3D),
            "ExtremumBoundary: the extremum method needs a plane (xy, xz or yz), not 3d");
  EXPECT_EQ(message([](auto&) {}), "no error");
}

// ---------------------------------------------------------------------------------------------
// Both baselines as PCL filters

/// Each baseline filter over each point type.
template <typename Filter>
class BaselineFilter : public ::testing::Test {};
using BaselineFilters =
    ::testing::Types<GridBoundary<pcl::PointXYZ>, GridBoundary<pcl::PointXYZL>,
                     GridBoundary<WorkspacePoint>, ExtremumBoundary<pcl::PointXYZ>,
                     ExtremumBoundary<pcl::PointXYZL>, ExtremumBoundary<WorkspacePoint>>;
TYPED_TEST_SUITE(BaselineFilter, BaselineFilters);

TYPED_TEST(BaselineFilter, NegativeModeIsTheComplementAndNaNIsAlwaysRemoved) {
  using PointT = typename TypeParam::PointCloud::PointType;
  auto cloud = shapeCloud<PointT>(Shape::kAnnulus, 20000, 3);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const pcl::Indices not_finite = {5, 77, 78};  // NaN in x, in y, in z
  (*cloud)[5].x = nan;
  (*cloud)[77].y = nan;
  (*cloud)[78].z = nan;
  auto split = [&](bool negative) {
    TypeParam filter(true);  // with removed indices
    filter.setNegative(negative);
    const pcl::Indices kept = boundaryOf(filter, cloud);
    return std::make_pair(kept, *filter.getRemovedIndices());
  };
  const auto [kept, removed] = split(false);
  EXPECT_EQ(kept.size() + removed.size(), cloud->size());
  for (const auto i : not_finite) EXPECT_EQ(std::count(kept.begin(), kept.end(), i), 0);
  const auto [negative_kept, negative_removed] = split(true);
  pcl::Indices expected;  // what positive mode removed, less the non-finite points
  std::copy_if(removed.begin(), removed.end(), std::back_inserter(expected),
               [&](auto i) { return std::count(not_finite.begin(), not_finite.end(), i) == 0; });
  EXPECT_EQ(negative_kept, expected);
  pcl::Indices expected_removed = kept;  // what positive mode kept, and the non-finite points
  expected_removed.insert(expected_removed.end(), not_finite.begin(), not_finite.end());
  std::sort(expected_removed.begin(), expected_removed.end());
  EXPECT_EQ(negative_removed, expected_removed);
}

}  // namespace
}  // namespace mcws
