#include "mcws/workspace/unique_positions.h"

#include <algorithm>
#include <numeric>
#include <tuple>

namespace mcws {

pcl::PointCloud<pcl::PointXYZ> uniquePositions(const pcl::PointCloud<pcl::PointXYZ>& cloud,
                                               std::vector<pcl::index_t>& position_of) {
  const std::size_t n = cloud.size();
  std::vector<pcl::index_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  auto key = [&](pcl::index_t i) { return std::make_tuple(cloud[i].x, cloud[i].y, cloud[i].z); };
  std::stable_sort(order.begin(), order.end(),
                   [&](pcl::index_t a, pcl::index_t b) { return key(a) < key(b); });
  // First appearance of each position, so the result keeps the input's order.
  std::vector<pcl::index_t> first(n);
  for (std::size_t k = 0; k < n; ++k) {
    first[order[k]] = k > 0 && key(order[k]) == key(order[k - 1]) ? first[order[k - 1]] : order[k];
  }
  pcl::PointCloud<pcl::PointXYZ> unique;
  std::vector<pcl::index_t> slot(n, -1);
  position_of.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (slot[first[i]] < 0) {
      slot[first[i]] = static_cast<pcl::index_t>(unique.size());
      unique.push_back(cloud[i]);
    }
    position_of[i] = slot[first[i]];
  }
  return unique;
}

}  // namespace mcws
