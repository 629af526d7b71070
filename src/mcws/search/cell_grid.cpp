#include "mcws/search/cell_grid.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace mcws {

double cellGridEdge(const Eigen::Vector3d& extent, int dimensions, double cell,
                    std::size_t points) {
  const double max_cells = 4.0 * static_cast<double>(points) + 16.0;
  for (;;) {
    double cells = 1.0;
    for (int k = 0; k < dimensions; ++k) cells *= std::floor(extent[k] / cell) + 1.0;
    if (cells <= max_cells) return cell;
    cell *= std::max(1.01, std::pow(cells / max_cells, 1.0 / dimensions));
  }
}

CellGrid::CellGrid(const pcl::PointCloud<pcl::PointXYZ>& cloud, int dimensions, double cell,
                   int threads)
    : dimensions_(dimensions), cell_(cell) {
  const auto n = static_cast<std::int64_t>(cloud.size());
  Eigen::Vector3d min = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector3d max = -min;
#pragma omp parallel num_threads(threads)
  {
    // Each thread's box, then their union: the same box in any order.
    // (from the constants, not min and max: another thread may already be writing those)
    Eigen::Vector3d own_min = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
    Eigen::Vector3d own_max = -own_min;
#pragma omp for schedule(static) nowait
    for (std::int64_t i = 0; i < n; ++i) {
      own_min = own_min.cwiseMin(cloud[i].getVector3fMap().cast<double>());
      own_max = own_max.cwiseMax(cloud[i].getVector3fMap().cast<double>());
    }
#pragma omp critical
    {
      min = min.cwiseMin(own_min);
      max = max.cwiseMax(own_max);
    }
  }
  origin_ = n > 0 ? min : Eigen::Vector3d::Zero();
  const Eigen::Vector3d extent = n > 0 ? Eigen::Vector3d(max - min) : Eigen::Vector3d::Zero();
  const double largest = extent.head(dimensions).maxCoeff();
  if (!(cell_ > 0.0) || !std::isfinite(cell_)) cell_ = largest > 0.0 ? largest : 1.0;
  cell_ = cellGridEdge(extent, dimensions, cell_, static_cast<std::size_t>(n));
  inverse_cell_ = 1.0 / cell_;
  std::int64_t total = 1;
  for (int k = 0; k < dimensions; ++k) {
    counts_[k] = static_cast<std::int64_t>(std::floor(extent[k] / cell_)) + 1;
    total *= counts_[k];
  }

  // Counting sort of the points by cell.
  std::vector<std::uint32_t> cell_of(static_cast<std::size_t>(n));
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    std::int64_t c = 0;
    for (int k = dimensions - 1; k >= 0; --k) c = c * counts_[k] + cellOf(cloud[i], k);
    cell_of[i] = static_cast<std::uint32_t>(c);
  }
  start_.assign(static_cast<std::size_t>(total) + 1, 0);
  for (const std::uint32_t c : cell_of) ++start_[c + 1];
  for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
  x_.resize(cell_of.size());
  y_.resize(cell_of.size());
  z_.resize(cell_of.size());
  index_.resize(cell_of.size());
  std::vector<std::uint32_t> next(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < cell_of.size(); ++i) {
    const std::uint32_t slot = next[cell_of[i]]++;
    x_[slot] = cloud[i].x;
    y_[slot] = cloud[i].y;
    z_[slot] = dimensions == 3 ? cloud[i].z : 0.0f;
    index_[slot] = static_cast<pcl::index_t>(i);
  }
}

std::int64_t CellGrid::cellOf(const pcl::PointXYZ& p, int axis) const {
  const double c = std::floor((static_cast<double>(p.data[axis]) - origin_[axis]) / cell_);
  return std::clamp<std::int64_t>(static_cast<std::int64_t>(std::max(c, -1.0)), 0,
                                  counts_[axis] - 1);
}

std::size_t CellGrid::population(const pcl::PointXYZ& p) const {
  std::int64_t c = 0;
  for (int k = dimensions_ - 1; k >= 0; --k) c = c * counts_[k] + cellOf(p, k);
  return start_[c + 1] - start_[c];
}

