#include "mcws/workspace/detail/measure_shell.h"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <future>
#include <iterator>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "mcws/core/first_error.h"
#include "mcws/workspace/detail/alpha_triangulation.h"
#include "mcws/workspace/detail/surface_repair.h"
#include "mcws/workspace/exposed_points.h"

namespace mcws::detail {
namespace {

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

/// The finite simplices around vertex v, and the infinite ones with `infinite` (read-only, so
/// threads may call it at once).
template <int D, typename Delaunay>
void incidentSimplices(const Delaunay& dt, typename Delaunay::Vertex_handle v,
                       std::vector<typename SimplexOf<D, Delaunay>::Handle>& out,
                       bool infinite = false) {
  out.clear();
  if constexpr (D == 2) {
    auto f = dt.incident_faces(v), done = f;
    do {
      out.push_back(f);
    } while (++f != done);
  } else {
    starCells(dt, v, out);
  }
  if (!infinite) {
    out.erase(
        std::remove_if(out.begin(), out.end(), [&](const auto& s) { return dt.is_infinite(s); }),
        out.end());
  }
}

/// The points an empty ball of alpha radius may touch (exposedPoints()): 1 for a point of the
/// shell, 0 for a point left out.
std::vector<char> shellPoints(const pcl::PointCloud<pcl::PointXYZ>& points, int dimensions,
                              const std::vector<double>& spacing, double alpha_factor, int threads,
                              const CancelCheck& cancel_check) {
  std::vector<double> reach(spacing.size());
  for (std::size_t i = 0; i < spacing.size(); ++i) reach[i] = alpha_factor * spacing[i];
  return exposedPoints(points, dimensions, reach, threads, cancel_check).exposed;
}

/// Flags every simplex of `dt` kept (1) or dropped (0) as `keep` says, the infinite ones dropped.
/// \return the finite simplices.
template <int D, typename Delaunay, typename Keep>
std::vector<typename SimplexOf<D, Delaunay>::Handle> flagSimplices(
    Delaunay& dt, const Keep& keep, int threads, const CancelCheck& cancel_check) {
  std::vector<typename SimplexOf<D, Delaunay>::Handle> finite;
  finite.reserve(D == 2 ? 2 * dt.number_of_vertices() : 7 * dt.number_of_vertices());
  for (const auto s : allSimplices<D>(dt)) {
    s->info() = 0;
    if (!dt.is_infinite(s)) finite.push_back(s);
  }
  FirstError error;  // what cancel_check throws leaves the parallel region through it
#pragma omp parallel num_threads(threads)
  {
    CancelPacer pacer = callingThreadPacer(cancel_check, kCancelStride);
#pragma omp for schedule(dynamic, 4096)
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(finite.size()); ++i) {
      error.run(i, [&] {
        pacer.step();
        finite[i]->info() = keep(finite[i]);
      });
    }
  }
  error.rethrow();
  return finite;
}

/// The kept simplices of the boundary vertices' stars (a simplex is in the stars of up to D + 1
/// vertices, so it may come more than once).
template <int D, typename Delaunay>
std::vector<typename SimplexOf<D, Delaunay>::Handle> keptStars(
    const Delaunay& dt, const std::vector<typename Delaunay::Vertex_handle>& boundary) {
  std::vector<typename SimplexOf<D, Delaunay>::Handle> around, stars;
  for (const auto v : boundary) {
    incidentSimplices<D>(dt, v, around);
    for (const auto& s : around) {
      if (s->info()) stars.push_back(s);
    }
  }
  return stars;
}

/// Drops the repeats of `simplices`, each first one staying in its place: a simplex is marked
/// (kListed, in its info beside the flags there) as it is first met, the marks cleared after.
template <typename Simplex>
void dropRepeats(std::vector<Simplex>& simplices) {
  constexpr char kListed = 0x40;  // above every flag the info holds (0 to 3)
  std::size_t kept = 0;
  for (std::size_t i = 0; i < simplices.size(); ++i) {
    const Simplex s = simplices[i];
    if (s->info() & kListed) continue;
    s->info() = static_cast<char>(s->info() | kListed);
    simplices[kept++] = s;
  }
  simplices.resize(kept);
  for (const Simplex s : simplices) s->info() = static_cast<char>(s->info() & ~kListed);
}

/// The left-out points in the circumspheres of `stars` (searched on all threads), sorted, each
/// once. The repeats of `stars` are dropped first.
template <int D, typename Delaunay, typename Simplex>
std::vector<std::uint32_t> leftOutInStars(const Delaunay& dt, std::vector<Simplex>& stars,
                                          const LeftOut<D>& left_out, int threads) {
  dropRepeats(stars);
  std::vector<std::uint32_t> joining;
  FirstError error;  // running out of memory leaves the parallel region through it
#pragma omp parallel num_threads(threads)
  {
    std::vector<std::uint32_t> found;
#pragma omp for schedule(dynamic, 1024)
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(stars.size()); ++i) {
      error.run(i, [&] { left_out.inside(dt, stars[i], true, &found); });
    }
#pragma omp critical
    error.run(stars.size(), [&] { joining.insert(joining.end(), found.begin(), found.end()); });
  }
  error.rethrow();
  std::sort(joining.begin(), joining.end());
  joining.erase(std::unique(joining.begin(), joining.end()), joining.end());
  return joining;
}

