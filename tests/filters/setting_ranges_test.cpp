// The ranges of the boundary methods' settings for a cloud (boundarySettingRanges), on summaries
// written by hand so that every bound is worked out here: lengths from a tenth of the spacing to
// the extent, the adaptive k below the distinct points, the outer radius beyond the radius.
#include <gtest/gtest.h>

#include <cmath>

#include "mcws/filters/setting_ranges.h"

namespace mcws {
namespace {

/// A planar cloud of 50 distinct points, mean spacing 2, largest extent 100 [unit].
CloudSummary summary() {
  CloudSummary cloud;
  cloud.plane = BoundaryPlane::kXY;
  cloud.points = cloud.finite = cloud.distinct = 50;
  cloud.largest = 100.0;
  cloud.spacing = 2.0;
  return cloud;
}

TEST(SettingRanges, BaselineLengthsRunFromATenthOfTheSpacingToTheExtent) {
  BoundarySettings grid;
  grid.baseline = true;
  grid.plane = BoundaryPlane::kXY;
  const BoundarySettingRanges ranges = boundarySettingRanges(summary(), grid);
  ASSERT_TRUE(ranges.cell && ranges.gap);
  EXPECT_DOUBLE_EQ(ranges.cell->low, 0.2);
  EXPECT_DOUBLE_EQ(ranges.cell->high, 100.0);
  EXPECT_DOUBLE_EQ(ranges.gap->low, 0.2);
  EXPECT_EQ(ranges.cell->why, "a tenth of the cloud's mean spacing 2 to its extent");
  EXPECT_EQ(ranges.cell->unit, "[length unit]");
  EXPECT_FALSE(ranges.radius || ranges.auto_radius || ranges.outer_radius);
  EXPECT_TRUE(ranges.cell->contains(0.2));
  EXPECT_FALSE(ranges.cell->contains(100.001));
}

TEST(SettingRanges, ABaselineCellIsCoarseEnoughFor21BitsAnAxis) {
  CloudSummary cloud = summary();
  cloud.largest = 1e7;  // 1e7 / 2097148 cells an axis = 4.768 > a tenth of the spacing
  BoundarySettings extremum;
  extremum.baseline = true;
  const BoundarySettingRanges ranges = boundarySettingRanges(cloud, extremum);
  EXPECT_NEAR(ranges.cell->low, 1e7 / 2097148.0, 1e-5);
  EXPECT_DOUBLE_EQ(ranges.gap->low, 0.2);  // the gap has no cells
}

TEST(SettingRanges, AdaptiveKStaysBelowTheDistinctPointsAndAt1000) {
  const BoundarySettingRanges few = boundarySettingRanges(summary(), {});
  EXPECT_DOUBLE_EQ(few.adaptive.low, 1.0);
  EXPECT_DOUBLE_EQ(few.adaptive.high, 49.0);
  EXPECT_EQ(few.adaptive.why, "fewer than the cloud's 50 distinct points, at most 1000");
  CloudSummary many = summary();
  many.distinct = kDistinctCounted;
  EXPECT_DOUBLE_EQ(boundarySettingRanges(many, {}).adaptive.high, 1000.0);
}

TEST(SettingRanges, WithoutTheSpacingOnlyTheAdaptiveKHasARange) {
  CloudSummary cloud = summary();
  cloud.spacing.reset();
  const BoundarySettingRanges ranges = boundarySettingRanges(cloud, {});
  EXPECT_FALSE(ranges.cell || ranges.gap || ranges.radius || ranges.auto_radius ||
               ranges.outer_radius);
}

TEST(SettingRanges, AFixedRadiusPutsTheOuterRadiusBeyondIt) {
  BoundarySettings fixed;
  fixed.radius = 3.0;
  const BoundarySettingRanges ranges = boundarySettingRanges(summary(), fixed);
  EXPECT_DOUBLE_EQ(ranges.radius->low, 0.2);
  EXPECT_DOUBLE_EQ(ranges.auto_radius->low, 0.1);  // in spacings: 0.2 / 2 to 100 / 2
  EXPECT_DOUBLE_EQ(ranges.auto_radius->high, 50.0);
  EXPECT_EQ(ranges.auto_radius->why, "the radius c x 2 from a tenth of a spacing to the extent");
  EXPECT_DOUBLE_EQ(ranges.outer_radius->low, 3.0);
  EXPECT_TRUE(ranges.outer_radius->open_low);
  EXPECT_FALSE(ranges.outer_radius->contains(3.0));
  EXPECT_TRUE(ranges.outer_radius->contains(100.0));

  BoundarySettings automatic;
  automatic.auto_radius_factor = 1.5;  // the radius 1.5 x 2
  EXPECT_DOUBLE_EQ(boundarySettingRanges(summary(), automatic).outer_radius->low, 3.0);
}

TEST(SettingRanges, AnAdaptiveRadiusTakesAnOuterFactorThatKeepsItWithinTheExtent) {
  BoundarySettings adaptive;
  adaptive.plane = BoundaryPlane::kXY;
  adaptive.adaptive_neighbours = 24;
  const BoundarySettingRanges ranges = boundarySettingRanges(summary(), adaptive);
  // The typical radius: 2 (scale) x the radius of a disk of 25 points at spacing 2,
  // 2 sqrt(25 / pi) = 10 / sqrt(pi); x 2 = 20 / sqrt(pi) = 11.2838; 100 over it = 5 sqrt(pi).
  EXPECT_DOUBLE_EQ(ranges.outer_radius->low, 1.0);
  EXPECT_NEAR(ranges.outer_radius->high, 5.0 * std::sqrt(M_PI), 1e-12);
  EXPECT_EQ(ranges.outer_radius->unit, "times each point's radius");
  EXPECT_EQ(ranges.outer_radius->why,
            "a factor beyond 1 of the radius, about 11.2838, that keeps it within the cloud's "
            "extent");
}

}  // namespace
}  // namespace mcws
