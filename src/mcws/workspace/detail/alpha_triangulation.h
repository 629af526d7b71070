#pragma once
/// \file
/// \brief The machinery of delaunayMeasure() (measure.h) that its parts share: CGAL's Delaunay
/// triangulations of a cloud in 2-D and 3-D, the alpha test of a simplex, the order-free sum of
/// the kept simplices, the boundary vertices and the leave-one-out count from a vertex's star.
/// Private to mcws_workspace (namespace mcws::detail).

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_lock_grid_3.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "mcws/core/cancel_check.h"
#include "mcws/core/decimal.h"
#include "mcws/core/error.h"
#include "mcws/core/first_error.h"
#include "mcws/workspace/detail/cancel_pacing.h"
#include "mcws/workspace/detail/star_locate.h"

namespace mcws::detail {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

/// Cells per side of the lock grid of the parallel 3-D triangulation (CGAL's examples use 50).
constexpr int kLockGridCells = 50;
/// Points per piece of an insertion that checks for cancelling between its pieces, well under a
/// second of work on a loaded machine: a sequential triangulation's (points inserted one at a time
/// from the last one's place, as CGAL's range insertion does), and a parallel one's (each piece a
/// parallel range insertion). A 2 x 10^5-point ball's shell, about 46000 points, is one piece,
/// inserted in one call as without the check.
constexpr std::size_t kInsertPiece = 65536;
constexpr std::size_t kParallelInsertPiece = 65536;
/// Simplices between two checks for cancelling in a loop over the triangulation.
constexpr unsigned kCancelStride = 65536;
/// Boundary vertices between two checks for cancelling in the leave-one-out count (a small
/// triangulation of each one's star: tens of microseconds).
constexpr unsigned kStarCancelStride = 512;

/// A simplex's vertex points in the order of their indices (the vertex info), so that what is
/// computed from them does not depend on how the triangulation happens to store the simplex
/// (which differs with the thread count of a parallel triangulation).
template <int D, typename Simplex>
auto canonicalPoints(const Simplex& s) {
  std::array<std::pair<std::uint32_t, int>, D + 1> order;
  for (int k = 0; k <= D; ++k) order[k] = {s->vertex(k)->info(), k};
  // Insertion sort: D + 1 pairs, all different (by k), so the order std::sort would give.
  for (int a = 1; a <= D; ++a) {
    const auto next = order[a];
    int b = a;
    for (; b > 0 && next < order[b - 1]; --b) order[b] = order[b - 1];
    order[b] = next;
  }
  std::array<typename std::decay_t<decltype(s->vertex(0)->point())>, D + 1> p;
  for (int k = 0; k <= D; ++k) p[k] = s->vertex(order[k].second)->point();
  return p;
}

/// Whether the circumradius of a triangle (D = 2) or tetrahedron (D = 3), its vertex points `p`
/// in the order of their indices, is at most `limit`.
template <int D, typename Points>
bool withinLimit(const Points& p, double limit) {
  if constexpr (D == 2) {
    return CGAL::squared_radius(p[0], p[1], p[2]) <= limit * limit;
  } else {
    return CGAL::squared_radius(p[0], p[1], p[2], p[3]) <= limit * limit;
  }
}

/// Whether a triangle (D = 2) or tetrahedron (D = 3) belongs to the region: its circumradius is
/// at most `alpha_factor` times the local spacing at its sparsest vertex.
template <int D, typename Simplex>
bool withinAlpha(const Simplex& s, const std::vector<double>& spacing, double alpha_factor) {
  double local = 0.0;
  for (int k = 0; k <= D; ++k) local = std::max(local, spacing[s->vertex(k)->info()]);
  return withinLimit<D>(canonicalPoints<D>(s), alpha_factor * local);
}

/// Area of a triangle (D = 2) or volume of a tetrahedron (D = 3).
template <int D, typename Simplex>
double simplexMeasure(const Simplex& s) {
  const auto p = canonicalPoints<D>(s);
  if constexpr (D == 2) {
    return std::abs(CGAL::area(p[0], p[1], p[2]));
  } else {
    return std::abs(CGAL::volume(p[0], p[1], p[2], p[3]));
  }
}

/// A sum of non-negative terms that does not depend on their order (a parallel triangulation
/// lists its simplices in an order that depends on the thread count): each term is rounded to a
/// multiple of 2^-61 of a bound on the total (the bounding box's area or volume) and the
/// multiples add exactly as integers. The rounding, at most 2^-62 of the bound per term, is far
/// below what adding doubles loses over millions of terms.
class OrderFreeSum {
 public:
  explicit OrderFreeSum(double bound) : shift_(0) {
    if (!(bound > 0.0 && std::isfinite(bound))) {
      throw Error("the bound of a sum must be a positive number, got " + formatNumber(bound));
    }
    shift_ = 61 - std::ilogb(bound);
  }
  void add(double term) { total_ += std::llround(std::ldexp(term, shift_)); }
  /// Takes off a term added before (exactly: the same multiple).
  void subtract(double term) { total_ -= std::llround(std::ldexp(term, shift_)); }
  /// Adds another sum of the same bound (partial sums of threads).
  void add(const OrderFreeSum& other) { total_ += other.total_; }
  /// A sum of nothing with this one's bound.
  OrderFreeSum empty() const {
    OrderFreeSum zero = *this;
    zero.total_ = 0;
    return zero;
  }
  double value() const { return std::ldexp(static_cast<double>(total_), -shift_); }

