#include "mcws/reach/voxel_box.h"

#include <sys/mman.h>

#include <array>
#include <cmath>
#include <limits>
#include <new>

#include "mcws/reach/reach_map.h"

namespace mcws {
namespace reach_map_build {

VoxelBox::VoxelBox(const std::int64_t low[3], const std::int64_t size[3], int stride)
    : stride_(stride) {
  voxels_ = 1;
  for (int a = 0; a < 3; ++a) {
    low_[a] = static_cast<std::uint64_t>(low[a] + ReachMap::kIndexLimit);
    size_[a] = static_cast<std::uint64_t>(size[a]);
    first_index_[a] = low[a];
    first_[a] = static_cast<double>(low[a]);
    end_[a] = static_cast<double>(low[a] + size[a]);
    voxels_ *= size_[a];
  }
  // Anonymous memory: zero pages from the kernel where first touched, 2 MB aligned and advised
  // as transparent huge pages (the records are swept in order, but millions of them).
  constexpr std::size_t kHuge = std::size_t{2} << 20;
  mapped_ = (bytes() + kHuge - 1) / kHuge * kHuge + kHuge;
  void* p = mmap(nullptr, mapped_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) throw std::bad_alloc();
  const auto address = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t aligned = (address + kHuge - 1) / kHuge * kHuge;
  madvise(reinterpret_cast<void*>(aligned), mapped_ - kHuge, MADV_HUGEPAGE);  // advice only
  base_ = p;
  data_ = reinterpret_cast<std::uint64_t*>(aligned);
}

VoxelBox::~VoxelBox() { munmap(base_, mapped_); }

std::uint64_t VoxelBox::keyOf(std::size_t index) const {
  const std::uint64_t z = index % size_[2], rest = index / size_[2];
  const std::uint64_t y = rest % size_[1], x = rest / size_[1];
  return ((x + low_[0]) << 42) | ((y + low_[1]) << 21) | (z + low_[2]);
}

std::unique_ptr<VoxelBox> reachBox(const Robot& robot, double radius, double resolution, int stride,
                                   std::uint64_t max_bytes) {
  const Eigen::Vector3d centre = robot.T_world_base.translation();
  std::int64_t low[3], size[3];
  double voxels = 1.0;
  for (int a = 0; a < 3; ++a) {
    const double first = std::floor((centre[a] - radius) / resolution) - 1.0;
    const double last = std::floor((centre[a] + radius) / resolution) + 1.0;
    if (!(first >= -ReachMap::kIndexLimit && last < ReachMap::kIndexLimit)) return nullptr;
    low[a] = static_cast<std::int64_t>(first);
    size[a] = static_cast<std::int64_t>(last - first) + 1;
    voxels *= static_cast<double>(size[a]);
  }
  if (!(voxels * stride * sizeof(std::uint64_t) <= static_cast<double>(max_bytes))) return nullptr;
  try {
    return std::make_unique<VoxelBox>(low, size, stride);
  } catch (const std::bad_alloc&) {
    return nullptr;  // the hash table then, which grows with the voxels reached only
  }
}

void BoxPart::record(const std::vector<BoxBatch>& batches) {
  const int stride = box_.stride();
  std::uint64_t* data = box_.record(0);
  if (cached()) {
    for (const auto& batch : batches) {
      for (const BoxSample& s : batch) add(data, stride, s);
    }
    return;
  }
  // Sorted by their code's leading bits (the index's; one counting pass), the samples sweep the
  // box in one direction, so its pages and lines are fetched ahead instead of at random.
  constexpr int kBucketBits = 11;
  int shift = bin_bits_;
  while ((box_.voxels() - 1) >> (shift - bin_bits_) >= (std::size_t{1} << kBucketBits)) ++shift;
  std::array<std::size_t, (1 << kBucketBits) + 1> start{};
  for (const auto& batch : batches) {
    for (const BoxSample& s : batch) ++start[(s.code >> shift) + 1];
  }
  for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
  sorted_.resize(start.back());
  for (const auto& batch : batches) {
    for (const BoxSample& s : batch) sorted_[start[s.code >> shift]++] = s;
  }
  constexpr std::size_t kAhead = 40;  // records fetched ahead of their sample
  for (std::size_t i = 0; i < sorted_.size(); ++i) {
    if (i + kAhead < sorted_.size()) {
      __builtin_prefetch(data + std::size_t{sorted_[i + kAhead].code >> bin_bits_} * stride, 1);
    }
    add(data, stride, sorted_[i]);
  }
}

}  // namespace reach_map_build
}  // namespace mcws
