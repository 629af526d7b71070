#pragma once
/// \file
/// \brief Reachability maps: which tool orientations the arm reaches in each voxel of space,
/// estimated by Monte Carlo sampling of the joint space through forward kinematics only
/// (Zacharias, Borst & Hirzinger 2007; ROS Reuleaux; Simox's WorkspaceRepresentation).

#include <pcl/point_types.h>
#include <pcl/register_point_struct.h>

#include <Eigen/Geometry>
#include <array>
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <iosfwd>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "mcws/kinematics/robot.h"
#include "mcws/reach/orientation_bins.h"
#include "mcws/reach/quality.h"

namespace mcws {

class CollisionChecker;
struct ReachSampling;

/// \brief The grid of a reachability map.
struct ReachGrid {
  double resolution{0.0};  ///< voxel edge [length unit]; voxel (i, j, k) spans [i, i+1) * edge
  int directions{200};     ///< approach-direction regions on the sphere (SpherePartition)
  int rolls{1};            ///< roll bins about the approach
  /// \throws mcws::Error naming the bad value (resolution not positive and finite, directions
  ///   or rolls < 1, or more than 65536 bins).
  void check() const;
};

/// \brief Allocator of the map's large arrays: blocks of 2 MB or more are 2 MB aligned and
/// advised to the kernel as transparent huge pages (madvise), so the random accesses of a map
/// with millions of voxels miss the TLB far less. Smaller blocks come from malloc.
template <typename T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <typename U>
  HugePageAllocator(const HugePageAllocator<U>&) {}
  T* allocate(std::size_t n);
  void deallocate(T* p, std::size_t) { std::free(p); }
  /// Elements added without a value are default-initialised (left as they are, for the
  /// map's integers), so a large array can be filled in parallel without a serial clearing first.
  template <typename U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <typename U>
  bool operator==(const HugePageAllocator<U>&) const {
    return true;
  }
  template <typename U>
  bool operator!=(const HugePageAllocator<U>&) const {
    return false;
  }
};

/// \brief A sparse 6-D reachability map: position voxels x orientation bins.
///
/// Only voxels some sample reached are stored (memory grows with the occupied voxels, about
/// 40 + bins / 8 bytes each plus the index, not with the samples). Per voxel: the orientation bins
/// reached (a bit set), the samples that fell in it and the best manipulability among them.
/// Merging two maps adds counts, unites bit sets and keeps the larger manipulability, so a map
/// filled from blocks of samples in any order is the same map.
class ReachMap {
 public:
  /// Voxel indices below -2^20 or at or above 2^20 cannot be stored (x / resolution beyond about
  /// one million).
  static constexpr std::int64_t kIndexLimit = 1 << 20;
  /// Bits of each voxel index packed in a voxel's key.
  static constexpr int kKeyBits = 21;

  ReachMap() = default;
  explicit ReachMap(const ReachGrid& grid);

  const ReachGrid& grid() const { return grid_; }
  const OrientationBins& bins() const { return bins_; }
  /// \brief Occupied voxels.
  std::size_t size() const { return keys_.size(); }
  /// \brief Samples added, over all voxels.
  std::uint64_t samples() const;

  /// \brief The voxel index of a position [length unit] (floor(x / resolution), ...).
  /// \throws mcws::Error when it is outside +-kIndexLimit.
  Eigen::Vector3i voxelOf(const Eigen::Vector3d& p) const;
  /// \brief Centre of a voxel [length unit].
  Eigen::Vector3d voxelCentre(const Eigen::Vector3i& index) const;

  /// \brief Records one sample: tool point p [length unit], orientation bin, manipulability.
  /// \throws mcws::Error for a bin outside [0, bins().size()) or p outside the grid's range.
  void add(const Eigen::Vector3d& p, int bin, float manipulability);
  /// \brief Adds another map of the same grid (counts add, bins unite, manipulability max).
  /// \throws mcws::Error when the grids differ.
  void merge(const ReachMap& other);
  /// \brief Orders the voxels by index (z fastest, then y, then x), the order of every output.
  void sort();

