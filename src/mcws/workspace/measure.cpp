#include "mcws/workspace/measure.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <omp.h>
#include <tbb/global_control.h>

#include <nanoflann.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <numeric>
#include <sstream>
#include <type_traits>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/points/unique_positions.h"
#include "mcws/workspace/exposed_points.h"
#include "mcws/workspace/nearest_neighbours.h"

namespace mcws {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
constexpr int kNeighbour = 8;
/// Cells per side of the lock grid of the parallel 3-D triangulation (CGAL's examples use 50).
constexpr int kLockGridCells = 50;
/// More points outside the others' region than this share: the cloud is too small to estimate
/// the band it misses (a uniform cloud of 100 points in a disk has about 15 %).
constexpr double kLargestMissingShare = 0.5;

/// Local spacing at every point: distance to the k-th nearest neighbour over its mean for a
/// uniform cloud of mean spacing 1, sqrt(k / pi) in 2-D and (3k / (4 pi))^(1/3) in 3-D.
std::vector<double> localSpacing(const pcl::PointCloud<pcl::PointXYZ>& cloud, int dimensions,
                                 int threads) {
  const double scale =
      dimensions == 2 ? std::sqrt(kNeighbour / M_PI) : std::cbrt(3.0 * kNeighbour / (4.0 * M_PI));
  const std::vector<float> d2 = kthNeighbourSquaredDistance(cloud, dimensions, kNeighbour, threads);
  std::vector<double> spacing(d2.size());
  for (std::size_t i = 0; i < d2.size(); ++i) {
    spacing[i] = std::sqrt(static_cast<double>(d2[i])) / scale;
  }
  return spacing;
}

/// A simplex's vertex points in the order of their indices (the vertex info), so that what is
/// computed from them does not depend on how the triangulation happens to store the simplex
/// (which differs with the thread count of a parallel triangulation).
template <int D, typename Simplex>
auto canonicalPoints(const Simplex& s) {
  std::array<std::pair<std::uint32_t, int>, D + 1> order;
  for (int k = 0; k <= D; ++k) order[k] = {s->vertex(k)->info(), k};
  std::sort(order.begin(), order.end());
  std::array<typename std::decay_t<decltype(s->vertex(0)->point())>, D + 1> p;
  for (int k = 0; k <= D; ++k) p[k] = s->vertex(order[k].second)->point();
  return p;
}

/// Whether a triangle (D = 2) or tetrahedron (D = 3) belongs to the region: its circumradius is
/// at most `alpha_factor` times the local spacing at its sparsest vertex.
template <int D, typename Simplex>
bool withinAlpha(const Simplex& s, const std::vector<double>& spacing, double alpha_factor) {
  double local = 0.0;
  for (int k = 0; k <= D; ++k) local = std::max(local, spacing[s->vertex(k)->info()]);
  const double limit = alpha_factor * local;
  const auto p = canonicalPoints<D>(s);
  if constexpr (D == 2) {
    return CGAL::squared_radius(p[0], p[1], p[2]) <= limit * limit;
  } else {
    return CGAL::squared_radius(p[0], p[1], p[2], p[3]) <= limit * limit;
  }
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
      throw Error("the bound of a sum must be a positive number, got " + std::to_string(bound));
    }
    shift_ = 61 - std::ilogb(bound);
  }
  void add(double term) { total_ += std::llround(std::ldexp(term, shift_)); }
  /// Adds another sum of the same bound (partial sums of threads).
  void add(const OrderFreeSum& other) { total_ += other.total_; }
  double value() const { return std::ldexp(static_cast<double>(total_), -shift_); }

 private:
  int shift_;
  __int128 total_{0};
};

/// Area (D = 2) or volume (D = 3) of the points' bounding box.
double boundingMeasure(const pcl::PointCloud<pcl::PointXYZ>& points, int dimensions) {
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
  using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, K>;
  using Delaunay = CGAL::Delaunay_triangulation_2<
      K, CGAL::Triangulation_data_structure_2<VertexBase,
                                              CGAL::Triangulation_face_base_with_info_2<char, K>>>;
  using Local = CGAL::Delaunay_triangulation_2<K, CGAL::Triangulation_data_structure_2<VertexBase>>;
};