namespace {

/// The candidates a k-nearest search keeps for the radius search after it: those with d^2 below
/// this many times the previous point's k-th d^2. An adaptive radius of s d_k (s = 2: 4 d_k^2)
/// then lies within them unless d_k^2 grew by more than 35 % from the previous point.
constexpr float kNearHint = 5.4f;
/// The k-th smallest is first selected among the candidates with d^2 below this many times the
/// previous answer, then below twice it, then among all: selecting among few is most of a
/// k-nearest search's time.
constexpr float kFirstHint = 1.3f;

/// Writes to `out` the places k (in order) of the values with d2s[k] < bound, and returns how many
/// there are; `out` must hold n + 3 entries. With SSE2, four at a time: the lanes below the bound
/// as a 4-bit mask, their places from a table of the 16 masks, stored whole and advanced by the
/// mask's count (a branch-free left-pack of places, which needs no byte shuffle).
std::size_t compactBelow(const float* d2s, std::size_t n, float bound, std::uint32_t* out) {
  std::size_t kept = 0, k = 0;
#if defined(__SSE2__)
  struct Table {
    alignas(16) std::uint32_t lanes[16][4];
    std::uint8_t count[16];
    Table() : lanes{}, count{} {
      for (unsigned mask = 0; mask < 16; ++mask) {
        for (unsigned lane = 0; lane < 4; ++lane) {
          if (mask >> lane & 1u) lanes[mask][count[mask]++] = lane;
        }
      }
    }
  };
  static const Table table;
  const __m128 limit = _mm_set1_ps(bound);
  for (; k + 4 <= n; k += 4) {
    const int mask = _mm_movemask_ps(_mm_cmplt_ps(_mm_loadu_ps(d2s + k), limit));
    const __m128i places =
        _mm_add_epi32(_mm_set1_epi32(static_cast<int>(k)),
                      _mm_load_si128(reinterpret_cast<const __m128i*>(table.lanes[mask])));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + kept), places);
    kept += table.count[mask];
  }
#endif
  for (; k < n; ++k) {
    out[kept] = static_cast<std::uint32_t>(k);
    kept += d2s[k] < bound;
  }
  return kept;
}

/// Squared distances from (px, py, pz) of `length` points in parallel arrays, and their slots
/// `first`, `first` + 1, ...: as FLANN's L2_Simple computes them (float, query minus point, summed
/// x, y, z in that order; q - p is exactly -(p - q)). Arrays that do not overlap: a vectorised
/// loop. Every element is computed alone, by IEEE operations without fused multiply-adds, so any
/// vector width gives the same values.
#define MCWS_SQUARED_DISTANCES_BODY                                \
  for (std::uint32_t k = 0; k < length; ++k) {                     \
    const float dx = xs[k] - px, dy = ys[k] - py, dz = zs[k] - pz; \
    float d = dx * dx;                                             \
    d += dy * dy;                                                  \
    d += dz * dz;                                                  \
    d2[k] = d;                                                     \
    slot[k] = first + k;                                           \
  }

void squaredDistances(const float* __restrict xs, const float* __restrict ys,
                      const float* __restrict zs, std::uint32_t length, float px, float py,
                      float pz, std::uint32_t first, float* __restrict d2,
                      std::uint32_t* __restrict slot) {
  MCWS_SQUARED_DISTANCES_BODY
}

#if defined(__x86_64__) && defined(__GNUC__)
/// squaredDistances() 8 at a time (AVX2, without FMA: no contraction of dx * dx + ...).
__attribute__((target("avx2"))) void squaredDistancesAvx2(
    const float* __restrict xs, const float* __restrict ys, const float* __restrict zs,
    std::uint32_t length, float px, float py, float pz, std::uint32_t first, float* __restrict d2,
    std::uint32_t* __restrict slot) {
  MCWS_SQUARED_DISTANCES_BODY
}
#endif
#undef MCWS_SQUARED_DISTANCES_BODY

using SquaredDistances = void (*)(const float*, const float*, const float*, std::uint32_t, float,
                                  float, float, std::uint32_t, float*, std::uint32_t*);

/// The squaredDistances() for this processor.
SquaredDistances squaredDistancesHere() {
#if defined(__x86_64__) && defined(__GNUC__)
  __builtin_cpu_init();  // this may run before the runtime's own initialisation
  if (__builtin_cpu_supports("avx2")) return squaredDistancesAvx2;
#endif
  return squaredDistances;
}

const SquaredDistances kSquaredDistances = squaredDistancesHere();

}  // namespace

