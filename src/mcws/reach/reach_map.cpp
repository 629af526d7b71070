#include "mcws/reach/reach_map.h"

#include <omp.h>
#include <sys/mman.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>
#include <istream>
#include <limits>
#include <mutex>
#include <numeric>
#include <ostream>

#include "mcws/collision/collision_checker.h"
#include "mcws/core/decimal.h"
#include "mcws/core/error.h"
#include "mcws/kinematics/jacobian.h"
#include "mcws/reach/pose_batch.h"
#include "mcws/workspace/sampler.h"

namespace mcws {

template <typename T>
T* HugePageAllocator<T>::allocate(std::size_t n) {
  constexpr std::size_t kHuge = std::size_t{2} << 20;
  if (n > std::numeric_limits<std::size_t>::max() / sizeof(T) - kHuge) throw std::bad_alloc();
  const std::size_t bytes = n * sizeof(T);
  void* p = nullptr;
  if (bytes >= kHuge) {
    p = std::aligned_alloc(kHuge, (bytes + kHuge - 1) / kHuge * kHuge);
    if (p) madvise(p, bytes, MADV_HUGEPAGE);  // advice only: failure changes nothing
  } else {
    p = std::malloc(bytes == 0 ? 1 : bytes);
  }
  if (!p) throw std::bad_alloc();
  return static_cast<T*>(p);
}
template struct HugePageAllocator<std::uint64_t>;
template struct HugePageAllocator<ReachMap::Entry>;
namespace {

constexpr char kMagic[] = "MCWS-REACH-MAP 1";
constexpr int kMaxBins = 65536;
constexpr std::uint64_t kIndexBits = 21;
constexpr std::uint64_t kIndexMask = (std::uint64_t{1} << kIndexBits) - 1;

/// Fibonacci hashing of a packed voxel index onto a table of 2^bits slots.
std::size_t hashSlot(std::uint64_t key, int bits) {
  return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> (64 - bits));
}

template <typename T>
void writeRaw(std::ostream& out, const T& value) {
  out.write(reinterpret_cast<const char*>(&value), sizeof value);
}
template <typename T>
void readRaw(std::istream& in, T& value, const std::string& source) {
  if (!in.read(reinterpret_cast<char*>(&value), sizeof value)) {
    throw Error(source + ": the reachability map ends early");
  }
}

}  // namespace

void ReachGrid::check() const {
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw Error("reachability map: the resolution must be positive and finite, not " +
                formatNumber(resolution));
  }
  if (directions < 1) {
    throw Error("reachability map: need at least 1 orientation, not " + std::to_string(directions));
  }
  if (rolls < 1)
    throw Error("reachability map: need at least 1 roll bin, not " + std::to_string(rolls));
  if (static_cast<long>(directions) * rolls > kMaxBins) {
    throw Error("reachability map: " + std::to_string(static_cast<long>(directions) * rolls) +
                " orientation bins, more than " + std::to_string(kMaxBins));
  }
}

ReachMap::ReachMap(const ReachGrid& grid) : grid_(grid) {
  grid_.check();
  bins_ = OrientationBins(grid.directions, grid.rolls);
  words_ = (bins_.size() + 63) / 64;
  stride_ = 2 + words_;
  inverse_resolution_ = 1.0 / grid.resolution;
}

std::uint64_t ReachMap::samples() const {
  std::uint64_t total = 0;
  for (std::size_t v = 0; v < size(); ++v) total += count(v);
  return total;
}

float ReachMap::bestManipulability(std::size_t v) const {
  float best;
  std::memcpy(&best, &records_[v * stride_ + 1], sizeof best);
  return best;
}

bool ReachMap::inGrid(const Eigen::Vector3d& p, Eigen::Vector3i& index) const {
  for (int a = 0; a < 3; ++a) {
    const double i = std::floor(p[a] * inverse_resolution_);
    if (!(i >= -kIndexLimit && i < kIndexLimit)) return false;  // NaN too
    index[a] = static_cast<int>(i);
  }
  return true;
}