template <typename Concurrency>
struct Simplices<3, Concurrency> {
  using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, K>;
  using Delaunay = CGAL::Delaunay_triangulation_3<
      K, CGAL::Triangulation_data_structure_3<
             VertexBase, CGAL::Triangulation_cell_base_with_info_3<char, K>, Concurrency>>;
  using Local = CGAL::Delaunay_triangulation_3<K, CGAL::Triangulation_data_structure_3<VertexBase>>;
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

/// The vertices that share an edge with v, the infinite one included. Read-only (in 3-D without
/// CGAL's visit flags), so threads may call it at once.
template <int D, typename Delaunay>
void adjacentVertices(const Delaunay& dt, typename Delaunay::Vertex_handle v,
                      std::vector<typename Delaunay::Vertex_handle>& out) {
  if constexpr (D == 2) {
    auto u = dt.incident_vertices(v), done = u;
    do {
      out.push_back(u);
    } while (++u != done);
  } else {
    dt.adjacent_vertices_threadsafe(v, std::back_inserter(out));
  }
}

/// Inserts the points, each with its index, into `dt`. A parallel triangulation
/// (`Concurrency` = CGAL::Parallel_tag) inserts spatially sorted points on TBB's threads, each
/// locking the cells of a grid over the points' bounding box.
template <typename Concurrency, typename Delaunay, typename Input>
void insertPoints(Delaunay& dt, const Input& input) {
  if constexpr (std::is_same_v<Concurrency, CGAL::Parallel_tag>) {
    CGAL::Bbox_3 box;
    for (const auto& item : input) box += item.first.bbox();
    typename Delaunay::Lock_data_structure locks(box, kLockGridCells);
    dt.set_lock_data_structure(&locks);
    try {
      dt.insert(input.begin(), input.end());
    } catch (...) {
      dt.set_lock_data_structure(nullptr);  // the locks end with this scope
      throw;
    }
    dt.set_lock_data_structure(nullptr);  // what follows only reads
  } else {
    dt.insert(input.begin(), input.end());
  }
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

/// Rounds of filling around singular edges and vertices before fillForSurface() gives up (each
/// round fills every singularity it finds; two are usual).
constexpr int kFillRounds = 16;

/// Volume of a finite cell, infinite for an infinite one: the weight by which the repairs below
/// choose the part of a singularity to leave as it is (the largest, or the one open to the
/// outside).
template <typename Delaunay>
double cellWeight(const Delaunay& dt, typename Delaunay::Cell_handle c) {
  if (dt.is_infinite(c)) return std::numeric_limits<double>::infinity();
  return std::abs(CGAL::volume(c->vertex(0)->point(), c->vertex(1)->point(), c->vertex(2)->point(),
                               c->vertex(3)->point()));
}

/// The cells around vertex v (in `cells`) grouped by whether they are kept (info != 0), each
/// group connected through the facets through v; `group[a]` is cell a's group. The kept
/// region's boundary near v is one disk when there is at most one group of each kind.
template <typename Delaunay>
void fansAround(const Delaunay& dt, typename Delaunay::Vertex_handle v,
                std::vector<typename Delaunay::Cell_handle>& cells,
                std::vector<std::size_t>& group) {
  cells.clear();
  dt.incident_cells(v, std::back_inserter(cells));
  group.resize(cells.size());
  std::iota(group.begin(), group.end(), 0);
  auto root = [&](std::size_t a) {
    while (group[a] != a) a = group[a] = group[group[a]];
    return a;
  };
  for (std::size_t a = 0; a < cells.size(); ++a) {
    const int own = cells[a]->index(v);
    for (int i = 0; i < 4; ++i) {
      if (i == own) continue;  // the facet opposite v does not pass through it
      const auto n = cells[a]->neighbor(i);
      if ((n->info() != 0) != (cells[a]->info() != 0)) continue;
      const auto b = std::find(cells.begin(), cells.end(), n) - cells.begin();
      group[root(a)] = root(static_cast<std::size_t>(b));
    }
  }
  for (std::size_t a = 0; a < cells.size(); ++a) group[a] = root(a);
}

/// Of the groups of `cells` (by `group`) that are kept (`kept`) or dropped, all but the heaviest
/// by cellWeight(), appended to `out`. \return the number of such groups.
template <typename Delaunay>
std::size_t lighterGroups(const Delaunay& dt,
                          const std::vector<typename Delaunay::Cell_handle>& cells,
                          const std::vector<std::size_t>& group, bool kept,
                          std::vector<typename Delaunay::Cell_handle>& out) {
  std::vector<double> weight(cells.size(), 0.0);
  std::size_t groups = 0, heaviest = cells.size();
  for (std::size_t a = 0; a < cells.size(); ++a) {
    if ((cells[a]->info() != 0) != kept) continue;
    groups += group[a] == a;
    weight[group[a]] += cellWeight(dt, cells[a]);
  }
  for (std::size_t a = 0; a < cells.size(); ++a) {
    if ((cells[a]->info() != 0) != kept || group[a] != a) continue;
    if (heaviest == cells.size() || weight[a] > weight[heaviest]) heaviest = a;
  }
  if (groups > 1) {
    for (std::size_t a = 0; a < cells.size(); ++a) {
      if ((cells[a]->info() != 0) == kept && group[a] != heaviest) out.push_back(cells[a]);
    }
  }
  return groups;
}

/// Keeps (info 2) the dropped cells no path of dropped cells connects to the infinite ones.
template <typename Delaunay>
void fillCavities(Delaunay& dt) {
  using Cell = typename Delaunay::Cell_handle;
  constexpr char kOutside = 3;  // a dropped cell reached from the infinite ones
  std::vector<Cell> stack;
  for (const Cell c : dt.all_cell_handles()) {
    if (dt.is_infinite(c)) {
      c->info() = kOutside;
      stack.push_back(c);
    }
  }
  while (!stack.empty()) {
    const Cell c = stack.back();
    stack.pop_back();
    for (int i = 0; i < 4; ++i) {
      const Cell n = c->neighbor(i);
      if (n->info() == 0) {
        n->info() = kOutside;
        stack.push_back(n);
      }
    }
  }
  for (const Cell c : dt.all_cell_handles()) {
    c->info() = c->info() == 0 ? 2 : (c->info() == kOutside ? 0 : c->info());
  }
}

/// Makes the kept tetrahedra's boundary a closed 2-manifold, round by round, changing as little
/// volume as it can: cavities (dropped cells no path of dropped cells connects to the infinite
/// ones) are kept (info 2, fillCavities()); around an edge where the kept region touches itself
/// (several runs of kept cells) every run of dropped cells but the heaviest (the one open to the
/// outside, else the largest) is kept; around a vertex with several groups of dropped cells
/// likewise, and where several groups of kept cells meet at a vertex across one group of dropped
/// ones, every kept group but the largest is dropped. Each round decides from the flags as they
/// were at its start, so the result does not depend on the order the cells are listed in; a cell
/// one round fills is not dropped again. \return false when singularities remain after
/// kFillRounds rounds.
template <typename Delaunay>
bool fillForSurface(Delaunay& dt) {
  using Cell = typename Delaunay::Cell_handle;
  std::vector<Cell> around, fill, drop;
  std::vector<std::size_t> group;
  for (int round = 0; round < kFillRounds; ++round) {
    fillCavities(dt);
    fill.clear();
    drop.clear();
    std::vector<typename Delaunay::Vertex_handle> singular;
    for (const Cell c : dt.finite_cell_handles()) {
      if (!c->info()) continue;
      for (int i = 0; i < 4; ++i) {
        if (c->neighbor(i)->info()) continue;  // not a boundary facet
        for (int j = 0; j < 4; ++j) {
          if (j == i) continue;
          for (int k = j + 1; k < 4; ++k) {
            if (k == i) continue;
            // Around edge (j, k): a manifold boundary edge has one run of kept cells.
            auto circ = dt.incident_cells(c, j, k), done = circ;
            around.clear();
            do {
              around.push_back(circ);
            } while (++circ != done);
            const std::size_t n = around.size();
            std::size_t changes = 0, start = 0;
            for (std::size_t a = 0; a < n; ++a) {
              if ((around[a]->info() != 0) != (around[(a + 1) % n]->info() != 0)) {
                ++changes;
                if (around[(a + 1) % n]->info() == 0) start = (a + 1) % n;  // a dropped run
              }
            }
            if (changes <= 2) continue;
            group.assign(n, 0);
            for (std::size_t m = 0, run = start; m < n; ++m) {  // runs from a run's first cell
              const std::size_t a = (start + m) % n;
              if (m > 0 && (around[a]->info() != 0) != (around[(a + n - 1) % n]->info() != 0))
                run = a;
              group[a] = run;
            }
            lighterGroups(dt, around, group, false, fill);
          }
          singular.push_back(c->vertex(j));
        }
      }
    }
    // Vertices of the boundary whose kept (or dropped) cells around them form several fans.
    std::sort(singular.begin(), singular.end());
    singular.erase(std::unique(singular.begin(), singular.end()), singular.end());
    for (const auto v : singular) {
      fansAround(dt, v, around, group);
      if (lighterGroups(dt, around, group, false, fill) <= 1)
        lighterGroups(dt, around, group, true, drop);
    }
    fill.erase(
        std::remove_if(fill.begin(), fill.end(), [&](const Cell a) { return dt.is_infinite(a); }),
        fill.end());
    drop.erase(
        std::remove_if(drop.begin(), drop.end(), [](const Cell a) { return a->info() == 2; }),
        drop.end());
    if (fill.empty() && drop.empty()) return true;
    for (const Cell a : fill) a->info() = 2;
    for (const Cell a : drop) a->info() = 0;
  }
  return false;
}

/// The facets between kept and dropped tetrahedra (info 1 and 0; infinite cells are dropped),
/// each oriented away from its kept tetrahedron (exact orientation test), over the points of
/// `points` they use. Canonical order, whatever order the triangulation lists its cells in:
/// vertices by point index, each triangle rotated to start at its smallest vertex, triangles
/// sorted.
template <typename Delaunay>
TriangleSurface keptSurface(const Delaunay& dt, const pcl::PointCloud<pcl::PointXYZ>& points) {
  std::vector<std::array<std::uint32_t, 3>> facets;
  for (const auto c : dt.finite_cell_handles()) {
    if (!c->info()) continue;
    for (int i = 0; i < 4; ++i) {
      if (c->neighbor(i)->info()) continue;
      std::array<typename Delaunay::Vertex_handle, 3> v{
          c->vertex((i + 1) & 3), c->vertex((i + 2) & 3), c->vertex((i + 3) & 3)};
      // Outward: the kept cell's fourth vertex on the negative side of (a, b, c).
      if (CGAL::orientation(v[0]->point(), v[1]->point(), v[2]->point(), c->vertex(i)->point()) ==
          CGAL::POSITIVE) {
        std::swap(v[1], v[2]);
      }
      std::array<std::uint32_t, 3> t{v[0]->info(), v[1]->info(), v[2]->info()};
      std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
      facets.push_back(t);
    }
  }
  std::sort(facets.begin(), facets.end());
  TriangleSurface surface;
  std::vector<std::uint32_t> renumbered(points.size(), std::numeric_limits<std::uint32_t>::max());
  for (const auto& t : facets) {
    for (const std::uint32_t k : t) renumbered[k] = 0;
  }
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (renumbered[k] == 0) {
      renumbered[k] = static_cast<std::uint32_t>(surface.vertices.size());
      surface.vertices.emplace_back(points[k].x, points[k].y, points[k].z);
    }
  }
  surface.triangles.reserve(facets.size());
  for (const auto& t : facets) {
    surface.triangles.push_back({renumbered[t[0]], renumbered[t[1]], renumbered[t[2]]});
  }
  return surface;
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
// returns depends on how that triangulation was built.
template <int D, typename Delaunay>
std::size_t outsideByStar(const Delaunay& dt,
                          const std::vector<typename Delaunay::Vertex_handle>& boundary,
                          const std::vector<double>& spacing, double alpha_factor, int threads) {
  using Local = typename Simplices<D>::Local;
  std::size_t outside = 0;
#pragma omp parallel num_threads(threads) reduction(+ : outside)
  {
    std::vector<typename Delaunay::Vertex_handle> neighbours;
    std::vector<std::pair<typename Delaunay::Point, std::uint32_t>> star;
#pragma omp for schedule(dynamic, 256)
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(boundary.size()); ++i) {
      const auto v = boundary[i];
      neighbours.clear();
      adjacentVertices<D>(dt, v, neighbours);
      if (std::any_of(neighbours.begin(), neighbours.end(),
                      [&](const auto& u) { return dt.is_infinite(u); })) {
        ++outside;  // on the convex hull
        continue;
      }
      star.clear();
      for (const auto& u : neighbours) star.emplace_back(u->point(), u->info());
      std::sort(star.begin(), star.end(),
                [](const auto& a, const auto& b) { return a.second < b.second; });
      const Local local(star.begin(), star.end());
      outside += !inRegion<D>(local, v->point(), spacing, alpha_factor);
    }
  }
  return outside;
}

/// Leave one out by removal (LeaveOneOut::kRemoveAndReinsert): each boundary vertex is removed
/// from the triangulation, its point located among the others, and put back (one thread).
template <int D, typename Delaunay>
std::size_t outsideByRemoval(Delaunay& dt,
                             const std::vector<typename Delaunay::Vertex_handle>& boundary,
                             const std::vector<double>& spacing, double alpha_factor) {
  std::size_t outside = 0;
  for (const auto v : boundary) {
    const typename Delaunay::Point p = v->point();
    const std::uint32_t index = v->info();
    dt.remove(v);
    outside += !inRegion<D>(dt, p, spacing, alpha_factor);
    dt.insert(p)->info() = index;
  }
  return outside;
}

/// Triangulates the points whose flag in `take` is set (all of them when `take` is empty), each
/// vertex carrying its point's index in `points`.
template <int D, typename Concurrency, typename Delaunay>
void triangulate(Delaunay& dt, const pcl::PointCloud<pcl::PointXYZ>& points,
                 const std::vector<char>& take) {
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
  insertPoints<Concurrency>(dt, input);
  if (dt.dimension() < D) {
    throw Error(D == 2 ? "the points lie on a line: no area"
                       : "the points lie in a plane: no volume");
  }
}

/// The points left out of a shell triangulation (MeasureOptions::shell), in a kd-tree (nanoflann),
/// to tell the shell's simplices that are simplices of every point's triangulation (no left-out
/// point inside their circumsphere) from those that fill in for the left-out points. Points that
/// join the shell later are removed from the searches, not from the tree.
template <int D>
class LeftOut {
 public:
  LeftOut(const pcl::PointCloud<pcl::PointXYZ>& points, const std::vector<char>& in_shell)
      : slot_of_(points.size(), kNone),
        adaptor_{coordinates_},
        tree_(D, adaptor_, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (in_shell[i]) continue;
      slot_of_[i] = static_cast<std::uint32_t>(index_.size());
      coordinates_.push_back({points[i].x, points[i].y, points[i].z});
      index_.push_back(static_cast<std::uint32_t>(i));
    }
    removed_.assign(index_.size(), 0);
    tree_.buildIndex();
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
    // Slack for the float coordinates of the tree and the rounding of the centre.
    const double slack =
        1e-5 * (radius + std::max({std::abs(centre[0]), std::abs(centre[1]), std::abs(centre[2])}));
    const std::array<float, 3> query{static_cast<float>(centre[0]), static_cast<float>(centre[1]),
                                     static_cast<float>(centre[2])};
    Nearest nearest{removed_};
    tree_.findNeighbors(nearest, query.data(), nanoflann::SearchParams());
    if (!nearest.full()) return false;  // every left-out point has joined
    const double distance = std::sqrt(static_cast<double>(nearest.worstDist()));
    if (distance > radius + slack) return false;
    if (distance < radius - slack && !all) {
      if (found) found->push_back(index_[nearest.slot]);
      return true;
    }
    std::vector<std::pair<std::uint32_t, float>> near;
    const double reach = radius + slack;
    tree_.radiusSearch(query.data(), static_cast<float>(reach * reach), near,
                       nanoflann::SearchParams(32, 0.0f, false));
    bool any = false;
    for (const auto& [k, d2] : near) {
      if (removed_[k]) continue;
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
      if (!in) continue;
      any = true;
      if (found) found->push_back(index_[k]);
      if (!all) break;
    }
    return any;
  }