  /// \brief Voxel v's index (v < size()).
  Eigen::Vector3i voxel(std::size_t v) const;
  std::uint64_t count(std::size_t v) const { return records_[v * stride_]; }
  float bestManipulability(std::size_t v) const;
  /// \brief Orientation bins reached in voxel v.
  int reachedBins(std::size_t v) const;
  /// \brief The reachability index D of voxel v: reached bins / all bins, in (0, 1].
  double reachability(std::size_t v) const {
    return static_cast<double>(reachedBins(v)) / bins_.size();
  }
  /// \brief Mean of the reachability index over the occupied voxels (0 for an empty map).
  double meanReachability() const;
  /// \brief Whether a bin of voxel v was reached. \throws mcws::Error for a bin out of range.
  bool reached(std::size_t v, int bin) const;
  /// \brief Whether any roll bin of approach-direction region `region` (bins().sphere()) was
  /// reached in voxel v: a tool approach reached with any roll.
  bool approachReached(std::size_t v, int region) const;
  /// \brief The stored voxel holding p, or -1 (also for p beyond the grid's range or NaN).
  long find(const Eigen::Vector3d& p) const;
  /// \brief Whether the map holds a sample with tool point in p's voxel and orientation in R's
  /// bin (R: the tool's rotation).
  bool reached(const Eigen::Vector3d& p, const Eigen::Matrix3d& R) const;

  /// \brief Writes the map in the binary format of docs/reach_map.md.
  /// \param header extra JSON members for the header (robot, unit, samples, seed), as a compact
  ///   JSON object on one line, or "{}". \throws mcws::Error for anything else.
  void write(std::ostream& out, const std::string& header) const;
  /// \brief Reads what write() wrote; \p header receives the header's JSON text.
  /// \throws mcws::Error naming `source` and what is wrong.
  static ReachMap read(std::istream& in, const std::string& source, std::string* header = nullptr);

 private:
  /// One slot of the open-addressing index: a packed voxel index + 1 (0: empty) and its voxel.
  struct Entry {
    std::uint64_t key_plus_one;
    std::uint64_t voxel;
  };
  std::size_t slotFor(std::uint64_t key);
  long lookup(std::uint64_t key) const;
  /// An index for `voxels` at load one half at most (built by `threads` threads).
  void rebuildIndex(std::size_t voxels, int threads = 1) const;
  /// Leaves the index of the voxels to the first lookup() (built by `threads` threads then):
  /// a map only written out never needs it.
  void deferIndex(int threads);
  /// Builds the index deferIndex() left (one thread at a time, the others wait).
  void buildDeferredIndex() const;
  void checkBin(int bin) const;
  bool inGrid(const Eigen::Vector3d& p, Eigen::Vector3i& index) const;
  void record(std::size_t v, int bin, float manipulability);
  friend class ReachMapBuilder;  ///< buildReachMap's steps (reach_map_build.cpp)
  std::uint64_t* bitsOf(std::size_t v) { return records_.data() + v * stride_ + 2; }
  const std::uint64_t* bitsOf(std::size_t v) const { return records_.data() + v * stride_ + 2; }
  std::uint64_t keyOf(const Eigen::Vector3d& p) const;
  static std::uint64_t keyOf(const Eigen::Vector3i& index);
  /// keyOf(p) for p = (p[0], p[stride], p[2 stride]) without Eigen or floor() calls (the same
  /// key); false where p is beyond the grid's range (or NaN), where keyOf() throws.
  bool keyInGrid(const double* p, int stride, std::uint64_t& key) const {
    key = 0;
    for (int a = 0; a < 3; ++a) {
      const double s = p[a * stride] * inverse_resolution_;
      // floor(s) is within [-limit, limit) exactly when s is (the limits are whole numbers).
      if (!(s >= -kIndexLimit && s < kIndexLimit)) return false;
      auto i = static_cast<std::int64_t>(s);    // toward zero
      i -= static_cast<double>(i) > s ? 1 : 0;  // floor
      key = (key << kKeyBits) | static_cast<std::uint64_t>(i + kIndexLimit);
    }
    return true;
  }