Eigen::Vector3i ReachMap::voxelOf(const Eigen::Vector3d& p) const {
  Eigen::Vector3i index;
  if (!inGrid(p, index)) {
    throw Error("reachability map: a tool point at (" + formatNumber(p.x()) + ", " +
                formatNumber(p.y()) + ", " + formatNumber(p.z()) +
                ") is beyond the grid's range at resolution " + formatNumber(grid_.resolution) +
                " (voxel indices within +-" + std::to_string(kIndexLimit) +
                "): give a coarser --resolution");
  }
  return index;
}

Eigen::Vector3d ReachMap::voxelCentre(const Eigen::Vector3i& index) const {
  return (index.cast<double>().array() + 0.5) * grid_.resolution;
}

std::uint64_t ReachMap::keyOf(const Eigen::Vector3i& index) {
  std::uint64_t key = 0;
  for (int a = 0; a < 3; ++a) {
    key = (key << kIndexBits) | static_cast<std::uint64_t>(index[a] + kIndexLimit);
  }
  return key;
}

std::uint64_t ReachMap::keyOf(const Eigen::Vector3d& p) const { return keyOf(voxelOf(p)); }

Eigen::Vector3i ReachMap::voxel(std::size_t v) const {
  const std::uint64_t key = keys_[v];
  return {static_cast<int>((key >> (2 * kIndexBits)) & kIndexMask) - static_cast<int>(kIndexLimit),
          static_cast<int>((key >> kIndexBits) & kIndexMask) - static_cast<int>(kIndexLimit),
          static_cast<int>(key & kIndexMask) - static_cast<int>(kIndexLimit)};
}

long ReachMap::lookup(std::uint64_t key) const {
  if (table_.empty()) return -1;
  for (std::size_t s = hashSlot(key, index_bits_);; s = (s + 1) & (table_.size() - 1)) {
    if (table_[s].key_plus_one == 0) return -1;
    if (table_[s].key_plus_one == key + 1) return static_cast<long>(table_[s].voxel);
  }
}

void ReachMap::rebuildIndex(std::size_t voxels) {
  std::size_t capacity = 1024;
  while (capacity < 2 * voxels) capacity *= 2;  // load at most one half
  table_.assign(capacity, Entry{0, 0});
  index_bits_ = __builtin_ctzll(capacity);
  for (std::size_t v = 0; v < keys_.size(); ++v) {
    std::size_t s = hashSlot(keys_[v], index_bits_);
    while (table_[s].key_plus_one != 0) s = (s + 1) & (capacity - 1);
    table_[s] = Entry{keys_[v] + 1, v};
  }
}

std::size_t ReachMap::slotFor(std::uint64_t key) {
  if (2 * (keys_.size() + 1) > table_.size()) rebuildIndex(keys_.size() + 1);
  std::size_t s = hashSlot(key, index_bits_);
  for (;; s = (s + 1) & (table_.size() - 1)) {
    if (table_[s].key_plus_one == key + 1) return table_[s].voxel;
    if (table_[s].key_plus_one == 0) break;
  }
  table_[s] = Entry{key + 1, keys_.size()};
  keys_.push_back(key);
  records_.resize(records_.size() + stride_, 0);
  return keys_.size() - 1;
}

void ReachMap::record(std::size_t v, int bin, float manipulability) {
  std::uint64_t* r = records_.data() + v * stride_;
  ++r[0];
  float best;
  std::memcpy(&best, &r[1], sizeof best);
  if (manipulability > best) std::memcpy(&r[1], &manipulability, sizeof manipulability);
  r[2 + bin / 64] |= std::uint64_t{1} << (bin % 64);
}

void ReachMap::checkBin(int bin) const {
  if (bin < 0 || bin >= bins_.size()) {
    throw Error("reachability map: no orientation bin " + std::to_string(bin) + " of " +
                std::to_string(bins_.size()));
  }
}

