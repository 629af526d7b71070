#include "mcws/workspace/detail/measure_shell.h"

#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <future>
#include <iterator>
#include <limits>
#include <memory>
#include <set>
#include <utility>
#include <vector>

#include "mcws/core/first_error.h"
#include "mcws/workspace/detail/alpha_triangulation.h"
#include "mcws/workspace/detail/left_out.h"
#include "mcws/workspace/detail/measure_steps.h"
#include "mcws/workspace/detail/surface_repair.h"
#include "mcws/workspace/exposed_points.h"

namespace mcws::detail {
namespace {

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
/// Adds the kept ones' area (D = 2) or volume (D = 3) to `kept_total`. \return the finite
/// simplices.
template <int D, typename Delaunay, typename Keep>
std::vector<typename SimplexOf<D, Delaunay>::Handle> flagSimplices(
    Delaunay& dt, const Keep& keep, OrderFreeSum& kept_total, int threads,
    const CancelCheck& cancel_check) {
  std::vector<typename SimplexOf<D, Delaunay>::Handle> finite;
  finite.reserve(D == 2 ? 2 * dt.number_of_vertices() : 7 * dt.number_of_vertices());
  for (const auto s : allSimplices<D>(dt)) {
    s->info() = 0;
    if (!dt.is_infinite(s)) finite.push_back(s);
  }
  FirstError error;  // what cancel_check throws leaves the parallel region through it
  const OrderFreeSum zero = kept_total.empty();  // made here: threads add to kept_total below
#pragma omp parallel num_threads(threads)
  {
    CancelPacer pacer = callingThreadPacer(cancel_check, kCancelStride);
    OrderFreeSum part = zero;
#pragma omp for schedule(dynamic, 4096) nowait
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(finite.size()); ++i) {
      error.run(i, [&] {
        pacer.step();
        const char flag = keep(finite[i]);
        finite[i]->info() = flag;
        if (flag) part.add(simplexMeasure<D>(finite[i]));
      });
    }
#pragma omp critical
    kept_total.add(part);
  }
  error.rethrow();
  return finite;
}

/// The vertices between kept and dropped simplices, as boundaryVertices() finds them, from the
/// list of the finite simplices `finite` read on all threads.
template <int D, typename Delaunay, typename Simplex>
std::vector<typename Delaunay::Vertex_handle> boundaryVerticesOf(const Delaunay& dt,
                                                                 const std::vector<Simplex>& finite,
                                                                 std::size_t points, int threads) {
  // By point index; set by any thread (the same value), read after the parallel region.
  const std::unique_ptr<std::atomic<char>[]> on_boundary(new std::atomic<char>[points]());
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t n = 0; n < static_cast<std::int64_t>(finite.size()); ++n) {
    const Simplex& s = finite[n];
    if (!s->info()) continue;
    for (int i = 0; i <= D; ++i) {
      if (s->neighbor(i)->info()) continue;
      for (int j = 0; j <= D; ++j) {  // the facet opposite vertex i
        if (j != i) on_boundary[s->vertex(j)->info()].store(1, std::memory_order_relaxed);
      }
    }
  }
  std::vector<typename Delaunay::Vertex_handle> boundary;
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
    if (on_boundary[v->info()].load(std::memory_order_relaxed)) boundary.push_back(v);
  }
  return boundary;
}

/// Sorts `found` and drops its repeats.
inline void sortUnique(std::vector<std::uint32_t>& found) {
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
}

