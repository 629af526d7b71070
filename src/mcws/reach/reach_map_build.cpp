#include "mcws/reach/reach_map.h"

#include <omp.h>
#if defined(__x86_64__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstring>
#include <deque>
#include <memory>
#include <mutex>
#include <utility>

#include "mcws/collision/collision_checker.h"
#include "mcws/core/first_error.h"
#include "mcws/core/stopwatch.h"
#include "mcws/reach/pose_batch.h"
#include "mcws/reach/voxel_box.h"
#include "mcws/sampling/sampler.h"

namespace mcws {

namespace reach_map_build {

/// One part of the map being filled: open addressing with each voxel's record inside its slot
/// ([key + 1 (0: empty), count, best manipulability's float bits, bit set], padded to 4 or 8
/// words), so a sample touches one cache line where ReachMap's index and records touch two.
/// The voxels are split between the parts by their hash, so no voxel is stored twice. Any
/// thread posts samples to a part; whichever thread finds a part due records its samples.
class SlotTable : public Part<PendingSample> {
 public:
  /// A table of voxels with `words` words of bits, one of `parts`.
  SlotTable(int words, int parts)
      : slot_words_(3 + words <= 4 ? 4 : (3 + words + 7) / 8 * 8), parts_(parts) {
    grow(1024);
  }

  /// The part holding a key's voxel.
  static int partOf(std::uint64_t key, int parts) {
    return static_cast<int>(scaled(key, parts) >> 64);
  }

  /// Voxels in the table.
  std::size_t size() const { return used_; }

  /// Calls f(key, record) for every voxel, record as ReachMap stores it (count, best, bits).
  template <typename F>
  void forEach(F&& f) const {
    for (std::size_t s = 0; s < capacity_; ++s) {
      const std::uint64_t* r = table_.data() + s * slot_words_;
      if (r[0] != 0) f(r[0] - 1, r + 1);
    }
  }

 private:
  /// Records samples in the order of their slots: sorted by the hash's leading bits (one
  /// counting pass), they sweep the table in one direction, so its pages and lines are fetched
  /// ahead instead of at random (a random slot per sample cost about one memory latency each,
  /// prefetched or not, on this machine).
  void record(const std::vector<std::vector<PendingSample>>& batches) override {
    // Voxels already in the table first; then room for the new ones at once and those: growing
    // while part of the hash range is in would pack it into the front of the table (one cluster).
    fresh_.clear();
    const auto lookup = [&](const PendingSample& s) {
      if (std::uint64_t* r = slot(s.key, false)) {
        apply(r, s);
      } else {
        fresh_.push_back(s);
      }
    };
    constexpr std::size_t kAhead = 16;  // slots fetched ahead of their sample
    if (cached()) {
      for (const auto& batch : batches) {
        for (std::size_t i = 0; i < batch.size(); ++i) {
          if (i + kAhead < batch.size()) {
            __builtin_prefetch(table_.data() + home(batch[i + kAhead].key) * slot_words_, 1);
          }
          lookup(batch[i]);
        }
      }
    } else {
      constexpr int kBucketBits = 11;
      std::array<std::size_t, (1 << kBucketBits) + 1> start{};
      for (const auto& batch : batches) {
        for (const PendingSample& s : batch) ++start[(fraction(s.key) >> (64 - kBucketBits)) + 1];
      }
      for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
      sorted_.resize(start.back());
      for (const auto& batch : batches) {
        for (const PendingSample& s : batch) {
          sorted_[start[fraction(s.key) >> (64 - kBucketBits)]++] = s;
        }
      }
      for (std::size_t i = 0; i < sorted_.size(); ++i) {
        if (i + kAhead < sorted_.size()) {
          __builtin_prefetch(table_.data() + home(sorted_[i + kAhead].key) * slot_words_, 1);
        }
        lookup(sorted_[i]);
      }
    }
    std::sort(fresh_.begin(), fresh_.end(), [this](const PendingSample& a, const PendingSample& b) {
      return fraction(a.key) < fraction(b.key);
    });
    std::size_t distinct = 0;
    for (std::size_t i = 0; i < fresh_.size(); ++i) {
      distinct += i == 0 || fresh_[i].key != fresh_[i - 1].key;
    }
    std::size_t capacity = capacity_;
    while (4 * (used_ + distinct) > 3 * capacity) capacity += capacity / 2;  // load <= 3/4
    if (capacity != capacity_) grow(capacity);
    for (const PendingSample& f : fresh_) apply(slot(f.key, true), f);
  }

