#include "mcws/workspace/unique_positions.h"

#include <parallel/algorithm>

#include <algorithm>
#include <tuple>

namespace mcws {

pcl::PointCloud<pcl::PointXYZ> uniquePositions(const pcl::PointCloud<pcl::PointXYZ>& cloud,
                                               std::vector<pcl::index_t>& position_of) {
  const std::size_t n = cloud.size();
  // Sorted by value (position, then index), which keeps the data next to the keys: copies of a
  // position end up adjacent, the first appearance first.
  struct Entry {
    float x, y, z;
    pcl::index_t index;
  };
  std::vector<Entry> entries(n);
  for (std::size_t i = 0; i < n; ++i) {
    entries[i] = {cloud[i].x, cloud[i].y, cloud[i].z, static_cast<pcl::index_t>(i)};
  }
  // A total order, so the parallel sort gives one result whatever the threads.
  __gnu_parallel::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return std::tie(a.x, a.y, a.z, a.index) < std::tie(b.x, b.y, b.z, b.index);
  });
  // first[i]: the first appearance of point i's position.
  std::vector<pcl::index_t> first(n);
  for (std::size_t k = 0; k < n; ++k) {
    const bool copy = k > 0 && entries[k].x == entries[k - 1].x &&
                      entries[k].y == entries[k - 1].y && entries[k].z == entries[k - 1].z;
    first[entries[k].index] = copy ? first[entries[k - 1].index] : entries[k].index;
  }
  pcl::PointCloud<pcl::PointXYZ> unique;
  unique.reserve(n);
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
