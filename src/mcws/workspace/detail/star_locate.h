#pragma once
/// \file
/// \brief A shortcut of the leave-one-out count from a vertex's star (outsideByStar() in
/// alpha_triangulation.h): the simplex of the Delaunay triangulation of the vertex's neighbours
/// that holds the vertex's point, found without building that triangulation, and proven to be
/// the one the triangulation would give, or no answer (the caller then builds it). Private to
/// mcws_workspace (namespace mcws::detail).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace mcws::detail {

/// The simplex (D + 1 places in `star`) of the Delaunay triangulation of the points `star` that
/// holds `p` strictly inside, found by a walk of exact predicates (CGAL's, of `Kernel`): from the
/// simplex on p's side of the facet `start` (D places in `star`; a facet of that triangulation,
/// as the facet of v's star cell opposite v is), gift-wrapped (the point on that side whose
/// sphere through the facet holds no other point there), across the facets that p lies beyond,
/// each next simplex gift-wrapped the same way. The simplex found is then proven: p strictly
/// inside it, every other point of `star` strictly outside its circumsphere. Such a simplex is a
/// simplex of every Delaunay triangulation of the points, CGAL's symbolic perturbation of ties
/// included, and the one its `locate(p)` returns, whatever order the points were inserted in.
/// Where something is degenerate (p, or a point, exactly on a plane or sphere the walk or the
/// proof tests) or the walk does not end in `kMaxSteps` steps, there is no answer.
/// \return whether `simplex` holds the answer.
template <int D, typename Point>
bool starSimplex(const Point& p, const std::vector<Point>& star, const std::array<int, D>& start,
                 std::array<int, D + 1>& simplex) {
  constexpr int kMaxSteps = 64;
  const int n = static_cast<int>(star.size());
  // The orientation of the simplex `s` with `x` in place of its vertex `k` (k = D + 1: none).
  const auto orient = [&](const std::array<int, D + 1>& s, int k, const Point& x) {
    const auto at = [&](int j) -> const Point& { return j == k ? x : star[s[j]]; };
    if constexpr (D == 2) {
      return CGAL::orientation(at(0), at(1), at(2));
    } else {
      return CGAL::orientation(at(0), at(1), at(2), at(3));
    }
  };
  // The side of the circumsphere of the positively oriented simplex `s` that `x` lies on
  // (ON_POSITIVE_SIDE: inside).
  const auto side = [&](const std::array<int, D + 1>& s, const Point& x) {
    if constexpr (D == 2) {
      return CGAL::side_of_oriented_circle(star[s[0]], star[s[1]], star[s[2]], x);
    } else {
      return CGAL::side_of_oriented_sphere(star[s[0]], star[s[1]], star[s[2]], star[s[3]], x);
    }
  };
  // The simplex on p's side of `facet` (vertex D the apex), positively oriented; false when p
  // lies on the facet's plane, no point lies strictly on p's side, or two tie.
  const auto wrap = [&](const std::array<int, D>& facet, std::array<int, D + 1>& s) {
    for (int j = 0; j < D; ++j) s[j] = facet[j];
    const CGAL::Orientation towards = orient(s, D, p);
    if (towards == CGAL::COPLANAR) return false;
    int best = -1;
    for (int u = 0; u < n; ++u) {
      bool in_facet = false;
      for (int j = 0; j < D; ++j) in_facet |= facet[j] == u;
      if (in_facet || orient(s, D, star[u]) != towards) continue;
      if (best >= 0) {
        // Both on p's side: u inside the sphere through the facet and `best` makes u the apex.
        const auto where = side(s, star[u]) * towards;
        if (where == CGAL::ON_ORIENTED_BOUNDARY) return false;
        if (where == CGAL::ON_NEGATIVE_SIDE) continue;
      }
      best = u;
      s[D] = u;
    }
    if (best < 0) return false;
    if (towards == CGAL::NEGATIVE) std::swap(s[0], s[1]);
    return true;
  };
  if (!wrap(start, simplex)) return false;
  for (int step = 0;; ++step) {
    if (step == kMaxSteps) return false;
    int beyond = -1;
    bool on_facet = false;
    for (int k = 0; k <= D && beyond < 0; ++k) {
      const CGAL::Orientation o = orient(simplex, k, p);
      if (o == CGAL::NEGATIVE) beyond = k;
      on_facet |= o == CGAL::COPLANAR;
    }
    if (beyond < 0) {
      if (on_facet) return false;
      break;  // p strictly inside
    }
    std::array<int, D> facet;
    for (int j = 0, m = 0; j <= D; ++j) {
      if (j != beyond) facet[m++] = simplex[j];
    }
    if (!wrap(facet, simplex)) return false;
  }
  for (int u = 0; u < n; ++u) {
    bool vertex = false;
    for (int j = 0; j <= D; ++j) vertex |= simplex[j] == u;
    if (!vertex && side(simplex, star[u]) != CGAL::ON_NEGATIVE_SIDE) return false;
  }
  return true;
}

}  // namespace mcws::detail
