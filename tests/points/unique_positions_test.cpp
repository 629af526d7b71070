#include "mcws/points/unique_positions.h"

#include <gtest/gtest.h>

#include "mcws/core/counter_rng.h"

namespace mcws {
namespace {

// Brute force: point i's position is the first j <= i with the same coordinates (float ==, so
// -0 and +0 are one position), numbered in order of first appearance.
void expectSameAsBruteForce(const pcl::PointCloud<pcl::PointXYZ>& cloud) {
  std::vector<pcl::index_t> position_of;
  const pcl::PointCloud<pcl::PointXYZ> unique = uniquePositions(cloud, position_of);
  ASSERT_EQ(position_of.size(), cloud.size());
  std::vector<pcl::index_t> expected(cloud.size());
  std::size_t positions = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    std::size_t j = 0;
    while (!(cloud[j].x == cloud[i].x && cloud[j].y == cloud[i].y && cloud[j].z == cloud[i].z)) {
      ++j;
    }
    expected[i] = j == i ? static_cast<pcl::index_t>(positions++) : expected[j];
  }
  EXPECT_EQ(position_of, expected);
  ASSERT_EQ(unique.size(), positions);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const pcl::PointXYZ& p = unique[position_of[i]];
    EXPECT_TRUE(p.x == cloud[i].x && p.y == cloud[i].y && p.z == cloud[i].z) << i;
  }
}

TEST(UniquePositions, MatchesBruteForceOnCopiesAndSignedZeros) {
  const CounterRng rng(5);
  pcl::PointCloud<pcl::PointXYZ> cloud;
  for (std::uint64_t i = 0; i < 3000; ++i) {
    // Coordinates from a small set, so that many points share a position.
    auto coordinate = [&](std::uint64_t stream) {
      return static_cast<float>(static_cast<int>(rng.uniform(i, stream) * 7.0) - 3) * 0.25f;
    };
    cloud.push_back(pcl::PointXYZ(coordinate(0), coordinate(1), coordinate(2)));
  }
  cloud.push_back(pcl::PointXYZ(-0.0f, 0.0f, -0.0f));  // the same position as (0, 0, 0)
  cloud.push_back(pcl::PointXYZ(0.0f, -0.0f, 0.0f));
  cloud.push_back(pcl::PointXYZ(1e30f, -1e-30f, 3.0f));
  expectSameAsBruteForce(cloud);

  pcl::PointCloud<pcl::PointXYZ> distinct;
  for (std::uint64_t i = 0; i < 2000; ++i) {
    distinct.push_back(pcl::PointXYZ(static_cast<float>(rng.uniform(i, 3)),
                                     static_cast<float>(rng.uniform(i, 4)), 0.0f));
  }
  expectSameAsBruteForce(distinct);
  expectSameAsBruteForce(pcl::PointCloud<pcl::PointXYZ>());
}

}  // namespace
}  // namespace mcws
