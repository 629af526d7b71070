#pragma once
/// \file
/// \brief The points a shell triangulation leaves out (MeasureOptions::shell), searched for those
/// inside a simplex's circumsphere. Private to mcws_workspace (namespace mcws::detail); used by
/// measure_shell.cpp.

#include <CGAL/number_utils.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "mcws/workspace/detail/alpha_triangulation.h"

namespace mcws::detail {

/// Bits per axis of the grid of the left-out points (3-D: 2^18 cells, 2-D the same).
constexpr int kOrderBits3 = 6, kOrderBits2 = 9;
/// Points of a node of the left-out points' tree that are read one by one rather than its
/// children's boxes.
constexpr std::uint32_t kScanPoints = 8;
/// Grid cells up to which a search reads the cells its reach spans one by one, not the tree.
constexpr std::uint32_t kDirectCells = 64;

/// The points `members` of `points` in the Morton (Z) order of the cells of a 2^bits per axis
/// grid over their bounding box, in index order within a cell (a counting sort); `first` gets the
/// first place of each cell's points there (by Morton code; one more: the point count).
template <int D>
std::vector<std::uint32_t> mortonOrder(const pcl::PointCloud<pcl::PointXYZ>& points,
                                       const std::vector<std::uint32_t>& members,
                                       std::vector<std::uint32_t>& first,
                                       std::array<double, 3>& origin, std::array<double, 3>& per) {
  constexpr int bits = D == 3 ? kOrderBits3 : kOrderBits2;
  constexpr std::uint32_t side = 1u << bits;
  std::array<double, 3> lo{0.0, 0.0, 0.0}, hi{0.0, 0.0, 0.0}, scale{0.0, 0.0, 0.0};
  for (int a = 0; a < D; ++a) {
    lo[a] = std::numeric_limits<double>::infinity();
    hi[a] = -lo[a];
  }
  for (const std::uint32_t i : members) {
    for (int a = 0; a < D; ++a) {
      lo[a] = std::min<double>(lo[a], points[i].data[a]);
      hi[a] = std::max<double>(hi[a], points[i].data[a]);
    }
  }
  for (int a = 0; a < D; ++a) scale[a] = hi[a] > lo[a] ? side / (hi[a] - lo[a]) : 0.0;
  origin = lo;
  per = scale;
  // A cell index's bits spread D apart (bit b to bit b D).
  std::array<std::uint32_t, side> spread{};
  for (std::uint32_t q = 0; q < side; ++q) {
    for (int b = 0; b < bits; ++b) spread[q] |= ((q >> b) & 1u) << (b * D);
  }
  std::vector<std::uint32_t> code(members.size());
  first.assign((std::size_t{1} << (D * bits)) + 1, 0);
  for (std::size_t j = 0; j < members.size(); ++j) {
    std::uint32_t c = 0;
    for (int a = 0; a < D; ++a) {
      const double t = (points[members[j]].data[a] - lo[a]) * scale[a];
      c |= spread[static_cast<std::uint32_t>(std::clamp(t, 0.0, side - 1.0))] << a;
    }
    code[j] = c;
    ++first[c + 1];
  }
  for (std::size_t c = 1; c < first.size(); ++c) first[c] += first[c - 1];
  std::vector<std::uint32_t> order(members.size());
  std::vector<std::uint32_t> next(first.begin(), first.end() - 1);
  for (std::size_t j = 0; j < members.size(); ++j) order[next[code[j]]++] = members[j];
  return order;
}

/// The points left out of a shell triangulation (MeasureOptions::shell), to tell the shell's
/// simplices that are simplices of every point's triangulation (no left-out point inside their
/// circumsphere) from those that fill in for the left-out points. They are held in the Morton
/// order of a grid's cells (mortonOrder()), which makes them a complete octree (2-D: quadtree)
/// without building one: the points of a node (a run of cells with one code prefix) are one
/// range of that order, and each node has the bounding box of its points. Points that join the
/// shell later are skipped by the searches. What inside() answers does not depend on the order
/// (whether there is a point, or the set of them).
template <int D>
class LeftOut {
 public:
  LeftOut(const pcl::PointCloud<pcl::PointXYZ>& points, const std::vector<char>& in_shell)
      : slot_of_(points.size(), kNone) {
    std::vector<std::uint32_t> members;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (!in_shell[i]) members.push_back(static_cast<std::uint32_t>(i));
    }
    index_ = mortonOrder<D>(points, members, first_, origin_, scale_);
    members = {};
    coordinates_.reserve(index_.size());
    for (const std::uint32_t i : index_) {
      slot_of_[i] = static_cast<std::uint32_t>(coordinates_.size());
      coordinates_.push_back({points[i].x, points[i].y, points[i].z});
    }
    removed_.assign(index_.size(), 0);
    for (std::uint32_t q = 0; q < spread_.size(); ++q) {
      for (int b = 0; b < kBits; ++b) spread_[q] |= ((q >> b) & 1u) << (b * D);
    }
    buildBoxes();
  }

