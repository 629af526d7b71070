#pragma once
/// \file
/// \brief buildReachMap's internals: the samples waiting to be recorded, the parts of the map
/// being filled that receive them, and the dense box of voxels that holds the map when the arm's
/// reach fits in memory (reach_map_build.cpp). Not a public interface.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <mutex>
#include <vector>

#include "mcws/kinematics/robot.h"
#include "mcws/reach/reach_map.h"

namespace mcws {

// Named rather than anonymous: ReachMapBuilder (a friend of ReachMap, so not file-local) holds
// these, and GCC warns (-Wsubobject-linkage) when a unity build compiles the file in a batch.
namespace reach_map_build {

/// \brief A sample waiting to be recorded: its voxel (a packed key of ReachMap, or a VoxelBox
/// index), orientation bin and manipulability.
struct PendingSample {
  std::uint64_t key;
  int bin;
  float manipulability;
};

/// \brief Adds a sample to a voxel's record as ReachMap stores it: count, the best
/// manipulability's float bits, the bit set of the bins reached. What a record holds does not
/// depend on the order its samples arrive in.
inline void recordSample(std::uint64_t* record, int bin, float manipulability) {
  ++record[0];
  float best;
  std::memcpy(&best, &record[1], sizeof best);
  if (manipulability > best) std::memcpy(&record[1], &manipulability, sizeof best);
  record[2 + bin / 64] |= std::uint64_t{1} << (bin % 64);
}

/// \brief A sample waiting to be recorded in a VoxelBox, in 8 bytes: its box index shifted left by
/// the bits of the orientation bins, or'd with its bin (BoxPart::code()), and its manipulability.
/// Half a PendingSample: the batches written at every sample and the sorting memory halve.
struct BoxSample {
  std::uint32_t code;
  float manipulability;
};

/// \brief A batch of BoxSamples: its allocator leaves the elements added unset (the builder
/// writes them with non-temporal stores).
using BoxBatch = std::vector<BoxSample, HugePageAllocator<BoxSample>>;

/// \brief What the map's builder does with any part, whatever its samples' format.
class PartBase {
 public:
  virtual ~PartBase() = default;
  /// \brief Whether enough samples wait to be recorded together: many for a part swept in
  /// order, any for one that fits in the cache.
  virtual bool due() = 0;
  /// \brief Frees the recorded batches kept for exchange() (when no more samples come).
  virtual void dropSpares() = 0;
  /// \brief Records the samples posted, unless another thread is recording this part (false).
  virtual bool tryRecord() = 0;
};

/// \brief One part of the map being filled, receiving samples of type Sample: any thread posts
/// samples to it; whichever thread finds it due records them (one thread at a time).
template <typename Sample, typename Batch = std::vector<Sample>>
class Part : public PartBase {
 public:
  /// \brief Hands over samples of this part (thread-safe).
  void post(Batch&& samples) {
    const std::lock_guard<std::mutex> lock(inbox_mutex_);
    inbox_size_ += samples.size();
    inbox_.push_back(std::move(samples));
  }
  /// \brief Hands over samples of this part (thread-safe) and returns an empty batch with room
  /// for `room` samples to fill next: one this part has recorded, its memory kept (a new
  /// batch's memory is faulted in page by page, and a freed one's unmapped again), or a new one.
  Batch exchange(Batch&& samples, std::size_t room) {
    Batch next;
    {
      const std::lock_guard<std::mutex> lock(inbox_mutex_);
      inbox_size_ += samples.size();
      inbox_.push_back(std::move(samples));
      if (!spare_.empty()) {
        next.swap(spare_.back());
        spare_.pop_back();
      }
    }
    next.reserve(room);
    return next;
  }
  bool due() override {
    const std::lock_guard<std::mutex> lock(inbox_mutex_);
    return inbox_size_ >= due_at_;
  }
  void dropSpares() override {
    const std::lock_guard<std::mutex> lock(inbox_mutex_);
    spare_ = {};
  }
  bool tryRecord() override;

 protected:
  /// Samples recorded at once into a part larger than the cache: its memory is swept in order.
  static constexpr std::size_t kPending = std::size_t{1} << 20;
  /// Bytes of a part's records up to which samples are recorded as they come.
  static constexpr std::size_t kCached = std::size_t{4} << 20;
  virtual void record(const std::vector<Batch>& batches) = 0;
  virtual bool cached() const = 0;
  /// Samples recorded at once when the part is not cached().
  virtual std::size_t pending() const { return kPending; }

