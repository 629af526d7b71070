#include "mcws/workspace/detail/star_locate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "mcws/workspace/detail/alpha_triangulation.h"

namespace mcws {
namespace {

// Clouds where the shortcut of the leave-one-out count (starSimplex()) is tried: uniform random,
// clustered (tight blobs, some points a hair apart) and a lattice (cospherical points, points on
// facets: the shortcut must give up there), in 2-D (z = 0) and 3-D.
std::vector<std::array<double, 3>> cloud(int kind, int dimensions, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<std::array<double, 3>> points;
  const int n = dimensions == 2 ? 1500 : 2500;
  if (kind == 0) {
    for (int i = 0; i < n; ++i) points.push_back({u(rng), u(rng), dimensions == 3 ? u(rng) : 0});
  } else if (kind == 1) {
    std::vector<std::array<double, 3>> centres(12);
    for (auto& c : centres) c = {u(rng), u(rng), dimensions == 3 ? u(rng) : 0};
    for (int i = 0; i < n; ++i) {
      const auto& c = centres[i % centres.size()];
      const double s = i % 7 == 0 ? 1e-6 : 0.05;
      points.push_back(
          {c[0] + s * g(rng), c[1] + s * g(rng), dimensions == 3 ? c[2] + s * g(rng) : 0});
    }
  } else {
    const int side = dimensions == 2 ? 30 : 11;
    for (int x = 0; x < side; ++x)
      for (int y = 0; y < side; ++y)
        for (int z = 0; z < (dimensions == 3 ? side : 1); ++z)
          points.push_back({1.0 * x, 1.0 * y, 1.0 * z});
  }
  return points;
}

// Local spacings of the points: not estimated from the cloud, only values around its spacing that
// make the alpha test keep some simplices and drop others near each vertex.
std::vector<double> spacings(std::size_t n, double typical, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.3, 1.2);
  std::vector<double> spacing(n);
  for (auto& s : spacing) s = typical * u(rng);
  return spacing;
}

template <int D>
void expectShortcutAgrees(int kind, std::uint32_t seed) {
  using Delaunay = typename detail::Simplices<D>::Delaunay;
  using Point = typename Delaunay::Point;
  const auto raw = cloud(kind, D, seed);
  std::vector<std::pair<Point, std::uint32_t>> input;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if constexpr (D == 2) {
      input.emplace_back(Point(raw[i][0], raw[i][1]), static_cast<std::uint32_t>(i));
    } else {
      input.emplace_back(Point(raw[i][0], raw[i][1], raw[i][2]), static_cast<std::uint32_t>(i));
    }
  }
  const Delaunay dt(input.begin(), input.end());
  ASSERT_EQ(dt.dimension(), D);
  const double typical = kind == 2 ? 1.0 : (D == 2 ? 0.05 : 0.15);
  const std::vector<double> spacing = spacings(raw.size(), typical, seed + 1);
  std::vector<typename Delaunay::Vertex_handle> vertices, neighbours;
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
    vertices.push_back(v);

  // Each simplex the shortcut gives is the one the neighbours' triangulation locates.
  std::vector<typename detail::SimplexOf<D, Delaunay>::Handle> cells;
  std::vector<Point> points;
  std::size_t tried = 0, decided = 0;
  for (const auto v : vertices) {
    neighbours.clear();
    detail::adjacentVertices<D>(dt, v, neighbours, cells);
    if (std::any_of(neighbours.begin(), neighbours.end(),
                    [&](auto u) { return dt.is_infinite(u); })) {
      continue;
    }
    ++tried;
    points.clear();
    for (const auto u : neighbours) points.push_back(u->point());
    std::array<int, D> start;
    for (int j = 0; j < D; ++j) start[j] = j;
    std::array<int, D + 1> simplex;
    if (!detail::starSimplex<D>(v->point(), points, start, simplex)) continue;
    ++decided;
    std::vector<std::pair<Point, std::uint32_t>> star;
    for (const auto u : neighbours) star.emplace_back(u->point(), u->info());
    const typename detail::Simplices<D>::Local local(star.begin(), star.end());
    const auto s = local.locate(v->point());
    ASSERT_FALSE(local.is_infinite(s));
    std::vector<std::uint32_t> found, expected;
    for (int k = 0; k <= D; ++k) {
      found.push_back(neighbours[simplex[k]]->info());
      expected.push_back(s->vertex(k)->info());
    }
    std::sort(found.begin(), found.end());
    std::sort(expected.begin(), expected.end());
    ASSERT_EQ(found, expected) << "vertex " << v->info();
  }
  ASSERT_GT(tried, raw.size() / 2);
  if (kind != 2) {
    EXPECT_GT(decided, tried * 9 / 10);  // the shortcut does its work
  }

  // The count and the vertices counted, with and without the shortcut, on one and two threads.
  for (const double alpha : {1.0, 2.0, 3.0}) {
    std::vector<char> plain(raw.size(), 0);
    const std::size_t expected =
        detail::outsideByStar<D>(dt, vertices, spacing, alpha, 1, &plain, {}, false);
    EXPECT_GT(expected, 0u);
    for (const int threads : {1, 2}) {
      std::vector<char> flags(raw.size(), 0);
      EXPECT_EQ(detail::outsideByStar<D>(dt, vertices, spacing, alpha, threads, &flags), expected);
      EXPECT_EQ(flags, plain);
    }
  }
}

TEST(StarLeaveOneOut, ShortcutGivesThePlainCount2D) {
  for (const int kind : {0, 1, 2}) {
    SCOPED_TRACE(kind);
    expectShortcutAgrees<2>(kind, 3);
  }
}

TEST(StarLeaveOneOut, ShortcutGivesThePlainCount3D) {
  for (const int kind : {0, 1, 2}) {
    SCOPED_TRACE(kind);
    expectShortcutAgrees<3>(kind, 5);
  }
}

}  // namespace
}  // namespace mcws
