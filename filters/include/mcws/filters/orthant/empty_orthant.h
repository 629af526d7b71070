#pragma once
/// \file
/// \brief Does some quadrant (2-D) or octant (3-D) around p hold none of p's neighbours, in the
/// axis frame or in the outward frame? The test of Yin, Wang & Yu 2010, section 4.3.

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define MCWS_ORTHANT_AVX2 1
#endif

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "mcws/filters/orthant/frames.h"
#include "mcws/search/neighbour_search.h"

namespace mcws::orthant {

/// \brief Quadrant of (x, y) with half-open angular sectors [0, 90), [90, 180), [180, 270),
/// [270, 360) degrees: a neighbour lying exactly on an axis falls on one side, cyclically, so that
/// the rim of a grid keeps an empty quadrant on every side.
inline unsigned quadrant(float x, float y) {
  if (x > 0 && y >= 0) return 0;
  if (x <= 0 && y > 0) return 1;
  if (x < 0 && y <= 0) return 2;
  return 3;
}

/// \brief Octant: the quadrant of (x, y) and the side of z; z == 0 goes up for even quadrants and
/// down for odd ones, so that in-plane neighbours leave two octants empty on either side of a
/// face.
inline unsigned octant(float x, float y, float z) {
  const unsigned q = quadrant(x, y);
  const bool up = z > 0 || (z == 0 && q % 2 == 0);
  return q + (up ? 4u : 0u);
}

/// \brief Sign code of a direction: bits x > 0, x < 0, y > 0, y < 0, z > 0, z < 0 (0 for the
/// origin).
inline unsigned signCode(float x, float y, float z) {
  return unsigned{x > 0} | unsigned{x < 0} << 1 | unsigned{y > 0} << 2 | unsigned{y < 0} << 3 |
         unsigned{z > 0} << 4 | unsigned{z < 0} << 5;
}

/// \brief For every sign code, the bit of the orthant holding such directions, 1 << quadrant(x, y)
/// (2-D, z ignored) or 1 << octant(x, y, z) (3-D), and 0 for the origin: p itself or a copy falls
/// in no orthant. A table look-up instead of the branches of quadrant() and octant(), whose
/// outcome is random from one neighbour to the next.
inline const std::uint8_t* orthantBits(int dimensions) {
  struct Table {
    std::uint8_t bit[2][64];  // [dimensions - 2][sign code]
    Table() : bit{} {
      for (unsigned code = 0; code < 64; ++code) {
        auto sign = [code](unsigned shift) {
          return static_cast<float>(static_cast<int>((code >> shift) & 1u) -
                                    static_cast<int>((code >> (shift + 1)) & 1u));
        };
        const float x = sign(0), y = sign(2), z = sign(4);
        if (x != 0 || y != 0) bit[0][code] = static_cast<std::uint8_t>(1u << quadrant(x, y));
        if (x != 0 || y != 0 || z != 0)
          bit[1][code] = static_cast<std::uint8_t>(1u << octant(x, y, z));
      }
    }
  };
  static const Table table;
  return table.bit[dimensions - 2];
}

#if defined(__SSE2__)
/// \brief orthantBits() indexed by sign masks instead of sign codes: bits 0-2 say x, y, z > 0,
/// bits 3-5 x, y, z < 0 (signMasks()), which two SSE comparisons give at once.
inline const std::uint8_t* orthantBitsByMasks(int dimensions) {
  struct Table {
    std::uint8_t bit[2][64];
    Table() : bit{} {
      for (unsigned masks = 0; masks < 64; ++masks) {
        unsigned code = 0;
        for (unsigned axis = 0; axis < 3; ++axis) {
          code |= (masks >> axis & 1u) << (2 * axis) | (masks >> (axis + 3) & 1u) << (2 * axis + 1);
        }
        bit[0][masks] = orthantBits(2)[code];
        bit[1][masks] = orthantBits(3)[code];
      }
    }
  };
  static const Table table;
  return table.bit[dimensions - 2];
}

/// \brief orthantBitsByMasks() indexed by laneMasks(): bits 0-3 say lanes 0-3 > 0, bits 4-7
/// lanes 0-3 < 0; the fourth lane's bits are ignored.
inline const std::uint8_t* orthantBitsByLaneMasks(int dimensions) {
  struct Table {
    std::uint8_t bit[2][256];
    Table() : bit{} {
      for (int d = 0; d < 2; ++d) {
        for (unsigned lanes = 0; lanes < 256; ++lanes) {
          bit[d][lanes] = orthantBitsByMasks(d + 2)[(lanes & 7u) | ((lanes >> 4) & 7u) << 3];
        }
      }
    }
  };
  static const Table table;
  return table.bit[dimensions - 2];
}

/// \brief The masks of the four lanes of `v` > 0 (bits 0-3) and < 0 (bits 4-7).
inline unsigned laneMasks(__m128 v) {
  const __m128 zero = _mm_setzero_ps();
  return static_cast<unsigned>(_mm_movemask_ps(_mm_cmpgt_ps(v, zero))) |
         static_cast<unsigned>(_mm_movemask_ps(_mm_cmplt_ps(v, zero))) << 4;
}

/// \brief The sign masks of lanes x, y, z of `v` (the fourth is ignored): bits 0-2 > 0, bits 3-5
/// < 0, as signCode() tells them apart (0 and -0 neither).
inline unsigned signMasks(__m128 v) {
  const __m128 zero = _mm_setzero_ps();
  return (static_cast<unsigned>(_mm_movemask_ps(_mm_cmpgt_ps(v, zero))) & 7u) |
         (static_cast<unsigned>(_mm_movemask_ps(_mm_cmplt_ps(v, zero))) & 7u) << 3;
}
#endif

#if defined(__SSE2__)
/// \brief A 3 x 3 float matrix E by columns, for E * v four lanes at a time with the very
/// rounding of Eigen's E * Eigen::Vector3f (for row i, E(i,0) x + (E(i,1) y + E(i,2) z): its
/// unrolled sum of three products, no fused multiply-add).
struct FrameColumns {
  explicit FrameColumns(const Eigen::Matrix3f& E)
      : c0(_mm_setr_ps(E(0, 0), E(1, 0), E(2, 0), 0.0f)),
        c1(_mm_setr_ps(E(0, 1), E(1, 1), E(2, 1), 0.0f)),
        c2(_mm_setr_ps(E(0, 2), E(1, 2), E(2, 2), 0.0f)) {}
  /// \brief E * (x, y, z) of v = (x, y, z, anything) in lanes 0-2 (lane 3: 0 for finite v).
  __m128 times(__m128 v) const {
    const __m128 x = _mm_shuffle_ps(v, v, 0x00), y = _mm_shuffle_ps(v, v, 0x55);
    const __m128 z = _mm_shuffle_ps(v, v, 0xAA);
    return _mm_add_ps(_mm_mul_ps(c0, x), _mm_add_ps(_mm_mul_ps(c1, y), _mm_mul_ps(c2, z)));
  }
  __m128 c0, c1, c2;
};
#endif

#if MCWS_ORTHANT_AVX2
/// \brief What hasEmptyOrthant()'s first pass finds: the axis frame's orthants (bits), the sums
/// of the offsets (in double, added in the neighbours' order) and the largest d^2.
struct AxisPass {
  unsigned mask;
  double sx, sy, sz;
  float size2;
};

/// \brief The orthants of eight offsets, transposed (x, y, z of the eight in v[0], v[1], v[2]),
/// as lane masks OR-ed into acc[orthant]: quadrant() and octant() (the origin in none).
__attribute__((target("avx2"), always_inline)) inline void orthantLanes(const __m256 (&v)[3],
                                                                        int dimensions,
                                                                        __m256 (&acc)[8]) {
  const __m256 zero = _mm256_setzero_ps();
  const __m256 gx = _mm256_cmp_ps(v[0], zero, _CMP_GT_OQ),
               lx = _mm256_cmp_ps(v[0], zero, _CMP_LT_OQ);
  const __m256 gy = _mm256_cmp_ps(v[1], zero, _CMP_GT_OQ),
               ly = _mm256_cmp_ps(v[1], zero, _CMP_LT_OQ);
  // quadrant(): [0, 90), [90, 180), [180, 270), the rest.
  const __m256 q0 = _mm256_andnot_ps(ly, gx), q1 = _mm256_andnot_ps(gx, gy);
  const __m256 q2 = _mm256_andnot_ps(gy, lx);
  const __m256 in_plane = _mm256_or_ps(_mm256_or_ps(gx, lx), _mm256_or_ps(gy, ly));
  const __m256 first3 = _mm256_or_ps(_mm256_or_ps(q0, q1), q2);
  if (dimensions == 2) {
    acc[0] = _mm256_or_ps(acc[0], q0);
    acc[1] = _mm256_or_ps(acc[1], q1);
    acc[2] = _mm256_or_ps(acc[2], q2);
    acc[3] = _mm256_or_ps(acc[3], _mm256_andnot_ps(first3, in_plane));
    return;
  }
  const __m256 gz = _mm256_cmp_ps(v[2], zero, _CMP_GT_OQ),
               lz = _mm256_cmp_ps(v[2], zero, _CMP_LT_OQ);
  const __m256 gzlz = _mm256_or_ps(gz, lz);
  const __m256 q3 = _mm256_andnot_ps(first3, _mm256_or_ps(in_plane, gzlz));
  // octant(): up when z > 0, or z == 0 in an even quadrant.
  const __m256 up = _mm256_or_ps(gz, _mm256_andnot_ps(gzlz, _mm256_or_ps(q0, q2)));
  acc[0] = _mm256_or_ps(acc[0], _mm256_andnot_ps(up, q0));
  acc[1] = _mm256_or_ps(acc[1], _mm256_andnot_ps(up, q1));
  acc[2] = _mm256_or_ps(acc[2], _mm256_andnot_ps(up, q2));
  acc[3] = _mm256_or_ps(acc[3], _mm256_andnot_ps(up, q3));
  acc[4] = _mm256_or_ps(acc[4], _mm256_and_ps(up, q0));
  acc[5] = _mm256_or_ps(acc[5], _mm256_and_ps(up, q1));
  acc[6] = _mm256_or_ps(acc[6], _mm256_and_ps(up, q2));
  acc[7] = _mm256_or_ps(acc[7], _mm256_and_ps(up, q3));
}

/// \brief Eight neighbours (x, y, z, d2 each, in a[0..7]) into axisPassAvx2()'s registers: each
/// one's x, y, z, d2 added to the four-lane double sums, in order; then, transposed to x, y, z
/// and d2 of the eight, the largest d2 and the orthants (orthantLanes()).
__attribute__((target("avx2"), always_inline)) inline void axisGroup(const __m128 (&a)[8],
                                                                     int dimensions, __m256d& sums,
                                                                     __m256& largest,
                                                                     __m256 (&acc)[8]) {
  for (int j = 0; j < 8; ++j) sums = _mm256_add_pd(sums, _mm256_cvtps_pd(a[j]));
  // Rows j and j + 4 side by side, then the 4 x 4 transposition within each half.
  const __m256 r0 = _mm256_set_m128(a[4], a[0]), r1 = _mm256_set_m128(a[5], a[1]);
  const __m256 r2 = _mm256_set_m128(a[6], a[2]), r3 = _mm256_set_m128(a[7], a[3]);
  const __m256 t0 = _mm256_unpacklo_ps(r0, r1), t1 = _mm256_unpackhi_ps(r0, r1);
  const __m256 t2 = _mm256_unpacklo_ps(r2, r3), t3 = _mm256_unpackhi_ps(r2, r3);
  const __m256 v[3] = {_mm256_shuffle_ps(t0, t2, 0x44), _mm256_shuffle_ps(t0, t2, 0xEE),
                       _mm256_shuffle_ps(t1, t3, 0x44)};
  largest = _mm256_max_ps(largest, _mm256_shuffle_ps(t1, t3, 0xEE));
  orthantLanes(v, dimensions, acc);
}

/// \brief The first pass with AVX2: each neighbour's x, y, z, d2 summed in one four-lane double
/// register (each lane the same additions in the same order as one by one), and the orthants of
/// eight neighbours at a time (axisGroup(); a last group padded with the origin, in no orthant,
/// whose zeros leave the sums as they were: they start at +0, so no sum is ever -0).
__attribute__((target("avx2"))) inline AxisPass axisPassAvx2(
    const std::vector<Neighbour>& neighbours, int dimensions) {
  const __m256 zero = _mm256_setzero_ps();
  __m256d sums = _mm256_setzero_pd();
  __m256 largest = zero;
  __m256 acc[8] = {zero, zero, zero, zero, zero, zero, zero, zero};
  const std::size_t n = neighbours.size();
  const Neighbour* q = neighbours.data();
  std::size_t k = 0;
  for (; k + 8 <= n; k += 8) {
    __m128 a[8];
    for (int j = 0; j < 8; ++j) a[j] = _mm_loadu_ps(&q[k + j].x);  // x, y, z, d2
    axisGroup(a, dimensions, sums, largest, acc);
  }
  if (k < n) {
    // Padded with zeros: adding +0 to a sum that starts at +0 leaves it as it was.
    __m128 a[8];
    for (std::size_t j = 0; j < 8; ++j)
      a[j] = k + j < n ? _mm_loadu_ps(&q[k + j].x) : _mm_setzero_ps();
    axisGroup(a, dimensions, sums, largest, acc);
  }
  AxisPass out{0u, 0.0, 0.0, 0.0, 0.0f};
  for (unsigned o = 0; o < 8; ++o) out.mask |= unsigned{_mm256_movemask_ps(acc[o]) != 0} << o;
  alignas(32) double s[4];
  _mm256_store_pd(s, sums);
  out.sx = s[0];
  out.sy = s[1];
  out.sz = s[2];
  __m128 most = _mm_max_ps(_mm256_castps256_ps128(largest), _mm256_extractf128_ps(largest, 1));
  most = _mm_max_ps(most, _mm_movehl_ps(most, most));
  most = _mm_max_ps(most, _mm_shuffle_ps(most, most, 0x55));
  out.size2 = _mm_cvtss_f32(most);
  return out;
}

/// \brief Whether this processor runs axisPassAvx2().
inline bool axisPassHasAvx2() {
  static const bool avx2 = __builtin_cpu_supports("avx2");
  return avx2;
}
#endif

/// \brief The rows of the outward frame for the unit outward direction n: in 2-D, n bisects the
/// first quadrant; in 3-D, e_k = n / sqrt(3) + sqrt(2/3) (cos t_k a + sin t_k b), t_k = 0, 120,
/// 240 degrees, an orthonormal frame whose first octant has n as its diagonal.
inline Eigen::Matrix3f outwardFrame(const Eigen::Vector3f& n, int dimensions) {
  Eigen::Matrix3f E = Eigen::Matrix3f::Identity();
  if (dimensions == 2) {
    const Eigen::Vector3f a(-n.y(), n.x(), 0.0f);
    E.row(0) = (n + a) / std::sqrt(2.0f);
    E.row(1) = (n - a) / std::sqrt(2.0f);
  } else {
    const Eigen::Vector3f a = n.unitOrthogonal();
    const Eigen::Vector3f b = n.cross(a);
    const float s = std::sqrt(2.0f / 3.0f), c = 1.0f / std::sqrt(3.0f);
    E.row(0) = c * n + s * a;
    E.row(1) = c * n + s * (-0.5f * a + 0.8660254f * b);
    E.row(2) = c * n + s * (-0.5f * a - 0.8660254f * b);
  }
  return E;
}

/// \brief True when some orthant around p holds none of `neighbours` (offsets from p in the
/// cloud's axes, z = 0 in 2-D) in the axis frame or the outward frame, whichever `frames` holds
/// (any rotation is the sector test's, empty_sector.h).
///
/// The outward direction is -(c - p), c the neighbours' centroid. Edge cases: with no neighbour
/// apart from p (copies have no orthant), every orthant is empty: true. A neighbourhood whose
/// centroid lies within 1e-6 of its size from p has no outward direction and is interior in the
/// outward frame.
inline bool hasEmptyOrthant(const std::vector<Neighbour>& neighbours, int dimensions,
                            OrthantFrames frames) {
  const unsigned full = dimensions == 2 ? 0xFu : 0xFFu;
  // One pass for the axis frame's orthants and what the outward frame needs: the centroid's offset
  // from p, summed as offsets so that far from the origin no precision is lost, and in double so
  // that the order of the neighbours (tree or grid) does not matter; and the neighbourhood's size,
  // against which "symmetric" is judged.
  unsigned axis_mask = 0;
  double sx = 0.0, sy = 0.0, sz = 0.0;
  float size2 = 0.0f;
#if defined(__SSE2__)
  const std::uint8_t* by_masks = orthantBitsByMasks(dimensions);
#endif
#if MCWS_ORTHANT_AVX2
  if (axisPassHasAvx2()) {
    const AxisPass pass = axisPassAvx2(neighbours, dimensions);
    axis_mask = pass.mask, sx = pass.sx, sy = pass.sy, sz = pass.sz, size2 = pass.size2;
  } else
#endif
  {
#if defined(__SSE2__)
    // The same sums and bits, x and y summed side by side in one register (each lane the same
    // double additions in the same order), the signs of x, y, z compared at once.
    // z summed beside d2 (unused) likewise, and the largest d2 kept in the fourth lane.
    const std::uint8_t* by_lanes = orthantBitsByLaneMasks(dimensions);
    __m128d sxy = _mm_setzero_pd(), szd = _mm_setzero_pd();
    __m128 largest = _mm_setzero_ps();
    for (const auto& q : neighbours) {
      const __m128 v = _mm_loadu_ps(&q.x);  // x, y, z, d2
      axis_mask |= by_lanes[laneMasks(v)];
      sxy = _mm_add_pd(sxy, _mm_cvtps_pd(v));
      szd = _mm_add_pd(szd, _mm_cvtps_pd(_mm_movehl_ps(v, v)));
      largest = _mm_max_ps(largest, v);
    }
    sx = _mm_cvtsd_f64(sxy);
    sy = _mm_cvtsd_f64(_mm_unpackhi_pd(sxy, sxy));
    sz = _mm_cvtsd_f64(szd);
    size2 = _mm_cvtss_f32(_mm_shuffle_ps(largest, largest, 0xFF));
#else
    const std::uint8_t* bits = orthantBits(dimensions);
    for (const auto& q : neighbours) {
      axis_mask |= bits[signCode(q.x, q.y, q.z)];
      sx += q.x;
      sy += q.y;
      sz += q.z;
      size2 = std::max(size2, q.d2);
    }
#endif
  }
  if (axis_mask == 0) return true;
  if (frames.has(OrthantFrame::kAxis) && axis_mask != full) return true;
  if (!frames.has(OrthantFrame::kOutward)) return false;
  const double count = static_cast<double>(neighbours.size());
  Eigen::Vector3f n(static_cast<float>(-sx / count), static_cast<float>(-sy / count),
                    static_cast<float>(-sz / count));
  if (dimensions == 2) n.z() = 0;
  const float length = n.norm();
  if (!(length > 1e-6f * std::sqrt(size2))) return false;
  n /= length;
  const Eigen::Matrix3f E = outwardFrame(n, dimensions);
  // The neighbours come in the search's cell order, a sweep through the neighbourhood: visited
  // `stride` apart, the first few spread over every side of p, so that an interior point fills
  // the orthants (and stops) after a few dozen of them. The mask does not depend on the order.
  const std::size_t size = neighbours.size();
  const std::size_t stride = 1 + size / 16;
#if defined(__SSE2__)
  const FrameColumns columns(E);
#endif
  unsigned outward_mask = 0;
  for (std::size_t first = 0; first < stride; ++first) {
    for (std::size_t k = first; k < size; k += stride) {
      const Neighbour& q = neighbours[k];
#if defined(__SSE2__)
      outward_mask |= by_masks[signMasks(columns.times(_mm_loadu_ps(&q.x)))];
#else
      const Eigen::Vector3f w = E * Eigen::Vector3f(q.x, q.y, q.z);
      outward_mask |= bits[signCode(w.x(), w.y(), w.z())];
#endif
      if (outward_mask == full) return false;
    }
  }
  return true;
}

}  // namespace mcws::orthant
