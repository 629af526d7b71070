// Base placement (mcws/reach/base_placement.h) from planar2's reachability map: the map's answer
// for single targets, the interval of bases reaching two targets in closed form, and the
// positions ReachStudy confirms (the studies themselves are in reach_study_test.cpp).
#include "mcws/reach/base_placement.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/robot_yaml.h"
#include "mcws/reach/orientation_bins.h"
#include "mcws/reach/reach_map.h"
#include "mcws/reach/reach_study.h"
#include "reach/planar2.h"
#include "reach/reach_study_fixture.h"
#include "test_support.h"

namespace mcws {
namespace {

using test::kDeg;
using test::kL1;
using test::kL2;
using test::kOuter;
using test::planar2;
using test::planarManipulability;
using test::planarManipulabilitySlope;
using test::planarOptions;

/// planar2's map of `resolution` [cm] voxels from `samples` samples, 16 direction regions (the
/// polar cap holds every direction within acos(1 - 2/16) = 28.96 deg of +z), position
/// manipulability.
ReachMap buildPlanarMap(double resolution, std::uint64_t samples) {
  ReachGrid grid;
  grid.resolution = resolution;
  grid.directions = 16;
  grid.rolls = 1;
  ReachSampling sampling;
  sampling.samples = samples;
  sampling.quality = QualityOptions{QualityTask::kPosition, 1.0};
  return buildReachMap(planar2(), grid, sampling);
}

/// planar2's map at 2 cm from 2e6 samples.
const ReachMap& planarMap() {
  static const ReachMap map = buildPlanarMap(2.0, 2000000);
  return map;
}

// The map's answer for single targets: the voxel of the point less the offset, and the approach's
// region or, within a tolerance, that of the probes around it.
TEST(BasePlacement, MapReachesAnnulusAndApproach) {
  const ReachMap& map = planarMap();
  const Eigen::Vector3d p(45.0, 12.0, 0.0);  // r = 46.6, voxel well inside the annulus
  const ReachTarget up = targetFromNormal(p, {0, 0, -1});
  float m = -1.f;
  ASSERT_TRUE(mapReaches(map, up, Eigen::Vector3d::Zero(), 0.0, &m));
  EXPECT_EQ(m, map.bestManipulability(static_cast<std::size_t>(map.find(p))));
  EXPECT_GT(m, 0.f);
  EXPECT_LE(m, kL1 * kL2 * (1.0 + 1e-6));
  // Moved: (45, 12) less (40, 0) is (5, 12), r = 13 < r_min; less (-30, 0): r = 75.9 > 70.
  EXPECT_FALSE(mapReaches(map, up, {40, 0, 0}, 0.0));
  EXPECT_FALSE(mapReaches(map, up, {-30, 0, 0}, 0.0));
  EXPECT_TRUE(mapReaches(map, up, {20, 0, 0}, 0.0));  // (25, 12): r = 27.7
  float untouched = -1.f;
  EXPECT_FALSE(mapReaches(map, up, {40, 0, 0}, 0.0, &untouched));
  EXPECT_EQ(untouched, -1.f);
  // Out of the plane: z = 3 is voxel k = 1, which no sample (z = 0) reaches.
  EXPECT_FALSE(mapReaches(map, targetFromNormal({45, 12, 3}, {0, 0, -1}), {0, 0, 0}, 0.0));
  // Approach -x, 90 deg from the only reached direction +z. The target's x axis is +y, its y axis
  // -z, so the probe turned 270 deg tilts towards +z: at 50 deg (half of 100) it is 40 deg from
  // +z, at 100 deg 10 deg from +z, inside the polar cap. With 60 deg the nearest probe is 30 deg
  // from +z, outside the cap (28.96 deg).
  const ReachTarget side = targetFromNormal(p, {1, 0, 0});
  EXPECT_FALSE(mapReaches(map, side, Eigen::Vector3d::Zero(), 0.0));
  EXPECT_FALSE(mapReaches(map, side, Eigen::Vector3d::Zero(), 60.0 * kDeg));
  EXPECT_TRUE(mapReaches(map, side, Eigen::Vector3d::Zero(), 100.0 * kDeg));
  // Approach tilted 40 deg from +z towards +x: the target's x axis points down that slope, so the
  // probe turned 180 deg tilts towards +z. Tolerance 10 deg: probes 35 and 30 deg from +z, outside
  // the cap; 20 deg: the full ring reaches 20 deg from +z, inside; 80 deg: the half ring lands on
  // +z itself (the full ring, 40 deg past it, would not).
  const Eigen::Vector3d slope(std::sin(40.0 * kDeg), 0.0, std::cos(40.0 * kDeg));
  const ReachTarget tilted = targetFromNormal(p, -slope);
  ASSERT_NEAR((tilted.pose.linear().col(0) -
               Eigen::Vector3d(std::cos(40.0 * kDeg), 0.0, -std::sin(40.0 * kDeg)))
                  .norm(),
              0.0, 1e-12);
  EXPECT_FALSE(mapReaches(map, tilted, Eigen::Vector3d::Zero(), 0.0));
  EXPECT_FALSE(mapReaches(map, tilted, Eigen::Vector3d::Zero(), 10.0 * kDeg));
  EXPECT_TRUE(mapReaches(map, tilted, Eigen::Vector3d::Zero(), 20.0 * kDeg));
  EXPECT_TRUE(mapReaches(map, tilted, Eigen::Vector3d::Zero(), 80.0 * kDeg));
  // A full pose counts its own bin: the roll is irrelevant with one roll bin.
  ReachTarget full = up;
  full.free_roll = false;
  full.pose.linear() = Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_TRUE(mapReaches(map, full, Eigen::Vector3d::Zero(), 0.0));
  full.pose.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  EXPECT_FALSE(mapReaches(map, full, Eigen::Vector3d::Zero(), 0.0));
}

// Two targets 40 cm apart at y = 50 and the robot moved along x by d: both reached iff
// d^2 + 50^2 <= 70^2 and (40 - d)^2 + 50^2 <= 70^2, d in [40 - sqrt(2400), sqrt(2400)] =
// [-8.99, 48.99]. Manipulabilities in closed form; the best base maximises their mean.
TEST(BasePlacement, TwoTargetsIntervalInClosedForm) {
  const ReachMap& map = planarMap();
  const Robot robot = planar2();
  ReachStudyOptions options = planarOptions();
  options.starts = 2;
  options.ik.restarts = 5;
  options.threads = 1;  // 101 tiny parallel loops: no gain, and slow on a busy machine
  const ReachStudy study(robot, nullptr, options);
  const std::vector<ReachTarget> targets = {targetFromNormal({0, 50, 0}, {0, 0, -1}),
                                            targetFromNormal({40, 50, 0}, {0, 0, -1})};
  std::vector<Eigen::Vector3d> offsets;
  for (int d = -30; d <= 70; ++d) offsets.emplace_back(d, 0.0, 0.0);
  PlacementOptions placement;
  placement.confirm = -1;
  std::size_t progress_calls = 0, progress_last = 0;
  const std::vector<BaseCandidate> candidates =
      placeBase(map, study, targets, offsets, placement, [&](std::size_t done, std::size_t all) {
        ++progress_calls;
        EXPECT_GE(done, progress_last);  // never backwards
        progress_last = done;
        EXPECT_EQ(all, offsets.size());
      });
  ASSERT_EQ(candidates.size(), offsets.size());
  EXPECT_GE(progress_calls, 1u);
  EXPECT_EQ(progress_last, offsets.size());  // ends with all confirmed

  const double half = std::sqrt(kOuter * kOuter - 50.0 * 50.0);  // 48.99
  const double low = 40.0 - half, high = half, centre = 20.0;
  const double slack = 2.0 * map.grid().resolution + 1.0;
  double best_expected = -1.0;
  int best_d = 0;
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const BaseCandidate& x = candidates[c];
    const double d = offsets[c].x();
    EXPECT_EQ(x.offset, offsets[c]);
    ASSERT_TRUE(x.confirmed) << d;
    const double r1 = std::hypot(d, 50.0), r2 = std::hypot(40.0 - d, 50.0);
    const int expected_reached = (r1 <= kOuter ? 1 : 0) + (r2 <= kOuter ? 1 : 0);
    EXPECT_EQ(x.ik.targets, 2u);
    EXPECT_EQ(x.ik.reached, static_cast<std::size_t>(expected_reached)) << d;
    const double expected_score = ((r1 <= kOuter ? planarManipulability(r1) : 0.0) +
                                   (r2 <= kOuter ? planarManipulability(r2) : 0.0)) /
                                  2.0;
    // Each target's manipulability within what the IK position tolerance moves it.
    const double score_tolerance =
        1.01e-6 * (planarManipulabilitySlope(r1) + planarManipulabilitySlope(r2)) / 2.0 +
        1e-9 * kL1 * kL2;
    EXPECT_NEAR(x.ik.mean_score, expected_score, score_tolerance) << d;
    if (d >= low && d <= high) {
      EXPECT_EQ(x.ik.share_reached, 1.0) << d;
      EXPECT_EQ(x.map_share, 1.0) << d;
      if (expected_score > best_expected) {
        best_expected = expected_score;
        best_d = static_cast<int>(d);
      }
    } else {
      EXPECT_LT(x.ik.share_reached, 1.0) << d;
    }
    // The map over-estimates by a voxel at most.
    if (std::abs(d - centre) > (high - centre) + slack) {
      EXPECT_LT(x.map_share, 1.0) << d;
    }
    EXPECT_GE(x.map_share, x.ik.share_reached) << d;
    EXPECT_GE(x.map_score, 0.0);
    EXPECT_LE(x.map_score, kL1 * kL2 * (1.0 + 1e-6));
  }
  EXPECT_EQ(best_d, 20);  // the symmetric middle, r = 53.85 for both
  const int best = bestCandidate(candidates);
  ASSERT_GE(best, 0);
  EXPECT_EQ(candidates[static_cast<std::size_t>(best)].ik.share_reached, 1.0);
  EXPECT_EQ(candidates[static_cast<std::size_t>(best)].offset.x(), best_d);
  const double r_best = std::hypot(20.0, 50.0);
  EXPECT_NEAR(candidates[static_cast<std::size_t>(best)].ik.mean_score, best_expected,
              1.01e-6 * planarManipulabilitySlope(r_best) + 1e-9 * kL1 * kL2);
}

// Only the best `confirm` by the map are confirmed; bestCandidate picks among them.
TEST(BasePlacement, ConfirmsTheMapsBestOnly) {
  const ReachMap& map = planarMap();
  ReachStudyOptions options = planarOptions();
  options.starts = 2;
  options.ik.restarts = 5;
  options.threads = 1;  // 101 tiny parallel loops: no gain, and slow on a busy machine
  const ReachStudy study(planar2(), nullptr, options);
  const std::vector<ReachTarget> targets = {targetFromNormal({0, 50, 0}, {0, 0, -1}),
                                            targetFromNormal({40, 50, 0}, {0, 0, -1})};
  // Offsets -40 .. 80 step 20: only 0, 20 and 40 lie in [-8.99, 48.99].
  std::vector<Eigen::Vector3d> offsets;
  for (int d = -40; d <= 80; d += 20) offsets.emplace_back(d, 0.0, 0.0);
  PlacementOptions placement;
  placement.confirm = 3;
  const std::vector<BaseCandidate> candidates = placeBase(map, study, targets, offsets, placement);
  std::vector<double> confirmed;
  for (const BaseCandidate& c : candidates) {
    if (c.confirmed) {
      confirmed.push_back(c.offset.x());
      EXPECT_EQ(c.ik.share_reached, 1.0) << c.offset.x();
    } else {
      EXPECT_EQ(c.ik.targets, 0u);
    }
  }
  EXPECT_EQ(confirmed, (std::vector<double>{0.0, 20.0, 40.0}));
  const int best = bestCandidate(candidates);
  ASSERT_GE(best, 0);
  EXPECT_EQ(candidates[static_cast<std::size_t>(best)].offset.x(), 20.0);

  placement.confirm = 0;
  const std::vector<BaseCandidate> none = placeBase(map, study, targets, offsets, placement);
  EXPECT_EQ(bestCandidate(none), -1);
  EXPECT_EQ(bestCandidate({}), -1);
  EXPECT_THROW(placeBase(map, study, {}, offsets, placement), Error);
  EXPECT_THROW(placeBase(map, study, targets, {}, placement), Error);
}

// The map's manipulability score is the best of a voxel's samples: with coarse voxels it is flat
// over many positions and does not rank them as IK does. Two targets 40 cm apart (IK's best
// position d = 20, the symmetric middle, in closed form: TwoTargetsIntervalInClosedForm) and a
// 10 cm map: the map ranks d = 20 below its fifth, so the five best by the map miss it; every
// position within a map share of 0.1 of the best is confirmed and IK finds it.
TEST(BasePlacement, ConfirmsEveryPositionWithinTheMarginOfTheMapsBest) {
  const ReachMap map = buildPlanarMap(10.0, 200000);
  ReachStudyOptions options = planarOptions();
  options.starts = 2;
  options.ik.restarts = 5;
  options.threads = 1;
  const ReachStudy study(planar2(), nullptr, options);
  const std::vector<ReachTarget> targets = {targetFromNormal({0, 50, 0}, {0, 0, -1}),
                                            targetFromNormal({40, 50, 0}, {0, 0, -1})};
  std::vector<Eigen::Vector3d> offsets;
  for (int d = -30; d <= 70; ++d) offsets.emplace_back(d, 0.0, 0.0);
  constexpr std::size_t kMiddle = 50;  // d = 20
  constexpr double kMargin = 0.1;

  PlacementOptions five;  // the old rule: the five best by the map
  five.confirm = 5;
  const std::vector<BaseCandidate> by_five = placeBase(map, study, targets, offsets, five);
  // Positions the map ranks above d = 20 (share, then score): five or more.
  std::size_t above = 0;
  for (const BaseCandidate& c : by_five) {
    const BaseCandidate& m = by_five[kMiddle];
    above += c.map_share > m.map_share || (c.map_share == m.map_share && c.map_score > m.map_score);
  }
  EXPECT_GE(above, 5u);
  EXPECT_FALSE(by_five[kMiddle].confirmed);
  const int five_best = bestCandidate(by_five);
  ASSERT_GE(five_best, 0);
  EXPECT_NE(by_five[static_cast<std::size_t>(five_best)].offset.x(), 20.0);

  PlacementOptions margin;
  margin.confirm = 0;
  margin.confirm_margin = kMargin;
  const std::vector<BaseCandidate> by_margin = placeBase(map, study, targets, offsets, margin);
  double best_share = 0.0;
  for (const BaseCandidate& c : by_margin) best_share = std::max(best_share, c.map_share);
  EXPECT_EQ(best_share, 1.0);
  for (const BaseCandidate& c : by_margin) {
    EXPECT_EQ(c.confirmed, c.map_share >= best_share - kMargin) << c.offset.x();
  }
  const int best = bestCandidate(by_margin);
  ASSERT_GE(best, 0);
  EXPECT_EQ(by_margin[static_cast<std::size_t>(best)].offset.x(), 20.0);
  EXPECT_EQ(by_margin[static_cast<std::size_t>(best)].ik.share_reached, 1.0);
}

// candidatesToConfirm: the best `confirm` by the map, united with every candidate whose share is
// at least the best less the margin (a share exactly at the edge included), in the map's order.
TEST(BasePlacement, CandidatesToConfirmUniteTheBestByMapAndTheMargin) {
  std::vector<BaseCandidate> c(6);
  const double share[] = {0.5, 1.0, 0.9, 0.8, 1.0, 0.0};
  const double score[] = {900.0, 10.0, 30.0, 50.0, 20.0, 0.0};
  for (std::size_t i = 0; i < c.size(); ++i) {
    c[i].map_share = share[i];
    c[i].map_score = score[i];
  }
  PlacementOptions o;
  o.confirm = 0;
  o.confirm_margin = 0.1;  // 1.0 - 0.1: 0.9 is in (to rounding)
  EXPECT_EQ(candidatesToConfirm(c, o), (std::vector<std::size_t>{4, 1, 2}));
  o.confirm_margin = 0.0;
  EXPECT_EQ(candidatesToConfirm(c, o), (std::vector<std::size_t>{4, 1}));
  o.confirm = 4;  // the four best by the map, more than the margin holds
  EXPECT_EQ(candidatesToConfirm(c, o), (std::vector<std::size_t>{4, 1, 2, 3}));
  o.confirm = 1;  // fewer: the margin's
  o.confirm_margin = 0.5;
  EXPECT_EQ(candidatesToConfirm(c, o), (std::vector<std::size_t>{4, 1, 2, 3, 0}));
  o.confirm_margin = -1.0;  // none by margin
  EXPECT_EQ(candidatesToConfirm(c, o), (std::vector<std::size_t>{4}));
  o.confirm = -1;
  EXPECT_EQ(candidatesToConfirm(c, o).size(), c.size());
  o.confirm = 0;
  o.confirm_margin = 1.0;
  EXPECT_EQ(candidatesToConfirm(c, o).size(), c.size());
  EXPECT_TRUE(candidatesToConfirm({}, o).empty());
}

TEST(BasePlacement, BestCandidateOrdersByShareThenScoreThenFirst) {
  std::vector<BaseCandidate> c(5);
  const double share[] = {0.5, 1.0, 1.0, 1.0, 0.9};
  const double score[] = {900.0, 10.0, 30.0, 30.0, 50.0};
  for (std::size_t i = 0; i < c.size(); ++i) {
    c[i].confirmed = true;
    c[i].ik.share_reached = share[i];
    c[i].ik.mean_score = score[i];
  }
  EXPECT_EQ(bestCandidate(c), 2);
  c[2].confirmed = false;
  EXPECT_EQ(bestCandidate(c), 3);
  c[3].confirmed = false;
  c[1].confirmed = false;
  EXPECT_EQ(bestCandidate(c), 4);
}

}  // namespace
}  // namespace mcws