  /// Point `i` of the cloud joins the shell: no longer searched.
  void remove(std::uint32_t i) {
    if (slot_of_[i] != kNone) removed_[slot_of_[i]] = 1;
  }

  /// Appends to `found` the left-out points inside the circumcircle (D = 2) or circumsphere
  /// (D = 3) of finite simplex `s` of `dt`: all of them with `all`, else at most the first.
  /// Exact (CGAL's perturbed in-sphere test, as the triangulation breaks ties) for the points near
  /// the sphere. \return whether there is one.
  template <typename Delaunay, typename Simplex>
  bool inside(const Delaunay& dt, const Simplex& s, bool all,
              std::vector<std::uint32_t>* found) const {
    if (index_.empty()) return false;
    const auto p = canonicalPoints<D>(s);
    std::array<double, 3> centre{0.0, 0.0, 0.0};
    double radius2 = 0.0;
    if constexpr (D == 2) {
      const auto c = CGAL::circumcenter(p[0], p[1], p[2]);
      centre = {c.x(), c.y(), 0.0};
      radius2 = CGAL::squared_distance(c, p[0]);
    } else {
      const auto c = CGAL::circumcenter(p[0], p[1], p[2], p[3]);
      centre = {c.x(), c.y(), c.z()};
      radius2 = CGAL::squared_distance(c, p[0]);
    }
    const double radius = std::sqrt(radius2);
    // Slack for the float coordinates and distances and the rounding of the centre: a point
    // nearer than radius - slack is inside, one at radius + slack or farther is not; between
    // the two, CGAL's exact test tells.
    const double slack =
        1e-5 * (radius + std::max({std::abs(centre[0]), std::abs(centre[1]), std::abs(centre[2])}));
    const std::array<float, 3> query{static_cast<float>(centre[0]), static_cast<float>(centre[1]),
                                     static_cast<float>(centre[2])};
    const double reach = radius + slack;
    const float reach2 = static_cast<float>(reach * reach);
    bool any = false;
    const auto visit = [&](std::uint32_t k, float d2) {
      if (!(d2 < reach2)) return true;
      bool in = std::sqrt(static_cast<double>(d2)) < radius - slack;
      if (!in) {
        const auto& q = coordinates_[k];
        if constexpr (D == 2) {
          in = dt.side_of_oriented_circle(s, typename Delaunay::Point(q[0], q[1]), true) ==
               CGAL::ON_POSITIVE_SIDE;
        } else {
          in = dt.side_of_sphere(s, typename Delaunay::Point(q[0], q[1], q[2]), true) ==
               CGAL::ON_BOUNDED_SIDE;
        }
      }
      if (!in) return true;
      any = true;
      if (found) found->push_back(index_[k]);
      return all;  // one is enough without `all`
    };
    // Boxes farther than the reach (a little enlarged for the float rounding) hold none.
    searchNear(query, centre, reach * reach * (1.0 + 1e-4), visit);
    return any;
  }