  bool cached() const override {
    return capacity_ * slot_words_ * sizeof(std::uint64_t) <= kCached;
  }

  /// Fibonacci hashing: the product's leading bits choose the part, the bits after them (the
  /// fraction) the slot within it, mapped onto [0, capacity) by a multiply (capacities grow by
  /// 1.5).
  static unsigned __int128 scaled(std::uint64_t key, int parts) {
    return static_cast<unsigned __int128>(key * 0x9E3779B97F4A7C15ull) *
           static_cast<unsigned>(parts);
  }
  std::uint64_t fraction(std::uint64_t key) const {
    return static_cast<std::uint64_t>(scaled(key, parts_));
  }
  std::size_t home(std::uint64_t key) const {
    return static_cast<std::size_t>((static_cast<unsigned __int128>(fraction(key)) * capacity_) >>
                                    64);
  }

  /// The slot of a key; when it is not in the table, nullptr or (insert) a new slot for it.
  std::uint64_t* slot(std::uint64_t key, bool insert) {
    for (std::size_t s = home(key);; s = s + 1 == capacity_ ? 0 : s + 1) {
      std::uint64_t* r = table_.data() + s * slot_words_;
      if (r[0] == key + 1) return r;
      if (r[0] == 0) {
        if (!insert) return nullptr;
        ++used_;
        r[0] = key + 1;
        return r;
      }
    }
  }

  static void apply(std::uint64_t* r, const PendingSample& s) {
    recordSample(r + 1, s.bin, s.manipulability);
  }

  void grow(std::size_t capacity) {
    std::vector<std::uint64_t, HugePageAllocator<std::uint64_t>> old(capacity * slot_words_, 0);
    old.swap(table_);
    const std::size_t old_capacity = capacity_;
    capacity_ = capacity;
    for (std::size_t s = 0; s < old_capacity; ++s) {
      const std::uint64_t* r = old.data() + s * slot_words_;
      if (r[0] == 0) continue;
      std::size_t t = home(r[0] - 1);
      while (table_[t * slot_words_] != 0) t = t + 1 == capacity_ ? 0 : t + 1;
      std::copy_n(r, slot_words_, table_.data() + t * slot_words_);
    }
  }

  int slot_words_;
  std::size_t capacity_{0}, used_{0};
  std::vector<std::uint64_t, HugePageAllocator<std::uint64_t>> table_;
  int parts_;
  std::vector<PendingSample, HugePageAllocator<PendingSample>> sorted_;  ///< see BoxPart's
  std::vector<PendingSample> fresh_;
};

}  // namespace reach_map_build

using reach_map_build::BoxPart;
using reach_map_build::BoxSample;
using reach_map_build::PartBase;
using reach_map_build::PendingSample;
using reach_map_build::SlotTable;
using reach_map_build::VoxelBox;

/// buildReachMap's steps: blocks of samples drawn and mapped to voxels and orientation bins in
/// parallel, posted to the part of the map holding each voxel. Where the arm's reach fits in
/// memory (ReachSampling::dense_bytes) the parts are blocks of one VoxelBox, whose voxels come
/// out in the map's order by a sweep; otherwise SlotTables, whose voxels are sorted by key and
/// merged into the map.
class ReachMapBuilder {
 public:
  using Progress = std::function<void(std::uint64_t, std::uint64_t)>;
  /// A voxel's key and its record in a table.
  using Voxel = std::pair<std::uint64_t, const std::uint64_t*>;