 private:
  std::mutex inbox_mutex_;   ///< guards inbox_, inbox_size_, due_at_, spare_
  std::mutex record_mutex_;  ///< held by the thread recording into the part
  std::vector<Batch> inbox_;
  std::vector<Batch> spare_;  ///< recorded batches, emptied, for reuse
  std::size_t inbox_size_{0}, due_at_{1};
};

template <typename Sample, typename Batch>
bool Part<Sample, Batch>::tryRecord() {
  const std::unique_lock<std::mutex> recording(record_mutex_, std::try_to_lock);
  if (!recording.owns_lock()) return false;
  std::vector<Batch> batches;
  {
    const std::lock_guard<std::mutex> lock(inbox_mutex_);
    batches.swap(inbox_);
    inbox_size_ = 0;
  }
  record(batches);
  for (auto& batch : batches) batch.clear();  // capacity kept
  const std::lock_guard<std::mutex> lock(inbox_mutex_);
  for (auto& batch : batches) {
    if (batch.capacity() > 0) spare_.push_back(std::move(batch));
  }
  due_at_ = cached() ? 1 : pending();
  return true;
}

/// \brief A box of voxels stored densely: every voxel's record (ReachMap's layout) at an index
/// computed from its voxel indices, z fastest, then y, then x, which is also the order of the
/// packed keys. Memory comes zeroed from the kernel as it is first touched, so a voxel never
/// reached (the box's corners beyond the reach) costs address space only.
class VoxelBox {
 public:
  /// \brief A box of size[a] voxels along axis a from voxel index low[a] (within ReachMap's
  /// range), records of `stride` words. \throws std::bad_alloc when it cannot be mapped.
  VoxelBox(const std::int64_t low[3], const std::int64_t size[3], int stride);
  ~VoxelBox();
  VoxelBox(const VoxelBox&) = delete;
  VoxelBox& operator=(const VoxelBox&) = delete;

  std::size_t voxels() const { return voxels_; }
  std::size_t bytes() const { return voxels_ * stride_ * sizeof(std::uint64_t); }
  int stride() const { return stride_; }
  /// \brief Voxels along axis a.
  std::uint64_t size(int a) const { return size_[a]; }
  /// \brief The index of the voxel of a packed key (ReachMap::keyOf); false outside the box.
  bool indexOf(std::uint64_t key, std::uint64_t& index) const {
    std::uint64_t at[3];
    for (int a = 0; a < 3; ++a) {
      at[a] = ((key >> (42 - 21 * a)) & kFieldMask) - low_[a];  // wraps when below the box
      if (at[a] >= size_[a]) return false;
    }
    index = (at[0] * size_[1] + at[1]) * size_[2] + at[2];
    return true;
  }
  /// \brief The index of the voxel of a point given as its coordinates over the voxel edge, s[a *
  /// stride] (what ReachMap::keyInGrid() computes from the point): the voxel of the same key,
  /// floor(s) on each axis; false outside the box (or NaN), where nothing is written.
  bool indexOfScaled(const double* s, int stride, std::uint64_t& index) const {
    std::uint64_t at[3];
    for (int a = 0; a < 3; ++a) {
      const double v = s[a * stride];
      // floor(v) within [first, end) exactly when v is (whole numbers, within ReachMap's range).
      if (!(v >= first_[a] && v < end_[a])) return false;
      auto i = static_cast<std::int64_t>(v);    // toward zero
      i -= static_cast<double>(i) > v ? 1 : 0;  // floor
      at[a] = static_cast<std::uint64_t>(i - first_index_[a]);
    }
    index = (at[0] * size_[1] + at[1]) * size_[2] + at[2];
    return true;
  }
  /// \brief The packed key of the voxel at an index.
  std::uint64_t keyOf(std::size_t index) const;
  std::uint64_t* record(std::size_t index) { return data_ + index * stride_; }
  const std::uint64_t* record(std::size_t index) const { return data_ + index * stride_; }
  /// Voxels in a block of the box (its indices [b, b + 1) * kBlock): the unit in which reached
  /// voxels are counted while the box fills, so the map is copied out without reading the
  /// blocks never reached.
  static constexpr std::size_t kBlockBits = 12, kBlock = std::size_t{1} << kBlockBits;
  /// \brief Blocks of the box (the last may be partial).
  std::size_t blocks() const { return (voxels_ + kBlock - 1) >> kBlockBits; }

