// mcws::buildReachMap: the planar 2R arm against its closed-form annulus and a brute-force map
// built from the same joint values, collision filtering counted by brute force, the map's kernel
// (PoseBatch) against the kinematics library, a 6R map by brute force, and the inspection arm's
// reachability against the geometry of its 500 mm boom (hand-made maps are in reach_map_test.cpp).
#include "mcws/reach/reach_map.h"

#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include "kinematics/random_joints.h"
#include "kinematics/test_chains.h"
#include "mcws/collision/collision_checker.h"
#include "mcws/collision/collision_model.h"
#include "mcws/core/error.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/jacobian.h"
#include "mcws/kinematics/robot_yaml.h"
#include "mcws/reach/pose_batch.h"
#include "mcws/sampling/sampler.h"
#include "reach/planar2.h"
#include "reach/reach_map_fixture.h"
#include "test_support.h"

namespace mcws {
namespace {

using test::kElbowLimit;
using test::kL1;
using test::kL2;
using test::planar2;

using test::shippedRobotFiles;
using test::tiltedAxesRobot;

using test::bytesOf;
using test::contents;
using test::readBytes;
using test::Voxel;
using test::VoxelIndex;

constexpr double kTwoPi = 2.0 * M_PI;
/// A manipulability stored as float against the closed form in double: float rounding of values
/// up to l1 l2 = 1200 cm^2 (ulp 1.2e-4), plus the Cholesky path's ~1e-12 relative.
constexpr double kFloatManipulability = 1e-6 * kL1 * kL2;

/// Samples and grid of the planar maps: not a multiple of the sampling block (16384), 2 cm voxels,
/// 20 x 6 orientation bins (two 64-bit words per voxel).
constexpr std::uint64_t kPlanarSamples = 100003;
ReachGrid planarGrid() { return test::reachGrid(2.0, 20, 6); }

// ---------------------------------------------------------------------------------------------
// buildReachMap on the planar 2R arm.

ReachSampling planarSampling(const Robot& robot, int threads) {
  return test::reachSampling(robot, kPlanarSamples, 7, threads);
}

/// The map by brute force from the same joint values (RobotSampler::jointValues, same seed,
/// samples first .. first + samples - 1), with the planar arm's closed forms instead of the
/// library's kinematics: tool point (l1 c1 + l2 c12, l1 s1 + l2 s12, 0), approach +z (region 0
/// of any partition: the north pole), roll q1 + q2 from +x (the reference of approach +z),
/// manipulability l1 l2 |sin q2|.
/// Only samples the checker labels free, when there is one.
std::map<VoxelIndex, Voxel> bruteForcePlanarMap(const Robot& robot, const ReachGrid& grid,
                                                const ReachSampling& sampling,
                                                const CollisionChecker* checker) {
  RobotSamplerOptions options;
  options.seed = sampling.seed;
  const RobotSampler sampler(robot, options);
  CollisionChecker::Scratch scratch;
  std::map<VoxelIndex, Voxel> map;
  double q[kMaxJoints];
  for (std::uint64_t i = sampling.first; i < sampling.first + sampling.samples; ++i) {
    sampler.jointValues(i, q);
    if (checker && checker->label(q, scratch) != kLabelFree) continue;
    const double x = kL1 * std::cos(q[0]) + kL2 * std::cos(q[0] + q[1]);
    const double y = kL1 * std::sin(q[0]) + kL2 * std::sin(q[0] + q[1]);
    const VoxelIndex index = {static_cast<int>(std::floor(x / grid.resolution)),
                              static_cast<int>(std::floor(y / grid.resolution)), 0};
    double roll = std::fmod(q[0] + q[1], kTwoPi);
    if (roll < 0.0) roll += kTwoPi;
    const int roll_bin = std::min(grid.rolls - 1, static_cast<int>(roll / (kTwoPi / grid.rolls)));
    Voxel& voxel = map[index];
    ++voxel.count;
    voxel.best = std::max(voxel.best, static_cast<float>(kL1 * kL2 * std::abs(std::sin(q[1]))));
    voxel.bins.insert(roll_bin);
  }
  return map;
}

/// The maps agree: same voxels, counts and bins; best manipulability to float rounding.
void expectSameMap(const std::map<VoxelIndex, Voxel>& actual,
                   const std::map<VoxelIndex, Voxel>& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  auto e = expected.begin();
  for (const auto& [index, voxel] : actual) {
    ASSERT_EQ(index, e->first);
    ASSERT_EQ(voxel.count, e->second.count) << index[0] << " " << index[1] << " " << index[2];
    ASSERT_EQ(voxel.bins, e->second.bins) << index[0] << " " << index[1] << " " << index[2];
    ASSERT_NEAR(voxel.best, e->second.best, kFloatManipulability);
    ++e;
  }
}

TEST(BuildReachMap, PlanarArmMatchesABruteForceMapOfTheSameJointValues) {
  const Robot robot = planar2();
  const ReachSampling sampling = planarSampling(robot, 2);
  ASSERT_EQ(sampling.quality.task, QualityTask::kPosition);
  std::vector<std::pair<std::uint64_t, std::uint64_t>> progress;
  const ReachMap map = buildReachMap(
      robot, planarGrid(), sampling,
      [&](std::uint64_t done, std::uint64_t all) { progress.emplace_back(done, all); });
  EXPECT_EQ(map.samples(), kPlanarSamples);
  expectSameMap(contents(map), bruteForcePlanarMap(robot, planarGrid(), sampling, nullptr));
  ASSERT_FALSE(progress.empty());
  EXPECT_EQ(progress.back(), std::make_pair(kPlanarSamples, kPlanarSamples));
  // Every sample's own pose is reached (ReachMap::reached(p, R)).
  RobotSamplerOptions options;
  options.seed = sampling.seed;
  const RobotSampler sampler(robot, options);
  double q[kMaxJoints];
  for (std::uint64_t i = 0; i < 1000; ++i) {
    sampler.jointValues(i, q);
    const Eigen::Isometry3d T = toolPose(robot, Eigen::Vector2d(q[0], q[1]));
    ASSERT_TRUE(map.reached(T.translation(), T.linear())) << i;
  }
}

TEST(BuildReachMap, PlanarArmFillsItsAnnulusAndNothingElse) {
  const Robot robot = planar2();
  const ReachGrid grid = planarGrid();
  const ReachMap map = buildReachMap(robot, grid, planarSampling(robot, 2));
  // The tool point's radius: r^2 = l1^2 + l2^2 + 2 l1 l2 cos q2 with |q2| <= 160 deg, so
  // sqrt(2500 + 2400 cos 160 deg) = 15.644 cm <= r <= 70 cm (at least |l1 - l2| = 10). A voxel's
  // centre is within half a diagonal of each of its samples.
  const double r_min = std::sqrt(kL1 * kL1 + kL2 * kL2 + 2 * kL1 * kL2 * std::cos(kElbowLimit));
  const double r_max = kL1 + kL2;
  const double half_diagonal = 0.5 * std::sqrt(3.0) * grid.resolution;
  ASSERT_NEAR(r_min, 15.6441, 1e-4);
  int in_band = 0;
  for (std::size_t v = 0; v < map.size(); ++v) {
    const Eigen::Vector3d c = map.voxelCentre(map.voxel(v));
    const double r = c.head<2>().norm();
    ASSERT_GE(r, r_min - half_diagonal) << c.transpose();
    ASSERT_LE(r, r_max + half_diagonal) << c.transpose();
    ASSERT_EQ(map.voxel(v).z(), 0) << "the plane z = 0 is voxel layer 0";
    // Only approach +z (region 0), so at most the 6 roll bins of region 0.
    for (int b = grid.rolls; b < map.bins().size(); ++b) ASSERT_FALSE(map.reached(v, b));
    in_band += r >= 30.0 && r <= 40.0;
  }
  // Brute force over the grid: every voxel of layer 0 whose centre is 30 to 40 cm out lies well
  // inside the annulus, where ~5.6 samples fall per cm^2 (density 1 / (l1 l2 |sin q2|) per rad^2
  // of joint space, two elbow branches), ~22 per voxel: every one is occupied.
  int band = 0;
  for (int i = -25; i <= 25; ++i) {
    for (int j = -25; j <= 25; ++j) {
      const Eigen::Vector3d c = map.voxelCentre({i, j, 0});
      const double r = c.head<2>().norm();
      if (r < 30.0 || r > 40.0) continue;
      ++band;
      ASSERT_GE(map.find(c), 0) << c.transpose();
    }
  }
  EXPECT_GT(band, 400);  // 2 pi * 35 * 10 cm^2 / 4 cm^2 = 550
  EXPECT_EQ(in_band, band);
}

TEST(BuildReachMap, PlanarBestManipulabilityIsBoundedByTheVoxelsRadii) {
  // w = l1 l2 |sin q2| is a function of the radius alone: cos q2 = (r^2 - l1^2 - l2^2) /
  // (2 l1 l2), rising from 15.64 cm to its maximum l1 l2 at r = 50 cm, then falling to 0 at
  // 70 cm. A voxel's samples have radii within half a planar diagonal h of its centre's (and
  // within the annulus), so its best w lies between the least and the greatest w over that
  // interval: at its ends, or l1 l2 when it holds r = 50 cm.
  const Robot robot = planar2();
  const ReachGrid grid = planarGrid();
  const ReachMap map = buildReachMap(robot, grid, planarSampling(robot, 1));
  const auto w = [](double r) {
    const double c = std::clamp((r * r - kL1 * kL1 - kL2 * kL2) / (2 * kL1 * kL2), -1.0, 1.0);
    return kL1 * kL2 * std::sqrt(1.0 - c * c);
  };
  const double r_min = std::sqrt(kL1 * kL1 + kL2 * kL2 + 2 * kL1 * kL2 * std::cos(kElbowLimit));
  const double h = std::sqrt(0.5) * grid.resolution;
  int peak_voxels = 0;
  for (std::size_t v = 0; v < map.size(); ++v) {
    const double r = map.voxelCentre(map.voxel(v)).head<2>().norm();
    const double a = std::max(r - h, r_min), b = std::min(r + h, kL1 + kL2);
    ASSERT_LE(a, b) << r;
    const double lo = std::min(w(a), w(b));
    const bool peak = a <= 50.0 && 50.0 <= b;
    const double hi = peak ? kL1 * kL2 : std::max(w(a), w(b));
    peak_voxels += peak;
    ASSERT_LE(map.bestManipulability(v), hi + kFloatManipulability) << r;
    ASSERT_GE(map.bestManipulability(v), lo - kFloatManipulability) << r;
  }
  EXPECT_GT(peak_voxels, 100);
}

TEST(BuildReachMap, MapDoesNotDependOnTheThreadCount) {
  const Robot robot = planar2();
  const std::string one = bytesOf(buildReachMap(robot, planarGrid(), planarSampling(robot, 1)));
  EXPECT_EQ(bytesOf(buildReachMap(robot, planarGrid(), planarSampling(robot, 2))), one);
  EXPECT_EQ(bytesOf(buildReachMap(robot, planarGrid(), planarSampling(robot, 3))), one);
  // and the seed matters.
  ReachSampling other = planarSampling(robot, 1);
  other.seed = 8;
  EXPECT_NE(bytesOf(buildReachMap(robot, planarGrid(), other)), one);
}

TEST(BuildReachMap, AMapLargerThanTheCacheMatchesABruteForceMapForAnyThreadCount) {
  // 1.5 mm voxels, over 1e5 of them: a thread's table (64-byte slots) outgrows the 4 MB up to
  // which samples are recorded as they come, and the rest are recorded sorted into the table's
  // order (with 1, 2 and 3 threads, at least one table each).
  const Robot robot = planar2();
  ReachGrid grid = planarGrid();
  grid.resolution = 0.15;
  ReachSampling sampling = planarSampling(robot, 1);
  sampling.samples = 400001;
  const auto expected = bruteForcePlanarMap(robot, grid, sampling, nullptr);
  ASSERT_GT(expected.size(), 100000u);
  std::string one;
  for (const int threads : {1, 2, 3}) {
    sampling.threads = threads;
    const ReachMap map = buildReachMap(robot, grid, sampling);
    expectSameMap(contents(map), expected);
    if (threads == 1) one = bytesOf(map);
    EXPECT_EQ(bytesOf(map), one) << threads;
  }
}

TEST(BuildReachMap, MapOfAllSamplesIsTheMergeOfTheMapsOfItsParts) {
  const Robot robot = planar2();
  ReachSampling all = planarSampling(robot, 2);
  all.samples = 40000;
  ReachSampling head = all, tail = all;
  head.samples = 17000;
  tail.first = 17000;
  tail.samples = 23000;
  ReachMap merged = buildReachMap(robot, planarGrid(), head);
  const ReachMap tail_map = buildReachMap(robot, planarGrid(), tail);
  expectSameMap(contents(tail_map), bruteForcePlanarMap(robot, planarGrid(), tail, nullptr));
  merged.merge(tail_map);
  merged.sort();
  EXPECT_EQ(bytesOf(merged), bytesOf(buildReachMap(robot, planarGrid(), all)));
}

TEST(BuildReachMap, RejectsABadCharacteristicLengthOnlyWhenItIsUsed) {
  const Robot robot = planar2();
  ReachSampling sampling = planarSampling(robot, 1);
  sampling.samples = 100;
  sampling.quality.task = QualityTask::kFull;
  sampling.quality.characteristic_length = 0.0;
  const std::string message = test::errorOf([&] { buildReachMap(robot, planarGrid(), sampling); });
  EXPECT_NE(message.find("characteristic length"), std::string::npos) << message;
  sampling.manipulability = false;
  EXPECT_EQ(buildReachMap(robot, planarGrid(), sampling).samples(), 100u);
}

TEST(BuildReachMap, ZeroSamplesGiveAnEmptyMap) {
  const Robot robot = planar2();
  ReachSampling sampling = planarSampling(robot, 2);
  sampling.samples = 0;
  const ReachMap map = buildReachMap(robot, planarGrid(), sampling);
  EXPECT_EQ(map.size(), 0u);
  EXPECT_EQ(map.samples(), 0u);
}

TEST(BuildReachMap, WithoutManipulabilityTheBestValueIsZero) {
  const Robot robot = planar2();
  ReachSampling sampling = planarSampling(robot, 2);
  sampling.samples = 5000;
  sampling.manipulability = false;
  const ReachMap map = buildReachMap(robot, planarGrid(), sampling);
  std::map<VoxelIndex, Voxel> expected =
      bruteForcePlanarMap(robot, planarGrid(), sampling, nullptr);
  for (auto& entry : expected) entry.second.best = 0.f;
  expectSameMap(contents(map), expected);
}

TEST(BuildReachMap, CollisionFreeSamplesOnlyMatchTheirBruteForceCount) {
  const Robot robot = planar2();
  const std::string path = test::robotPath("planar2");
  const CollisionChecker checker(robot, loadCollisionModel(robot, path));
  ReachSampling sampling = planarSampling(robot, 2);
  sampling.samples = 30011;
  sampling.collision = &checker;
  const ReachMap map = buildReachMap(robot, planarGrid(), sampling);

  // Brute force: the checker's label of each of the same joint values.
  RobotSamplerOptions options;
  options.seed = sampling.seed;
  const RobotSampler sampler(robot, options);
  CollisionChecker::Scratch scratch;
  double q[kMaxJoints];
  std::uint64_t free = 0;
  for (std::uint64_t i = 0; i < sampling.samples; ++i) {
    sampler.jointValues(i, q);
    free += checker.label(q, scratch) == kLabelFree;
  }
  // The posts around the arm take a real share, so the filter is exercised.
  ASSERT_GT(free, sampling.samples / 10);
  ASSERT_LT(free, sampling.samples * 9 / 10);
  EXPECT_EQ(map.samples(), free);
  expectSameMap(contents(map), bruteForcePlanarMap(robot, planarGrid(), sampling, &checker));
  // Threads do not change it either.
  sampling.threads = 3;
  EXPECT_EQ(bytesOf(buildReachMap(robot, planarGrid(), sampling)), bytesOf(map));
}

TEST(BuildReachMap, ABuiltMapRoundTripsThroughTheFile) {
  const Robot robot = planar2();
  ReachSampling sampling = planarSampling(robot, 2);
  sampling.samples = 20000;
  const ReachMap map = buildReachMap(robot, planarGrid(), sampling);
  const std::string header = R"({"robot":"planar2","unit":"cm","samples":20000,"seed":7})";
  const std::string bytes = bytesOf(map, header);
  const ReachMap copy = readBytes(bytes, "planar2.map");
  EXPECT_EQ(bytesOf(copy, header), bytes);
  EXPECT_TRUE(contents(copy) == contents(map));
  // reachPoints: one point per voxel, its centre, D, best value and count.
  const auto points = reachPoints(map);
  ASSERT_EQ(points.size(), map.size());
  for (std::size_t v = 0; v < map.size(); ++v) {
    const Eigen::Vector3d c = map.voxelCentre(map.voxel(v));
    ASSERT_EQ(points[v].x, static_cast<float>(c.x()));
    ASSERT_EQ(points[v].y, static_cast<float>(c.y()));
    ASSERT_EQ(points[v].z, static_cast<float>(c.z()));
    ASSERT_FLOAT_EQ(points[v].reachability, map.reachedBins(v) / 120.0f);
    ASSERT_EQ(points[v].manipulability, map.bestManipulability(v));
    ASSERT_EQ(points[v].count, map.count(v));
  }
  // A slice of the points, as mcws_reach writes them a part at a time: the same bytes.
  ASSERT_GT(map.size(), 10u);
  for (const std::size_t first : {std::size_t{0}, std::size_t{3}, map.size() - 7}) {
    std::vector<ReachPoint, Eigen::aligned_allocator<ReachPoint>> slice(7);
    reachPoints(map, first, 7, slice.data());
    for (std::size_t i = 0; i < 7; ++i) {
      const ReachPoint &a = slice[i], &b = points[first + i];
      const float fa[] = {a.x, a.y, a.z, a.reachability, a.manipulability};
      const float fb[] = {b.x, b.y, b.z, b.reachability, b.manipulability};
      ASSERT_EQ(std::memcmp(fa, fb, sizeof fa), 0) << first + i;  // the same bits
      ASSERT_EQ(a.count, b.count) << first + i;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// The map's kernel, PoseBatch, against the kinematics library, and a 6R map by brute force.

/// Tool points from two code paths: rounding of sums of lengths up to the chain's scale.
constexpr double kPoseRelative = 1e-12;
/// manipulability() through a Gram matrix and Cholesky factor, against the singular values of
/// the measured rows: 1e-12 relative away from singularities (inverse condition >= 1e-2), and
/// k eps / inverse_condition^2 nearer (the Gram matrix's condition number; see
/// quality_test.cpp). Where the Jacobian is singular (insulator_cleaner's J1 and J2 turn about
/// one axis) the factor's last pivot is rounding, about sqrt(eps) sigma_max: the value is at most
/// ~1.5e-8 sigma_max^k, 0 when the factorisation stops.
double gramTolerance(const Jacobian& J, const QualityOptions& options) {
  Eigen::MatrixXd A = J;
  if (options.task == QualityTask::kPosition) {
    A = J.topRows<3>();
  } else {
    A.topRows<3>() /= options.characteristic_length;
  }
  const Eigen::VectorXd sigma = Eigen::JacobiSVD<Eigen::MatrixXd>(A).singularValues();
  const double w = sigma.prod(), sigma_max = sigma[0];
  const double ic = sigma_max > 0.0 ? sigma[sigma.size() - 1] / sigma_max : 0.0;
  if (ic >= 1e-2) return 1e-12 * w;
  const double singular = 1e-6 * std::pow(sigma_max, static_cast<double>(sigma.size()));
  if (ic < 1e-7) return singular;
  return 64.0 * std::numeric_limits<double>::epsilon() / (ic * ic) * w + singular;
}

TEST(PoseBatch, PosesAndManipulabilityMatchTheKinematicsLibrary) {
  std::vector<Robot> robots;
  for (const std::string& path : shippedRobotFiles()) robots.push_back(loadRobot(path));
  robots.push_back(tiltedAxesRobot());
  ASSERT_GE(robots.size(), 6u);
  constexpr int L = PoseBatch::kLanes;
  for (const Robot& robot : robots) {
    SCOPED_TRACE(robot.name);
    const PoseBatch batch(robot);
    ASSERT_EQ(batch.dof(), robot.dof());
    const double length = chainLengthScale(robot);
    std::mt19937_64 rng(89);
    QualityOptions position, full;
    position.task = QualityTask::kPosition;
    full.characteristic_length = length;
    for (int round = 0; round < 100; ++round) {
      std::vector<Eigen::VectorXd> qs(L);
      double q[8 * L];
      for (int k = 0; k < L; ++k) {
        qs[k] = test::randomJoints(robot, rng);
        for (int j = 0; j < robot.dof(); ++j) q[j * L + k] = qs[k][j];
      }
      for (const QualityOptions* quality :
           {&position, &full, static_cast<QualityOptions*>(nullptr)}) {
        double p[3 * L], approach[3 * L], x_axis[3 * L], w[L];
        batch.poses(q, p, approach, x_axis, quality, w);
        for (int k = 0; k < L; ++k) {
          const Eigen::Isometry3d T = toolPose(robot, qs[k]);
          const Eigen::Vector3d p_k(p[k], p[L + k], p[2 * L + k]);
          const Eigen::Vector3d a_k(approach[k], approach[L + k], approach[2 * L + k]);
          const Eigen::Vector3d x_k(x_axis[k], x_axis[L + k], x_axis[2 * L + k]);
          ASSERT_LT((p_k - T.translation()).norm(), kPoseRelative * length) << qs[k].transpose();
          ASSERT_LT((a_k - T.linear().col(2)).norm(), 1e-12) << qs[k].transpose();
          ASSERT_LT((x_k - T.linear().col(0)).norm(), 1e-12) << qs[k].transpose();
          if (!quality) continue;
          const Jacobian J = toolJacobian(robot, qs[k]);
          ASSERT_NEAR(w[k], jacobianQuality(J, *quality).manipulability, gramTolerance(J, *quality))
              << qualityTaskName(quality->task) << " " << qs[k].transpose();
        }
      }
    }
  }
}

TEST(PoseBatch, RejectsMoreThanEightJoints) {
  Robot robot;
  robot.source = "nine.yaml";
  robot.joints.resize(9);
  EXPECT_NE(test::errorOf([&] { PoseBatch{robot}; }).find("nine.yaml: more than 8 joints"),
            std::string::npos);
}

TEST(BuildReachMap, SixJointArmMatchesABruteForceMapOfTheSameJointValues) {
  // inspection6 with 4 roll bins: positions, approach regions and rolls of a 6R arm, and its
  // full-twist manipulability, each sample by toolPose(), OrientationBins::bin() and the SVD of
  // toolJacobian().
  const Robot robot = loadRobot(test::robotPath("inspection6"));
  const ReachGrid grid = test::reachGrid(100.0, 30, 4);
  ReachSampling sampling = test::reachSampling(robot, 20000, 3, 2);
  sampling.first = 1000;
  ASSERT_EQ(sampling.quality.task, QualityTask::kFull);
  const ReachMap map = buildReachMap(robot, grid, sampling);

  const OrientationBins bins(grid.directions, grid.rolls);
  RobotSamplerOptions options;
  options.seed = sampling.seed;
  const RobotSampler sampler(robot, options);
  std::map<VoxelIndex, Voxel> expected;
  double q[kMaxJoints];
  for (std::uint64_t i = sampling.first; i < sampling.first + sampling.samples; ++i) {
    sampler.jointValues(i, q);
    const Eigen::VectorXd qv = Eigen::Map<const Eigen::VectorXd>(q, robot.dof());
    const Eigen::Isometry3d T = toolPose(robot, qv);
    const Eigen::Vector3d p = T.translation();
    const VoxelIndex index = {static_cast<int>(std::floor(p.x() / grid.resolution)),
                              static_cast<int>(std::floor(p.y() / grid.resolution)),
                              static_cast<int>(std::floor(p.z() / grid.resolution))};
    Voxel& voxel = expected[index];
    ++voxel.count;
    voxel.bins.insert(bins.bin(T.linear().col(2), T.linear().col(0)));
    const double w = jacobianQuality(toolJacobian(robot, qv), sampling.quality).manipulability;
    voxel.best = std::max(voxel.best, static_cast<float>(w));
  }
  const std::map<VoxelIndex, Voxel> actual = contents(map);
  ASSERT_EQ(actual.size(), expected.size());
  auto e = expected.begin();
  std::set<int> rolls_seen;
  for (const auto& [index, voxel] : actual) {
    ASSERT_EQ(index, e->first);
    ASSERT_EQ(voxel.count, e->second.count);
    ASSERT_EQ(voxel.bins, e->second.bins);
    // float rounding of the best (relative 6e-8), the Cholesky path's error on it.
    ASSERT_NEAR(voxel.best, e->second.best, 1e-6 * e->second.best);
    for (int b : voxel.bins) rolls_seen.insert(b % grid.rolls);
    ++e;
  }
  EXPECT_EQ(rolls_seen.size(), 4u);
}

// ---------------------------------------------------------------------------------------------
// The inspection arm: its 500 mm boom.

/// inspection6's wrist point o5 (the origin of D-H frame 5) is the sum of the rotated offsets of
/// joints 1-5: |o5| <= 50 + 2 |(500, 0, 50)| + 50 + 50 = 1154.99 mm. Joint 6 adds d6 = 500 mm along
/// z5 and alpha6 = 0, so the tool point is p = o5 + 500 a with a = z5 = z6 the approach.
constexpr double kBoom = 500.0;
const double kWristReach = 150.0 + 2.0 * std::sqrt(252500.0);

/// The largest cosine between direction u and a direction of region `region` (colatitude x
/// longitude patch): over the patch, the nearest longitude, then the best colatitude there.
double maxCosine(const SpherePartition& sphere, int region, const Eigen::Vector3d& u) {
  double theta0, theta1, phi0, phi1;
  sphere.bounds(region, theta0, theta1, phi0, phi1);
  const double theta_u = std::acos(std::clamp(u.z(), -1.0, 1.0));
  double phi_u = std::atan2(u.y(), u.x());
  if (phi_u < 0) phi_u += kTwoPi;
  double dphi = 0.0;  // angular distance from phi_u to [phi0, phi1]
  if (phi_u < phi0 || phi_u > phi1) {
    const auto gap = [](double a, double b) {
      const double d = std::fmod(std::abs(a - b), kTwoPi);
      return std::min(d, kTwoPi - d);
    };
    dphi = std::min(gap(phi_u, phi0), gap(phi_u, phi1));
  }
  // cos(angle) = A sin(theta) + B cos(theta), A = sin(theta_u) cos(dphi), B = cos(theta_u):
  // one maximum, at atan2(A, B), so the best is there (if inside) or at an end.
  const double A = std::sin(theta_u) * std::cos(dphi), B = std::cos(theta_u);
  const auto f = [&](double t) { return A * std::sin(t) + B * std::cos(t); };
  double best = std::max(f(theta0), f(theta1));
  const double peak = std::atan2(A, B);
  if (peak >= theta0 && peak <= theta1) best = std::max(best, f(peak));
  return best;
}

TEST(BuildReachMap, InspectionArmReachesMostApproachesMidWorkspaceAndFewAtTheRim) {
  const Robot robot = loadRobot(test::robotPath("inspection6"));
  const ReachGrid grid = test::reachGrid(100.0, 50, 1);  // mm
  ReachSampling sampling = test::reachSampling(robot, 1000000, 1, 2);
  sampling.manipulability = false;
  const ReachMap map = buildReachMap(robot, grid, sampling);
  ASSERT_EQ(map.samples(), sampling.samples);
  const SpherePartition& sphere = map.bins().sphere();
  const double half_diagonal = 0.5 * std::sqrt(3.0) * grid.resolution;

  // Necessary condition for every voxel and every reached bin: some sample p (within a half
  // diagonal of the centre c) has o5 = p - 500 a with |o5| <= 1155, so some a of the bin has
  // |c - 500 a| <= 1155 + half diagonal, i.e. a . c >= (|c|^2 + 500^2 - (1155 + h)^2) / 1000.
  // This fails for bins on the wrong side of the sphere: near the rim only approaches pointing
  // outward are reachable.
  std::size_t busiest = 0;
  for (std::size_t v = 0; v < map.size(); ++v) {
    if (map.count(v) > map.count(busiest)) busiest = v;
    const Eigen::Vector3d c = map.voxelCentre(map.voxel(v));
    ASSERT_LE(c.norm(), kWristReach + kBoom + half_diagonal);
    const double reach = kWristReach + half_diagonal;
    const double needed = (c.squaredNorm() + kBoom * kBoom - reach * reach) / (2 * kBoom);
    int feasible = 0;
    for (int b = 0; b < map.bins().size(); ++b) {
      const bool possible = c.norm() * maxCosine(sphere, b, c.normalized()) >= needed - 1e-9;
      feasible += possible;
      if (map.reached(v, b)) {
        ASSERT_TRUE(possible) << "voxel " << c.transpose() << ", bin " << b;
      }
    }
    ASSERT_LE(map.reachedBins(v), feasible);
  }

  // The busiest voxel is ~360 mm from the base, in the middle of the workspace (the tool reaches
  // out to ~1650 mm). Every approach there is geometrically possible (|c - 500 a| <= 860 <
  // 1155), and about 500 of the million samples fall in it; the bins are hit unevenly (the
  // sample density follows 1 / |det J|), and 0.88 of the 50 bins were observed (seed 1). 0.75 is
  // well above what a wrong bin assignment or a one-sided wrist would give (~0.5).
  const Eigen::Vector3d middle = map.voxelCentre(map.voxel(busiest));
  EXPECT_LT(middle.norm(), 600.0) << middle.transpose();
  EXPECT_GT(map.count(busiest), 300u);
  EXPECT_GE(map.reachability(busiest), 0.75) << middle.transpose();

  // At the rim (centres over 1450 mm out) the cap of feasible approaches is small: by the
  // condition above, a . c/|c| >= (1450^2 + 500^2 - 1241.6^2) / (1000 * 1450) = 0.56, a cap of
  // (1 - 0.56) / 2 = 0.22 of the sphere, plus the bins its edge cuts (a circle of 2 pi sin 56 deg
  // = 5.2 rad through bins ~0.5 rad wide: ~10 of 50, 0.2). Observed at most 0.24.
  for (std::size_t v = 0; v < map.size(); ++v) {
    if (map.voxelCentre(map.voxel(v)).norm() > 1450.0) {
      ASSERT_LE(map.reachability(v), 0.5);
    }
  }
}

}  // namespace
}  // namespace mcws