  /// \param radius the bound on the tool point's distance from the base for the dense box
  ///   (negative: chainLengthScale()).
  ReachMapBuilder(const Robot& robot, const ReachGrid& grid, const ReachSampling& sampling,
                  double radius)
      : empty_(grid),
        sampling_(sampling),
        sampler_(robot, samplerOptions(sampling)),
        n_(robot.dof()),
        batch_(robot),
        quality_(sampling.manipulability ? &sampling.quality : nullptr) {
    if (quality_) quality_->check();
    threads_ = sampling.threads > 0 ? sampling.threads : omp_get_num_procs();
    box_ = reach_map_build::reachBox(robot, radius < 0.0 ? chainLengthScale(robot) : radius,
                                     grid.resolution, empty_.stride_, sampling.dense_bytes);
    const int bins = empty_.bins().size();
    if (box_ && !BoxPart::fits(box_->voxels(), bins)) box_.reset();  // the hash tables then
    bin_bits_ = BoxPart::binBits(bins);
    for (int t = 0; t < threads_; ++t) {
      if (box_) {
        box_parts_.push_back(std::make_unique<BoxPart>(*box_, threads_, bins));
        parts_.push_back(box_parts_.back().get());
      } else {
        tables_.push_back(std::make_unique<SlotTable>(empty_.words_, threads_));
      }
      spill_.emplace_back(grid);
    }
    if (!box_) {
      for (const auto& table : tables_) parts_.push_back(table.get());
    }
    outgoing_.assign(threads_, std::vector<Outgoing>(threads_));
  }

  /// Records every sample in the parts, a chunk at a time (progress after each). The first chunk
  /// is a few hundred samples per thread, so its time gives an early estimate of the whole run;
  /// each next chunk is sized from the rate so far to last about kChunkSeconds, so progress comes
  /// every second or so even when a sample is slow (a mesh robot's self-collision check). The map
  /// does not depend on the chunks: each sample's values depend on its index only, and what a
  /// voxel records (count, best, bits) does not depend on the order samples arrive in.
  void fill(const Progress& progress) {
    std::uint64_t chunk = kFirstChunkPerThread * static_cast<std::uint64_t>(threads_);
    for (std::uint64_t begin = 0; begin < sampling_.samples;) {
      const std::uint64_t end = std::min(sampling_.samples, begin + chunk);
      const std::uint64_t block =
          std::clamp<std::uint64_t>((end - begin) / static_cast<std::uint64_t>(threads_),
                                    static_cast<std::uint64_t>(kLanes), kBlock);
      const auto blocks = static_cast<std::int64_t>((end - begin + block - 1) / block);
      const Stopwatch watch;
      FirstError error;
#pragma omp parallel for schedule(dynamic) num_threads(threads_)
      for (std::int64_t b = 0; b < blocks; ++b) {
        error.run(static_cast<std::size_t>(b), [&] {
          const std::uint64_t first = begin + static_cast<std::uint64_t>(b) * block;
          sampleBlock(first, std::min(end, first + block), omp_get_thread_num());
          for (PartBase* part : parts_) {
            if (part->due()) part->tryRecord();
          }
        });
      }
      error.rethrow();
      const double rate = static_cast<double>(end - begin) / std::max(watch.seconds(), 1e-6);
      chunk = static_cast<std::uint64_t>(std::clamp(
          rate * kChunkSeconds, static_cast<double>(kBlock), static_cast<double>(kChunk)));
      begin = end;
      if (progress) progress(end, sampling_.samples);
    }
  }

  /// The map of every sample recorded.
  ReachMap map() {
    finish();
    ReachMap map = box_ ? boxMap() : merge(sortedVoxels());
    bool spilled = false;
    for (const ReachMap& spill : spill_) {
      if (spill.size() == 0) continue;
      map.merge(spill);
      spilled = true;
    }
    if (spilled) map.sort();
    return map;
  }