 private:
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  struct Adaptor {
    const std::vector<std::array<float, 3>>& points;
    std::size_t kdtree_get_point_count() const { return points.size(); }
    float kdtree_get_pt(std::size_t i, std::size_t axis) const { return points[i][axis]; }
    template <typename Box>
    bool kdtree_get_bbox(Box& /*box*/) const {
      return false;
    }
  };
  /// nanoflann result set: the nearest point not removed.
  struct Nearest {
    using DistanceType = float;
    using IndexType = std::uint32_t;
    const std::vector<char>& removed;
    float best{std::numeric_limits<float>::max()};
    std::uint32_t slot{kNone};
    bool full() const { return slot != kNone; }
    std::size_t size() const { return full() ? 1 : 0; }
    float worstDist() const { return best; }
    bool addPoint(float d2, std::uint32_t k) {
      if (!removed[k] && d2 < best) {
        best = d2;
        slot = k;
      }
      return true;
    }
  };
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Adaptor>,
                                                   Adaptor, D, std::uint32_t>;
  std::vector<std::array<float, 3>> coordinates_;
  std::vector<std::uint32_t> index_;    // the point's index in the whole cloud
  std::vector<std::uint32_t> slot_of_;  // the point's place in the tree, by its index
  std::vector<char> removed_;           // by place in the tree: joined the shell
  Adaptor adaptor_;
  Tree tree_;
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
    dt.incident_cells_threadsafe(v, std::back_inserter(out));
  }
  if (!infinite) {
    out.erase(
        std::remove_if(out.begin(), out.end(), [&](const auto& s) { return dt.is_infinite(s); }),
        out.end());
  }
}