/// Inserts the points `joining` into `dt`, each vertex carrying its point's index, and takes them
/// off the left-out points. \return their vertices.
template <int D, typename Delaunay>
std::vector<typename Delaunay::Vertex_handle> insertJoining(
    Delaunay& dt, const pcl::PointCloud<pcl::PointXYZ>& points,
    const std::vector<std::uint32_t>& joining, LeftOut<D>& left_out) {
  std::vector<typename Delaunay::Vertex_handle> joined;
  for (const std::uint32_t k : joining) {
    left_out.remove(k);
    const pcl::PointXYZ& p = points[k];
    typename Delaunay::Vertex_handle v;
    if constexpr (D == 2) {
      v = dt.insert(typename Delaunay::Point(p.x, p.y));
    } else {
      v = dt.insert(typename Delaunay::Point(p.x, p.y, p.z));
    }
    v->info() = k;
    joined.push_back(v);
  }
  return joined;
}

/// Flags the simplices around the vertices `joined` (the new ones insertion made) as `keep` says,
/// the infinite ones dropped. \return the kept ones in a boundary vertex's star (`on_boundary`, by
/// point index): the others were checked before.
template <int D, typename Delaunay, typename Keep>
std::vector<typename SimplexOf<D, Delaunay>::Handle> retestAround(
    Delaunay& dt, const std::vector<typename Delaunay::Vertex_handle>& joined, const Keep& keep,
    const std::vector<char>& on_boundary) {
  std::vector<typename SimplexOf<D, Delaunay>::Handle> around, stars;
  for (const auto v : joined) {
    incidentSimplices<D>(dt, v, around, true);
    for (const auto& s : around) {
      s->info() = dt.is_infinite(s) ? 0 : keep(s);
      if (!s->info()) continue;
      for (int k = 0; k <= D; ++k) {
        if (on_boundary[s->vertex(k)->info()]) {
          stars.push_back(s);
          break;
        }
      }
    }
  }
  return stars;
}

/// Makes each of the vertices' stars the whole triangulation's: a star simplex with left-out
/// points in its circumsphere is not the whole triangulation's, so those points join (inserted,
/// the simplices around them flagged by `keep`), round by round until no star simplex has one.
/// Only simplices with a left-out point in their circumsphere are replaced (the whole
/// triangulation's are not), and they are all kept (filling in for a covered point), as are the
/// new ones (the whole triangulation's simplices around a covered point are within its alpha
/// limit). \return whether a point joined (simplex handles listed before may be gone).
template <int D, typename Delaunay, typename Keep>
bool completeStars(Delaunay& dt, const pcl::PointCloud<pcl::PointXYZ>& points,
                   const std::vector<typename Delaunay::Vertex_handle>& vertices,
                   LeftOut<D>& left_out, const Keep& keep, int threads,
                   const CancelCheck& cancel_check) {
  std::vector<typename SimplexOf<D, Delaunay>::Handle> stars = keptStars<D>(dt, vertices);
  std::vector<char> on_boundary(points.size(), 0);
  for (const auto v : vertices) on_boundary[v->info()] = 1;
  bool joined_any = false;
  for (;;) {
    if (cancel_check) cancel_check();  // between rounds
    const std::vector<std::uint32_t> joining = leftOutInStars<D>(dt, stars, left_out, threads);
    if (joining.empty()) return joined_any;
    joined_any = true;
    const auto joined = insertJoining<D>(dt, points, joining, left_out);
    stars = retestAround<D>(dt, joined, keep, on_boundary);
  }
}

/// The envelope surface (MeasureOptions::surface) of a shell triangulation whose boundary
/// vertices' stars are complete: fillForSurface() with the stars of the vertices of the cells
/// each round fills or drops completed before the next round (a dropped cell's vertices join the
/// boundary; a filled one's were on it, or had only dropped cells, the whole triangulation's,
/// around them), so that every cell the repair and keptSurface() look at, those around the
/// boundary's vertices and edges, is the whole triangulation's, flagged as there.
template <typename Delaunay, typename Keep>
bool repairShellSurface(Delaunay& dt, const pcl::PointCloud<pcl::PointXYZ>& points,
                        LeftOut<3>& left_out, const Keep& keep, int threads,
                        const CancelCheck& cancel_check) {
  using Cell = typename Delaunay::Cell_handle;
  const auto complete = [&](const std::vector<Cell>& changed) {
    std::vector<typename Delaunay::Vertex_handle> vertices;
    for (const Cell c : changed) {
      for (int k = 0; k < 4; ++k) {
        if (!dt.is_infinite(c->vertex(k))) vertices.push_back(c->vertex(k));
      }
    }
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    completeStars<3>(dt, points, vertices, left_out, keep, threads, cancel_check);
  };
  return fillForSurface(dt, cancel_check, std::function<void(const std::vector<Cell>&)>(complete));
}

