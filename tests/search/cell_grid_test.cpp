// CellGridSearch against brute force, query by query: the k-th distance, the k nearest and the
// radius neighbourhoods (their points, squared distances and offsets bit for bit, in cell order,
// which the orthant test's sums follow), on uniform, clustered, flat, duplicated, lattice and
// planar clouds, with the searches in the orders the boundary filter asks for them and others.
#include "mcws/search/cell_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "mcws/search/grid_then_tree_search.h"

namespace mcws {
namespace {

struct TestCloud {
  std::string name;
  pcl::PointCloud<pcl::PointXYZ> cloud;
  int dimensions;
};

std::vector<TestCloud> clouds() {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::normal_distribution<float> g(0.0f, 1.0f);
  std::vector<TestCloud> out;
  TestCloud ball{"ball", {}, 3};
  while (ball.cloud.size() < 6000) {
    const pcl::PointXYZ p(u(rng), u(rng), u(rng));
    if (p.getVector3fMap().norm() <= 1.0f) ball.cloud.push_back(p);
  }
  out.push_back(ball);
  TestCloud clustered{"clustered", {}, 3};
  for (int k = 0; k < 6000; ++k) {
    const float sigma = k % 3 == 0 ? 0.01f : (k % 3 == 1 ? 0.1f : 0.0f);
    const float cx = static_cast<float>(k % 3) * 0.7f;
    clustered.cloud.push_back(
        sigma > 0 ? pcl::PointXYZ(cx + sigma * g(rng), sigma * g(rng), sigma * g(rng))
                  : pcl::PointXYZ(u(rng), u(rng), u(rng)));
  }
  out.push_back(clustered);
  TestCloud slab{"thin slab", {}, 3};
  for (int k = 0; k < 5000; ++k)
    slab.cloud.push_back(pcl::PointXYZ(u(rng), u(rng), 1e-3f * u(rng)));
  out.push_back(slab);
  TestCloud copies{"copies", {}, 3};
  for (int k = 0; k < 1500; ++k) {
    const pcl::PointXYZ p(u(rng), u(rng), u(rng));
    for (unsigned c = 0; c <= rng() % 3; ++c) copies.cloud.push_back(p);
  }
  out.push_back(copies);
  TestCloud lattice{"lattice", {}, 3};
  for (int x = 0; x < 14; ++x) {
    for (int y = 0; y < 14; ++y) {
      for (int z = 0; z < 14; ++z) lattice.cloud.push_back(pcl::PointXYZ(x, y, z));
    }
  }
  out.push_back(lattice);
  TestCloud disk{"disk", {}, 2};
  while (disk.cloud.size() < 5000) {
    const pcl::PointXYZ p(u(rng), u(rng), 0.0f);
    if (p.x * p.x + p.y * p.y <= 1.0f) disk.cloud.push_back(p);
  }
  out.push_back(disk);
  return out;
}

/// The search the boundary filter builds for k = 16 and scale 2 on `c` (its typical radius from
/// the bounding box's mean spacing), the cloud renumbered in cell order.
GridThenTreeSearch searchOf(const TestCloud& c, int threads = 1) {
  Eigen::Array3f lo = Eigen::Array3f::Constant(1e30f), hi = -lo;
  for (const auto& p : c.cloud) {
    lo = lo.min(p.getArray3fMap());
    hi = hi.max(p.getArray3fMap());
  }
  const Eigen::Array3f extent = (hi - lo).max(1e-3f);
  const double volume = c.dimensions == 2 ? extent.x() * extent.y() : extent.prod();
  const double spacing = std::pow(volume / c.cloud.size(), 1.0 / c.dimensions);
  const double typical = 2.0 * std::cbrt(3.0 * 17 / (4.0 * M_PI)) * spacing;
  std::vector<pcl::index_t> position_of(c.cloud.size());
  std::iota(position_of.begin(), position_of.end(), 0);
  pcl::PointCloud<pcl::PointXYZ> copy = c.cloud;
  return GridThenTreeSearch(std::move(copy), position_of, c.dimensions, typical, spacing, true,
                            threads);
}

/// Squared distances from point i to every point, as pcl::KdTreeFLANN computes them.
std::vector<float> bruteDistances(const pcl::PointCloud<pcl::PointXYZ>& cloud, pcl::index_t i) {
  std::vector<float> d2(cloud.size());
  const pcl::PointXYZ& p = cloud[i];
  for (std::size_t j = 0; j < cloud.size(); ++j) {
    const float dx = cloud[j].x - p.x, dy = cloud[j].y - p.y, dz = cloud[j].z - p.z;
    float d = dx * dx;
    d += dy * dy;
    d += dz * dz;
    d2[j] = d;
  }
  return d2;
}

/// `found` must be exactly the points `expected`, in that order, with their squared distances
/// and offsets from point i.
void expectList(const pcl::PointCloud<pcl::PointXYZ>& cloud, pcl::index_t i,
                const std::vector<float>& d2, const std::vector<Neighbour>& found,
                const std::vector<std::size_t>& expected, const std::string& what) {
  ASSERT_EQ(found.size(), expected.size()) << what;
  const pcl::PointXYZ& p = cloud[i];
  for (std::size_t k = 0; k < found.size(); ++k) {
    const std::size_t j = expected[k];
    const Neighbour& q = found[k];
    ASSERT_EQ(q.index, static_cast<pcl::index_t>(j)) << what;
    ASSERT_EQ(q.d2, d2[j]) << what;
    const float dx = cloud[j].x - p.x, dy = cloud[j].y - p.y, dz = cloud[j].z - p.z;
    ASSERT_EQ(0, std::memcmp(&q.x, &dx, sizeof dx)) << what;
    ASSERT_EQ(0, std::memcmp(&q.y, &dy, sizeof dy)) << what;
    ASSERT_EQ(0, std::memcmp(&q.z, &dz, sizeof dz)) << what;
  }
}

/// The indices j that `take` accepts, in order.
template <typename Take>
std::vector<std::size_t> indicesWhere(std::size_t n, Take take) {
  std::vector<std::size_t> out;
  for (std::size_t j = 0; j < n; ++j) {
    if (take(j)) out.push_back(j);
  }
  return out;
}

/// The searches of point i in the filter's order and a few more, each checked.
void checkPoint(CellGridSearch& search, const pcl::PointCloud<pcl::PointXYZ>& cloud, pcl::index_t i,
                int& served) {
  const std::vector<float> d2 = bruteDistances(cloud, i);
  // The 17th and 25th smallest (those before them smaller or equal).
  std::vector<float> sorted = d2;
  std::nth_element(sorted.begin(), sorted.begin() + 24, sorted.end());
  std::nth_element(sorted.begin(), sorted.begin() + 16, sorted.begin() + 24);
  const std::string at = "point " + std::to_string(i);
  std::vector<Neighbour> found;
  // The 2-D filter's first question, then the k nearest, then radii about the adaptive one.
  if (search.adaptiveSubset(i, 17, 2.0f, found)) {
    // A subset of those within r_i: every point closer than its farthest one, in index order.
    const float kth = sorted[16];
    const float r = 2.0f * std::sqrt(kth);
    float farthest = 0.0f;
    for (const auto& q : found) farthest = std::max(farthest, q.d2);
    ASSERT_LT(farthest, static_cast<float>(static_cast<double>(r) * r)) << at;
    expectList(cloud, i, d2, found,
               indicesWhere(cloud.size(), [&](std::size_t j) { return d2[j] <= farthest; }),
               at + " subset");
  }
  const std::optional<float> kth = search.kthDistance2(i, 17, &found);
  if (!kth) return;
  ++served;
  ASSERT_EQ(*kth, sorted[16]) << at;

  // Those closer than the k-th distance, then ties at it up to k + 1 points, each in index
  // (cell) order.
  std::vector<std::size_t> nearest =
      indicesWhere(cloud.size(), [&](std::size_t j) { return d2[j] < *kth; });
  for (std::size_t j = 0; j < cloud.size() && nearest.size() < 17; ++j) {
    if (d2[j] == *kth) nearest.push_back(j);
  }
  expectList(cloud, i, d2, found, nearest, at + " nearest");
  const float rk = 2.0f * std::sqrt(*kth);
  for (const double factor : {1.0, 0.65, 1.0, 1.6, 0.3}) {
    const double r = factor * rk;
    if (!search.radius(i, r, found)) continue;
    const auto limit = static_cast<float>(r * r);
    expectList(cloud, i, d2, found,
               indicesWhere(cloud.size(), [&](std::size_t j) { return d2[j] < limit; }),
               at + " radius " + std::to_string(factor));
  }
  const std::optional<float> again = search.kthDistance2(i, 25, nullptr);
  if (again) {
    ASSERT_EQ(*again, sorted[24]) << at;
  }
}

TEST(CellGridSearch, EqualsBruteForceOnEveryKindOfCloud) {
  for (const TestCloud& c : clouds()) {
    SCOPED_TRACE(c.name);
    const GridThenTreeSearch grid = searchOf(c);
    const pcl::PointCloud<pcl::PointXYZ>& cloud = grid.positions();
    CellGridSearch search = grid.gridSearch();
    // Every point in cell order (as the filter goes), then 500 in a random order (the hints
    // jump), then a few twice in a row.
    std::vector<pcl::index_t> order(cloud.size());
    std::iota(order.begin(), order.end(), 0);
    std::mt19937 rng(1);
    std::vector<pcl::index_t> shuffled = order;
    std::shuffle(shuffled.begin(), shuffled.end(), rng);
    shuffled.resize(std::min<std::size_t>(500, shuffled.size()));
    order.insert(order.end(), shuffled.begin(), shuffled.end());
    order.insert(order.end(), {0, 0, 5, 5, 0});
    int served = 0;
    for (const pcl::index_t i : order) {
      checkPoint(search, cloud, i, served);
      if (::testing::Test::HasFatalFailure()) return;
    }
    // The grid answers most queries (else the comparison would test little).
    EXPECT_GT(served, static_cast<int>(order.size()) / 2);
  }
}

TEST(CellGridSearch, SameAnswersOnOneAndTwoThreads) {
  for (const TestCloud& c : clouds()) {
    SCOPED_TRACE(c.name);
    std::vector<double> summary[2];
    for (int threads = 1; threads <= 2; ++threads) {
      GridThenTreeSearch grid = searchOf(c, threads);
      std::vector<pcl::index_t> every(grid.size());
      std::iota(every.begin(), every.end(), 0);
      std::vector<double>& out = summary[threads - 1];
      out.assign(2 * grid.size(), 0.0);
      grid.forEachPoint<std::vector<Neighbour>>(
          every, threads, [&](NeighbourSearch& s, pcl::index_t i, std::vector<Neighbour>& found) {
            const std::optional<float> kth = s.kthDistance2(i, 17, nullptr);
            if (!kth || !s.radius(i, 2.0f * std::sqrt(*kth), found)) return false;
            double sum = 0.0;
            for (const auto& q : found) sum += q.index;
            out[2 * i] = *kth;
            out[2 * i + 1] = sum;
            return true;
          });
    }
    EXPECT_EQ(summary[0], summary[1]);
  }
}

}  // namespace
}  // namespace mcws
