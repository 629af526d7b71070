// kthNeighbourSquaredDistance against brute force.
#include "mcws/workspace/nearest_neighbours.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "mcws/core/error.h"

namespace mcws {
namespace {

pcl::PointCloud<pcl::PointXYZ> randomCloud(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  pcl::PointCloud<pcl::PointXYZ> cloud;
  for (std::size_t i = 0; i < n; ++i) cloud.push_back(pcl::PointXYZ(u(rng), u(rng), u(rng)));
  return cloud;
}

/// The k-th smallest squared distance from point i to the others, in float as the tree computes.
float bruteForce(const pcl::PointCloud<pcl::PointXYZ>& cloud, std::size_t i, int dimensions,
                 int k) {
  std::vector<float> d2;
  for (std::size_t j = 0; j < cloud.size(); ++j) {
    if (j == i) continue;
    const float dx = cloud[j].x - cloud[i].x, dy = cloud[j].y - cloud[i].y,
                dz = dimensions == 3 ? cloud[j].z - cloud[i].z : 0.0f;
    float d = dx * dx;
    d += dy * dy;
    d += dz * dz;
    d2.push_back(d);
  }
  if (d2.empty()) return 0.0f;
  const std::size_t rank = std::min<std::size_t>(k, d2.size()) - 1;
  std::nth_element(d2.begin(), d2.begin() + rank, d2.end());
  return d2[rank];
}

TEST(KthNeighbour, MatchesBruteForceIn2DAnd3D) {
  const auto cloud = randomCloud(3000, 7);
  for (int dimensions : {2, 3}) {
    for (int k : {1, 8, 20}) {
      const std::vector<float> d2 = kthNeighbourSquaredDistance(cloud, dimensions, k);
      ASSERT_EQ(d2.size(), cloud.size());
      for (std::size_t i = 0; i < cloud.size(); ++i) {
        ASSERT_EQ(d2[i], bruteForce(cloud, i, dimensions, k))
            << "point " << i << ", D = " << dimensions << ", k = " << k;
      }
    }
  }
}

TEST(KthNeighbour, MatchesBruteForceOnUnevenClouds) {
  // The grid search on a Gaussian blob (dense core, sparse tails: many rings of cells far out),
  // and the kd-tree where the grid does not fit: two tight clusters far apart (crowded cells) and
  // points on a line (a box of no volume).
  std::mt19937 rng(11);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  pcl::PointCloud<pcl::PointXYZ> blob, clusters, line;
  for (int i = 0; i < 3000; ++i) {
    blob.push_back(pcl::PointXYZ(normal(rng), normal(rng), normal(rng)));
    const float offset = i % 2 ? 1000.0f : 0.0f;
    clusters.push_back(pcl::PointXYZ(offset + normal(rng), normal(rng), normal(rng)));
    line.push_back(pcl::PointXYZ(normal(rng), 2.0f, 3.0f));
  }
  for (const auto* cloud : {&blob, &clusters, &line}) {
    for (int dimensions : {2, 3}) {
      const std::vector<float> d2 = kthNeighbourSquaredDistance(*cloud, dimensions, 8, 2);
      for (std::size_t i = 0; i < cloud->size(); ++i) {
        ASSERT_EQ(d2[i], bruteForce(*cloud, i, dimensions, 8)) << "point " << i;
      }
    }
  }
}

TEST(KthNeighbour, CopiesAreNeighboursAtDistanceZero) {
  pcl::PointCloud<pcl::PointXYZ> cloud;
  for (int i = 0; i < 3; ++i) cloud.push_back(pcl::PointXYZ(0.0f, 0.0f, 0.0f));
  cloud.push_back(pcl::PointXYZ(3.0f, 4.0f, 0.0f));
  const std::vector<float> first = kthNeighbourSquaredDistance(cloud, 3, 1);
  EXPECT_EQ(first[0], 0.0f);  // another copy
  EXPECT_EQ(first[3], 25.0f);
  const std::vector<float> third = kthNeighbourSquaredDistance(cloud, 3, 3);
  EXPECT_EQ(third[0], 25.0f);  // two copies, then the far point
}

TEST(KthNeighbour, SmallCloudsGiveTheFarthestOtherPoint) {
  pcl::PointCloud<pcl::PointXYZ> cloud;
  cloud.push_back(pcl::PointXYZ(0.0f, 0.0f, 0.0f));
  EXPECT_EQ(kthNeighbourSquaredDistance(cloud, 3, 8), std::vector<float>{0.0f});
  cloud.push_back(pcl::PointXYZ(1.0f, 0.0f, 0.0f));
  cloud.push_back(pcl::PointXYZ(0.0f, 2.0f, 5.0f));  // z ignored in 2-D
  const std::vector<float> d2 = kthNeighbourSquaredDistance(cloud, 2, 8);
  EXPECT_EQ(d2, (std::vector<float>{4.0f, 5.0f, 5.0f}));
  EXPECT_TRUE(kthNeighbourSquaredDistance(pcl::PointCloud<pcl::PointXYZ>(), 3, 8).empty());
}

TEST(KthNeighbour, SameResultForAnyThreadCount) {
  const auto cloud = randomCloud(20000, 3);
  const std::vector<float> one = kthNeighbourSquaredDistance(cloud, 3, 8, 1);
  for (int threads : {2, 3}) EXPECT_EQ(kthNeighbourSquaredDistance(cloud, 3, 8, threads), one);
}

TEST(KthNeighbour, MatchesBruteForceOnLargerUniformBallsAndDisks) {
  // Clouds large enough that most queries are settled by their cell's block of cells (a few by
  // the wider block or the grid search): points inside, near the edge and on the bounding box's
  // faces, with a cluster of copies, against brute force for every 37th point.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int dimensions : {2, 3}) {
    pcl::PointCloud<pcl::PointXYZ> cloud;
    while (cloud.size() < 30000) {
      const pcl::PointXYZ p(u(rng), u(rng), dimensions == 3 ? u(rng) : 0.0f);
      const float r2 = p.x * p.x + p.y * p.y + p.z * p.z;
      if (r2 <= 1.0f) cloud.push_back(p);
    }
    for (int i = 0; i < 12; ++i) cloud.push_back(cloud[100]);
    for (int k : {1, 8}) {
      const std::vector<float> d2 = kthNeighbourSquaredDistance(cloud, dimensions, k, 2);
      for (std::size_t i = 0; i < cloud.size(); i += i < 100 || i > 29990 ? 1 : 37) {
        ASSERT_EQ(d2[i], bruteForce(cloud, i, dimensions, k))
            << "point " << i << ", D = " << dimensions << ", k = " << k;
      }
    }
  }
}

TEST(KthNeighbour, MatchesBruteForceOnLatticesWhereDistancesTie) {
  // An integer lattice (every inner point has 4 or 6 neighbours at distance 1, then 4 or 12 at
  // sqrt 2, exactly in float): the k-th smallest must count the ties (k = 5 and 8 fall among
  // them), as brute force.
  for (int dimensions : {2, 3}) {
    pcl::PointCloud<pcl::PointXYZ> cloud;
    const int side = dimensions == 3 ? 18 : 70;
    for (int z = 0; z < (dimensions == 3 ? side : 1); ++z)
      for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x)
          cloud.push_back(
              pcl::PointXYZ(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)));
    for (int k : {1, 5, 8}) {
      const std::vector<float> d2 = kthNeighbourSquaredDistance(cloud, dimensions, k, 2);
      for (std::size_t i = 0; i < cloud.size(); i += 3) {
        ASSERT_EQ(d2[i], bruteForce(cloud, i, dimensions, k))
            << "point " << i << ", D = " << dimensions << ", k = " << k;
      }
    }
  }
}

TEST(KthNeighbour, RejectsBadArguments) {
  const auto cloud = randomCloud(10, 1);
  EXPECT_THROW(kthNeighbourSquaredDistance(cloud, 1, 8), Error);
  EXPECT_THROW(kthNeighbourSquaredDistance(cloud, 3, 0), Error);
}

}  // namespace
}  // namespace mcws