 private:
  int shift_;
  __int128 total_{0};
};

/// Area (D = 2) or volume (D = 3) of the points' bounding box.
inline double boundingMeasure(const pcl::PointCloud<pcl::PointXYZ>& points, int dimensions) {
  Eigen::Array3d lo = Eigen::Array3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& p : points) {
    const Eigen::Array3d q(p.x, p.y, p.z);
    lo = lo.min(q);
    hi = hi.max(q);
  }
  const Eigen::Array3d extent = hi - lo;
  return dimensions == 2 ? extent[0] * extent[1] : extent.prod();
}

/// The types that differ between an area (D = 2: triangles, CGAL's faces) and a volume (D = 3:
/// tetrahedra, CGAL's cells); the measuring below is written once over D. `Concurrency` chooses
/// CGAL's parallel (CGAL::Parallel_tag, TBB) or sequential 3-D triangulation; the 2-D
/// triangulation is always sequential. Vertex info: the point's index; simplex info: 1 for a kept
/// simplex, 0 for a dropped one. `Local`: the small triangulation of one vertex's neighbours
/// (LeaveOneOut::kStar).
template <int D, typename Concurrency = CGAL::Sequential_tag>
struct Simplices;

template <typename Concurrency>
struct Simplices<2, Concurrency> {
  using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Kernel>;
  using Delaunay = CGAL::Delaunay_triangulation_2<
      Kernel, CGAL::Triangulation_data_structure_2<
                  VertexBase, CGAL::Triangulation_face_base_with_info_2<char, Kernel>>>;
  using Local =
      CGAL::Delaunay_triangulation_2<Kernel, CGAL::Triangulation_data_structure_2<VertexBase>>;
};

/// The parallel 3-D triangulation's lock grid: a thread that finds a cell locked gives up the
/// point and takes it again later (CGAL::Tag_non_blocking) instead of waiting when it has the
/// lower priority (CGAL's default, CGAL::Tag_priority_blocking). On the shell of the 10^6-point
/// ball (1.4 x 10^5 points), 2 threads: 0.29-0.32 s in every run, against 0.29 s to 1.2 s waiting.
/// The triangulation is the same (CGAL's symbolic perturbation makes it unique).
template <typename Concurrency>
using LockGrid =
    std::conditional_t<std::is_same_v<Concurrency, CGAL::Parallel_tag>,
                       CGAL::Spatial_lock_grid_3<CGAL::Tag_non_blocking>, CGAL::Default>;

template <typename Concurrency>
struct Simplices<3, Concurrency> {
  using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, Kernel>;
  using Delaunay = CGAL::Delaunay_triangulation_3<
      Kernel,
      CGAL::Triangulation_data_structure_3<
          VertexBase, CGAL::Triangulation_cell_base_with_info_3<char, Kernel>, Concurrency>,
      CGAL::Default, LockGrid<Concurrency>>;
  using Local =
      CGAL::Delaunay_triangulation_3<Kernel, CGAL::Triangulation_data_structure_3<VertexBase>>;
};

