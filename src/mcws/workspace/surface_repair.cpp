#include "mcws/workspace/detail/surface_repair.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <numeric>
#include <vector>

#include "mcws/workspace/detail/alpha_triangulation.h"

namespace mcws::detail {
namespace {

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
void fillCavities(Delaunay& dt, CancelPacer& pacer) {
  using Cell = typename Delaunay::Cell_handle;
  constexpr char kOutside = 3;  // a dropped cell reached from the infinite ones
  std::vector<Cell> stack;
  for (const Cell c : dt.all_cell_handles()) {
    pacer.step();
    if (dt.is_infinite(c)) {
      c->info() = kOutside;
      stack.push_back(c);
    }
  }
  while (!stack.empty()) {
    pacer.step();
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
    pacer.step();
    c->info() = c->info() == 0 ? 2 : (c->info() == kOutside ? 0 : c->info());
  }
}

}  // namespace

template <typename Delaunay>
bool fillForSurface(
    Delaunay& dt, const CancelCheck& cancel_check,
    const std::function<void(const std::vector<typename Delaunay::Cell_handle>&)>& changed) {
  using Cell = typename Delaunay::Cell_handle;
  std::vector<Cell> around, fill, drop;
  std::vector<std::size_t> group;
  CancelPacer pacer(cancel_check, kCancelStride);
  for (int round = 0; round < kFillRounds; ++round) {
    fillCavities(dt, pacer);
    fill.clear();
    drop.clear();
    std::vector<typename Delaunay::Vertex_handle> singular;
    for (const Cell c : dt.finite_cell_handles()) {
      pacer.step();
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
    if (changed) {
      fill.insert(fill.end(), drop.begin(), drop.end());
      changed(fill);
    }
  }
  return false;
}

template <typename Delaunay>
TriangleSurface keptSurface(const Delaunay& dt, const pcl::PointCloud<pcl::PointXYZ>& points,
                            const CancelCheck& cancel_check) {
  std::vector<std::array<std::uint32_t, 3>> facets;
  CancelPacer pacer(cancel_check, kCancelStride);
  for (const auto c : dt.finite_cell_handles()) {
    pacer.step();
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

template <typename Concurrency>
using ChangedCells = std::function<void(
    const std::vector<typename Simplices<3, Concurrency>::Delaunay::Cell_handle>&)>;
template bool fillForSurface(Simplices<3, CGAL::Sequential_tag>::Delaunay&, const CancelCheck&,
                             const ChangedCells<CGAL::Sequential_tag>&);
template bool fillForSurface(Simplices<3, CGAL::Parallel_tag>::Delaunay&, const CancelCheck&,
                             const ChangedCells<CGAL::Parallel_tag>&);
template TriangleSurface keptSurface(const Simplices<3, CGAL::Sequential_tag>::Delaunay&,
                                     const pcl::PointCloud<pcl::PointXYZ>&, const CancelCheck&);
template TriangleSurface keptSurface(const Simplices<3, CGAL::Parallel_tag>::Delaunay&,
                                     const pcl::PointCloud<pcl::PointXYZ>&, const CancelCheck&);

}  // namespace mcws::detail