 private:
  static constexpr int kLanes = PoseBatch::kLanes;
  static constexpr std::size_t kPost = std::size_t{1} << 16;  ///< samples handed to a part at once
  /// Samples a thread draws at once; the largest chunk; the first chunk's samples per thread.
  static constexpr std::uint64_t kBlock = 1 << 14, kChunk = 1 << 22, kFirstChunkPerThread = 256;
  static constexpr double kChunkSeconds = 1.0;  ///< a chunk's time after the first [s]

  static RobotSamplerOptions samplerOptions(const ReachSampling& sampling) {
    RobotSamplerOptions options;
    options.seed = sampling.seed;
    return options;
  }

  /// The samples still on their way recorded (a part per thread).
  void finish() {
    for (int t = 0; t < threads_; ++t) {
      for (int u = 0; u < threads_; ++u) {
        if (box_) {
          box_parts_[u]->post(std::move(outgoing_[t][u].box_samples));
        } else {
          tables_[u]->post(std::move(outgoing_[t][u].samples));
        }
      }
    }
    FirstError error;
#pragma omp parallel for schedule(static, 1) num_threads(threads_)
    for (int t = 0; t < threads_; ++t) {
      error.run(static_cast<std::size_t>(t), [&] {
        parts_[t]->tryRecord();
        parts_[t]->dropSpares();  // their memory before the map's, which reuses it
        if (box_) box_parts_[t]->dropSorted();
      });
    }
    error.rethrow();
  }

  /// The voxels of each table, sorted by key (a thread each).
  std::vector<std::vector<Voxel>> sortedVoxels() {
    std::vector<std::vector<Voxel>> lists(threads_);
    FirstError error;
#pragma omp parallel for schedule(static, 1) num_threads(threads_)
    for (int t = 0; t < threads_; ++t) {
      error.run(static_cast<std::size_t>(t), [&] {
        lists[t].reserve(tables_[t]->size());
        tables_[t]->forEach([&](std::uint64_t key, const std::uint64_t* record) {
          lists[t].emplace_back(key, record);
        });
        std::sort(lists[t].begin(), lists[t].end(),
                  [](const Voxel& a, const Voxel& b) { return a.first < b.first; });
      });
    }
    error.rethrow();
    return lists;
  }

  /// The map of the sorted lists, merged (no voxel is in two lists).
  ReachMap merge(const std::vector<std::vector<Voxel>>& lists) const {
    std::size_t voxels = 0;
    for (const auto& list : lists) voxels += list.size();
    ReachMap map(empty_.grid());
    map.keys_.reserve(voxels);
    map.records_.reserve(voxels * map.stride_);
    std::vector<std::size_t> next(lists.size(), 0);
    for (;;) {
      int first = -1;  // the list whose next voxel has the lowest key
      for (int t = 0; t < static_cast<int>(lists.size()); ++t) {
        if (next[t] < lists[t].size() &&
            (first < 0 || lists[t][next[t]].first < lists[first][next[first]].first)) {
          first = t;
        }
      }
      if (first < 0) break;
      const auto [key, record] = lists[first][next[first]++];
      map.keys_.push_back(key);
      map.records_.insert(map.records_.end(), record, record + map.stride_);
    }
    map.deferIndex(threads_);
    return map;
  }

  /// The map of the box's reached voxels, in the box's order (the keys'): each block's voxels
  /// placed after those of the blocks before it (counted as the box filled), the blocks never
  /// reached left unread, the blocks shared out between the threads.
  ReachMap boxMap() const {
    const std::size_t blocks = box_->blocks();
    std::vector<std::size_t> before(blocks + 1, 0);
    for (std::size_t b = 0; b < blocks; ++b) {
      std::size_t reached = 0;  // each block is one part's
      for (const auto& part : box_parts_) reached += part->reached()[b];
      before[b + 1] = before[b] + reached;
    }
    const int stride = empty_.stride_;
    ReachMap map(empty_.grid());
    map.keys_.resize(before[blocks]);
    map.records_.resize(before[blocks] * stride);
    FirstError error;
#pragma omp parallel for schedule(dynamic, 8) num_threads(threads_)
    for (std::int64_t b = 0; b < static_cast<std::int64_t>(blocks); ++b) {
      const auto block = static_cast<std::size_t>(b);
      if (before[block + 1] == before[block]) continue;
      error.run(block, [&] { copyBlock(block, before[block], map); });
    }
    error.rethrow();
    map.deferIndex(threads_);
    return map;
  }

