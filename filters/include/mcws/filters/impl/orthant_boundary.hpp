#pragma once

#include <omp.h>
#include <pcl/common/common.h>
#include <pcl/kdtree/kdtree_flann.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <sstream>

#include "mcws/core/error.h"
#include "mcws/filters/cell_grid.h"
#include "mcws/filters/orthant_boundary.h"
#include "mcws/workspace/unique_positions.h"

namespace mcws {
namespace detail {

/// Quadrant of (x, y) with half-open angular sectors [0, 90), [90, 180), [180, 270), [270, 360):
/// a neighbour lying exactly on an axis falls on one side, cyclically, so that the rim of a grid
/// keeps an empty quadrant on every side.
inline unsigned quadrant(float x, float y) {
  if (x > 0 && y >= 0) return 0;
  if (x <= 0 && y > 0) return 1;
  if (x < 0 && y <= 0) return 2;
  return 3;
}

/// Octant: the quadrant of (x, y) and the side of z; z == 0 goes up for even quadrants and down
/// for odd ones, so that in-plane neighbours leave two octants empty on either side of a face.
inline unsigned octant(float x, float y, float z) {
  const unsigned q = quadrant(x, y);
  const bool up = z > 0 || (z == 0 && q % 2 == 0);
  return q + (up ? 4u : 0u);
}

/// A neighbour of p: its offset from p and squared distance (see CellGrid::Neighbour).
using Neighbour = CellGrid::Neighbour;

/// A direction from p to a neighbour, in the x-y plane.
struct Direction {
  float x, y;
};

/// Cross and dot products in double: exact for float inputs up to the final rounding, which
/// keeps their signs, so directions are ordered and compared without rounding errors.
inline double cross(const Direction& a, const Direction& b) {
  return static_cast<double>(a.x) * b.y - static_cast<double>(a.y) * b.x;
}
inline double dot(const Direction& a, const Direction& b) {
  return static_cast<double>(a.x) * b.x + static_cast<double>(a.y) * b.y;
}
/// Polar angle in [0, pi) rather than [pi, 2 pi).
inline bool upperHalf(const Direction& d) { return d.y > 0 || (d.y == 0 && d.x > 0); }

/// Angular bins of the quick sector test: 8 per octant, so the bin of a direction follows
/// from its octant and 7 comparisons of min(|x|, |y|) / max(|x|, |y|) with tan(k pi / 32),
/// without atan2.
constexpr int kAngleBins = 64;
/// Bound on how far a direction's bin may lie from its true angle [rad] (the rounding of one
/// division and of the tangents, about 1e-7, with a wide margin).
constexpr double kAngleError = 1e-4;

/// The bin of direction (x, y) (not both 0): floor(atan2(y, x) / (2 pi / 64)) mod 64, up to
/// kAngleError.
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

/// The empty sector the 2-D any-rotation test looks for: its cosine, and the longest run of
/// empty angular bins (of kAngleBins) that cannot hold it. Two neighbours on either side of a
/// run of E empty bins are less than (E + 2) w + 2 kAngleError apart, w the bin width, so a point
/// whose longest empty run is at most `empty_run_limit` has no such sector.
struct SectorGap {
  double cos_gap;
  int empty_run_limit;
};
inline SectorGap sectorGap(double gap) {
  const double w = 2 * M_PI / kAngleBins;
  return {std::cos(gap), static_cast<int>(std::ceil((gap - 2 * kAngleError) / w)) - 3};
}

/// True when the 64-bit mask of occupied bins (circular) has a run of more than `limit` empty
/// bins; `occupied` is not 0.
inline bool hasLongEmptyRun(std::uint64_t occupied, int limit) {
  // Rotated so that bit 0 is occupied, no run of empty bins wraps around.
  const int s = __builtin_ctzll(occupied);
  std::uint64_t empty = ~((occupied >> s) | (s ? occupied << (64 - s) : 0));
  for (int k = 0; k < limit && empty; ++k) empty &= empty >> 1;
  return empty != 0;
}

/// True when the directions from p to its neighbours (x-y plane) leave an empty sector of at
/// least `gap` radians (pi/2: some rotation of the local frame has an empty quadrant). Directions
/// are sorted by angle exactly (half-plane, then the sign of the cross product); consecutive
/// directions u, v are less than `gap` apart exactly when cross(u, v) > 0 and
/// dot(u, v) > |u| |v| cos(gap), `cos_gap` = cos(gap) <= 0 up to rounding at 90 degrees.
inline bool hasEmptySector(const std::vector<Neighbour>& neighbours, const SectorGap& gap,
                           std::vector<Direction>& directions) {
  // Most interior points are decided by angular bins; the rest by the exact test below. (p
  // itself, or a duplicate, has no direction.)
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
    return true;  // a single direction: everything else is empty
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

/// Sign code of a direction: bits x > 0, x < 0, y > 0, y < 0, z > 0, z < 0 (0 for the origin).
inline unsigned signCode(float x, float y, float z) {
  return unsigned{x > 0} | unsigned{x < 0} << 1 | unsigned{y > 0} << 2 | unsigned{y < 0} << 3 |
         unsigned{z > 0} << 4 | unsigned{z < 0} << 5;
}

/// For every sign code, the bit of the orthant holding such directions, 1 << quadrant(x, y) (2-D,
/// z ignored) or 1 << octant(x, y, z) (3-D), and 0 for the origin: p itself or a duplicate falls
/// in no orthant. A table look-up instead of the branches of quadrant() and octant(), whose
/// outcome is random from one neighbour to the next.
struct OrthantBits {
  std::uint8_t bit[2][64];  // [dimensions - 2][sign code]
  OrthantBits() : bit{} {
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
inline const std::uint8_t* orthantBits(int dimensions) {
  static const OrthantBits table;
  return table.bit[dimensions - 2];
}

/// The orthant test of one point against its neighbours (see OrthantBoundary).
/// \param frames bit 1: axis frame, bit 2: outward frame.
inline bool hasEmptyOrthant(const std::vector<Neighbour>& neighbours, int dimensions,
                            unsigned frames) {
  const unsigned full = dimensions == 2 ? 0xFu : 0xFFu;
  const std::uint8_t* bits = orthantBits(dimensions);
  // One pass for the axis frame's orthants and what the outward frame needs: the centroid's offset
  // from p, summed as offsets so that far from the origin no precision is lost, and in double so
  // that the order of the neighbours (tree or grid) does not matter; and the neighbourhood's size,
  // against which "symmetric" is judged.
  unsigned axis_mask = 0;
  double sx = 0.0, sy = 0.0, sz = 0.0;
  float size2 = 0.0f;
  for (const auto& q : neighbours) {
    axis_mask |= bits[signCode(q.x, q.y, q.z)];
    sx += q.x;
    sy += q.y;
    sz += q.z;
    size2 = std::max(size2, q.d2);
  }
  if (axis_mask == 0) return true;  // no neighbour apart from p: every orthant is empty
  if ((frames & 1u) && axis_mask != full) return true;
  if (!(frames & 2u)) return false;
  const double count = static_cast<double>(neighbours.size());
  Eigen::Vector3f n(static_cast<float>(-sx / count), static_cast<float>(-sy / count),
                    static_cast<float>(-sz / count));
  if (dimensions == 2) n.z() = 0;
  const float length = n.norm();
  // No outward direction: a symmetric neighbourhood is interior (the axis frame, if on, is full).
  if (!(length > 1e-6f * std::sqrt(size2))) return false;
  n /= length;
  Eigen::Matrix3f E = Eigen::Matrix3f::Identity();  // rows: the outward frame's axes
  if (dimensions == 2) {
    const Eigen::Vector3f a(-n.y(), n.x(), 0.0f);
    E.row(0) = (n + a) / std::sqrt(2.0f);
    E.row(1) = (n - a) / std::sqrt(2.0f);
  } else {
    // e_k = n / sqrt(3) + sqrt(2/3) (cos t_k a + sin t_k b), t_k = 0, 120, 240 degrees:
    // orthonormal, and n is the diagonal of the first octant.
    const Eigen::Vector3f a = n.unitOrthogonal();
    const Eigen::Vector3f b = n.cross(a);
    const float s = std::sqrt(2.0f / 3.0f), c = 1.0f / std::sqrt(3.0f);
    E.row(0) = c * n + s * a;
    E.row(1) = c * n + s * (-0.5f * a + 0.8660254f * b);
    E.row(2) = c * n + s * (-0.5f * a - 0.8660254f * b);
  }
  unsigned outward_mask = 0;
  for (const auto& q : neighbours) {
    const Eigen::Vector3f w = E * Eigen::Vector3f(q.x, q.y, q.z);
    outward_mask |= bits[signCode(w.x(), w.y(), w.z())];
    if (outward_mask == full) return false;
  }
  return true;
}

/// Scratch space of hullDepthInSpacings().
struct HullScratch {
  std::vector<Eigen::Vector2d> points, hull;
};

/// The depth of p below the edge of the convex hull of its neighbourhood (offsets from p, p
/// itself among them as (0, 0)), in local spacings sqrt(area / number of neighbours); 0 when p
/// is on the hull or the hull has no area (fewer than 3 positions, or all on a line).
inline double hullDepthInSpacings(const std::vector<Neighbour>& neighbours, HullScratch& s) {
  s.points.clear();
  s.points.emplace_back(0.0, 0.0);
  for (const auto& q : neighbours) s.points.emplace_back(q.x, q.y);
  std::sort(s.points.begin(), s.points.end(),
            [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
              return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
            });
  auto turn = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  // Andrew's monotone chain: the hull counter-clockwise, without collinear points.
  const std::size_t m = s.points.size();
  s.hull.resize(2 * m);
  std::size_t k = 0;
  for (std::size_t i = 0; i < m; ++i) {
    while (k >= 2 && turn(s.hull[k - 2], s.hull[k - 1], s.points[i]) <= 0.0) --k;
    s.hull[k++] = s.points[i];
  }
  for (std::size_t i = m - 1, lower = k + 1; i > 0; --i) {
    while (k >= lower && turn(s.hull[k - 2], s.hull[k - 1], s.points[i - 1]) <= 0.0) --k;
    s.hull[k++] = s.points[i - 1];
  }
  const std::size_t corners = k - 1;
  if (m < 3 || corners < 3) return 0.0;
  double twice_area = 0.0, depth = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < corners; ++i) {
    const Eigen::Vector2d& a = s.hull[i];
    const Eigen::Vector2d& b = s.hull[(i + 1) % corners];
    twice_area += a.x() * b.y() - a.y() * b.x();
    // p lies to the left of every counter-clockwise edge: its distance from the edge's line.
    depth = std::min(depth, turn(a, b, Eigen::Vector2d::Zero()) / (b - a).norm());
  }
  if (!(twice_area > 0.0)) return 0.0;
  const double spacing = std::sqrt(0.5 * twice_area / static_cast<double>(neighbours.size()));
  return std::max(depth, 0.0) / spacing;
}

/// The whole test of one point (frames already resolved by orthantFrames()).
inline bool isBoundaryPoint(const std::vector<Neighbour>& neighbours, int dimensions,
                            unsigned frames, const SectorGap& gap,
                            std::vector<Direction>& scratch) {
  if (dimensions == 2 && (frames & 4u)) return hasEmptySector(neighbours, gap, scratch);
  return hasEmptyOrthant(neighbours, dimensions, frames);
}

/// A first search at this fraction of the radius: with k random directions a spurious 90-degree
/// gap has probability about k (3/4)^(k-1), 0.4 % for k = 32, and the automatic radius (about
/// 5 spacings, 80 neighbours) times 0.65 holds about 33: almost every interior point is decided
/// by the small search. Exact: if a subset of the neighbours leaves no gap, all of them leave none.
constexpr double kPrefilterRadius = 0.65;

/// The grid's cell side as a fraction of the typical outer radius: the k nearest are then found
/// within one ring of cells and the radius neighbourhood within two.
constexpr double kCellPerRadius = 0.55;
/// How far a grid search may reach [cell sides]; beyond that (sparse regions) the tree searches.
/// A lonely point at the rim of a uniform cloud needs 4 or 5 cells in 2-D.
inline double maxReach(int dimensions) { return dimensions == 2 ? 8.0 : 4.0; }
/// A k-nearest search first collects this many times the typical outer radius, so that the
/// radius searches after it reuse its candidates.
constexpr double kFirstReach = 1.15;
/// A cell holding this many times the expected number of points sends its points to the tree,
/// which copes better with density far above the mean.
constexpr double kCrowdedCell = 16.0;

/// Expected distance to the k-th nearest neighbour in a uniform cloud [mean spacings]: the
/// radius of the disk (ball) holding k + 1 points.
inline double kthNeighbourDistance(int k, int dimensions) {
  return dimensions == 2 ? std::sqrt((k + 1) / M_PI) : std::cbrt(3.0 * (k + 1) / (4.0 * M_PI));
}

/// The filter's searches through pcl::KdTreeFLANN (the reference; it always answers).
struct TreeSearch {
  const pcl::KdTreeFLANN<pcl::PointXYZ>& tree;
  const pcl::PointCloud<pcl::PointXYZ>& cloud;
  std::vector<float> d2;

  pcl::Indices indices;

  bool kthDistance2(pcl::index_t i, int count, float& kth, std::vector<Neighbour>* nearest) {
    const int found = tree.nearestKSearch(cloud[i], count, indices, d2);
    kth = found > 0 ? *std::max_element(d2.begin(), d2.begin() + found) : 0.0f;
    if (nearest) offsets(i, *nearest);
    return true;
  }
  bool radius(pcl::index_t i, double r, std::vector<Neighbour>& found) {
    tree.radiusSearch(cloud[i], r, indices, d2);
    offsets(i, found);
    return true;
  }
  bool adaptiveSubset(pcl::index_t, int, float, std::vector<Neighbour>&) { return false; }

 private:
  void offsets(pcl::index_t i, std::vector<Neighbour>& out) const {
    out.resize(indices.size());
    for (std::size_t k = 0; k < indices.size(); ++k) {
      const pcl::PointXYZ& q = cloud[indices[k]];
      out[k] = {q.x - cloud[i].x, q.y - cloud[i].y, q.z - cloud[i].z, d2[k], indices[k]};
    }
  }
};

/// The test of one point with its parameters resolved; `Search` is TreeSearch or CellGridSearch.
struct PointTest {
  const pcl::PointCloud<pcl::PointXYZ>* cloud;
  int dimensions;
  unsigned frames;
  SectorGap gap;
  bool adaptive;
  int k;
  double scale;
  double radius;  // fixed radius (not adaptive)
  double outer;   // 0, or R (a factor when adaptive)
  bool monotone;  // more neighbours can only fill the orthants

  struct Scratch {
    std::vector<Neighbour> nn;
    std::vector<Direction> directions;
    HullScratch hull;
  };

  bool isBoundary(Scratch& s) const {
    return isBoundaryPoint(s.nn, dimensions, frames, gap, s.directions);
  }

  /// Decides point i into `boundary` and, when adaptive, its radius into `*r_i`; false (nothing
  /// written) if the search cannot answer.
  template <typename Search>
  bool decide(Search& search, pcl::index_t i, Scratch& s, char& boundary, float* r_i) const {
    double r = radius;
    bool prefiltered = false;
    if (adaptive && monotone && scale > 1.001 &&
        search.adaptiveSubset(i, k + 1, static_cast<float>(scale), s.nn)) {
      if (!isBoundary(s)) {  // decided from a subset; r_i is not needed
        boundary = 0;
        *r_i = std::numeric_limits<float>::quiet_NaN();
        return true;
      }
    }
    if (adaptive) {
      float d2k = 0.0f;
      const bool subset = monotone && scale > 1.001;  // the k nearest are tested below
      if (!search.kthDistance2(i, k + 1, d2k, subset ? &s.nn : nullptr)) return false;
      const float rk = static_cast<float>(scale) * std::sqrt(d2k);
      if (!(rk > 0.0f)) {  // all neighbours coincide with the point: it is alone
        boundary = 1;
        *r_i = rk;
        return true;
      }
      r = rk;
      // The k nearest lie within r when the scale exceeds 1: a subset, decisive when monotone.
      if (subset) {
        if (!isBoundary(s)) {
          boundary = 0;
          *r_i = rk;
          return true;
        }
        prefiltered = true;
      }
    }
    const double R = outer > 0.0 ? (adaptive ? outer * r : outer) : r;
    if (monotone && !prefiltered) {
      if (!search.radius(i, kPrefilterRadius * R, s.nn)) return false;
      if (!isBoundary(s)) {
        boundary = 0;
        if (adaptive) *r_i = static_cast<float>(r);
        return true;
      }
    }
    if (!search.radius(i, r, s.nn)) return false;
    bool is_boundary = isBoundary(s);
    if (is_boundary && outer > 0.0) {
      if (!search.radius(i, R, s.nn)) return false;
      is_boundary = isBoundary(s);
    }
    boundary = is_boundary;
    if (adaptive) *r_i = static_cast<float>(r);
    return true;
  }
};

}  // namespace detail

template <typename PointT>
void OrthantBoundary<PointT>::applyFilter(pcl::Indices& indices) {
  const int dimensions = boundaryDimensions(plane_);
  const bool adaptive = adaptive_k_ > 0;
  const bool automatic = !adaptive && auto_factor_ >= 0.0;
  if (adaptive_k_ < 0) throw Error(filter_name_ + ": adaptive k must be at least 1");
  if (adaptive && !(adaptive_scale_ > 0.0 && std::isfinite(adaptive_scale_))) {
    throw Error(filter_name_ + ": adaptive radius scale must be a positive number");
  }
  if (!adaptive && !automatic && !(radius_ > 0.0 && std::isfinite(radius_))) {
    std::ostringstream msg;
    msg << filter_name_ << ": radius " << radius_ << " must be a positive number";
    throw Error(msg.str());
  }
  if (automatic && !std::isfinite(auto_factor_)) throw Error(filter_name_ + ": bad radius factor");
  if (outer_radius_ < 0.0 || !std::isfinite(outer_radius_)) {
    throw Error(filter_name_ + ": outer radius must be 0 (off) or positive");
  }
  if (!(minimum_gap_ >= M_PI / 2 - 1e-9 && minimum_gap_ < M_PI)) {
    throw Error(filter_name_ + ": minimum gap must be in [pi/2, pi) rad");
  }
  if (!(hull_depth_ >= 0.0 && std::isfinite(hull_depth_))) {
    throw Error(filter_name_ + ": hull depth must be 0 (off) or a positive number of spacings");
  }
  if (hull_depth_ > 0.0 && dimensions != 2) {
    throw Error(filter_name_ + ": the hull depth test works in a plane; set a plane (xy, xz, yz)");
  }
  if (frames_ & ~(kAxisFrame | kOutwardFrame | kAnyRotation)) {
    throw Error(filter_name_ + ": unknown frame bits " + std::to_string(frames_));
  }

  pcl::PointCloud<pcl::PointXYZ> finite;
  pcl::Indices source;
  projectToPlane(*input_, *indices_, plane_, finite, source);
  // Copies of a point are one position: the spacing, the search and the test see each position
  // once, and every copy gets its position's answer.
  std::vector<pcl::index_t> position_of;
  auto projected =
      std::make_shared<pcl::PointCloud<pcl::PointXYZ>>(uniquePositions(finite, position_of));
  const std::size_t n = projected->size();

  used_spacing_ = 0.0;
  double radius = radius_;
  if (automatic || adaptive) used_spacing_ = n > 1 ? meanSpacing(*projected, dimensions) : 0.0;
  if (automatic) {
    const double factor = auto_factor_ > 0.0 ? auto_factor_ : orthantAutoFactor(n, dimensions);
    radius = factor * used_spacing_;
  }
  if (adaptive && outer_radius_ > 0.0 && outer_radius_ <= 1.0) {
    std::ostringstream msg;
    msg << filter_name_ << ": with an adaptive radius the outer radius is a factor of each point's "
        << "radius and must exceed 1, not " << outer_radius_;
    throw Error(msg.str());
  }
  if (!adaptive && outer_radius_ > 0.0 && outer_radius_ < radius) {
    std::ostringstream msg;
    msg << filter_name_ << ": outer radius " << outer_radius_ << " is smaller than radius "
        << radius;
    throw Error(msg.str());
  }
  used_radius_ = radius;

  const unsigned frames = orthantFrames(frames_, dimensions);
  detail::PointTest test{projected.get(), dimensions, frames, detail::sectorGap(minimum_gap_),
                         adaptive, adaptive_k_, adaptive_scale_, radius, outer_radius_,
                         // A test that more neighbours can only pass (no frame built from the
                         // neighbourhood) may decide interior points from a subset.
                         (dimensions == 2 && (frames & kAnyRotation)) || frames == kAxisFrame};
  // A cloud of identical points (spacing 0) has no neighbour at a distinct position: every point
  // is alone, hence a boundary point, as with any fixed radius.
  std::vector<char> boundary(n, automatic && !(radius > 0.0) ? 1 : 0);
  std::vector<float> point_radius(adaptive ? n : 0, 0.0f);
  if (n > 0 && (adaptive || radius > 0.0)) {
    // Most points are searched on a grid of cells about half the typical outer radius wide, in
    // cell order; the grid returns exactly what the tree would (see CellGrid). Points in very
    // dense cells, or whose radius reaches beyond 3 cells, are searched in the tree, built only
    // if there are any. The result is stored per point, so neither order nor thread matters.
    const double typical_radius =
        adaptive ? adaptive_scale_ * detail::kthNeighbourDistance(adaptive_k_, dimensions) *
                       used_spacing_
                 : radius;
    const double typical_outer = outer_radius_ > 0.0
                                     ? (adaptive ? outer_radius_ * typical_radius : outer_radius_)
                                     : typical_radius;
    std::unique_ptr<CellGrid> grid =
        std::make_unique<CellGrid>(*projected, dimensions, detail::kCellPerRadius * typical_outer);
    {
      // Positions renumbered in cell order, so that neighbours lie close in memory too.
      auto sorted = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
      sorted->resize(n);
      std::vector<pcl::index_t> rank(n);
      for (std::size_t k = 0; k < n; ++k) {
        (*sorted)[k] = (*projected)[grid->order()[k]];
        rank[grid->order()[k]] = static_cast<pcl::index_t>(k);
      }
      for (auto& position : position_of) position = rank[position];
      projected = sorted;
      grid->renumberInCellOrder();
      test.cloud = projected.get();
    }
    const double expected = used_spacing_ > 0.0
                                ? std::pow(grid->cellSize() / used_spacing_, dimensions)
                                : static_cast<double>(n);
    const auto crowded = static_cast<std::size_t>(detail::kCrowdedCell * std::max(1.0, expected));
    const int threads = threads_ > 0 ? threads_ : omp_get_num_procs();
    // Runs work(search, i, scratch) for every i in `points` with the grid search, on `workers`
    // threads, each with its own scratch space;
    // the points it cannot answer (crowded cells, searches beyond the grid's reach, or every
    // point with setGridSearch(false)) then with the kd-tree, built on first need.
    std::unique_ptr<pcl::KdTreeFLANN<pcl::PointXYZ>> tree;
    auto forEachPoint = [&](const std::vector<pcl::index_t>& points, int workers, auto work) {
      std::vector<char> deferred(points.size(), 0);
#pragma omp parallel num_threads(workers)
      {
        CellGridSearch search(*grid, *projected, detail::kFirstReach * typical_outer,
                              detail::maxReach(dimensions) * grid->cellSize());
        detail::PointTest::Scratch scratch;
#pragma omp for schedule(dynamic, 1024)
        for (std::int64_t k = 0; k < static_cast<std::int64_t>(points.size()); ++k) {
          const pcl::index_t i = points[k];
          deferred[k] = !grid_search_ || grid->population((*projected)[i]) > crowded ||
                        !work(search, i, scratch);
        }
      }
      std::vector<pcl::index_t> rest;
      for (std::size_t k = 0; k < points.size(); ++k) {
        if (deferred[k]) rest.push_back(points[k]);
      }
      if (rest.empty()) return;
      if (!tree) {
        tree = std::make_unique<pcl::KdTreeFLANN<pcl::PointXYZ>>(false);  // unsorted results
        tree->setInputCloud(projected);
      }
#pragma omp parallel num_threads(workers)
      {
        detail::TreeSearch search{*tree, *projected, {}, {}};
        detail::PointTest::Scratch scratch;
#pragma omp for schedule(dynamic, 256)
        for (std::int64_t k = 0; k < static_cast<std::int64_t>(rest.size()); ++k) {
          work(search, rest[k], scratch);
        }
      }
    };
    forEachPoint(grid->order(), threads, [&](auto& search, pcl::index_t i, auto& scratch) {
      return test.decide(search, i, scratch, boundary[i], adaptive ? &point_radius[i] : nullptr);
    });
    if (hull_depth_ > 0.0) {
      // The neighbourhood radius of point i (r_i when adaptive; R if set), or false.
      auto hullRadius = [&](auto& search, pcl::index_t i, double& r) {
        if (adaptive && std::isnan(point_radius[i])) {  // decided interior from a subset
          float d2k = 0.0f;
          if (!search.kthDistance2(i, adaptive_k_ + 1, d2k, nullptr)) return false;
          point_radius[i] = static_cast<float>(adaptive_scale_) * std::sqrt(d2k);
        }
        r = adaptive ? point_radius[i] : radius;
        if (outer_radius_ > 0.0) r = adaptive ? outer_radius_ * r : outer_radius_;
        return true;
      };
      // Candidates: the points the test found and those within a quarter of their radius (the
      // points the test misses lie about a spacing from one it finds; one thread:
      // a few thousand searches).
      std::vector<pcl::index_t> found;
      for (const auto i : grid->order()) {
        if (boundary[i]) found.push_back(i);
      }
      std::vector<char> candidate(n, 0);
      forEachPoint(found, 1, [&](auto& search, pcl::index_t i, auto& scratch) {
        double r = 0.0;
        if (!hullRadius(search, i, r) || !search.radius(i, 0.25 * r, scratch.nn)) return false;
        for (const auto& q : scratch.nn) candidate[q.index] = 1;
        return true;
      });
      std::vector<pcl::index_t> candidates;
      for (const auto i : grid->order()) {
        if (candidate[i]) candidates.push_back(i);
      }
      std::vector<char> shallow(n, 0);
      forEachPoint(candidates, threads, [&](auto& search, pcl::index_t i, auto& scratch) {
        double r = 0.0;
        if (!hullRadius(search, i, r) || !search.radius(i, r, scratch.nn)) return false;
        shallow[i] = detail::hullDepthInSpacings(scratch.nn, scratch.hull) < hull_depth_;
        return true;
      });
      boundary.swap(shallow);
    }
    if (adaptive) {
      // The median r_i over about 1000 points spread through the cloud (interior points decided
      // from a subset did not need theirs).
      CellGridSearch search(*grid, *projected, detail::kFirstReach * typical_outer,
                            detail::maxReach(dimensions) * grid->cellSize());
      std::vector<float> sample;
      for (std::size_t i = 0; i < n; i += std::max<std::size_t>(1, n / 1000)) {
        float d2k = 0.0f;
        if (std::isnan(point_radius[i]) && search.kthDistance2(i, adaptive_k_ + 1, d2k, nullptr))
          point_radius[i] = static_cast<float>(adaptive_scale_) * std::sqrt(d2k);
        if (!std::isnan(point_radius[i])) sample.push_back(point_radius[i]);
      }
      if (!sample.empty()) {
        std::nth_element(sample.begin(), sample.begin() + sample.size() / 2, sample.end());
        used_radius_ = sample[sample.size() / 2];
      }
    }
  }

  splitByBoundary(
      *indices_, source, [&](std::size_t k) { return boundary[position_of[k]] != 0; }, negative_,
      extract_removed_indices_, indices, *removed_indices_);
}

}  // namespace mcws