/// A handle of a triangle (D = 2) or tetrahedron (D = 3) of a triangulation.
template <int D, typename Delaunay>
struct SimplexOf {
  using Handle = typename Delaunay::Face_handle;
};
template <typename Delaunay>
struct SimplexOf<3, Delaunay> {
  using Handle = typename Delaunay::Cell_handle;
};

/// Every triangle (D = 2) or tetrahedron (D = 3) of `dt`, the infinite ones included.
template <int D, typename Delaunay>
auto allSimplices(const Delaunay& dt) {
  if constexpr (D == 2) {
    return dt.all_face_handles();
  } else {
    return dt.all_cell_handles();
  }
}

/// The finite triangles (D = 2) or tetrahedra (D = 3) of `dt`.
template <int D, typename Delaunay>
auto finiteSimplices(const Delaunay& dt) {
  if constexpr (D == 2) {
    return dt.finite_face_handles();
  } else {
    return dt.finite_cell_handles();
  }
}

/// The cells around vertex v of a 3-D triangulation, the infinite ones included: the cells CGAL's
/// incident_cells_threadsafe() lists (in another order), found by a walk from v's cell across the
/// facets through v, each cell reached looked up among those found: in a small table on the
/// stack (open addressing) while the star has at most kStarTable / 2 cells (a star has a few
/// dozen), else in `out` itself; no hash set to allocate, as CGAL's has. Read-only, so threads
/// may call it at once.
template <typename Delaunay>
void starCells(const Delaunay& dt, typename Delaunay::Vertex_handle v,
               std::vector<typename Delaunay::Cell_handle>& out) {
  out.clear();
  if (dt.dimension() < 3) {
    dt.incident_cells_threadsafe(v, std::back_inserter(out));
    return;
  }
  constexpr std::size_t kStarTable = 256;  // 2^8: the top 8 bits of the hash below
  std::array<const void*, kStarTable> table{};
  // Whether c was found before; records it when not.
  const auto seen = [&](const typename Delaunay::Cell_handle& c) {
    const void* key = &*c;
    if (out.size() > kStarTable / 2) return std::find(out.begin(), out.end(), c) != out.end();
    auto slot = static_cast<std::size_t>(
        (reinterpret_cast<std::uintptr_t>(key) >> 4) * 0x9E3779B97F4A7C15ull >> 56);
    for (; table[slot] != nullptr; slot = (slot + 1) % kStarTable) {
      if (table[slot] == key) return true;
    }
    table[slot] = key;
    return false;
  };
  seen(v->cell());
  out.push_back(v->cell());
  for (std::size_t head = 0; head < out.size(); ++head) {
    const auto c = out[head];
    for (int i = 0; i < 4; ++i) {
      if (c->vertex(i) == v) continue;  // the facet opposite v leaves the star
      const auto next = c->neighbor(i);
      if (!seen(next)) out.push_back(next);
    }
  }
}

/// The vertices that share an edge with v, the infinite one included, appended to `out` (in 3-D
/// from v's star cells, found into `cells`); the first D of them make a simplex with v (2-D: two
/// neighbours in turn around v; 3-D: v's cell's other vertices). Read-only, so threads may call
/// it at once.
template <int D, typename Delaunay, typename Cells>
void adjacentVertices(const Delaunay& dt, typename Delaunay::Vertex_handle v,
                      std::vector<typename Delaunay::Vertex_handle>& out, Cells& cells) {
  if constexpr (D == 2) {
    auto u = dt.incident_vertices(v), done = u;
    do {
      out.push_back(u);
    } while (++u != done);
  } else {
    starCells(dt, v, cells);
    const std::size_t first = out.size();
    // Each vertex once: looked up in a small table on the stack (open addressing) while there
    // are at most kTable / 2 of them (a star has a few dozen), else in `out` itself.
    constexpr std::size_t kTable = 128;  // 2^7: the top 7 bits of the hash below
    std::array<const void*, kTable> table{};
    for (const auto& c : cells) {
      for (int k = 0; k < 4; ++k) {
        const auto u = c->vertex(k);
        if (u == v) continue;
        if (out.size() - first > kTable / 2) {
          if (std::find(out.begin() + first, out.end(), u) == out.end()) out.push_back(u);
          continue;
        }
        const void* key = &*u;
        auto slot = static_cast<std::size_t>(
            (reinterpret_cast<std::uintptr_t>(key) >> 4) * 0x9E3779B97F4A7C15ull >> 57);
        for (; table[slot] != nullptr && table[slot] != key; slot = (slot + 1) % kTable) {
        }
        if (table[slot] == key) continue;
        table[slot] = key;
        out.push_back(u);
      }
    }
  }
}

