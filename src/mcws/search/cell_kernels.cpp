#include "mcws/search/cell_kernels.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define MCWS_CELL_KERNELS_AVX2 1
#endif

#include <algorithm>
#include <limits>

namespace mcws::detail {
namespace {

std::size_t rowDistancesPlain(const float* xs, const float* ys, const float* zs,
                              const RowSpan* rows, std::size_t row_count, float px, float py,
                              float pz, float bound, float* d2, std::uint32_t* slot, float* near_d2,
                              std::uint32_t* near_slot) {
  std::size_t m = 0, base = 0;
  for (std::size_t r = 0; r < row_count; ++r) {
    for (std::uint32_t k = rows[r].begin; k < rows[r].end; ++k, ++base) {
      const float dx = xs[k] - px, dy = ys[k] - py, dz = zs[k] - pz;
      float d = dx * dx;
      d += dy * dy;
      d += dz * dz;
      d2[base] = d;
      slot[base] = k;
      near_d2[m] = d;
      near_slot[m] = k;
      m += d < bound;
    }
  }
  return m;
}

std::size_t valuesBelowPlain(const float* v, std::size_t n, float bound, float* out) {
  std::size_t m = 0;
  for (std::size_t k = 0; k < n; ++k) {
    out[m] = v[k];
    m += v[k] < bound;
  }
  return m;
}

/// For each N-bit mask, the lanes of its set bits in order (then zeros), and their count: what a
/// vector compare's mask keeps, to pack those lanes in front.
template <unsigned N>
struct LaneTable {
  alignas(4 * N) std::uint32_t lanes[1u << N][N];
  std::uint8_t count[1u << N];
  LaneTable() : lanes{}, count{} {
    for (unsigned mask = 0; mask < (1u << N); ++mask) {
      for (unsigned lane = 0; lane < N; ++lane) {
        if (mask >> lane & 1u) lanes[mask][count[mask]++] = lane;
      }
    }
  }
};

/// The places of the values below `bound`: with SSE2 four at a time.
std::size_t placesBelowPlain(const float* v, std::size_t n, float bound, std::uint32_t* out) {
  std::size_t kept = 0, k = 0;
#if defined(__SSE2__)
  // Four at a time: the lanes below the bound as a 4-bit mask, their places from a table of the
  // 16 masks, stored whole and advanced by the mask's count (no byte shuffle needed).
  static const LaneTable<4> table;
  const __m128 limit = _mm_set1_ps(bound);
  for (; k + 4 <= n; k += 4) {
    const int mask = _mm_movemask_ps(_mm_cmplt_ps(_mm_loadu_ps(v + k), limit));
    const __m128i places =
        _mm_add_epi32(_mm_set1_epi32(static_cast<int>(k)),
                      _mm_load_si128(reinterpret_cast<const __m128i*>(table.lanes[mask])));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + kept), places);
    kept += table.count[mask];
  }
#endif
  for (; k < n; ++k) {
    out[kept] = static_cast<std::uint32_t>(k);
    kept += v[k] < bound;
  }
  return kept;
}

float kthSmallestPlain(float* v, std::size_t m, int count) {
  std::nth_element(v, v + (count - 1), v + m);
  return v[count - 1];
}

#if MCWS_CELL_KERNELS_AVX2
const LaneTable<8> kLanes;

/// The AVX2 registers of rowDistancesAvx2(): the query, the bound, and the slots of the next
/// group (advanced by 8 a group, set anew at each row's start).
struct RowQuery {
  __m256 qx, qy, qz, limit;
  __m256i slots;
};

/// One group of 8 points of rowDistancesAvx2(), from point k of the arrays on (q.slots holds k,
/// k + 1, ..., k + 7, and is advanced by 8), into d2 and slot (lanes outside `valid` are never
/// near); returns how many are near (a population count: AVX2 processors have POPCNT).
__attribute__((target("avx2,popcnt"), always_inline)) inline std::size_t rowGroupAvx2(
    const float* xs, const float* ys, const float* zs, std::uint32_t k, unsigned valid, RowQuery& q,
    float* d2, std::uint32_t* slot, float* near_d2, std::uint32_t* near_slot) {
  const __m256 dx = _mm256_sub_ps(_mm256_loadu_ps(xs + k), q.qx);
  const __m256 dy = _mm256_sub_ps(_mm256_loadu_ps(ys + k), q.qy);
  const __m256 dz = _mm256_sub_ps(_mm256_loadu_ps(zs + k), q.qz);
  const __m256 d = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)),
                                 _mm256_mul_ps(dz, dz));
  const __m256i slots = q.slots;
  q.slots = _mm256_add_epi32(slots, _mm256_set1_epi32(8));
  _mm256_storeu_ps(d2, d);
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(slot), slots);
  const unsigned mask =
      static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(d, q.limit, _CMP_LT_OQ))) & valid;
  const __m256i lanes = _mm256_load_si256(reinterpret_cast<const __m256i*>(kLanes.lanes[mask]));
  _mm256_storeu_ps(near_d2, _mm256_permutevar8x32_ps(d, lanes));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(near_slot),
                      _mm256_permutevar8x32_epi32(slots, lanes));
  return static_cast<std::size_t>(__builtin_popcount(mask));
}

