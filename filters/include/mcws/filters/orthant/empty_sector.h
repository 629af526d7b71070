#pragma once
/// \file
/// \brief Do the directions from p to its neighbours (in a plane) leave an empty sector of a
/// given angle? The 2-D orthant test in every rotation of the frame: at 90 degrees, some rotation
/// of the quadrants has an empty quadrant.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "mcws/search/neighbour_search.h"

namespace mcws::orthant {

/// \brief A direction from p to a neighbour, in the x-y plane.
struct Direction {
  float x, y;
};

/// \brief Cross and dot products in double: exact for float inputs up to the final rounding,
/// which keeps their signs, so directions are ordered and compared without rounding errors.
inline double cross(const Direction& a, const Direction& b) {
  return static_cast<double>(a.x) * b.y - static_cast<double>(a.y) * b.x;
}
inline double dot(const Direction& a, const Direction& b) {
  return static_cast<double>(a.x) * b.x + static_cast<double>(a.y) * b.y;
}
/// \brief Polar angle in [0, pi) rather than [pi, 2 pi).
inline bool upperHalf(const Direction& d) { return d.y > 0 || (d.y == 0 && d.x > 0); }

/// \brief Angular bins of the quick test: 8 per octant, so the bin of a direction follows from
/// its octant and 7 comparisons of min(|x|, |y|) / max(|x|, |y|) with tan(k pi / 32), without
/// atan2.
constexpr int kAngleBins = 64;
/// \brief Bound on how far a direction's bin may lie from its true angle [rad] (the rounding of
/// one division and of the tangents, about 1e-7, with a wide margin).
constexpr double kAngleError = 1e-4;

/// \brief The bin of direction (x, y) (not both 0): floor(atan2(y, x) / (2 pi / 64)) mod 64, up
/// to kAngleError.
inline unsigned angleBin(float x, float y) {
  static constexpr float kTan[7] = {0.09849140f, 0.19891237f, 0.30334668f, 0.41421356f,
                                    0.53451114f, 0.66817864f, 0.82067879f};
  const float ax = std::fabs(x), ay = std::fabs(y);
  const float t = std::min(ax, ay) / std::max(ax, ay);  // tan of the angle within the octant
  unsigned fine = 0;
  for (const float b : kTan) fine += t > b;
  // Quadrant 0..3 counter-clockwise; its first octant is the one next to its starting axis.
  const unsigned quadrant = 2u * (y < 0) + ((x < 0) != (y < 0));
  const bool first = quadrant % 2 == 0 ? ay <= ax : ay > ax;
  return 16u * quadrant + (first ? fine : 15u - fine);
}

/// \brief The empty sector looked for: its cosine, and the longest run of empty angular bins (of
/// kAngleBins) that cannot hold it. Two neighbours on either side of a run of E empty bins are
/// less than (E + 2) w + 2 kAngleError apart, w the bin width, so a point whose longest empty run
/// is at most `empty_run_limit` has no such sector.
struct SectorGap {
  double cos_gap;
  int empty_run_limit;
};
/// \brief The SectorGap of an angle `gap` [rad] in [pi/2, pi).
inline SectorGap sectorGap(double gap) {
  const double w = 2 * M_PI / kAngleBins;
  return {std::cos(gap), static_cast<int>(std::ceil((gap - 2 * kAngleError) / w)) - 3};
}

/// \brief True when the 64-bit mask of occupied bins (circular, not 0) has a run of more than
/// `limit` empty bins.
inline bool hasLongEmptyRun(std::uint64_t occupied, int limit) {
  // Rotated so that bit 0 is occupied, no run of empty bins wraps around.
  const int s = __builtin_ctzll(occupied);
  std::uint64_t empty = ~((occupied >> s) | (s ? occupied << (64 - s) : 0));
  for (int k = 0; k < limit && empty; ++k) empty &= empty >> 1;
  return empty != 0;
}

/// \brief True when the directions from p to `neighbours` (offsets from p, x-y plane) leave an
/// empty sector of at least the gap's angle.
///
/// Directions are sorted by angle exactly (half-plane, then the sign of the cross product);
/// consecutive directions u, v are less than the gap apart exactly when cross(u, v) > 0 and
/// dot(u, v) > |u| |v| cos(gap). Edge cases: no direction at all (p alone, or only copies of p)
/// or a single direction leaves every other direction empty: true. `directions` is scratch space.
inline bool hasEmptySector(const std::vector<Neighbour>& neighbours, const SectorGap& gap,
                           std::vector<Direction>& directions) {
  // Most interior points are decided by angular bins; the rest by the exact test below.
  // Neighbours come cell by cell, so nearby entries point the same way: taking every 4th first
  // spreads the directions and fills the bins sooner.
  std::uint64_t occupied = 0;
  const std::size_t m = neighbours.size();
  std::size_t done = 0;
  for (std::size_t first = 0; first < 4; ++first) {
    for (std::size_t k = first; k < m; k += 4) {
      const Neighbour& q = neighbours[k];
      const bool direction = q.x != 0.0f || q.y != 0.0f;  // angleBin(0, 0) is defined, unused
      occupied |= std::uint64_t{direction} << angleBin(q.x, q.y);
      if (++done % 8 == 0 && occupied != 0 && gap.empty_run_limit >= 0 &&
          !hasLongEmptyRun(occupied, gap.empty_run_limit)) {
        return false;  // the bins so far leave no room for the gap: more neighbours cannot either
      }
    }
  }
  if (occupied == 0) return true;
  if (gap.empty_run_limit >= 0 && !hasLongEmptyRun(occupied, gap.empty_run_limit)) return false;
  directions.clear();
  for (const auto& q : neighbours) {
    if (q.x != 0.0f || q.y != 0.0f) directions.push_back({q.x, q.y});
  }
  const double cos_gap = gap.cos_gap;
  std::sort(directions.begin(), directions.end(), [](const Direction& a, const Direction& b) {
    const bool ua = upperHalf(a), ub = upperHalf(b);
    return ua != ub ? ua : cross(a, b) > 0.0;
  });
  auto same = [](const Direction& u, const Direction& v) {
    return cross(u, v) == 0.0 && dot(u, v) > 0.0;
  };
  if (same(directions.front(), directions.back()) &&
      upperHalf(directions.front()) == upperHalf(directions.back())) {
    return true;  // a single direction
  }
  const double cos2 = cos_gap * cos_gap;
  auto apart = [&](const Direction& u, const Direction& v) {  // v at least `gap` after u
    if (same(u, v)) return false;
    if (!(cross(u, v) > 0.0)) return true;  // 180 degrees or more
    const double d = dot(u, v);
    if (d >= 0.0) return cos_gap >= 0.0 && d == 0.0;  // at most 90 degrees
    return d * d >= cos2 * dot(u, u) * dot(v, v);
  };
  for (std::size_t k = 1; k < directions.size(); ++k) {
    if (apart(directions[k - 1], directions[k])) return true;
  }
  return apart(directions.back(), directions.front());
}

}  // namespace mcws::orthant