/// Inserts input[begin, end) (points with their indices, sorted along a Hilbert curve) one at a
/// time, each located from the vertex inserted before it (`last`), as CGAL's sequential range
/// insertion does after its own sort.
template <typename Delaunay, typename Input>
void insertSorted(Delaunay& dt, const Input& input, std::size_t begin, std::size_t end,
                  typename Delaunay::Vertex_handle& last) {
  using Vertex = typename Delaunay::Vertex_handle;
  for (std::size_t i = begin; i < end; ++i) {
    if constexpr (Delaunay::Point::Ambient_dimension::value == 2) {
      const Vertex v = dt.insert(
          input[i].first, last != Vertex() ? last->face() : typename Delaunay::Face_handle());
      if (v != Vertex()) {
        v->info() = input[i].second;
        last = v;
      }
    } else {
      last = dt.insert(input[i].first, last);
      if (last != Vertex()) last->info() = input[i].second;
    }
  }
}

/// Inserts the points, each with its index, into `dt`: in one call (CGAL's range insertion: a
/// spatial sort, then each point located from the one before), or with `cancel_check` set and
/// more points than a piece holds, in pieces with a check before each (the Delaunay
/// triangulation does not depend on the order its points come in). A sequential triangulation
/// then sorts the points once along a Hilbert curve (CGAL::spatial_sort, as CGAL sorts the points
/// of one call) and inserts them as CGAL's range insertion does, checking every kInsertPiece
/// points: the same work as one call. A parallel triangulation (`Concurrency` =
/// CGAL::Parallel_tag) inserts spatially sorted points on TBB's threads, each locking the cells
/// of a grid over the points' bounding box: there each piece of kParallelInsertPiece points is
/// one range insertion.
template <typename Concurrency, typename Delaunay, typename Input>
void insertPoints(Delaunay& dt, Input& input, const CancelCheck& cancel_check) {
  constexpr bool kParallel = std::is_same_v<Concurrency, CGAL::Parallel_tag>;
  const std::size_t piece = kParallel ? kParallelInsertPiece : kInsertPiece;
  const auto insert = [&] {
    if (!cancel_check || input.size() <= piece) {
      if (cancel_check) cancel_check();
      dt.insert(input.begin(), input.end());
      return;
    }
    using Pair = typename Input::value_type;
    using Position = CGAL::First_of_pair_property_map<Pair>;
    if constexpr (Delaunay::Point::Ambient_dimension::value == 2) {
      CGAL::spatial_sort(input.begin(), input.end(),
                         CGAL::Spatial_sort_traits_adapter_2<Kernel, Position>());
    } else {
      CGAL::spatial_sort(input.begin(), input.end(),
                         CGAL::Spatial_sort_traits_adapter_3<Kernel, Position>());
    }
    [[maybe_unused]] typename Delaunay::Vertex_handle last;
    for (std::size_t begin = 0; begin < input.size(); begin += piece) {
      cancel_check();
      const std::size_t end = std::min(input.size(), begin + piece);
      if constexpr (kParallel) {
        dt.insert(input.begin() + begin, input.begin() + end);
      } else {
        insertSorted(dt, input, begin, end, last);
      }
    }
  };
  if constexpr (kParallel) {
    CGAL::Bbox_3 box;
    for (const auto& item : input) box += item.first.bbox();
    typename Delaunay::Lock_data_structure locks(box, kLockGridCells);
    dt.set_lock_data_structure(&locks);
    try {
      insert();
    } catch (...) {
      dt.set_lock_data_structure(nullptr);  // the locks end with this scope
      throw;
    }
    dt.set_lock_data_structure(nullptr);  // what follows only reads
  } else {
    insert();
  }
}