 private:
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  static constexpr int kBits = D == 3 ? kOrderBits3 : kOrderBits2;
  using Box = std::array<float, 2 * D>;  // lower corner, upper corner

  /// search() of the nodes within `bound` (squared) of `query` (`centre` rounded to float).
  template <typename Visit>
  void searchNear(const std::array<float, 3>& query, const std::array<double, 3>& centre,
                  double bound, Visit& visit) const {
    // It starts at the deepest level where the grid cells within the bound's distance of the
    // query (and a margin for rounding) span at most two nodes per axis, in those nodes: the
    // others hold no point within it. Of a node's children, the one on the way to the query's
    // cell comes first.
    const double half =
        std::sqrt(bound) * 1.001 +
        1e-6 * std::max({std::abs(centre[0]), std::abs(centre[1]), std::abs(centre[2])});
    std::array<std::uint32_t, 3> low{0, 0, 0}, high{0, 0, 0}, mid{0, 0, 0};
    for (int a = 0; a < D; ++a) {
      low[a] = cellOf(query[a] - half, a);
      high[a] = cellOf(query[a] + half, a);
      mid[a] = cellOf(query[a], a);
    }
    std::uint32_t cells = 1;
    for (int a = 0; a < D; ++a) cells *= high[a] - low[a] + 1;
    if (cells <= kDirectCells) {  // a small reach: its grid cells one by one
      std::array<std::uint32_t, 3> cell{0, 0, 0};
      for (cell[2] = low[2]; cell[2] <= high[2]; ++cell[2]) {
        for (cell[1] = low[1]; cell[1] <= high[1]; ++cell[1]) {
          for (cell[0] = low[0]; cell[0] <= high[0]; ++cell[0]) {
            if (!search(kBits, interleave(cell), query, bound, 0, visit)) return;
          }
        }
      }
      return;
    }
    int level = kBits;
    const auto spans = [&](int shift) {
      for (int a = 0; a < D; ++a) {
        if ((high[a] >> shift) - (low[a] >> shift) > 1) return false;
      }
      return true;
    };
    while (level > 0 && !spans(kBits - level)) --level;
    const int shift = kBits - level;
    const std::uint32_t near = interleave(mid);
    for (std::uint32_t t = 0; t < (1u << D); ++t) {
      std::array<std::uint32_t, 3> node{0, 0, 0};
      bool twice = false;
      for (int a = 0; a < D; ++a) {
        const bool upper = (t >> a) & 1u;
        node[a] = (upper ? high[a] : low[a]) >> shift;
        twice |= upper && node[a] == low[a] >> shift;
      }
      if (!twice && !search(level, interleave(node), query, bound, near, visit)) break;
    }
  }

  /// The grid cell of coordinate x on axis a (as mortonOrder() places the points; every point
  /// in cell 0 of an axis where they all have one coordinate).
  std::uint32_t cellOf(double x, int a) const {
    const double t = (x - origin_[a]) * scale_[a];  // NaN for an infinite x on a flat axis
    return t >= 0.0 ? static_cast<std::uint32_t>(std::min(t, (1u << kBits) - 1.0)) : 0u;
  }
  /// The Morton code of the node of integer coordinates `node` (at any level).
  std::uint32_t interleave(const std::array<std::uint32_t, 3>& node) const {
    std::uint32_t code = 0;
    for (int a = 0; a < D; ++a) code |= spread_[node[a]] << a;
    return code;
  }

  std::uint32_t begin(int level, std::uint32_t code) const {
    return first_[std::size_t{code} << (D * (kBits - level))];
  }
  std::uint32_t end(int level, std::uint32_t code) const {
    return first_[std::size_t{code + 1} << (D * (kBits - level))];
  }

