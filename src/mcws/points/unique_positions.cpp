#include "mcws/points/unique_positions.h"

#include <cstdint>
#include <cstring>

namespace mcws {
namespace {

/// The bits of v with -0 turned into +0, so that positions equal as floats hash alike.
std::uint32_t bitsOf(float v) {
  const float normalised = v + 0.0f;  // -0 + 0 = +0; every other value unchanged
  std::uint32_t bits;
  std::memcpy(&bits, &normalised, sizeof bits);
  return bits;
}

std::uint64_t hashOf(const pcl::PointXYZ& p) {
  std::uint64_t h = (static_cast<std::uint64_t>(bitsOf(p.x)) << 32) ^ bitsOf(p.y);
  h ^= static_cast<std::uint64_t>(bitsOf(p.z)) * 0x9E3779B97F4A7C15ULL;
  // SplitMix64's finaliser: every input bit reaches the low bits that index the table.
  h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ULL;
  h = (h ^ (h >> 27)) * 0x94D049BB133111EBULL;
  return h ^ (h >> 31);
}

}  // namespace

pcl::PointCloud<pcl::PointXYZ> uniquePositions(const pcl::PointCloud<pcl::PointXYZ>& cloud,
                                               std::vector<pcl::index_t>& position_of) {
  const std::size_t n = cloud.size();
  // An open-addressing hash table of the positions seen so far (their index in the result),
  // at most half full; one pass in input order, so the result is in order of first appearance.
  std::size_t size = 16;
  while (size < 2 * n) size *= 2;
  const std::size_t mask = size - 1;
  std::vector<pcl::index_t> table(size, -1);
  pcl::PointCloud<pcl::PointXYZ> unique;
  unique.reserve(n);
  position_of.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const pcl::PointXYZ& p = cloud[i];
    std::size_t slot = hashOf(p) & mask;
    for (;; slot = (slot + 1) & mask) {
      const pcl::index_t seen = table[slot];
      if (seen < 0) {
        table[slot] = static_cast<pcl::index_t>(unique.size());
        position_of[i] = table[slot];
        unique.push_back(p);
        break;
      }
      const pcl::PointXYZ& q = unique[seen];
      if (q.x == p.x && q.y == p.y && q.z == p.z) {
        position_of[i] = seen;
        break;
      }
    }
  }
  return unique;
}

}  // namespace mcws