/// The kept simplices' total area (D = 2) or volume (D = 3), summed on all threads (OrderFreeSum
/// of `bound`).
template <int D, typename Simplex>
double keptTotal(const std::vector<Simplex>& finite, double bound, int threads) {
  OrderFreeSum kept(bound);
#pragma omp parallel num_threads(threads)
  {
    OrderFreeSum part(bound);  // not a copy of `kept`, which other threads may be adding to
#pragma omp for schedule(static) nowait
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(finite.size()); ++i) {
      if (finite[i]->info()) part.add(simplexMeasure<D>(finite[i]));
    }
#pragma omp critical
    kept.add(part);
  }
  return kept.value();
}

}  // namespace

template <int D, typename Concurrency>
RegionMeasure measureShell(const pcl::PointCloud<pcl::PointXYZ>& points,
                           const std::vector<double>& spacing, const MeasureOptions& options) {
  using Delaunay = typename Simplices<D, Concurrency>::Delaunay;
  using Simplex = typename SimplexOf<D, Delaunay>::Handle;
  const double alpha_factor = options.alpha_factor;
  const int threads = options.threads;
  if (options.phase) options.phase("exposed points");
  const std::vector<char> in_shell =
      shellPoints(points, D, spacing, alpha_factor, threads, options.cancel_check);
  // The left-out points' tree is built while the shell is triangulated (on a thread of its own
  // when there are several: a 3-D triangulation shares the cores with it, a 2-D one runs on one).
  // threads 0: OpenMP's default, all cores unless OMP_NUM_THREADS says otherwise.
  const int workers = threads > 0 ? threads : omp_get_max_threads();
  std::future<std::unique_ptr<LeftOut<D>>> building =
      std::async(workers > 1 ? std::launch::async : std::launch::deferred,
                 [&] { return std::make_unique<LeftOut<D>>(points, in_shell); });
  if (options.phase) options.phase("triangulation");
  Delaunay dt;
  triangulate<D, Concurrency>(dt, points, in_shell, options.cancel_check);
  const std::unique_ptr<LeftOut<D>> left_out_tree = building.get();
  LeftOut<D>& left_out = *left_out_tree;

  if (options.phase) options.phase("alpha test");
  // Kept (1): within the alpha limit, or filling in for left-out points; else dropped (0).
  const auto keep = [&](const Simplex& s) -> char {
    return withinAlpha<D>(s, spacing, alpha_factor) || left_out.inside(dt, s, false, nullptr);
  };
  std::vector<Simplex> finite = flagSimplices<D>(dt, keep, threads, options.cancel_check);
  // Joins below replace only kept simplices (a dropped one has no left-out point in its
  // circumsphere, and a simplex around a covered point is within its alpha limit), so the
  // boundary vertices are final.
  const auto boundary = boundaryVertices<D>(dt, points.size());
  const bool surface = D == 3 && options.surface;
  if ((options.edge_correction || surface) &&
      completeStars<D>(dt, points, boundary, left_out, keep, threads, options.cancel_check)) {
    finite.clear();
    for (const auto s : finiteSimplices<D>(dt)) finite.push_back(s);
  }
  RegionMeasure result;
  result.uncorrected = keptTotal<D>(finite, boundingMeasure(points, D), threads);
  result.points = points.size();
  result.triangulated = dt.number_of_vertices();
  result.boundary_vertices = boundary.size();
  if (options.edge_correction) {
    if (options.phase) options.phase("edge correction");
    result.outside = outsideByStar<D>(dt, boundary, spacing, alpha_factor, threads, nullptr,
                                      options.cancel_check);
  }
  if constexpr (D == 3) {
    if (surface) {
      if (options.phase) options.phase("surface");
      result.surface_is_manifold =
          repairShellSurface(dt, points, left_out, keep, threads, options.cancel_check);
      result.surface = keptSurface(dt, points, options.cancel_check);
    }
  }
  return result;
}

template RegionMeasure measureShell<2, CGAL::Sequential_tag>(const pcl::PointCloud<pcl::PointXYZ>&,
                                                             const std::vector<double>&,
                                                             const MeasureOptions&);
template RegionMeasure measureShell<3, CGAL::Sequential_tag>(const pcl::PointCloud<pcl::PointXYZ>&,
                                                             const std::vector<double>&,
                                                             const MeasureOptions&);
template RegionMeasure measureShell<3, CGAL::Parallel_tag>(const pcl::PointCloud<pcl::PointXYZ>&,
                                                           const std::vector<double>&,
                                                           const MeasureOptions&);

}  // namespace mcws::detail