  /// The bounding box of each node's points, the leaves' from the points, each parent's from its
  /// children's (an empty node's box is empty: lower above upper).
  void buildBoxes() {
    boxes_.resize(kBits + 1);
    for (int level = 0; level <= kBits; ++level) {
      Box empty;
      for (int a = 0; a < D; ++a) {
        empty[a] = std::numeric_limits<float>::infinity();
        empty[D + a] = -empty[a];
      }
      boxes_[level].assign(std::size_t{1} << (D * level), empty);
    }
    auto& leaves = boxes_[kBits];
    for (std::uint32_t c = 0; c < leaves.size(); ++c) {
      for (std::uint32_t k = first_[c]; k < first_[c + 1]; ++k) {
        for (int a = 0; a < D; ++a) {
          leaves[c][a] = std::min(leaves[c][a], coordinates_[k][a]);
          leaves[c][D + a] = std::max(leaves[c][D + a], coordinates_[k][a]);
        }
      }
    }
    for (int level = kBits - 1; level >= 0; --level) {
      for (std::size_t c = 0; c < boxes_[level].size(); ++c) {
        Box& box = boxes_[level][c];
        for (std::size_t t = 0; t < (std::size_t{1} << D); ++t) {
          const Box& child = boxes_[level + 1][(c << D) | t];
          for (int a = 0; a < D; ++a) {
            box[a] = std::min(box[a], child[a]);
            box[D + a] = std::max(box[D + a], child[D + a]);
          }
        }
      }
    }
  }

  /// Calls visit(place, squared distance) for each point not removed of node `code` at `level`
  /// whose box is within `bound` (squared) of `query`, until visit returns false; of the children,
  /// first the one on the way to grid cell `cell`. The distance is
  /// the float sum of the squared float differences per axis. \return whether it went on.
  template <typename Visit>
  bool search(int level, std::uint32_t code, const std::array<float, 3>& query, double bound,
              std::uint32_t cell, Visit& visit) const {
    const std::uint32_t from = begin(level, code), to = end(level, code);
    if (from == to) return true;
    const Box& box = boxes_[level][code];
    double gap2 = 0.0;
    for (int a = 0; a < D; ++a) {
      const double below = static_cast<double>(box[a]) - query[a];
      const double above = static_cast<double>(query[a]) - box[D + a];
      const double gap = below > 0.0 ? below : above > 0.0 ? above : 0.0;
      gap2 += gap * gap;
    }
    if (gap2 > bound) return true;
    if (level == kBits || to - from <= kScanPoints) {
      for (std::uint32_t k = from; k < to; ++k) {
        if (removed_[k]) continue;
        float d2 = 0.0f;
        for (int a = 0; a < D; ++a) {
          const float diff = query[a] - coordinates_[k][a];
          d2 += diff * diff;
        }
        if (!visit(k, d2)) return false;
      }
      return true;
    }
    const std::uint32_t near = (cell >> (D * (kBits - level - 1))) & ((1u << D) - 1);
    for (std::uint32_t t = 0; t < (1u << D); ++t) {
      if (!search(level + 1, (code << D) | (t ^ near), query, bound, cell, visit)) return false;
    }
    return true;
  }

  std::vector<std::array<float, 3>> coordinates_;  // by place in the order
  std::vector<std::uint32_t> index_;               // the point's index in the whole cloud
  std::vector<std::uint32_t> slot_of_;             // the point's place in the order, by its index
  std::vector<std::uint32_t> first_;               // the first place of each grid cell's points
  std::array<std::uint32_t, (1u << kBits)> spread_{};  // bit b of a coordinate to bit b D
  std::vector<std::vector<Box>> boxes_;                // by level (0: the root), then by code
  std::array<double, 3> origin_{}, scale_{};  // of the grid: the cell of x from (x - origin) scale
  std::vector<char> removed_;                 // by place: joined the shell
};

}  // namespace mcws::detail