/// The area (D = 2) or volume (D = 3) of the region from the triangulation of the points an empty
/// ball of alpha radius may touch (MeasureOptions::shell). A simplex the alpha test drops has an
/// empty circumball wider than the alpha radius at each of its vertices, so all its vertices are
/// exposed (exposedPoints()), and it is a simplex of the shell's triangulation too. The shell's
/// triangulation covers the same hull, so the kept total is its finite simplices' total less the
/// dropped ones: the shell's simplices with a left-out point in their circumsphere fill in for the
/// whole triangulation's simplices there, all kept, whatever their size. The boundary vertices are
/// the same; the leave-one-out test needs each one's star, which is the whole triangulation's when
/// none of the star's simplices has a left-out point in its circumsphere. Where one has (a few
/// dozen points of 10^6, where the shell is thinnest), those left-out points are inserted and the
/// simplices around them tested again, until no star has one.
template <int D, typename Concurrency = CGAL::Sequential_tag>
RegionMeasure measureShell(const pcl::PointCloud<pcl::PointXYZ>& points,
                           const std::vector<double>& spacing, const MeasureOptions& options) {
  using Delaunay = typename Simplices<D, Concurrency>::Delaunay;
  using Simplex = typename SimplexOf<D, Delaunay>::Handle;
  const double alpha_factor = options.alpha_factor;
  const int threads = options.threads;
  if (options.phase) options.phase("exposed points");
  std::vector<double> reach(spacing.size());
  for (std::size_t i = 0; i < spacing.size(); ++i) reach[i] = alpha_factor * spacing[i];
  const std::vector<char> in_shell = exposedPoints(points, D, reach, threads).exposed;
  reach = {};
  LeftOut<D> left_out(points, in_shell);
  if (options.phase) options.phase("triangulation");
  Delaunay dt;
  triangulate<D, Concurrency>(dt, points, in_shell);

  if (options.phase) options.phase("alpha test");
  // Kept (1): within the alpha limit, or filling in for left-out points; else dropped (0).
  const auto keep = [&](const Simplex& s) -> char {
    return withinAlpha<D>(s, spacing, alpha_factor) || left_out.inside(dt, s, false, nullptr);
  };
  std::vector<Simplex> finite;
  finite.reserve(D == 2 ? 2 * dt.number_of_vertices() : 7 * dt.number_of_vertices());
  for (const auto s : allSimplices<D>(dt)) {
    s->info() = 0;
    if (!dt.is_infinite(s)) finite.push_back(s);
  }
#pragma omp parallel for num_threads(threads) schedule(dynamic, 4096)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(finite.size()); ++i) {
    finite[i]->info() = keep(finite[i]);
  }
  // Joins below replace only kept simplices (a dropped one has no left-out point in its
  // circumsphere, and a simplex around a covered point is within its alpha limit), so the
  // boundary vertices are final.
  const auto boundary = boundaryVertices<D>(dt, points.size());
  std::vector<Simplex> around, stars;
  if (options.edge_correction) {
    // The kept simplices of the boundary vertices' stars, each once (a simplex is in the stars
    // of up to D + 1 vertices).
    for (const auto v : boundary) {
      incidentSimplices<D>(dt, v, around);
      for (const auto& s : around) {
        if (s->info()) stars.push_back(s);
      }
    }
    std::vector<char> on_boundary(points.size(), 0);
    for (const auto v : boundary) on_boundary[v->info()] = 1;
    for (;;) {
      // A star simplex with left-out points in its circumsphere is not the whole
      // triangulation's: those points join.
      std::sort(stars.begin(), stars.end());
      stars.erase(std::unique(stars.begin(), stars.end()), stars.end());
      std::vector<std::uint32_t> joining;
#pragma omp parallel num_threads(threads)
      {
        std::vector<std::uint32_t> found;
#pragma omp for schedule(dynamic, 1024)
        for (std::int64_t i = 0; i < static_cast<std::int64_t>(stars.size()); ++i) {
          left_out.inside(dt, stars[i], true, &found);
        }
#pragma omp critical
        joining.insert(joining.end(), found.begin(), found.end());
      }
      if (joining.empty()) break;
      std::sort(joining.begin(), joining.end());
      joining.erase(std::unique(joining.begin(), joining.end()), joining.end());
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
      // Insertion replaces simplices by new ones around the inserted points: test those, and
      // check next the new ones in a boundary vertex's star (the others were checked).
      stars.clear();
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
      finite.clear();  // some are gone
      for (const auto s : finiteSimplices<D>(dt)) finite.push_back(s);
    }
  }
  RegionMeasure result;
  const double bound = boundingMeasure(points, D);
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
  result.uncorrected = kept.value();
  result.points = points.size();
  result.triangulated = dt.number_of_vertices();
  result.boundary_vertices = boundary.size();
  if (options.edge_correction) {
    if (options.phase) options.phase("edge correction");
    result.outside = outsideByStar<D>(dt, boundary, spacing, alpha_factor, threads);
  }
  return result;
}