void CellGrid::collect(const pcl::PointXYZ& p, double reach, Candidates& out) const {
  out.size = 0;
  // The ball, widened for rounding, against the cells' extents [origin + c cell, + cell).
  // The margin also covers multiplying by 1 / cell where the points' cells were found dividing
  // by cell (relative errors of 1e-16 on at most a few million cells).
  const double r = reach * (1.0 + 1e-6) + cell_ * 1e-6;
  const Eigen::Vector3d q(p.x, p.y, dimensions_ == 3 ? p.z : 0.0f);
  const double inverse = inverse_cell_;
  auto cellAt = [&](double v, int axis) {
    // Truncation is floor at and above 0, and below 0 both clamp to cell 0: the same cell
    // without std::floor, which the x86-64 baseline (no SSE4.1) computes in a dozen instructions.
    const double c = std::clamp((v - origin_[axis]) * inverse, -1.0, 1e15);
    return std::clamp<std::int64_t>(static_cast<std::int64_t>(c), 0, counts_[axis] - 1);
  };
  auto gapTo = [&](std::int64_t c, int axis) {  // distance from q to cell c's slab
    const double lo = origin_[axis] + c * cell_, hi = lo + cell_;
    return q[axis] < lo ? lo - q[axis] : (q[axis] > hi ? q[axis] - hi : 0.0);
  };
  std::int64_t lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (int k = 0; k < dimensions_; ++k) {
    lo[k] = cellAt(q[k] - r, k);
    hi[k] = cellAt(q[k] + r, k);
  }
  // In 2-D, z is 0 - 0 and adds nothing to the squared distances.
  const float px = p.x, py = p.y, pz = dimensions_ == 3 ? p.z : 0.0f;
  for (std::int64_t cz = lo[2]; cz <= hi[2]; ++cz) {
    const double gz = dimensions_ == 3 ? gapTo(cz, 2) : 0.0;
    const double slab = r * r - gz * gz;
    for (std::int64_t cy = lo[1]; cy <= hi[1]; ++cy) {
      const double gy = gapTo(cy, 1);
      const double left = slab - gy * gy;
      if (left < 0.0) continue;  // this row of cells misses the ball
      const double w = std::sqrt(left);
      const std::int64_t x0 = cellAt(q.x() - w, 0), x1 = cellAt(q.x() + w, 0);
      const std::int64_t row = (cz * counts_[1] + cy) * counts_[0];
      const std::uint32_t begin = start_[row + x0], end = start_[row + x1 + 1];
      const std::size_t base = out.size;
      out.size += end - begin;
      if (out.d2.size() < out.size) {
        out.d2.resize(2 * out.size);
        out.slot.resize(2 * out.size);
      }
      kSquaredDistances(x_.data() + begin, y_.data() + begin, z_.data() + begin, end - begin, px,
                        py, pz, begin, out.d2.data() + base, out.slot.data() + base);
    }
  }
}

bool CellGridSearch::gather(pcl::index_t i, double reach) {
  if (reach > max_reach_) return false;
  if (point_ != i || reach_ < reach) {
    grid_.collect(cloud_[i], reach, candidates_);
    point_ = i;
    reach_ = reach;
    near_count_ = 0;
    near_bound_ = 0.0f;
  }
  return true;
}