 private:
  static constexpr std::uint64_t kFieldMask = (std::uint64_t{1} << 21) - 1;
  std::uint64_t low_[3]{};         ///< the first voxel's packed fields (index + 2^20)
  std::uint64_t size_[3]{};        ///< voxels along each axis
  std::int64_t first_index_[3]{};  ///< the first voxel's index
  double first_[3]{}, end_[3]{};   ///< the first voxel's index and the last's + 1
  std::size_t voxels_{0};
  int stride_;
  void* base_{nullptr};           ///< the mapping
  std::size_t mapped_{0};         ///< its bytes
  std::uint64_t* data_{nullptr};  ///< the records: base_ rounded up to 2 MB
};

/// \brief The box of the voxels of a grid of edge `resolution` [length unit] within `radius`
/// [length unit] of the robot's base (chainLengthScale() bounds the tool point's distance), and a
/// voxel more on each side for rounding, records of `stride` words; nullptr when they would take
/// more than `max_bytes` or cannot be mapped.
std::unique_ptr<VoxelBox> reachBox(const Robot& robot, double radius, double resolution, int stride,
                                   std::uint64_t max_bytes);

/// \brief buildReachMap() with the dense box sized for `radius` [length unit] instead of the
/// chain's bound: for tests, where a radius too small makes samples fall outside the box.
ReachMap buildReachMapInBox(const Robot& robot, const ReachGrid& grid,
                            const ReachSampling& sampling, double radius);

/// \brief A part of a VoxelBox: the blocks of 2^kBlockBits voxels whose number hashes to `part`
/// of `parts` (so the parts share the work whatever the shape of the reach). Its samples are
/// BoxSamples: a box whose indices and bins do not fit their 32-bit code (fits()) is not used.
class BoxPart : public Part<BoxSample, BoxBatch> {
 public:
  static constexpr int kBlockBits = static_cast<int>(VoxelBox::kBlockBits);
  /// A part of `box` split in `parts`, for samples of `bins` orientation bins.
  BoxPart(VoxelBox& box, int parts, int bins)
      : box_(box),
        parts_(parts),
        bin_bits_(binBits(bins)),
        bin_mask_((std::uint32_t{1} << bin_bits_) - 1),
        reached_(box.blocks(), 0) {}
  /// \brief The bits of a bin in a BoxSample's code, for `bins` bins (at least 1).
  static int binBits(int bins) {
    int bits = 0;
    while ((1 << bits) < bins) ++bits;
    return bits;
  }
  /// \brief Whether every index of a box of `voxels` voxels with every bin of `bins` has a code.
  static bool fits(std::size_t voxels, int bins) {
    return voxels <= (std::uint64_t{1} << (32 - binBits(bins)));
  }
  /// \brief A sample's code (BoxSample): its box index and bin, of `bin_bits` bits (binBits()).
  static std::uint32_t code(std::uint64_t index, int bin, int bin_bits) {
    return static_cast<std::uint32_t>(index << bin_bits) | static_cast<std::uint32_t>(bin);
  }
  /// \brief A sample's code (BoxSample) in this part.
  std::uint32_t code(std::uint64_t index, int bin) const { return code(index, bin, bin_bits_); }
  /// \brief The part holding a box index: Fibonacci hashing of its block (a multiply, where a
  /// modulo would divide).
  static int partOf(std::uint64_t index, int parts) {
    const auto hash = static_cast<std::uint32_t>((index >> kBlockBits) * 0x9E3779B9u);
    return static_cast<int>((std::uint64_t{hash} * static_cast<unsigned>(parts)) >> 32);
  }
  /// \brief The voxels reached so far in each block of the box (VoxelBox::blocks()) that this
  /// part holds; 0 for the others.
  const std::vector<std::uint32_t>& reached() const { return reached_; }
  /// \brief Frees the memory kept for sorting samples (when no more samples come): the map's
  /// arrays allocated next then reuse its pages, where new pages cost a fault each.
  void dropSorted() { decltype(sorted_)().swap(sorted_); }

 private:
  void record(const std::vector<BoxBatch>& batches) override;
  bool cached() const override { return box_.bytes() <= kCached; }
  /// 2^23 samples over all parts, 2^20 at least: with few parts, fewer sweeps of the box (each
  /// sweep's traffic is its touched lines, read and written back).
  std::size_t pending() const override {
    return std::max(kPending, (std::size_t{1} << 23) / static_cast<unsigned>(parts_));
  }
  /// Adds a sample to its record, counting the voxel in its block when it is its first.
  void add(std::uint64_t* data, int stride, const BoxSample& s) {
    const std::uint32_t index = s.code >> bin_bits_;
    std::uint64_t* record = data + std::size_t{index} * stride;
    reached_[index >> kBlockBits] += record[0] == 0;
    recordSample(record, static_cast<int>(s.code & bin_mask_), s.manipulability);
  }
  VoxelBox& box_;
  int parts_;
  int bin_bits_;
  std::uint32_t bin_mask_;
  std::vector<std::uint32_t> reached_;  ///< per block of the box: its voxels reached
  /// The samples sorted; huge pages, as its 2^11 buckets are written at random (and resize
  /// leaves it unset: every element is written).
  std::vector<BoxSample, HugePageAllocator<BoxSample>> sorted_;
};

}  // namespace reach_map_build
}  // namespace mcws