/// Flags every simplex of `dt` kept (info 1: finite and within the alpha limit) or dropped
/// (info 0) and returns the kept simplices' total area or volume, summed order-free within the
/// points' bounding box. `cancel_check` (when set) is called every kCancelStride simplices.
template <int D, typename Delaunay>
double keepWithinAlpha(Delaunay& dt, const pcl::PointCloud<pcl::PointXYZ>& points,
                       const std::vector<double>& spacing, double alpha_factor,
                       const CancelCheck& cancel_check = {}) {
  OrderFreeSum kept(boundingMeasure(points, D));
  for (const auto s : allSimplices<D>(dt)) s->info() = 0;
  CancelPacer pacer(cancel_check, kCancelStride);
  for (const auto s : finiteSimplices<D>(dt)) {
    pacer.step();
    if (withinAlpha<D>(s, spacing, alpha_factor)) {
      s->info() = 1;
      kept.add(simplexMeasure<D>(s));
    }
  }
  return kept.value();
}

/// The vertices between kept and dropped simplices (info 1 and 0; the infinite ones are dropped),
/// in the triangulation's vertex order. A vertex has both kinds around it exactly when some facet
/// through it separates a kept simplex from a dropped one (its star is connected through such
/// facets), so one pass over the kept simplices' facets finds them all.
template <int D, typename Delaunay>
std::vector<typename Delaunay::Vertex_handle> boundaryVertices(const Delaunay& dt,
                                                               std::size_t points) {
  std::vector<char> on_boundary(points, 0);  // by vertex info, the point's index
  for (const auto s : finiteSimplices<D>(dt)) {
    if (!s->info()) continue;
    for (int i = 0; i <= D; ++i) {
      if (s->neighbor(i)->info()) continue;
      for (int j = 0; j <= D; ++j) {
        if (j != i) on_boundary[s->vertex(j)->info()] = 1;  // the facet opposite vertex i
      }
    }
  }
  std::vector<typename Delaunay::Vertex_handle> boundary;
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
    if (on_boundary[v->info()]) boundary.push_back(v);
  }
  return boundary;
}

/// Whether `p` lies in the region of the points of `dt`: in a finite simplex within the alpha
/// limit. Where the points span only a line (2-D) or a plane (3-D), no simplex holds p.
template <int D, typename Delaunay>
bool inRegion(const Delaunay& dt, const typename Delaunay::Point& p,
              const std::vector<double>& spacing, double alpha_factor) {
  if (dt.dimension() < D) return false;
  const auto s = dt.locate(p);
  return !dt.is_infinite(s) && withinAlpha<D>(s, spacing, alpha_factor);
}

/// Whether point `p` of vertex v, not on the convex hull, lies outside the region of the other
/// points, from v's `neighbours` (adjacentVertices(): the first D of them with v make a simplex
/// of v's star): the simplex of the Delaunay triangulation of the neighbours that holds p (the
/// simplex of the others' triangulation that holds it, outsideByStar()) is not within the alpha
/// limit. With `shortcut`, that simplex comes from starSimplex() when it gives one, without the
/// neighbours' triangulation; else (or without `shortcut`) from that triangulation (`Local`),
/// built from the neighbours sorted by index, as located there. The same answer either way:
/// where p lies strictly inside a simplex whose circumsphere holds no other neighbour, that
/// simplex is the triangulation's and the one it locates. `points`, `star`: scratch space.
template <int D, typename Vertex, typename Point>
bool outsideOfNeighbours(const Point& p, const std::vector<Vertex>& neighbours,
                         const std::vector<double>& spacing, double alpha_factor, bool shortcut,
                         std::vector<Point>& points,
                         std::vector<std::pair<Point, std::uint32_t>>& star) {
  std::array<int, D + 1> simplex;
  std::array<int, D> start;
  for (int j = 0; j < D; ++j) start[j] = j;
  if (shortcut && neighbours.size() > static_cast<std::size_t>(D)) {
    points.clear();
    for (const auto& u : neighbours) points.push_back(u->point());
    if (starSimplex<D>(p, points, start, simplex)) {
      std::array<std::pair<std::uint32_t, int>, D + 1> order;
      for (int k = 0; k <= D; ++k) order[k] = {neighbours[simplex[k]]->info(), simplex[k]};
      std::sort(order.begin(), order.end());
      std::array<Point, D + 1> q;
      double local = 0.0;
      for (int k = 0; k <= D; ++k) {
        q[k] = points[order[k].second];
        local = std::max(local, spacing[order[k].first]);
      }
      return !withinLimit<D>(q, alpha_factor * local);
    }
  }
  star.clear();
  for (const auto& u : neighbours) star.emplace_back(u->point(), u->info());
  std::sort(star.begin(), star.end(),
            [](const auto& a, const auto& b) { return a.second < b.second; });
  const typename Simplices<D>::Local local(star.begin(), star.end());
  return !inRegion<D>(local, p, spacing, alpha_factor);
}

