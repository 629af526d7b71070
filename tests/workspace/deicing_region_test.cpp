// The closed-form de-icing region (tests/deicing_region.h) against the sampler and the measures:
// two independent routes to the same region must agree.
#include <gtest/gtest.h>

#include <random>

#include "deicing_region.h"
#include "mcws/kinematics/robot_yaml.h"
#include "mcws/sampling/sampler.h"
#include "mcws/workspace/measure.h"
#include "test_support.h"

namespace mcws {
namespace {

TEST(DeicingRegion, EverySampledPointIsInTheClosedFormRegion) {
  const Robot robot = loadRobot(test::robotPath("deicing"));
  RobotSamplerOptions plane;
  plane.fixed = {{"theta3", 0.0}};
  const auto cloud = sampleCloud(RobotSampler(robot, plane), 20000, 2);
  const test::DeicingArm arm;
  std::size_t outside = 0;
  for (const auto& p : cloud) outside += !arm.reaches(p.x, p.z);
  // Float coordinates put a rare sample at a joint limit a hair outside: allow 0.05 %.
  EXPECT_LE(outside, 10u);
}

TEST(DeicingRegion, ClosedFormAreaAgreesWithHitOrMissAndTheTriangulation) {
  // Hit or miss in the bounding square [-120, 120]^2: 1e6 uniform points, standard error of the
  // area about 0.1 % of it.
  const test::DeicingArm arm;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> coordinate(-120.0, 120.0);
  std::size_t hits = 0;
  constexpr std::size_t kDraws = 1000000;
  pcl::PointCloud<pcl::PointXYZ> inside;
  for (std::size_t k = 0; k < kDraws; ++k) {
    const double x = coordinate(rng), z = coordinate(rng);
    if (arm.reaches(x, z)) {
      ++hits;
      if (inside.size() < 100000) inside.push_back(pcl::PointXYZ(x, z, 0));
    }
  }
  const double hit_or_miss = 240.0 * 240.0 * hits / kDraws;
  const double exact = test::integrateDeicing(0.1).area;
  EXPECT_NEAR(hit_or_miss / exact, 1.0, 0.005);
  // Uniform samples of the region: the default estimator is as accurate as on the disk.
  EXPECT_NEAR(delaunayMeasure(inside, 2).measure / exact, 1.0, 0.003);
}

}  // namespace
}  // namespace mcws