std::optional<float> CellGridSearch::kthDistance2(pcl::index_t i, int count,
                                                  std::vector<Neighbour>* nearest) {
  double reach = std::min(std::max(first_reach_, grid_.cellSize()), max_reach_);
  for (;; reach = std::min(2 * reach, max_reach_)) {
    gather(i, reach);
    // Every point whose float distance is below `limit` lies within reach, so it was collected;
    // if `count` of them were, the count-th smallest of all points is among them. The previous
    // query's answer, a little enlarged, usually leaves a short list to select from (a hint
    // only: the answer does not depend on it).
    const auto limit = static_cast<float>(reach * reach * (1.0 - 1e-5));
    const std::size_t n = candidates_.size;
    const float* d2s = candidates_.d2.data();
    if (smallest_.size() < n) smallest_.resize(n);
    // First the candidates within a few times the previous answer (near_: an adaptive radius
    // of twice the k-th distance is then likely to lie within them), and of those the ones
    // within twice the previous answer to select from; then, if too few, every candidate.
    near_bound_ = std::min(limit, kNearHint * hint_);
    if (near_.size() < n + 3) near_.resize(2 * n + 3);  // compactBelow() may write 3 past
    near_count_ = compactBelow(d2s, n, near_bound_, near_.data());
    std::size_t m = 0;
    for (const float factor : {kFirstHint, 2.0f}) {
      const float first = std::min(limit, factor * hint_);
      m = 0;
      for (std::size_t j = 0; j < near_count_; ++j) {
        smallest_[m] = d2s[near_[j]];
        m += d2s[near_[j]] < first;
      }
      if (m >= static_cast<std::size_t>(count)) break;
    }
    if (m < static_cast<std::size_t>(count)) {
      m = 0;
      for (std::size_t k = 0; k < n; ++k) {
        smallest_[m] = d2s[k];
        m += d2s[k] < limit;
      }
    }
    if (m < static_cast<std::size_t>(count)) {
      if (reach >= max_reach_) return std::nullopt;
      continue;
    }
    std::nth_element(smallest_.begin(), smallest_.begin() + (count - 1), smallest_.begin() + m);
    const float d2 = smallest_[count - 1];
    hint_ = d2;
    if (!nearest) return d2;
    // The points themselves: those strictly closer, then ties at d2 up to `count`.
    within(i, d2, *nearest);
    for (std::size_t k = 0; k < n && nearest->size() < static_cast<std::size_t>(count); ++k) {
      if (d2s[k] == d2) nearest->push_back(grid_.neighbour(candidates_.slot[k], cloud_[i], d2));
    }
    return d2;
  }
}

bool CellGridSearch::adaptiveSubset(pcl::index_t i, int count, float scale,
                                    std::vector<Neighbour>& subset) {
  const double reach = grid_.cellSize();
  if (!gather(i, reach)) return false;
  // If fewer than `count` points have d^2 < inner, then d^2 >= inner, r_i >= scale sqrt(inner)
  // (rounding is monotone) and every point with d^2 < float(r_min^2) lies within r_i.
  const auto inner = static_cast<float>(reach * reach / (static_cast<double>(scale) * scale));
  const float r_min = scale * std::sqrt(inner);
  const auto limit = std::min(static_cast<float>(static_cast<double>(r_min) * r_min),
                              static_cast<float>(reach * reach * (1.0 - 1e-5)));
  return within(i, limit, subset, inner) < static_cast<std::size_t>(count);
}

bool CellGridSearch::radius(pcl::index_t i, double radius, std::vector<Neighbour>& found) {
  if (!gather(i, radius)) return false;
  const auto limit = static_cast<float>(radius * radius);  // d^2 < float(r^2), as KdTreeFLANN
  if (limit <= near_bound_) {
    // Every candidate with d^2 < limit is in near_, in the candidates' order.
    const float* d2s = candidates_.d2.data();
    const std::uint32_t* slots = candidates_.slot.data();
    if (kept_.size() < near_count_) kept_.resize(near_count_);
    std::size_t m = 0;
    for (std::size_t j = 0; j < near_count_; ++j) {
      kept_[m] = near_[j];
      m += d2s[near_[j]] < limit;
    }
    found.resize(m);
    const pcl::PointXYZ& p = cloud_[i];
    for (std::size_t k = 0; k < m; ++k) {
      found[k] = grid_.neighbour(slots[kept_[k]], p, d2s[kept_[k]]);
    }
    return true;
  }
  within(i, limit, found);
  return true;
}

std::size_t CellGridSearch::within(pcl::index_t i, float limit, std::vector<Neighbour>& out,
                                   float count_below) {
  // Branch-free: the slots of those within first, then their offsets.
  const std::size_t n = candidates_.size;
  if (kept_.size() < n) kept_.resize(n);
  const float* d2s = candidates_.d2.data();
  const std::uint32_t* slots = candidates_.slot.data();
  std::size_t m = 0, below = 0;
  for (std::size_t k = 0; k < n; ++k) {
    kept_[m] = static_cast<std::uint32_t>(k);
    m += d2s[k] < limit;
    below += d2s[k] < count_below;
  }
  out.resize(m);
  const pcl::PointXYZ& p = cloud_[i];
  for (std::size_t k = 0; k < m; ++k) out[k] = grid_.neighbour(slots[kept_[k]], p, d2s[kept_[k]]);
  return below;
}

}  // namespace mcws
