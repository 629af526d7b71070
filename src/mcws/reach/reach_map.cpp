#include "mcws/reach/reach_map.h"

#include <omp.h>
#include <sys/mman.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <istream>
#include <limits>
#include <numeric>
#include <ostream>

#include "mcws/core/decimal.h"
#include "mcws/core/error.h"
#include "mcws/reach/voxel_box.h"  // PendingSample, BoxSample

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
template struct HugePageAllocator<reach_map_build::PendingSample>;
template struct HugePageAllocator<reach_map_build::BoxSample>;
namespace {

constexpr char kMagic[] = "MCWS-REACH-MAP 1";
constexpr int kMaxBins = 65536;
constexpr std::uint64_t kIndexBits = ReachMap::kKeyBits;
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
  if (deferred_.pending.load(std::memory_order_acquire)) buildDeferredIndex();
  if (table_.empty()) return -1;
  for (std::size_t s = hashSlot(key, index_bits_);; s = (s + 1) & (table_.size() - 1)) {
    if (table_[s].key_plus_one == 0) return -1;
    if (table_[s].key_plus_one == key + 1) return static_cast<long>(table_[s].voxel);
  }
}

void ReachMap::deferIndex(int threads) {
  table_ = {};
  deferred_.threads = threads;
  deferred_.pending.store(true, std::memory_order_release);
}

void ReachMap::buildDeferredIndex() const {
  const std::lock_guard<std::mutex> lock(deferred_.mutex);
  if (deferred_.pending.load(std::memory_order_relaxed)) {
    rebuildIndex(keys_.size(), deferred_.threads);  // stores pending = false
  }
}

void ReachMap::rebuildIndex(std::size_t voxels, int threads) const {
  // The index built here is complete: nothing is left deferred (stored with release at each
  // return: the slots before).
  std::size_t capacity = 1024;
  while (capacity < 2 * voxels) capacity *= 2;  // load at most one half
  index_bits_ = __builtin_ctzll(capacity);
  if (threads <= 1 || keys_.size() < (std::size_t{1} << 16)) {
    table_.assign(capacity, Entry{0, 0});
    for (std::size_t v = 0; v < keys_.size(); ++v) {
      std::size_t s = hashSlot(keys_[v], index_bits_);
      while (table_[s].key_plus_one != 0) s = (s + 1) & (capacity - 1);
      table_[s] = Entry{keys_[v] + 1, v};
    }
    deferred_.pending.store(false, std::memory_order_release);
    return;
  }
  // Each thread clears and fills its own range of slots with the voxels whose home slot is in it;
  // a voxel that would probe past the range's end waits, and is placed after them all in the
  // first empty slot from its home. Every voxel then lies at the end of a run of full slots from
  // its home, as lookup() expects (slots are only ever filled); where it lies does not matter.
  table_.clear();
  table_.resize(capacity);  // uninitialised (HugePageAllocator): the threads clear their slots
  std::vector<std::vector<std::size_t>> waiting(static_cast<std::size_t>(threads));
#pragma omp parallel for schedule(static, 1) num_threads(threads)
  for (int t = 0; t < threads; ++t) {
    const std::size_t begin = capacity / threads * t, end = capacity / threads * (t + 1);
    const std::size_t last = t + 1 == threads ? capacity : end;
    std::fill(table_.begin() + begin, table_.begin() + last, Entry{0, 0});
    for (std::size_t v = 0; v < keys_.size(); ++v) {
      std::size_t s = hashSlot(keys_[v], index_bits_);
      if (s < begin || s >= last) continue;
      while (s < last && table_[s].key_plus_one != 0) ++s;
      if (s == last) {
        waiting[t].push_back(v);
      } else {
        table_[s] = Entry{keys_[v] + 1, v};
      }
    }
  }
  for (const auto& list : waiting) {
    for (const std::size_t v : list) {
      std::size_t s = hashSlot(keys_[v], index_bits_);
      while (table_[s].key_plus_one != 0) s = (s + 1) & (capacity - 1);
      table_[s] = Entry{keys_[v] + 1, v};
    }
  }
  deferred_.pending.store(false, std::memory_order_release);
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

namespace {

/// Set bits of words[0 .. n) by the bit-slicing sum (the build targets plain x86-64, where
/// __builtin_popcountll is a call into libgcc).
int setBitsPortable(const std::uint64_t* words, int n) {
  int count = 0;
  for (int k = 0; k < n; ++k) {
    std::uint64_t x = words[k];
    x -= (x >> 1) & 0x5555555555555555ull;
    x = (x & 0x3333333333333333ull) + ((x >> 2) & 0x3333333333333333ull);
    x = (x + (x >> 4)) & 0x0F0F0F0F0F0F0F0Full;
    count += static_cast<int>((x * 0x0101010101010101ull) >> 56);
  }
  return count;
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
/// The same with the popcnt instruction, for processors that have it.
__attribute__((target("popcnt"))) int setBitsPopcnt(const std::uint64_t* words, int n) {
  int count = 0;
  for (int k = 0; k < n; ++k) count += __builtin_popcountll(words[k]);
  return count;
}

int setBits(const std::uint64_t* words, int n) {
  static const bool popcnt = (__builtin_cpu_init(), __builtin_cpu_supports("popcnt"));
  return popcnt ? setBitsPopcnt(words, n) : setBitsPortable(words, n);
}
#else
int setBits(const std::uint64_t* words, int n) { return setBitsPortable(words, n); }
#endif

}  // namespace

int ReachMap::reachedBins(std::size_t v) const { return setBits(bitsOf(v), words_); }

double ReachMap::meanReachability() const {
  double sum = 0.0;
  for (std::size_t v = 0; v < size(); ++v) sum += reachability(v);
  return size() ? sum / static_cast<double>(size()) : 0.0;
}

bool ReachMap::reached(std::size_t v, int bin) const {
  checkBin(bin);
  return (bitsOf(v)[bin / 64] >> (bin % 64)) & 1u;
}

bool ReachMap::approachReached(std::size_t v, int region) const {
  const int rolls = bins_.rolls();
  for (int k = 0; k < rolls; ++k) {
    if (reached(v, region * rolls + k)) return true;
  }
  return false;
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

std::vector<ReachPoint, Eigen::aligned_allocator<ReachPoint>> reachPoints(const ReachMap& map) {
  std::vector<ReachPoint, Eigen::aligned_allocator<ReachPoint>> points(map.size());
  reachPoints(map, 0, map.size(), points.data());
  return points;
}

void reachPoints(const ReachMap& map, std::size_t first, std::size_t count, ReachPoint* out,
                 int threads) {
  // Each point on its own: any thread's.
  threads = threads > 0 ? threads : omp_get_num_procs();
#pragma omp parallel for schedule(static) num_threads(threads) if (count >= 8192 && threads > 1)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(count); ++i) {
    const std::size_t v = first + static_cast<std::size_t>(i);
    const Eigen::Vector3d c = map.voxelCentre(map.voxel(v));
    ReachPoint& point = out[i];
    point.x = static_cast<float>(c.x());
    point.y = static_cast<float>(c.y());
    point.z = static_cast<float>(c.z());
    point.reachability = static_cast<float>(map.reachability(v));
    point.manipulability = map.bestManipulability(v);
    point.count = static_cast<std::uint32_t>(
        std::min<std::uint64_t>(map.count(v), std::numeric_limits<std::uint32_t>::max()));
  }
}

}  // namespace mcws