/// rowDistancesPlain() 8 at a time (AVX2, no FMA: the same roundings), the near ones left-packed
/// by a permutation from kLanes. A row's last group may read up to 7 points past it (and write
/// as many entries past the row's), which the next row's overwrite.
__attribute__((target("avx2,popcnt"))) std::size_t rowDistancesAvx2(
    const float* xs, const float* ys, const float* zs, const RowSpan* rows, std::size_t row_count,
    float px, float py, float pz, float bound, float* d2, std::uint32_t* slot, float* near_d2,
    std::uint32_t* near_slot) {
  const __m256i iota = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  RowQuery q{_mm256_set1_ps(px), _mm256_set1_ps(py), _mm256_set1_ps(pz), _mm256_set1_ps(bound),
             iota};
  std::size_t m = 0, base = 0;
  for (std::size_t r = 0; r < row_count; ++r) {
    const std::uint32_t end = rows[r].end;
    std::uint32_t k = rows[r].begin;
    q.slots = _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(k)), iota);
    for (; k + 8 <= end; k += 8, base += 8) {
      m +=
          rowGroupAvx2(xs, ys, zs, k, 0xFFu, q, d2 + base, slot + base, near_d2 + m, near_slot + m);
    }
    if (k < end) {
      m += rowGroupAvx2(xs, ys, zs, k, (1u << (end - k)) - 1u, q, d2 + base, slot + base,
                        near_d2 + m, near_slot + m);
      base += end - k;
    }
  }
  return m;
}

/// Which of the (up to) 8 values at v[k] (of n) lie below `limit`, as a bit mask.
__attribute__((target("avx2"))) inline unsigned maskBelow(__m256 x, std::size_t n, std::size_t k,
                                                          __m256 limit) {
  const unsigned valid = n - k >= 8 ? 0xFFu : (1u << (n - k)) - 1u;
  return static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(x, limit, _CMP_LT_OQ))) & valid;
}

/// The lanes of v[0, n) below `bound` packed in front of `out`, 8 at a time: `store(out + m, x,
/// lanes, k)` writes the 8 values of v[k, k + 8) in `x` (or their places) in the order `lanes`
/// gives, the lanes below the bound first; returns how many were kept.
template <typename T, typename Store>
__attribute__((target("avx2"))) inline std::size_t packBelowAvx2(const float* v, std::size_t n,
                                                                 float bound, T* out, Store store) {
  const __m256 limit = _mm256_set1_ps(bound);
  std::size_t m = 0;
  for (std::size_t k = 0; k < n; k += 8) {
    const __m256 x = _mm256_loadu_ps(v + k);
    const unsigned mask = maskBelow(x, n, k, limit);
    const __m256i lanes = _mm256_load_si256(reinterpret_cast<const __m256i*>(kLanes.lanes[mask]));
    store(out + m, x, lanes, k);
    m += kLanes.count[mask];
  }
  return m;
}

/// valuesBelowPlain() 8 at a time.
__attribute__((target("avx2"))) std::size_t valuesBelowAvx2(const float* v, std::size_t n,
                                                            float bound, float* out) {
  return packBelowAvx2(
      v, n, bound, out,
      [](float* at, __m256 x, __m256i lanes, std::size_t) __attribute__((target("avx2"))) {
        _mm256_storeu_ps(at, _mm256_permutevar8x32_ps(x, lanes));
      });
}

/// placesBelowPlain() 8 at a time.
__attribute__((target("avx2"))) std::size_t placesBelowAvx2(const float* v, std::size_t n,
                                                            float bound, std::uint32_t* out) {
  return packBelowAvx2(
      v, n, bound, out,
      [](std::uint32_t * at, __m256, __m256i lanes, std::size_t k) __attribute__((target("avx2"))) {
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(at),
                            _mm256_add_epi32(lanes, _mm256_set1_epi32(static_cast<int>(k))));
      });
}