// Leave one out from the star (LeaveOneOut::kStar). Removing a vertex v from a Delaunay
// triangulation changes only its star: the hole is filled by the part of the Delaunay
// triangulation of v's neighbours that lies in it (Devillers, "On deletion in Delaunay
// triangulations", 1999). v's point lies in its own star, so the simplex that holds it once v
// is gone is the simplex of that small triangulation that holds it; a vertex on the convex hull
// lies outside the hull of the others. Each vertex is read-only work on the big triangulation,
// so the vertices are shared among threads; the count does not depend on their number. The
// neighbours are sorted by index before the small triangulation is built: a parallel
// triangulation lists them in an order that depends on the thread count, and where v's point
// lies exactly on a facet of the small triangulation (lattice data), the simplex `locate`
// returns depends on how that triangulation was built. Most vertices need no small
// triangulation (outsideOfNeighbours(), `shortcut`; without it, every vertex builds one).
/// With `flags` (one per point, by vertex info), also flags each vertex counted. `cancel_check`
/// (when set) is called on the calling thread every kStarCancelStride of its vertices.
template <int D, typename Delaunay>
std::size_t outsideByStar(const Delaunay& dt,
                          const std::vector<typename Delaunay::Vertex_handle>& boundary,
                          const std::vector<double>& spacing, double alpha_factor, int threads,
                          std::vector<char>* flags = nullptr, const CancelCheck& cancel_check = {},
                          bool shortcut = true) {
  std::size_t outside = 0;
  FirstError error;  // running out of memory or cancelling leaves the parallel region through it
#pragma omp parallel num_threads(threads) reduction(+ : outside)
  {
    std::vector<typename Delaunay::Vertex_handle> neighbours;
    std::vector<typename SimplexOf<D, Delaunay>::Handle> cells;  // 3-D: the star's
    std::vector<typename Delaunay::Point> points;
    std::vector<std::pair<typename Delaunay::Point, std::uint32_t>> star;
    CancelPacer pacer = callingThreadPacer(cancel_check, kStarCancelStride);
#pragma omp for schedule(dynamic, 256)
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(boundary.size()); ++i) {
      error.run(i, [&] {
        pacer.step();
        const auto v = boundary[i];
        neighbours.clear();
        adjacentVertices<D>(dt, v, neighbours, cells);
        const bool out = std::any_of(neighbours.begin(), neighbours.end(),
                                     [&](const auto& u) { return dt.is_infinite(u); }) ||
                         outsideOfNeighbours<D>(v->point(), neighbours, spacing, alpha_factor,
                                                shortcut, points, star);
        outside += out;  // on the convex hull, or outside the others' region
        if (flags && out) (*flags)[v->info()] = 1;
      });
    }
  }
  error.rethrow();
  return outside;
}

/// Triangulates the points whose flag in `take` is set (all of them when `take` is empty), each
/// vertex carrying its point's index in `points`; `cancel_check` as insertPoints().
template <int D, typename Concurrency, typename Delaunay>
void triangulate(Delaunay& dt, const pcl::PointCloud<pcl::PointXYZ>& points,
                 const std::vector<char>& take, const CancelCheck& cancel_check = {}) {
  std::vector<std::pair<typename Delaunay::Point, std::uint32_t>> input;
  input.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!take.empty() && !take[i]) continue;
    const pcl::PointXYZ& p = points[i];
    if constexpr (D == 2) {
      input.emplace_back(typename Delaunay::Point(p.x, p.y), static_cast<std::uint32_t>(i));
    } else {
      input.emplace_back(typename Delaunay::Point(p.x, p.y, p.z), static_cast<std::uint32_t>(i));
    }
  }
  insertPoints<Concurrency>(dt, input, cancel_check);
  if (dt.dimension() < D) {
    throw Error(D == 2 ? "the points lie on a line: no area"
                       : "the points lie in a plane: no volume");
  }
}

}  // namespace mcws::detail