/// The area (D = 2) or volume (D = 3) of the region, on a triangulation built on all threads
/// (3-D with `Concurrency` = CGAL::Parallel_tag, TBB) or on one (CGAL::Sequential_tag, which the
/// remove-and-reinsert leave-one-out needs). CGAL breaks ties between cospherical points by a
/// symbolic perturbation, so the Delaunay triangulation is the same whatever the insertion order
/// and thread count, degenerate input included; what is summed over it does not depend on the
/// order its simplices are listed in.
template <int D, typename Concurrency = CGAL::Sequential_tag>
RegionMeasure measureRegion(const pcl::PointCloud<pcl::PointXYZ>& points,
                            const std::vector<double>& spacing, const MeasureOptions& options) {
  using Delaunay = typename Simplices<D, Concurrency>::Delaunay;
  const double alpha_factor = options.alpha_factor;
  if (options.phase) options.phase("triangulation");
  Delaunay dt;
  triangulate<D, Concurrency>(dt, points, {});

  if (options.phase) options.phase("alpha test");
  RegionMeasure result;
  OrderFreeSum kept(boundingMeasure(points, D));
  for (const auto s : allSimplices<D>(dt)) s->info() = 0;
  for (const auto s : finiteSimplices<D>(dt)) {
    if (withinAlpha<D>(s, spacing, alpha_factor)) {
      s->info() = 1;
      kept.add(simplexMeasure<D>(s));
    }
  }
  result.uncorrected = kept.value();
  const auto boundary = boundaryVertices<D>(dt, points.size());
  result.points = result.triangulated = dt.number_of_vertices();
  result.boundary_vertices = boundary.size();
  if (options.edge_correction) {
    if (options.phase) options.phase("edge correction");
    // A boundary vertex counts when its point lies outside the region of the others.
    result.outside = options.leave_one_out == LeaveOneOut::kStar
                         ? outsideByStar<D>(dt, boundary, spacing, alpha_factor, options.threads)
                         : outsideByRemoval<D>(dt, boundary, spacing, alpha_factor);
  }
  if constexpr (D == 3) {
    if (options.surface) {
      if (options.phase) options.phase("surface");
      result.surface_is_manifold = fillForSurface(dt);  // last: it changes the kept flags
      result.surface = keptSurface(dt, points);
    }
  }
  return result;
}

}  // namespace