/// The longest list kthSmallestAvx2() ranks; longer ones go to std::nth_element.
constexpr std::size_t kRankedAtMost = 48;

/// kthSmallestPlain() by ranks, without a data-dependent branch but the last: for 8 values a_j
/// at a time, lt_j = #{i : v_i < a_j} and le_j = #{i : v_i <= a_j}; the answer is the a_j with
/// lt_j < count <= le_j (equal values share it). The list is padded with +infinity, which no
/// value of it exceeds (the values are below a finite bound) and which is never the answer.
__attribute__((target("avx2"))) float kthSmallestAvx2(float* v, std::size_t m, int count) {
  if (m > kRankedAtMost) return kthSmallestPlain(v, m, count);
  for (std::size_t k = m; k < m + 8; ++k) v[k] = std::numeric_limits<float>::infinity();
  const __m256i wanted = _mm256_set1_epi32(count);
  for (std::size_t j = 0; j < m; j += 8) {
    const __m256 a = _mm256_loadu_ps(v + j);
    __m256i lt = _mm256_setzero_si256(), le = _mm256_setzero_si256();
    for (std::size_t i = 0; i < m; ++i) {
      const __m256 x = _mm256_broadcast_ss(v + i);
      lt = _mm256_sub_epi32(lt, _mm256_castps_si256(_mm256_cmp_ps(x, a, _CMP_LT_OQ)));
      le = _mm256_sub_epi32(le, _mm256_castps_si256(_mm256_cmp_ps(x, a, _CMP_LE_OQ)));
    }
    // lt < count and count <= le, i.e. count > lt and le + 1 > count.
    const __m256i hit =
        _mm256_and_si256(_mm256_cmpgt_epi32(wanted, lt),
                         _mm256_cmpgt_epi32(_mm256_add_epi32(le, _mm256_set1_epi32(1)), wanted));
    const int mask = _mm256_movemask_ps(_mm256_castsi256_ps(hit));
    if (mask != 0) return v[j + static_cast<std::size_t>(__builtin_ctz(mask))];
  }
  return kthSmallestPlain(v, m, count);  // not reached: some value has the rank
}
#endif

/// The kernels for this processor.
struct Kernels {
  decltype(&rowDistancesPlain) row_distances = rowDistancesPlain;
  decltype(&valuesBelowPlain) values_below = valuesBelowPlain;
  decltype(&placesBelowPlain) places_below = placesBelowPlain;
  decltype(&kthSmallestPlain) kth_smallest = kthSmallestPlain;
  Kernels() {
#if MCWS_CELL_KERNELS_AVX2
    __builtin_cpu_init();  // this may run before the runtime's own initialisation
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("popcnt")) {
      row_distances = rowDistancesAvx2;
      values_below = valuesBelowAvx2;
      places_below = placesBelowAvx2;
      kth_smallest = kthSmallestAvx2;
    }
#endif
  }
};

const Kernels kKernels;

}  // namespace

std::size_t rowDistances(const float* xs, const float* ys, const float* zs, const RowSpan* rows,
                         std::size_t row_count, float px, float py, float pz, float bound,
                         float* d2, std::uint32_t* slot, float* near_d2, std::uint32_t* near_slot) {
  return kKernels.row_distances(xs, ys, zs, rows, row_count, px, py, pz, bound, d2, slot, near_d2,
                                near_slot);
}

std::size_t placesBelow(const float* v, std::size_t n, float bound, std::uint32_t* out) {
  return kKernels.places_below(v, n, bound, out);
}

std::size_t valuesBelow(const float* v, std::size_t n, float bound, float* out) {
  return kKernels.values_below(v, n, bound, out);
}

float kthSmallest(float* v, std::size_t m, int count) { return kKernels.kth_smallest(v, m, count); }

namespace plain {
std::size_t rowDistances(const float* xs, const float* ys, const float* zs, const RowSpan* rows,
                         std::size_t row_count, float px, float py, float pz, float bound,
                         float* d2, std::uint32_t* slot, float* near_d2, std::uint32_t* near_slot) {
  return rowDistancesPlain(xs, ys, zs, rows, row_count, px, py, pz, bound, d2, slot, near_d2,
                           near_slot);
}
std::size_t valuesBelow(const float* v, std::size_t n, float bound, float* out) {
  return valuesBelowPlain(v, n, bound, out);
}
std::size_t placesBelow(const float* v, std::size_t n, float bound, std::uint32_t* out) {
  return placesBelowPlain(v, n, bound, out);
}
float kthSmallest(float* v, std::size_t m, int count) { return kthSmallestPlain(v, m, count); }
}  // namespace plain

}  // namespace mcws::detail