void ReachMap::add(const Eigen::Vector3d& p, int bin, float manipulability) {
  checkBin(bin);
  record(slotFor(keyOf(p)), bin, manipulability);
}

void ReachMap::merge(const ReachMap& other) {
  if (other.grid_.resolution != grid_.resolution || other.grid_.directions != grid_.directions ||
      other.grid_.rolls != grid_.rolls) {
    throw Error("reachability map: cannot merge maps of different grids");
  }
  for (std::size_t w = 0; w < other.keys_.size(); ++w) {
    const std::size_t v = slotFor(other.keys_[w]);  // may grow records_: before its address
    std::uint64_t* r = records_.data() + v * stride_;
    r[0] += other.count(w);
    const float best = std::max(bestManipulability(v), other.bestManipulability(w));
    std::memcpy(&r[1], &best, sizeof best);
    for (int k = 0; k < words_; ++k) r[2 + k] |= other.bitsOf(w)[k];
  }
}

void ReachMap::sort() {
  std::vector<std::size_t> order(keys_.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return keys_[a] < keys_[b]; });
  Array<std::uint64_t> keys(keys_.size()), records(records_.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    keys[i] = keys_[order[i]];
    std::copy_n(records_.begin() + order[i] * stride_, stride_, records.begin() + i * stride_);
  }
  keys_.swap(keys);
  records_.swap(records);
  rebuildIndex(keys_.size());
}

int ReachMap::reachedBins(std::size_t v) const {
  int reached = 0;
  for (int k = 0; k < words_; ++k) reached += __builtin_popcountll(bitsOf(v)[k]);
  return reached;
}

double ReachMap::meanReachability() const {
  double sum = 0.0;
  for (std::size_t v = 0; v < size(); ++v) sum += reachability(v);
  return size() ? sum / static_cast<double>(size()) : 0.0;
}

bool ReachMap::reached(std::size_t v, int bin) const {
  checkBin(bin);
  return (bitsOf(v)[bin / 64] >> (bin % 64)) & 1u;
}

long ReachMap::find(const Eigen::Vector3d& p) const {
  Eigen::Vector3i index;
  return inGrid(p, index) ? lookup(keyOf(index)) : -1;
}

bool ReachMap::reached(const Eigen::Vector3d& p, const Eigen::Matrix3d& R) const {
  const long v = find(p);
  return v >= 0 && reached(static_cast<std::size_t>(v), bins_.bin(R.col(2), R.col(0)));
}

void ReachMap::write(std::ostream& out, const std::string& header) const {
  // The header's members join the grid's on one line: a compact JSON object is required.
  const std::size_t open = header.find_first_not_of(" \t"), close = header.find_last_not_of(" \t");
  if (open == std::string::npos || header[open] != '{' || header[close] != '}' ||
      header.find_first_of("\r\n") != std::string::npos) {
    throw Error("reachability map: the header must be a JSON object on one line, not '" + header +
                "'");
  }
  const std::string members = header.substr(open + 1, close - open - 1);
  char grid[256];
  std::snprintf(grid, sizeof grid,
                "\"resolution\":%.17g,\"directions\":%d,\"rolls\":%d,\"voxels\":%zu,\"words\":%d",
                grid_.resolution, grid_.directions, grid_.rolls, keys_.size(), words_);
  out << kMagic << "\n{" << grid << (members.empty() ? "" : ",") << members << "}\n";
  for (std::size_t v = 0; v < keys_.size(); ++v) {
    const Eigen::Vector3i index = voxel(v);
    for (int a = 0; a < 3; ++a) writeRaw(out, static_cast<std::int32_t>(index[a]));
    writeRaw(out, count(v));
    writeRaw(out, bestManipulability(v));
    for (int k = 0; k < words_; ++k) writeRaw(out, bitsOf(v)[k]);
  }
  if (!out) throw Error("reachability map: write error");
}