/// The left-out points in the circumspheres of the kept simplices of the stars of `vertices`
/// (`on_vertex`: 1 for their points, by index), sorted, each once. The vertices are shared among
/// the threads; a simplex in several of the stars is searched from the star of its vertex of
/// lowest index only.
template <int D, typename Delaunay>
std::vector<std::uint32_t> leftOutInKeptStars(
    const Delaunay& dt, const std::vector<typename Delaunay::Vertex_handle>& vertices,
    const std::vector<char>& on_vertex, const LeftOut<D>& left_out, int threads) {
  std::vector<std::uint32_t> joining;
  FirstError error;  // running out of memory leaves the parallel region through it
#pragma omp parallel num_threads(threads)
  {
    std::vector<typename SimplexOf<D, Delaunay>::Handle> around;
    std::vector<std::uint32_t> found;
#pragma omp for schedule(dynamic, 256)
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(vertices.size()); ++i) {
      error.run(i, [&] {
        const std::uint32_t self = vertices[i]->info();
        incidentSimplices<D>(dt, vertices[i], around);
        for (const auto& s : around) {
          if (!s->info()) continue;
          bool first = true;  // no vertex of lower index among `vertices`
          for (int k = 0; k <= D && first; ++k) {
            const std::uint32_t other = s->vertex(k)->info();
            first = other >= self || !on_vertex[other];
          }
          if (first) left_out.inside(dt, s, true, &found);
        }
      });
    }
#pragma omp critical
    error.run(vertices.size(), [&] { joining.insert(joining.end(), found.begin(), found.end()); });
  }
  error.rethrow();
  sortUnique(joining);
  return joining;
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
  sortUnique(joining);
  return joining;
}

/// Orders simplex handles by the simplex they point to.
struct ByAddress {
  template <typename Simplex>
  bool operator()(const Simplex& a, const Simplex& b) const {
    return std::less<const void*>()(&*a, &*b);
  }
};
template <int D, typename Delaunay>
using SimplexSet = std::set<typename SimplexOf<D, Delaunay>::Handle, ByAddress>;

/// Inserts the points `joining` into `dt`, each vertex carrying its point's index, and takes them
/// off the left-out points. With `kept_total`, takes off it the kept simplices each insertion
/// destroys (those in conflict with its point: their circumsphere holds it) and keeps in `made`
/// the simplices the insertions make (those around the new vertex; dropped again when a later
/// one destroys them), not flagged yet. \return the new vertices.
template <int D, typename Delaunay>
std::vector<typename Delaunay::Vertex_handle> insertJoining(
    Delaunay& dt, const pcl::PointCloud<pcl::PointXYZ>& points,
    const std::vector<std::uint32_t>& joining, LeftOut<D>& left_out, OrderFreeSum* kept_total,
    SimplexSet<D, Delaunay>& made) {
  using Simplex = typename SimplexOf<D, Delaunay>::Handle;
  std::vector<typename Delaunay::Vertex_handle> joined;
  std::vector<Simplex> conflicts, around;
  for (const std::uint32_t k : joining) {
    left_out.remove(k);
    const pcl::PointXYZ& p = points[k];
    typename Delaunay::Point point;
    if constexpr (D == 2) {
      point = typename Delaunay::Point(p.x, p.y);
    } else {
      point = typename Delaunay::Point(p.x, p.y, p.z);
    }
    Simplex start;
    if (kept_total) {
      start = dt.locate(point);
      conflicts.clear();
      if constexpr (D == 2) {
        dt.get_conflicts(point, std::back_inserter(conflicts), start);
      } else {
        dt.find_conflicts(point, start, CGAL::Emptyset_iterator(), std::back_inserter(conflicts));
      }
      for (const Simplex& s : conflicts) {
        if (made.erase(s) > 0) continue;  // made by this round, not added yet
        if (!dt.is_infinite(s) && s->info()) kept_total->subtract(simplexMeasure<D>(s));
      }
    }
    const typename Delaunay::Vertex_handle v = dt.insert(point, start);
    v->info() = k;
    joined.push_back(v);
    if (kept_total) {
      incidentSimplices<D>(dt, v, around, true);
      made.insert(around.begin(), around.end());
    }
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
/// limit). With `kept_total` (the kept simplices' total before), keeps it the kept simplices'
/// total after. \return whether a point joined (simplex handles listed before may be gone).
template <int D, typename Delaunay, typename Keep>
bool completeStars(Delaunay& dt, const pcl::PointCloud<pcl::PointXYZ>& points,
                   const std::vector<typename Delaunay::Vertex_handle>& vertices,
                   LeftOut<D>& left_out, const Keep& keep, OrderFreeSum* kept_total, int threads,
                   const CancelCheck& cancel_check) {
  std::vector<char> on_boundary(points.size(), 0);
  for (const auto v : vertices) on_boundary[v->info()] = 1;
  if (cancel_check) cancel_check();
  std::vector<std::uint32_t> joining =
      leftOutInKeptStars<D>(dt, vertices, on_boundary, left_out, threads);
  SimplexSet<D, Delaunay> made;
  bool joined_any = false;
  while (!joining.empty()) {
    joined_any = true;
    made.clear();
    const auto joined = insertJoining<D>(dt, points, joining, left_out, kept_total, made);
    auto stars = retestAround<D>(dt, joined, keep, on_boundary);
    if (kept_total) {
      for (const auto& s : made) {
        if (s->info()) kept_total->add(simplexMeasure<D>(s));
      }
    }
    if (cancel_check) cancel_check();  // between rounds
    joining = leftOutInStars<D>(dt, stars, left_out, threads);
  }
  return joined_any;
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
    completeStars<3>(dt, points, vertices, left_out, keep, nullptr, threads, cancel_check);
  };
  return fillForSurface(dt, cancel_check, std::function<void(const std::vector<Cell>&)>(complete));
}

}  // namespace

