#pragma once

#include <omp.h>
#include <pcl/common/common.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <future>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "mcws/core/error.h"
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

/// True when the directions from p to its neighbours (x-y plane) leave an empty sector of at
/// least `gap` radians (pi/2: some rotation of the local frame has an empty quadrant). Directions
/// are sorted by angle exactly (half-plane, then the sign of the cross product); consecutive
/// directions u, v are less than `gap` apart exactly when cross(u, v) > 0 and
/// dot(u, v) > |u| |v| cos(gap), `cos_gap` = cos(gap) <= 0 up to rounding at 90 degrees.
inline bool hasEmptySector(const pcl::PointCloud<pcl::PointXYZ>& cloud, pcl::index_t i,
                           const pcl::Indices& neighbours, double cos_gap,
                           std::vector<Direction>& directions) {
  const pcl::PointXYZ& p = cloud[i];
  directions.clear();
  for (const auto j : neighbours) {
    const Direction d{cloud[j].x - p.x, cloud[j].y - p.y};
    if (d.x != 0.0f || d.y != 0.0f) directions.push_back(d);
  }
  if (directions.empty()) return true;
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

/// The orthant test of one point against its neighbours (see OrthantBoundary).
/// \param frames bit 1: axis frame, bit 2: outward frame.
inline bool hasEmptyOrthant(const pcl::PointCloud<pcl::PointXYZ>& cloud, pcl::index_t i,
                            const pcl::Indices& neighbours, int dimensions, unsigned frames) {
  const Eigen::Vector3f p = cloud[i].getVector3fMap();
  const unsigned full = dimensions == 2 ? 0xFu : 0xFFu;
  bool use_axis = frames & 1u;
  bool use_outward = frames & 2u;
  Eigen::Matrix3f E = Eigen::Matrix3f::Identity();  // rows: the outward frame's axes
  if (use_outward) {
    // The centroid's offset from p, summed as offsets so that far from the origin no precision
    // is lost; "symmetric" is judged against the neighbourhood's own size.
    Eigen::Vector3f offset = Eigen::Vector3f::Zero();
    float size = 0.0f;
    for (const auto j : neighbours) {
      const Eigen::Vector3f v = cloud[j].getVector3fMap() - p;
      offset += v;
      size = std::max(size, v.norm());
    }
    Eigen::Vector3f n = -offset / static_cast<float>(std::max<std::size_t>(1, neighbours.size()));
    if (dimensions == 2) n.z() = 0;
    const float length = n.norm();
    if (!(length > 1e-6f * size)) {
      use_outward = false;  // no outward direction: a symmetric neighbourhood is interior
    } else {
      n /= length;
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
    }
  }
  const bool alone = std::all_of(neighbours.begin(), neighbours.end(), [&](pcl::index_t j) {
    return cloud[j].getVector3fMap() == p;  // the search returns p itself
  });
  if (alone) return true;  // every orthant is empty
  if (!use_axis && !use_outward) return false;
  unsigned axis_mask = use_axis ? 0u : full;
  unsigned outward_mask = use_outward ? 0u : full;
  for (const auto j : neighbours) {
    const Eigen::Vector3f v = cloud[j].getVector3fMap() - p;
    if (v.isZero(0.0f)) continue;  // p itself, or a duplicate
    if (dimensions == 2) {
      if (use_axis) axis_mask |= 1u << quadrant(v.x(), v.y());
      if (use_outward) outward_mask |= 1u << quadrant(E.row(0).dot(v), E.row(1).dot(v));
    } else {
      if (use_axis) axis_mask |= 1u << octant(v.x(), v.y(), v.z());
      if (use_outward) {
        const Eigen::Vector3f w = E * v;
        outward_mask |= 1u << octant(w.x(), w.y(), w.z());
      }
    }
    if (axis_mask == full && outward_mask == full) return false;
  }
  return true;
}

/// The whole test of one point (frames already resolved by orthantFrames()).
inline bool isBoundaryPoint(const pcl::PointCloud<pcl::PointXYZ>& cloud, pcl::index_t i,
                            const pcl::Indices& neighbours, int dimensions, unsigned frames,
                            double cos_gap, std::vector<Direction>& scratch) {
  if (dimensions == 2 && (frames & 4u))
    return hasEmptySector(cloud, i, neighbours, cos_gap, scratch);
  return hasEmptyOrthant(cloud, i, neighbours, dimensions, frames);
}

/// A first search at this fraction of the radius: with k random directions a spurious 90-degree
/// gap has probability about k (3/4)^(k-1), 0.4 % for k = 32, and the automatic radius (about
/// 5 spacings, 80 neighbours) times 0.65 holds about 33: almost every interior point is decided
/// by the small search. Exact: if a subset of the neighbours leaves no gap, all of them leave none.
constexpr double kPrefilterRadius = 0.65;

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
  if (frames_ & ~(kAxisFrame | kOutwardFrame | kAnyRotation)) {
    throw Error(filter_name_ + ": unknown frame bits " + std::to_string(frames_));
  }

  pcl::PointCloud<pcl::PointXYZ> finite;
  pcl::Indices source;
  projectToPlane(*input_, *indices_, plane_, finite, source);
  // Copies of a point are one position: the spacing, the search and the test see each position
  // once, and every copy gets its position's answer.
  std::vector<pcl::index_t> position_of;
  const auto projected =
      std::make_shared<pcl::PointCloud<pcl::PointXYZ>>(uniquePositions(finite, position_of));
  const std::size_t n = projected->size();

  // The tree is built in the background while the radius is chosen (both are serial work).
  pcl::KdTreeFLANN<pcl::PointXYZ> tree(false);  // unsorted results: the test needs no order
  auto built = std::async(std::launch::async, [&] {
    if (n > 0) tree.setInputCloud(projected);
  });

  used_spacing_ = 0.0;
  double radius = radius_;
  if (automatic) {
    used_spacing_ = meanSpacing(*projected, dimensions);
    const double factor = auto_factor_ > 0.0 ? auto_factor_ : orthantAutoFactor(n, dimensions);
    radius = factor * used_spacing_;
  }
  if (adaptive && outer_radius_ > 0.0 && outer_radius_ <= 1.0) {
    built.wait();
    std::ostringstream msg;
    msg << filter_name_ << ": with an adaptive radius the outer radius is a factor of each point's "
        << "radius and must exceed 1, not " << outer_radius_;
    throw Error(msg.str());
  }
  if (!adaptive && outer_radius_ > 0.0 && outer_radius_ < radius) {
    built.wait();
    std::ostringstream msg;
    msg << filter_name_ << ": outer radius " << outer_radius_ << " is smaller than radius "
        << radius;
    throw Error(msg.str());
  }
  used_radius_ = radius;

  // A cloud of identical points (spacing 0) has no neighbour at a distinct position: every point
  // is alone, hence a boundary point, as with any fixed radius.
  std::vector<char> boundary(n, automatic && !(radius > 0.0) ? 1 : 0);
  if (n > 0 && (adaptive || radius > 0.0)) {
    // Query in a spatially sorted order (cells of about one radius), so that consecutive
    // searches walk the same part of the tree; the result is stored per point, so the order does
    // not change it.
    std::vector<pcl::index_t> order(n);
    {
      Eigen::Vector4f min, max;
      pcl::getMinMax3D(*projected, min, max);
      const float extent = (max - min).head<3>().maxCoeff();
      const float cell = radius > 0.0 ? static_cast<float>(radius)
                                      : extent / std::max(1.0f, std::cbrt(static_cast<float>(n)));
      std::vector<std::pair<std::uint64_t, pcl::index_t>> keyed(n);
      for (std::size_t k = 0; k < n; ++k) {
        const Eigen::Vector3f c =
            ((*projected)[k].getVector3fMap() - min.head<3>()) / std::max(cell, 1e-30f);
        keyed[k] = {(static_cast<std::uint64_t>(std::min(c.z(), 2.0e6f)) << 42) |
                        (static_cast<std::uint64_t>(std::min(c.y(), 2.0e6f)) << 21) |
                        static_cast<std::uint64_t>(std::min(c.x(), 2.0e6f)),
                    static_cast<pcl::index_t>(k)};
      }
      std::sort(keyed.begin(), keyed.end());
      for (std::size_t k = 0; k < n; ++k) order[k] = keyed[k].second;
    }
    built.wait();

    std::vector<float> point_radius;
    if (adaptive) {
      point_radius.resize(n);
#pragma omp parallel num_threads(threads_ > 0 ? threads_ : omp_get_num_procs())
      {
        pcl::Indices nn;
        std::vector<float> d2;
#pragma omp for schedule(dynamic, 1024)
        for (std::int64_t k = 0; k < static_cast<std::int64_t>(n); ++k) {
          const pcl::index_t i = order[k];
          const int found = tree.nearestKSearch((*projected)[i], adaptive_k_ + 1, nn, d2);
          const float dk = found > 0 ? std::sqrt(*std::max_element(d2.begin(), d2.end())) : 0.0f;
          point_radius[i] = static_cast<float>(adaptive_scale_) * dk;
        }
      }
      std::vector<float> sorted = point_radius;
      std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.end());
      used_radius_ = sorted[n / 2];
    }

    const unsigned frames = orthantFrames(frames_, dimensions);
    const double cos_gap = std::cos(minimum_gap_);
    // A test that more neighbours can only pass (no frame built from the neighbourhood) decides
    // most interior points from the nearest few: if those within r already fill every orthant,
    // the full neighbourhood does too.
    const bool monotone = (dimensions == 2 && (frames & kAnyRotation)) || frames == kAxisFrame;
#pragma omp parallel num_threads(threads_ > 0 ? threads_ : omp_get_num_procs())
    {
      pcl::Indices nn;
      std::vector<float> d2;
      std::vector<detail::Direction> scratch;
#pragma omp for schedule(dynamic, 1024)
      for (std::int64_t k = 0; k < static_cast<std::int64_t>(n); ++k) {
        const pcl::index_t i = order[k];
        const double r = adaptive ? point_radius[i] : radius;
        if (!(r > 0.0)) {  // all neighbours coincide with the point: it is alone
          boundary[i] = 1;
          continue;
        }
        const double R = outer_radius_ > 0.0 ? (adaptive ? outer_radius_ * r : outer_radius_) : r;
        if (monotone) {
          tree.radiusSearch((*projected)[i], detail::kPrefilterRadius * R, nn, d2);
          if (!detail::isBoundaryPoint(*projected, i, nn, dimensions, frames, cos_gap, scratch))
            continue;
        }
        tree.radiusSearch((*projected)[i], r, nn, d2);
        bool is_boundary =
            detail::isBoundaryPoint(*projected, i, nn, dimensions, frames, cos_gap, scratch);
        if (is_boundary && outer_radius_ > 0.0) {
          tree.radiusSearch((*projected)[i], R, nn, d2);
          is_boundary =
              detail::isBoundaryPoint(*projected, i, nn, dimensions, frames, cos_gap, scratch);
        }
        boundary[i] = is_boundary;
      }
    }
  }

  // Output in input order: kept = boundary != negative; non-finite points are always removed.
  indices.clear();
  indices.reserve(indices_->size());
  removed_indices_->clear();
  std::size_t next = 0;  // walks `source`, which is in input order
  for (const auto index : *indices_) {
    bool keep = false;
    if (next < source.size() && source[next] == index) {
      keep = (boundary[position_of[next]] != 0) != negative_;
      ++next;
    }
    if (keep) {
      indices.push_back(index);
    } else if (extract_removed_indices_) {
      removed_indices_->push_back(index);
    }
  }
}

}  // namespace mcws
