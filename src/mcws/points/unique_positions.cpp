#include "mcws/points/unique_positions.h"

#include <algorithm>
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
  // An open-addressing hash table of the positions seen so far, at most half full; one pass in
  // input order, so the result is in order of first appearance. A slot holds the position's
  // index + 1 (0: empty) above the top 32 bits of its hash, which rule out most other positions
  // without reading them. The table is larger than the caches: the slot of the point kAhead
  // places on is fetched while this one is looked up (the hashes of those between kept in a
  // ring).
  constexpr std::size_t kAhead = 16;
  std::size_t size = 16;
  while (size < 2 * n) size *= 2;
  const std::size_t mask = size - 1;
  std::vector<std::uint64_t> table(size, 0);
  std::uint64_t ring[kAhead];
  for (std::size_t i = 0; i < std::min(n, kAhead); ++i) ring[i] = hashOf(cloud[i]);
  pcl::PointCloud<pcl::PointXYZ> unique;
  unique.reserve(n);
  position_of.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t hash = ring[i % kAhead];
    if (i + kAhead < n) {
      ring[i % kAhead] = hashOf(cloud[i + kAhead]);
      __builtin_prefetch(&table[ring[i % kAhead] & mask]);
    }
    const pcl::PointXYZ& p = cloud[i];
    const std::uint64_t tag = hash >> 32;
    std::size_t slot = hash & mask;
    for (;; slot = (slot + 1) & mask) {
      const std::uint64_t entry = table[slot];
      if (entry == 0) {
        position_of[i] = static_cast<pcl::index_t>(unique.size());
        table[slot] = (static_cast<std::uint64_t>(unique.size()) + 1) << 32 | tag;
        unique.push_back(p);
        break;
      }
      if ((entry & 0xFFFFFFFFu) != tag) continue;
      const auto seen = static_cast<pcl::index_t>((entry >> 32) - 1);
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