RegionMeasure delaunayMeasure(const pcl::PointCloud<pcl::PointXYZ>& points, int dimensions,
                              double alpha_factor) {
  MeasureOptions options;
  options.alpha_factor = alpha_factor;
  return delaunayMeasure(points, dimensions, options);
}

RegionMeasure delaunayMeasure(const pcl::PointCloud<pcl::PointXYZ>& points, int dimensions,
                              const MeasureOptions& options) {
  const double alpha_factor = options.alpha_factor;
  if (dimensions != 2 && dimensions != 3) throw Error("dimensions must be 2 or 3");
  if (!(alpha_factor > 0.0 && std::isfinite(alpha_factor))) {
    std::ostringstream msg;
    msg << "alpha factor " << alpha_factor << " must be a positive number";
    throw Error(msg.str());
  }
  if (points.size() < static_cast<std::size_t>(dimensions + 1)) {
    throw Error("a region needs at least " + std::to_string(dimensions + 1) + " points, got " +
                std::to_string(points.size()));
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || (dimensions == 3 && !std::isfinite(p.z))) {
      throw Error("point " + std::to_string(i) + " has a non-finite coordinate");
    }
  }
  // One position per set of copies (CGAL would merge them anyway), so copies neither shrink the
  // local spacing nor count as points.
  std::vector<pcl::index_t> position_of;
  auto flat = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  if (dimensions == 2) {
    pcl::PointCloud<pcl::PointXYZ> projected = points;
    for (auto& p : projected) p.z = 0.0f;
    *flat = uniquePositions(projected, position_of);
  } else {
    *flat = uniquePositions(points, position_of);
  }
  position_of = {};
  if (options.phase) options.phase("local spacing");
  MeasureOptions resolved = options;
  resolved.threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  const std::vector<double> spacing = localSpacing(*flat, dimensions, resolved.threads);
  // CGAL's parallel triangulation runs on TBB's threads: at most as many as OpenMP's (TBB also
  // stops at the core count). The limit holds for the whole process while this call runs.
  const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism,
                                        static_cast<std::size_t>(resolved.threads));
  RegionMeasure result;
  const bool star = options.leave_one_out == LeaveOneOut::kStar;
  if (options.shell && star && !options.surface) {
    if (dimensions == 2) {
      result = measureShell<2>(*flat, spacing, resolved);
    } else if (resolved.threads > 1) {
      result = measureShell<3, CGAL::Parallel_tag>(*flat, spacing, resolved);
    } else {
      result = measureShell<3, CGAL::Sequential_tag>(*flat, spacing, resolved);
    }
  } else if (dimensions == 2) {
    result = measureRegion<2>(*flat, spacing, resolved);
  } else if (resolved.threads > 1 && star) {
    result = measureRegion<3, CGAL::Parallel_tag>(*flat, spacing, resolved);
  } else {
    result = measureRegion<3, CGAL::Sequential_tag>(*flat, spacing, resolved);
  }
  result.alpha_factor = alpha_factor;
  if (!(result.uncorrected > 0.0)) {
    throw Error(std::string("no ") + (dimensions == 2 ? "triangle" : "tetrahedron") +
                " passes the alpha limit: the points are (nearly) " +
                (dimensions == 2 ? "collinear" : "coplanar") + " or too sparse for alpha " +
                std::to_string(alpha_factor));
  }
  if (!options.edge_correction) {
    result.measure = result.uncorrected;
    return result;
  }
  const double missing = static_cast<double>(result.outside) / result.points;
  if (missing > kLargestMissingShare) {
    throw Error("too few points for the edge correction: " + std::to_string(result.outside) +
                " of " + std::to_string(result.points) + " lie outside the region of the others");
  }
  result.measure = result.uncorrected / (1.0 - missing);
  return result;
}