template <int D, typename Concurrency>
RegionMeasure measureShell(const pcl::PointCloud<pcl::PointXYZ>& points,
                           const std::vector<double>& spacing, const MeasureOptions& options) {
  using Delaunay = typename Simplices<D, Concurrency>::Delaunay;
  using Simplex = typename SimplexOf<D, Delaunay>::Handle;
  const double alpha_factor = options.alpha_factor;
  const int threads = options.threads;
  startPhase(options, "exposed points");
  const std::vector<char> in_shell =
      shellPoints(points, D, spacing, alpha_factor, threads, options.cancel_check);
  // The left-out points' tree is built while the shell is triangulated (on a thread of its own
  // when there are several: a 3-D triangulation shares the cores with it, a 2-D one runs on one).
  // threads 0: OpenMP's default, all cores unless OMP_NUM_THREADS says otherwise.
  const int workers = threads > 0 ? threads : omp_get_max_threads();
  std::future<std::unique_ptr<LeftOut<D>>> building =
      std::async(workers > 1 ? std::launch::async : std::launch::deferred,
                 [&] { return std::make_unique<LeftOut<D>>(points, in_shell); });
  startPhase(options, "triangulation");
  Delaunay dt;
  triangulate<D, Concurrency>(dt, points, in_shell, options.cancel_check);
  const std::unique_ptr<LeftOut<D>> left_out_tree = building.get();
  LeftOut<D>& left_out = *left_out_tree;

  startPhase(options, "alpha test");
  // Kept (1): within the alpha limit, or filling in for left-out points; else dropped (0).
  const auto keep = [&](const Simplex& s) -> char {
    return withinAlpha<D>(s, spacing, alpha_factor) || left_out.inside(dt, s, false, nullptr);
  };
  // The kept simplices' total, summed on all threads (OrderFreeSum), kept up to date by the joins.
  OrderFreeSum kept_total(boundingMeasure(points, D));
  std::vector<Simplex> finite =
      flagSimplices<D>(dt, keep, kept_total, threads, options.cancel_check);
  // Joins below replace only kept simplices (a dropped one has no left-out point in its
  // circumsphere, and a simplex around a covered point is within its alpha limit), so the
  // boundary vertices are final.
  const auto boundary = boundaryVerticesOf<D>(dt, finite, points.size(), threads);
  finite = {};
  const bool surface = D == 3 && options.surface;
  if (options.edge_correction || surface) {
    completeStars<D>(dt, points, boundary, left_out, keep, &kept_total, threads,
                     options.cancel_check);
  }
  RegionMeasure result;
  result.uncorrected = kept_total.value();
  result.points = points.size();
  result.triangulated = dt.number_of_vertices();
  result.boundary_vertices = boundary.size();
  if (options.edge_correction) {
    startPhase(options, "edge correction");
    result.outside = outsideByStar<D>(dt, boundary, spacing, alpha_factor, threads, nullptr,
                                      options.cancel_check);
  }
  if constexpr (D == 3) {
    if (surface) {
      startPhase(options, "surface");
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