  /// A block's reached voxels copied into the map from voxel v on.
  void copyBlock(std::size_t block, std::size_t v, ReachMap& map) const {
    const int stride = empty_.stride_;
    const std::size_t first = block << VoxelBox::kBlockBits;
    const std::size_t last = std::min(box_->voxels(), first + VoxelBox::kBlock);
    // The key runs with the index along a column of z; recomputed where a column starts.
    const std::uint64_t column = box_->size(2);
    std::uint64_t z = first % column, key = box_->keyOf(first);
    for (std::size_t i = first; i < last; ++i, ++z, ++key) {
      if (z == column) {
        z = 0;
        key = box_->keyOf(i);
      }
      const std::uint64_t* record = box_->record(i);
      if (record[0] == 0) continue;
      map.keys_[v] = key;
      std::copy_n(record, stride, map.records_.data() + v * stride);
      ++v;
    }
  }

  /// Samples [first, last) mapped to their voxels and bins, posted from thread t.
  void sampleBlock(std::uint64_t first, std::uint64_t last, int t) {
    sampleLanes(first, last, t);
    storeFence();  // the batches' non-temporal stores (postBox) seen by the other threads
  }

  /// sampleBlock()'s samples.
  void sampleLanes(std::uint64_t first, std::uint64_t last, int t) {
    CollisionChecker::Scratch scratch;
    // s: the tool points over the voxel edge (ReachMap::keyInGrid()'s products).
    double sample_q[kMaxJoints], q[kMaxJoints * kLanes], p[3 * kLanes], a[3 * kLanes],
        x[3 * kLanes], w[kLanes] = {}, s[3 * kLanes];
    bool counted[kLanes];
    int bins[kLanes];
    for (std::uint64_t i = first; i < last; i += kLanes) {
      // A last, partial batch repeats its last sample in the unused lanes (not counted).
      const int lanes = static_cast<int>(std::min<std::uint64_t>(kLanes, last - i));
      for (int k = 0; k < kLanes; ++k) {
        sampler_.jointValues(
            sampling_.first + i + static_cast<std::uint64_t>(std::min(k, lanes - 1)), sample_q);
        for (int j = 0; j < n_; ++j) q[j * kLanes + k] = sample_q[j];
        counted[k] = k < lanes && (!sampling_.collision ||
                                   sampling_.collision->label(sample_q, scratch) == kLabelFree);
      }
      // The tool's x axis only for roll bins.
      batch_.poses(q, p, a, empty_.bins().rolls() > 1 ? x : nullptr, quality_, w);
      empty_.bins().bins(a, x, kLanes, bins);
      for (int c = 0; c < 3 * kLanes; ++c) s[c] = p[c] * empty_.inverse_resolution_;
      for (int k = 0; k < kLanes; ++k) {
        if (!counted[k]) continue;
        if (static_cast<unsigned>(bins[k]) >= static_cast<unsigned>(empty_.bins().size())) {
          empty_.checkBin(bins[k]);  // throws
        }
        // In the box: its index straight from the scaled point (the key's voxel).
        if (std::uint64_t index; box_ && box_->indexOfScaled(s + k, kLanes, index)) {
          postBox(t, index, bins[k], static_cast<float>(w[k]));
          continue;
        }
        std::uint64_t key;
        if (!empty_.keyInGrid(p + k, kLanes, key)) {
          key = empty_.keyOf(Eigen::Vector3d(p[k], p[kLanes + k], p[2 * kLanes + k]));  // throws
        }
        const auto manipulability = static_cast<float>(w[k]);
        if (!box_) {
          post(t, SlotTable::partOf(key, threads_), key, bins[k], manipulability);
        } else if (std::uint64_t index; box_->indexOf(key, index)) {
          postBox(t, index, bins[k], manipulability);
        } else {  // beyond the reach's bound (only by a rounding error, if ever)
          ReachMap& spill = spill_[t];
          spill.record(spill.slotFor(key), bins[k], manipulability);
        }
      }
    }
  }