ReachMap ReachMap::read(std::istream& in, const std::string& source, std::string* header) {
  std::string magic, json;
  if (!std::getline(in, magic) || magic != kMagic) {
    throw Error(source + ": not a reachability map (the first line is not '" + kMagic + "')");
  }
  if (!std::getline(in, json)) throw Error(source + ": the reachability map has no header");
  const auto number = [&](const char* name) {
    const std::string tag = std::string("\"") + name + "\":";
    const std::size_t at = json.find(tag);
    if (at == std::string::npos) throw Error(source + ": header has no '" + name + "'");
    char* end = nullptr;
    const double value = std::strtod(json.c_str() + at + tag.size(), &end);
    if (end == json.c_str() + at + tag.size() || !std::isfinite(value)) {
      throw Error(source + ": header field '" + name + "' is not a number");
    }
    return value;
  };
  ReachGrid grid;
  grid.resolution = number("resolution");
  const double directions = number("directions"), rolls = number("rolls"),
               voxels = number("voxels");
  if (directions < 1 || directions > kMaxBins || rolls < 1 || rolls > kMaxBins || voxels < 0 ||
      voxels > 4e9 || directions != std::floor(directions) || rolls != std::floor(rolls) ||
      voxels != std::floor(voxels)) {
    throw Error(source + ": header has an impossible grid or voxel count");
  }
  grid.directions = static_cast<int>(directions);
  grid.rolls = static_cast<int>(rolls);
  ReachMap map = [&] {
    try {
      return ReachMap(grid);
    } catch (const Error& e) {
      throw Error(source + ": " + e.what());
    }
  }();
  if (number("words") != map.words_)
    throw Error(source + ": header 'words' does not match its bins");
  const auto count = static_cast<std::size_t>(voxels);
  for (std::size_t v = 0; v < count; ++v) {
    Eigen::Vector3i index;
    for (int a = 0; a < 3; ++a) {
      std::int32_t i;
      readRaw(in, i, source);
      if (i < -kIndexLimit || i >= kIndexLimit) throw Error(source + ": voxel index out of range");
      index[a] = i;
    }
    const std::size_t slot = map.slotFor(keyOf(index));
    if (slot != v) throw Error(source + ": a voxel appears twice");
    std::uint64_t* r = map.records_.data() + v * map.stride_;
    float best;
    readRaw(in, r[0], source);
    readRaw(in, best, source);
    std::memcpy(&r[1], &best, sizeof best);
    for (int k = 0; k < map.words_; ++k) readRaw(in, r[2 + k], source);
  }
  if (in.peek() != std::char_traits<char>::eof())
    throw Error(source + ": data after the last voxel");
  if (header) *header = json;
  return map;
}

namespace {

/// A sample waiting to be recorded: its voxel's key (ReachMap's packing), orientation bin and
/// manipulability.
struct PendingSample {
  std::uint64_t key;
  int bin;
  float manipulability;
};

/// One part of the map being filled: open addressing with each voxel's record inside its slot
/// ([key + 1 (0: empty), count, best manipulability's float bits, bit set], padded to 4 or 8
/// words), so a sample touches one cache line where ReachMap's index and records touch two.
/// The voxels are split between the parts by their hash, so no voxel is stored twice. Any
/// thread posts samples to a part; whichever thread finds a part due records its samples.
class SlotTable {
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

  /// Hands over samples of this part (thread-safe).
  void post(std::vector<PendingSample>&& samples) {
    const std::lock_guard<std::mutex> lock(inbox_mutex_);
    inbox_size_ += samples.size();
    inbox_.push_back(std::move(samples));
  }
  /// Whether enough samples wait to be recorded together: many for a table swept in order,
  /// any for one that fits in the cache.
  bool due() {
    const std::lock_guard<std::mutex> lock(inbox_mutex_);
    return inbox_size_ >= due_at_;
  }