ColumnArea columnArea(const pcl::PointCloud<pcl::PointXYZ>& boundary, double width, double gap) {
  if (boundary.size() < 3) {
    throw Error("the column method needs at least 3 boundary points, got " +
                std::to_string(boundary.size()));
  }
  if (width < 0.0 || gap < 0.0 || !std::isfinite(width) || !std::isfinite(gap)) {
    throw Error("column width and gap must be 0 (automatic) or positive");
  }
  ColumnArea result;
  float min_x = boundary[0].x, max_x = boundary[0].x;
  for (const auto& p : boundary) {
    min_x = std::min(min_x, p.x);
    max_x = std::max(max_x, p.x);
  }
  if (width == 0.0) {
    // About sqrt(n) columns for n boundary points: each crossing then holds a few points, so no
    // column misses a side, and columns stay narrow next to the region.
    width = (max_x - min_x) / std::sqrt(static_cast<double>(boundary.size()));
    if (!(width > 0.0)) throw Error("the boundary points have no extent in x: no columns");
  }
  if (gap == 0.0) gap = 3.0 * width;
  result.width = width;
  result.gap = gap;

  std::vector<std::pair<std::int64_t, float>> cells;  // (column, y)
  cells.reserve(boundary.size());
  for (const auto& p : boundary) {
    cells.emplace_back(static_cast<std::int64_t>((p.x - min_x) / width), p.y);
  }
  std::sort(cells.begin(), cells.end());
  for (std::size_t begin = 0; begin < cells.size();) {
    std::size_t end = begin;
    while (end < cells.size() && cells[end].first == cells[begin].first) ++end;
    // Crossings of this column: (lowest y, highest y, mean y).
    struct Crossing {
      double low, high, sum;
      std::size_t count;
    };
    std::vector<Crossing> crossings;
    for (std::size_t k = begin; k < end; ++k) {
      const double y = cells[k].second;
      if (crossings.empty() || y - crossings.back().high > gap) {
        crossings.push_back({y, y, y, 1});
      } else {
        crossings.back().high = y;
        crossings.back().sum += y;
        ++crossings.back().count;
      }
    }
    std::vector<double> ys;
    if (crossings.size() % 2 == 1) {
      ++result.odd_columns;
      std::size_t tallest = 0;
      for (std::size_t k = 1; k < crossings.size(); ++k) {
        if (crossings[k].high - crossings[k].low >
            crossings[tallest].high - crossings[tallest].low) {
          tallest = k;
        }
      }
      for (std::size_t k = 0; k < crossings.size(); ++k) {
        if (k == tallest) {
          ys.push_back(crossings[k].low);
          ys.push_back(crossings[k].high);
        } else {
          ys.push_back(crossings[k].sum / crossings[k].count);
        }
      }
    } else {
      for (const Crossing& c : crossings) ys.push_back(c.sum / c.count);
    }
    for (std::size_t j = 0; j + 1 < ys.size(); j += 2) result.area += width * (ys[j + 1] - ys[j]);
    ++result.columns;
    begin = end;
  }
  return result;
}

}  // namespace mcws