  ReachGrid grid_;
  OrientationBins bins_{1, 1};
  int words_{1};   ///< 64-bit words of one voxel's bit set
  int stride_{3};  ///< words of one voxel's record: count, best manipulability, bits
  double inverse_resolution_{0.0};
  template <typename T>
  using Array = std::vector<T, HugePageAllocator<T>>;
  Array<std::uint64_t> keys_;     ///< packed voxel indices
  Array<std::uint64_t> records_;  ///< per voxel: count, float bits of the best, bit set
  /// The index: every voxel's key at the end of a run of full slots from its home; empty while
  /// deferred (built by lookup(), which is const and may run on several threads: mutable).
  mutable Array<Entry> table_;
  mutable int index_bits_{0};  ///< log2 of the index's size
  /// Whether the index is deferred (table_ empty then), and the lock of whoever builds it. A
  /// copy has a lock of its own.
  struct Deferred {
    Deferred() = default;
    Deferred(const Deferred& other) : pending(other.pending.load()), threads(other.threads) {}
    Deferred& operator=(const Deferred& other) {
      pending.store(other.pending.load());
      threads = other.threads;
      return *this;
    }
    std::atomic<bool> pending{false};
    int threads{1};
    std::mutex mutex;
  };
  mutable Deferred deferred_;
};

/// \brief How a map is filled.
struct ReachSampling {
  std::uint64_t first{0};  ///< index of the first sample (a map of samples [0, 2N) is the merge
                           ///< of the maps of [0, N) and [N, 2N))
  std::uint64_t samples{0};
  std::uint64_t seed{1};
  int threads{0};             ///< 0: all cores; the map does not depend on it
  bool manipulability{true};  ///< compute the Jacobian and keep the best per voxel
  QualityOptions quality;     ///< how manipulability is measured
  /// Only collision-free samples count (nullptr: all). Must outlive the call.
  const CollisionChecker* collision{nullptr};
  /// Largest memory [bytes] for the map as a dense box of voxels around the arm's reach (its
  /// records at computed places, fastest to fill); beyond it (0: always) a hash table of the
  /// voxels reached. The map is the same either way.
  std::uint64_t dense_bytes{std::uint64_t{1} << 30};
};

/// \brief Fills a map with joint samples first .. first+samples-1: joint values uniform within the
/// limits, drawn exactly as mcws::RobotSampler draws them (same seed, same joint values as
/// mcws_sample), mapped to the tool pose by forward kinematics.
/// \param progress called now and then with (samples done, samples); may be empty.
/// \throws mcws::Error for a robot with more than kMaxJoints joints or a tool point outside the
///   map's index range.
ReachMap buildReachMap(const Robot& robot, const ReachGrid& grid, const ReachSampling& sampling,
                       const std::function<void(std::uint64_t, std::uint64_t)>& progress = {});

/// \brief A voxel of a reachability map as a point: its centre, D, best manipulability, count.
///
/// PCD fields: `x y z` [length unit] (float), `reachability` [1] (float, the share of orientation
/// bins reached), `manipulability` (float, the best of the voxel's samples; the unit of
/// Quality::manipulability), `count` (uint32, samples in the voxel, saturating).
struct EIGEN_ALIGN16 ReachPoint {
  PCL_ADD_POINT4D;
  float reachability;
  float manipulability;
  std::uint32_t count;
  ReachPoint() : data{0.f, 0.f, 0.f, 1.f}, reachability(0.f), manipulability(0.f), count(0) {}
  PCL_MAKE_ALIGNED_OPERATOR_NEW
};

/// \brief The map's voxels as points, in the map's order.
std::vector<ReachPoint, Eigen::aligned_allocator<ReachPoint>> reachPoints(const ReachMap& map);
/// \brief Voxels first .. first + count - 1 of the map as points into out[0 .. count): a slice
/// of reachPoints(), for writing a large map a part at a time, by `threads` threads (0: all
/// cores).
void reachPoints(const ReachMap& map, std::size_t first, std::size_t count, ReachPoint* out,
                 int threads = 1);

}  // namespace mcws

// clang-format off
POINT_CLOUD_REGISTER_POINT_STRUCT(mcws::ReachPoint,
    (float, x, x) (float, y, y) (float, z, z)
    (float, reachability, reachability) (float, manipulability, manipulability)
    (std::uint32_t, count, count))
// clang-format on