  /// Adds a sample to thread t's batch for a table, handing the batch over when full.
  void post(int t, int part, std::uint64_t key, int bin, float manipulability) {
    auto& out = outgoing_[t][part].samples;
    // Field by field into the batch: a sample built on the stack and copied in one 16-byte load
    // waited for its three stores (no store-to-load forwarding), a stall at every sample.
    PendingSample& sample = out.emplace_back();
    sample.key = key;
    sample.bin = bin;
    sample.manipulability = manipulability;
    if (out.size() >= kPost) out = tables_[part]->exchange(std::move(out), kPost);
  }

  /// Adds a sample of box index `index` to thread t's batch for its part of the box, handing
  /// the batch over when full.
  void postBox(int t, std::uint64_t index, int bin, float manipulability) {
    const int part = BoxPart::partOf(index, threads_);
    auto& out = outgoing_[t][part].box_samples;
    // A non-temporal store: the batch's line is not fetched before it is written (a recycled
    // batch left the cache long ago); the element is left unset by emplace_back (its allocator).
    out.emplace_back();
#if defined(__x86_64__)
    std::uint32_t bits;
    std::memcpy(&bits, &manipulability, sizeof bits);
    static_assert(sizeof(BoxSample) == sizeof(long long) && offsetof(BoxSample, code) == 0);
    _mm_stream_si64(
        reinterpret_cast<long long*>(&out.back()),
        static_cast<long long>(BoxPart::code(index, bin, bin_bits_) | (std::uint64_t{bits} << 32)));
#else
    out.back() = {BoxPart::code(index, bin, bin_bits_), manipulability};
#endif
    if (out.size() >= kPost) {
      storeFence();  // the stores seen by the thread that records them
      out = box_parts_[part]->exchange(std::move(out), kPost);
    }
  }

  /// Orders this thread's non-temporal stores before its later stores (x86-64; else nothing).
  static void storeFence() {
#if defined(__x86_64__)
    _mm_sfence();
#endif
  }

  const ReachMap empty_;  ///< the grid's map: bins, keys
  const ReachSampling& sampling_;
  const RobotSampler sampler_;
  const int n_;
  const PoseBatch batch_;
  const QualityOptions* quality_;
  int threads_{1};
  std::unique_ptr<VoxelBox> box_;  ///< the dense map, or null: hash tables
  int bin_bits_{0};                ///< of a bin in a BoxSample's code
  std::vector<std::unique_ptr<BoxPart>> box_parts_;
  std::vector<std::unique_ptr<SlotTable>> tables_;
  std::vector<PartBase*> parts_;
  std::deque<ReachMap> spill_;  ///< per thread: samples outside the box
  /// A thread's samples for a part, on a cache line of its own: the threads' batches (their
  /// ends written at every sample) would otherwise share lines.
  struct alignas(64) Outgoing {
    std::vector<PendingSample> samples;     ///< for a SlotTable
    reach_map_build::BoxBatch box_samples;  ///< for a BoxPart
  };
  /// outgoing_[t][u]: thread t's samples for table u, or for part u of the box.
  std::vector<std::vector<Outgoing>> outgoing_;
};

ReachMap buildReachMap(const Robot& robot, const ReachGrid& grid, const ReachSampling& sampling,
                       const std::function<void(std::uint64_t, std::uint64_t)>& progress) {
  ReachMapBuilder builder(robot, grid, sampling, -1.0);
  builder.fill(progress);
  return builder.map();
}

namespace reach_map_build {

ReachMap buildReachMapInBox(const Robot& robot, const ReachGrid& grid,
                            const ReachSampling& sampling, double radius) {
  ReachMapBuilder builder(robot, grid, sampling, radius);
  builder.fill({});
  return builder.map();
}

}  // namespace reach_map_build

}  // namespace mcws