  /// Records the samples posted, unless another thread is recording this part (then false).
  bool tryRecord() {
    const std::unique_lock<std::mutex> recording(record_mutex_, std::try_to_lock);
    if (!recording.owns_lock()) return false;
    std::vector<std::vector<PendingSample>> batches;
    {
      const std::lock_guard<std::mutex> lock(inbox_mutex_);
      batches.swap(inbox_);
      inbox_size_ = 0;
    }
    record(batches);
    const std::lock_guard<std::mutex> lock(inbox_mutex_);
    due_at_ = cached() ? 1 : kPending;
    return true;
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
  void record(const std::vector<std::vector<PendingSample>>& batches) {
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

  bool cached() const { return capacity_ * slot_words_ * sizeof(std::uint64_t) <= kCached; }

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
    ++r[1];
    float best;
    std::memcpy(&best, &r[2], sizeof best);
    if (s.manipulability > best) std::memcpy(&r[2], &s.manipulability, sizeof best);
    r[3 + s.bin / 64] |= std::uint64_t{1} << (s.bin % 64);
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
  static constexpr std::size_t kPending = std::size_t{1} << 20;  ///< samples swept at once
  static constexpr std::size_t kCached = std::size_t{4} << 20;   ///< table bytes not swept
  int parts_;
  std::mutex inbox_mutex_;   ///< guards inbox_, inbox_size_, due_at_
  std::mutex record_mutex_;  ///< held by the thread recording into the table
  std::vector<std::vector<PendingSample>> inbox_;
  std::size_t inbox_size_{0}, due_at_{1};
  std::vector<PendingSample> sorted_, fresh_;
};

}  // namespace

ReachMap buildReachMap(const Robot& robot, const ReachGrid& grid, const ReachSampling& sampling,
                       const std::function<void(std::uint64_t, std::uint64_t)>& progress) {
  const ReachMap empty(grid);
  RobotSamplerOptions options;
  options.seed = sampling.seed;
  const RobotSampler sampler(robot, options);
  const int n = robot.dof();

  const PoseBatch batch(robot);
  constexpr int kLanes = PoseBatch::kLanes;
  const QualityOptions* quality = sampling.manipulability ? &sampling.quality : nullptr;
  if (quality) quality->check();

  const int threads = sampling.threads > 0 ? sampling.threads : omp_get_num_procs();
  std::deque<SlotTable> tables;
  for (int t = 0; t < threads; ++t) tables.emplace_back(empty.words_, threads);
  constexpr std::size_t kPost = std::size_t{1} << 16;  // samples handed to a part at once
  // outgoing[t][u]: thread t's samples for part u.
  std::vector<std::vector<std::vector<PendingSample>>> outgoing(
      threads, std::vector<std::vector<PendingSample>>(threads));
  constexpr std::uint64_t kBlock = 1 << 14, kChunk = 1 << 22;
  std::vector<std::string> errors(threads);
  const auto rethrow = [&] {
    for (const std::string& error : errors) {
      if (!error.empty()) throw Error(error);
    }
  };
  for (std::uint64_t begin = 0; begin < sampling.samples; begin += kChunk) {
    const std::uint64_t end = std::min(sampling.samples, begin + kChunk);
    const auto blocks = static_cast<std::int64_t>((end - begin + kBlock - 1) / kBlock);
#pragma omp parallel for schedule(dynamic) num_threads(threads)
    for (std::int64_t b = 0; b < blocks; ++b) {
      const int t = omp_get_thread_num();
      if (!errors[t].empty()) continue;
      try {
        CollisionChecker::Scratch scratch;
        double sample_q[kMaxJoints], q[kMaxJoints * kLanes], p[3 * kLanes], a[3 * kLanes],
            x[3 * kLanes], w[kLanes] = {};
        bool counted[kLanes];
        int bins[kLanes];
        const std::uint64_t first = begin + static_cast<std::uint64_t>(b) * kBlock;
        const std::uint64_t offset = sampling.first;
        const std::uint64_t last = std::min(end, first + kBlock);
        for (std::uint64_t i = first; i < last; i += kLanes) {
          // A last, partial batch repeats its last sample in the unused lanes (not counted).
          const int lanes = static_cast<int>(std::min<std::uint64_t>(kLanes, last - i));
          for (int k = 0; k < kLanes; ++k) {
            sampler.jointValues(offset + i + static_cast<std::uint64_t>(std::min(k, lanes - 1)),
                                sample_q);
            for (int j = 0; j < n; ++j) q[j * kLanes + k] = sample_q[j];
            counted[k] = k < lanes && (!sampling.collision ||
                                       sampling.collision->label(sample_q, scratch) == kLabelFree);
          }
          batch.poses(q, p, a, x, quality, w);
          empty.bins().bins(a, x, kLanes, bins);
          for (int k = 0; k < kLanes; ++k) {
            if (!counted[k]) continue;
            empty.checkBin(bins[k]);
            const std::uint64_t key =
                empty.keyOf(Eigen::Vector3d(p[k], p[kLanes + k], p[2 * kLanes + k]));
            auto& out = outgoing[t][SlotTable::partOf(key, threads)];
            out.push_back({key, bins[k], static_cast<float>(w[k])});
            if (out.size() >= kPost) {
              tables[SlotTable::partOf(key, threads)].post(std::move(out));
              out = {};
              out.reserve(kPost);
            }
          }
        }
        for (SlotTable& table : tables) {
          if (table.due()) table.tryRecord();
        }
      } catch (const std::exception& e) {
        errors[t] = e.what();
      }
    }
    rethrow();
    if (progress) progress(end, sampling.samples);
  }
  // The samples still on their way recorded, each table's voxels sorted by key (a thread each),
  // then merged into the map (no voxel is in two tables): the map in its final order.
  using Voxel = std::pair<std::uint64_t, const std::uint64_t*>;
  const auto byKey = [](const Voxel& a, const Voxel& b) { return a.first < b.first; };
  std::vector<std::vector<Voxel>> lists(threads);
  for (int t = 0; t < threads; ++t) {
    for (int u = 0; u < threads; ++u) tables[u].post(std::move(outgoing[t][u]));
  }
#pragma omp parallel for schedule(static, 1) num_threads(threads)
  for (int t = 0; t < threads; ++t) {
    try {
      tables[t].tryRecord();
      lists[t].reserve(tables[t].size());
      tables[t].forEach([&](std::uint64_t key, const std::uint64_t* record) {
        lists[t].emplace_back(key, record);
      });
      std::sort(lists[t].begin(), lists[t].end(), byKey);
    } catch (const std::exception& e) {
      errors[t] = e.what();
    }
  }
  rethrow();
  std::size_t voxels = 0;
  for (const auto& list : lists) voxels += list.size();
  ReachMap map(grid);
  map.keys_.reserve(voxels);
  map.records_.reserve(voxels * map.stride_);
  std::vector<std::size_t> next(threads, 0);
  for (;;) {
    int first = -1;  // the list whose next voxel has the lowest key
    for (int t = 0; t < threads; ++t) {
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
  map.rebuildIndex(map.keys_.size());
  return map;
}

std::vector<ReachPoint, Eigen::aligned_allocator<ReachPoint>> reachPoints(const ReachMap& map) {
  std::vector<ReachPoint, Eigen::aligned_allocator<ReachPoint>> points(map.size());
  for (std::size_t v = 0; v < map.size(); ++v) {
    const Eigen::Vector3d c = map.voxelCentre(map.voxel(v));
    points[v].x = static_cast<float>(c.x());
    points[v].y = static_cast<float>(c.y());
    points[v].z = static_cast<float>(c.z());
    points[v].reachability = static_cast<float>(map.reachability(v));
    points[v].manipulability = map.bestManipulability(v);
    points[v].count = static_cast<std::uint32_t>(
        std::min<std::uint64_t>(map.count(v), std::numeric_limits<std::uint32_t>::max()));
  }
  return points;
}

}  // namespace mcws
