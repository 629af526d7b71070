#include "mcws/planning/k_shortest_paths.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "mcws/core/error.h"

namespace mcws {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

// Random real weights are summed in the same order by the brute force and by the library, but
// equal-length paths may come in a different order, so lengths agree to rounding only.
constexpr double kLengthTol = 1e-9;
constexpr std::uint32_t kSeed = 20240611;
constexpr int kRandomGraphs = 50;

struct WeightedEdge {
  std::size_t u;
  std::size_t v;
  double w;
};

RoadmapGraph makeGraph(std::size_t n, const std::vector<WeightedEdge>& edges) {
  RoadmapGraph graph(n);
  for (const WeightedEdge& e : edges) boost::add_edge(e.u, e.v, e.w, graph);
  return graph;
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no mcws::Error thrown)";
}

/// Every loop-free path from source to target with its length, by depth-first search over the
/// edges themselves: with parallel edges each choice of edge is walked, and a vertex sequence
/// keeps the least length of its realisations. Lengths are summed source to target.
std::map<VertexPath, double> allSimplePaths(const RoadmapGraph& graph, std::size_t source,
                                            std::size_t target) {
  std::map<VertexPath, double> paths;
  VertexPath path{source};
  std::vector<char> on_path(boost::num_vertices(graph), 0);
  on_path[source] = 1;
  const std::function<void(std::size_t, double)> walk = [&](std::size_t u, double length) {
    if (u == target) {
      auto [it, inserted] = paths.emplace(path, length);
      if (!inserted) it->second = std::min(it->second, length);
      return;
    }
    for (auto [it, end] = boost::out_edges(u, graph); it != end; ++it) {
      const std::size_t v = boost::target(*it, graph);
      if (on_path[v]) continue;
      on_path[v] = 1;
      path.push_back(v);
      walk(v, length + boost::get(boost::edge_weight, graph, *it));
      path.pop_back();
      on_path[v] = 0;
    }
  };
  walk(source, 0.0);
  return paths;
}

/// All loop-free paths sorted by (length, vertex sequence).
std::vector<std::pair<double, VertexPath>> sortedPaths(const std::map<VertexPath, double>& all) {
  std::vector<std::pair<double, VertexPath>> sorted;
  for (const auto& [path, length] : all) sorted.emplace_back(length, path);
  std::sort(sorted.begin(), sorted.end());
  return sorted;
}

/// A random graph on 8 to 10 vertices: each pair joined with probability 0.4, sometimes by a
/// second, parallel edge, and sometimes a self-loop. Integer weights 0..4 when `integer`
/// (sums exact in double, zero weights included), else real weights in [0.1, 10).
RoadmapGraph randomGraph(int index, bool integer) {
  std::mt19937 rng(kSeed + static_cast<std::uint32_t>(index));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<int> small(0, 4);
  const auto weight = [&]() {
    return integer ? static_cast<double>(small(rng)) : 0.1 + 9.9 * unit(rng);
  };
  const std::size_t n = 8 + static_cast<std::size_t>(index % 3);
  RoadmapGraph graph(n);
  for (std::size_t u = 0; u < n; ++u) {
    for (std::size_t v = u + 1; v < n; ++v) {
      if (unit(rng) >= 0.4) continue;
      boost::add_edge(u, v, weight(), graph);
      if (unit(rng) < 0.15) boost::add_edge(v, u, weight(), graph);
    }
  }
  if (unit(rng) < 0.3) {
    const std::size_t v = static_cast<std::size_t>(unit(rng) * static_cast<double>(n));
    boost::add_edge(v, v, weight(), graph);
  }
  return graph;
}

std::set<std::pair<std::size_t, std::size_t>> edgesOf(const VertexPath& path) {
  std::set<std::pair<std::size_t, std::size_t>> edges;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    edges.emplace(std::min(path[i], path[i + 1]), std::max(path[i], path[i + 1]));
  }
  return edges;
}

std::size_t sharedEdges(const VertexPath& a, const VertexPath& b) {
  const auto ea = edgesOf(a);
  const auto eb = edgesOf(b);
  return static_cast<std::size_t>(
      std::count_if(ea.begin(), ea.end(), [&](const auto& e) { return eb.count(e) > 0; }));
}

// Yen's example from Wikipedia ("Yen's algorithm"), with its directed edges made undirected:
// C=0, D=1, E=2, F=3, G=4, H=5.
enum : std::size_t { C, D, E, F, G, H };
RoadmapGraph yenExample() {
  return makeGraph(6, {{C, D, 3},
                       {C, E, 2},
                       {D, F, 4},
                       {E, D, 1},
                       {E, F, 2},
                       {E, G, 3},
                       {F, G, 2},
                       {F, H, 1},
                       {G, H, 2}});
}

TEST(KShortestPaths, FindsTheShortestPathsOfWikipediasYenExample) {
  // Worked by hand. Directed (as on Wikipedia) the three shortest are CEFH 5, CEGH 7, CDFH 8;
  // undirected, D-E may also be walked D->E, which adds CDEFH 7. Ties go by vertex sequence.
  const RoadmapGraph graph = yenExample();
  const std::vector<VertexPath> paths = kShortestPaths(graph, C, H, 5);
  ASSERT_EQ(paths.size(), 5u);
  EXPECT_EQ(paths[0], (VertexPath{C, E, F, H}));
  EXPECT_EQ(paths[1], (VertexPath{C, D, E, F, H}));
  EXPECT_EQ(paths[2], (VertexPath{C, E, G, H}));
  EXPECT_EQ(paths[3], (VertexPath{C, D, F, H}));
  EXPECT_EQ(paths[4], (VertexPath{C, E, D, F, H}));
  const std::vector<double> lengths = {5, 7, 7, 8, 8};
  for (std::size_t i = 0; i < paths.size(); ++i) {
    EXPECT_EQ(pathLength(graph, paths[i]), lengths[i]) << "path " << i;
  }
}

TEST(KShortestPaths, ReturnsEveryPathWhenKExceedsTheirNumber) {
  // The 13 loop-free C-H paths of the undirected example, enumerated by hand from C-D and C-E.
  const RoadmapGraph graph = yenExample();
  const std::vector<VertexPath> paths = kShortestPaths(graph, C, H, 20);
  std::vector<double> lengths;
  for (const VertexPath& path : paths) lengths.push_back(pathLength(graph, path));
  EXPECT_THAT(lengths, ElementsAre(5, 7, 7, 8, 8, 8, 8, 9, 10, 10, 11, 11, 14));
  EXPECT_EQ(std::set<VertexPath>(paths.begin(), paths.end()).size(), paths.size());
  EXPECT_EQ(paths.back(), (VertexPath{C, D, F, E, G, H}));
}

TEST(KShortestPaths, LengthsMatchBruteForceOnRandomGraphs) {
  int graphs_with_more_than_k = 0;
  for (int index = 0; index < kRandomGraphs; ++index) {
    SCOPED_TRACE("graph " + std::to_string(index));
    const RoadmapGraph graph = randomGraph(index, /*integer=*/false);
    const std::size_t source = 0;
    const std::size_t target = boost::num_vertices(graph) - 1;
    const std::size_t k = 12;
    const std::map<VertexPath, double> all = allSimplePaths(graph, source, target);
    const auto sorted = sortedPaths(all);
    if (sorted.size() > k) ++graphs_with_more_than_k;

    const std::vector<VertexPath> paths = kShortestPaths(graph, source, target, k);
    ASSERT_EQ(paths.size(), std::min(k, sorted.size()));
    EXPECT_EQ(std::set<VertexPath>(paths.begin(), paths.end()).size(), paths.size());
    for (std::size_t i = 0; i < paths.size(); ++i) {
      const VertexPath& path = paths[i];
      ASSERT_EQ(all.count(path), 1u) << "path " << i << " is not a loop-free source-target path";
      EXPECT_EQ(path.front(), source);
      EXPECT_EQ(path.back(), target);
      EXPECT_NEAR(all.at(path), sorted[i].first, kLengthTol) << "path " << i;
      EXPECT_NEAR(pathLength(graph, path), all.at(path), kLengthTol) << "path " << i;
    }
  }
  // The comparison is only a test of the ranking when there are more paths than asked for.
  EXPECT_GE(graphs_with_more_than_k, kRandomGraphs / 2);
}

TEST(KShortestPaths, IsTheFirstKInLengthThenSequenceOrderWithIntegerWeights) {
  // Integer weights (zeros included) sum exactly, so ties are real and the documented order
  // (length, then lexicographic vertex sequence) fixes every path.
  int graphs_with_ties = 0;
  for (int index = 0; index < kRandomGraphs; ++index) {
    SCOPED_TRACE("graph " + std::to_string(index));
    const RoadmapGraph graph = randomGraph(index, /*integer=*/true);
    const std::size_t target = boost::num_vertices(graph) - 1;
    const std::size_t k = 15;
    const auto sorted = sortedPaths(allSimplePaths(graph, 0, target));
    std::vector<VertexPath> expected;
    for (std::size_t i = 0; i < std::min(k, sorted.size()); ++i) {
      expected.push_back(sorted[i].second);
      if (i > 0 && sorted[i].first == sorted[i - 1].first) ++graphs_with_ties;
    }
    EXPECT_EQ(kShortestPaths(graph, 0, target, k), expected);
  }
  EXPECT_GT(graphs_with_ties, 0);
}

TEST(KShortestPaths, ResultForKIsAPrefixOfTheResultForMoreK) {
  const RoadmapGraph graph = randomGraph(3, /*integer=*/false);
  const std::size_t target = boost::num_vertices(graph) - 1;
  const std::vector<VertexPath> more = kShortestPaths(graph, 0, target, 10);
  ASSERT_GE(more.size(), 5u);
  const std::vector<VertexPath> fewer = kShortestPaths(graph, 0, target, 5);
  EXPECT_EQ(fewer, std::vector<VertexPath>(more.begin(), more.begin() + 5));
}

TEST(KShortestPaths, UnreachableTargetGivesNoPath) {
  // Two components: {0, 1, 2} and {3, 4}.
  const RoadmapGraph graph = makeGraph(5, {{0, 1, 1}, {1, 2, 1}, {0, 2, 3}, {3, 4, 1}});
  EXPECT_TRUE(kShortestPaths(graph, 0, 4, 3).empty());
  EXPECT_TRUE(diversePaths(graph, 0, 4, 3, 0.5).empty());
  EXPECT_EQ(kShortestPaths(graph, 0, 2, 3).size(), 2u);
}

TEST(KShortestPaths, SourceEqualToTargetGivesTheSingleVertexPath) {
  const RoadmapGraph graph = yenExample();
  EXPECT_EQ(kShortestPaths(graph, E, E, 4), (std::vector<VertexPath>{{E}}));
  EXPECT_EQ(diversePaths(graph, E, E, 4, 1.0), (std::vector<VertexPath>{{E}}));
  EXPECT_EQ(pathLength(graph, {E}), 0.0);
}

TEST(KShortestPaths, KZeroGivesNoPath) {
  EXPECT_TRUE(kShortestPaths(yenExample(), C, H, 0).empty());
  EXPECT_TRUE(diversePaths(yenExample(), C, H, 0, 1.0).empty());
}

TEST(KShortestPaths, ParallelEdgesCountOnceAsTheLightest) {
  // 0-1 twice (5 and 2), a zero-weight self-loop at 1: the vertex paths are 0-1-2 (2 + 1) and
  // 0-2 (4), each once.
  const RoadmapGraph graph = makeGraph(3, {{0, 1, 5}, {1, 0, 2}, {1, 1, 0}, {1, 2, 1}, {0, 2, 4}});
  const std::vector<VertexPath> paths = kShortestPaths(graph, 0, 2, 5);
  EXPECT_EQ(paths, (std::vector<VertexPath>{{0, 1, 2}, {0, 2}}));
  EXPECT_EQ(pathLength(graph, {0, 1, 2}), 3.0);
  EXPECT_EQ(pathLength(graph, {2, 1, 0}), 3.0);
}

TEST(KShortestPaths, ZeroWeightEdgesNeitherTrapNorLoopTheSearch) {
  // Vertex 1 hangs off the source by a zero-weight edge: as short to the target as the source,
  // but a dead end. Vertices 0, 2, 3 form a zero-weight triangle before the target 4.
  const RoadmapGraph graph =
      makeGraph(5, {{0, 1, 0}, {0, 2, 0}, {2, 3, 0}, {0, 3, 0}, {3, 4, 1}, {2, 4, 2}});
  const std::vector<VertexPath> paths = kShortestPaths(graph, 0, 4, 10);
  // By hand: 0-2-3-4 and 0-3-4 have length 1, 0-2-4 and 0-3-2-4 length 2.
  EXPECT_EQ(paths, (std::vector<VertexPath>{{0, 2, 3, 4}, {0, 3, 4}, {0, 2, 4}, {0, 3, 2, 4}}));
}

TEST(KShortestPaths, PathLengthNamesTheMissingEdgeAndBadVertex) {
  const RoadmapGraph graph = yenExample();
  EXPECT_EQ(pathLength(graph, {}), 0.0);
  EXPECT_EQ(pathLength(graph, {C, D, F, H}), 8.0);
  const std::string missing = errorOf([&] { pathLength(graph, {C, E, H}); });
  EXPECT_THAT(missing, HasSubstr("vertices 2 and 5"));
  const std::string range = errorOf([&] { pathLength(graph, {C, 9}); });
  EXPECT_THAT(range, HasSubstr("vertex 9"));
  EXPECT_THAT(range, HasSubstr("6 vertices"));
}

TEST(KShortestPaths, RejectsOutOfRangeVertices) {
  const RoadmapGraph graph = yenExample();
  const std::string source = errorOf([&] { kShortestPaths(graph, 7, H, 3); });
  EXPECT_THAT(source, HasSubstr("source vertex 7"));
  EXPECT_THAT(source, HasSubstr("6 vertices"));
  EXPECT_THAT(errorOf([&] { kShortestPaths(graph, C, 6, 3); }), HasSubstr("target vertex 6"));
  EXPECT_THAT(errorOf([&] { diversePaths(graph, C, 11, 3, 0.5); }), HasSubstr("target vertex 11"));
}

TEST(KShortestPaths, RejectsNegativeAndNonFiniteWeights) {
  const std::string negative = errorOf([] {
    kShortestPaths(makeGraph(3, {{0, 1, 1}, {1, 2, -2.5}}), 0, 2, 2);
  });
  EXPECT_THAT(negative, HasSubstr("-2.5"));
  EXPECT_THAT(negative, HasSubstr("(1, 2)"));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(errorOf([&] {
                kShortestPaths(makeGraph(3, {{0, 1, nan}}), 0, 2, 2);
              }),
              HasSubstr("nan"));
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THAT(errorOf([&] {
                kShortestPaths(makeGraph(3, {{2, 2, inf}}), 0, 2, 2);
              }),
              HasSubstr("inf"));
  EXPECT_THAT(errorOf([] {
                diversePaths(makeGraph(3, {{0, 1, -0.25}}), 0, 2, 2, 0.5);
              }),
              HasSubstr("-0.25"));
}

TEST(DiversePaths, PenaltyZeroEqualsKShortestPaths) {
  EXPECT_EQ(diversePaths(yenExample(), C, H, 8, 0.0), kShortestPaths(yenExample(), C, H, 8));
  for (int index = 0; index < 10; ++index) {
    const RoadmapGraph graph = randomGraph(index, /*integer=*/false);
    const std::size_t target = boost::num_vertices(graph) - 1;
    EXPECT_EQ(diversePaths(graph, 0, target, 6, 0.0), kShortestPaths(graph, 0, target, 6))
        << "graph " << index;
  }
}

// A ladder 0-1-2-3-4 over 5-6-7-8-9 with rungs i-(i+5). Top rail 1 per edge, bottom rail 1.25,
// rungs 1 (all exact in double). Source 0, target 4.
RoadmapGraph ladder() {
  std::vector<WeightedEdge> edges;
  for (std::size_t i = 0; i < 4; ++i) {
    edges.push_back({i, i + 1, 1.0});
    edges.push_back({i + 5, i + 6, 1.25});
  }
  for (std::size_t i = 0; i < 5; ++i) edges.push_back({i, i + 5, 1.0});
  return makeGraph(10, edges);
}

TEST(DiversePaths, SecondPathOnALadderLeavesTheFirst) {
  // By hand: the top rail (4) is shortest. Yen's second is a one-rung detour (4 - 1 + 3.25 =
  // 6.25; four of them tie, the smallest sequence is 0-1-2-3-8-9-4), sharing 3 of the 4 top
  // edges. With penalty 1 the top edges cost 2: a one-rung detour costs 9.25, a two-rung 8.5,
  // a three-rung 7.75, the whole bottom rail 7, so the bottom rail comes second.
  const RoadmapGraph graph = ladder();
  const std::vector<VertexPath> yen = kShortestPaths(graph, 0, 4, 2);
  ASSERT_EQ(yen.size(), 2u);
  EXPECT_EQ(yen[0], (VertexPath{0, 1, 2, 3, 4}));
  EXPECT_EQ(yen[1], (VertexPath{0, 1, 2, 3, 8, 9, 4}));
  EXPECT_EQ(sharedEdges(yen[1], yen[0]), 3u);

  const std::vector<VertexPath> diverse = diversePaths(graph, 0, 4, 4, 1.0);
  ASSERT_EQ(diverse.size(), 4u);
  EXPECT_EQ(diverse[0], (VertexPath{0, 1, 2, 3, 4}));
  EXPECT_EQ(diverse[1], (VertexPath{0, 5, 6, 7, 8, 9, 4}));
  EXPECT_EQ(pathLength(graph, diverse[1]), 7.0);
  EXPECT_LT(sharedEdges(diverse[1], diverse[0]), sharedEdges(yen[1], yen[0]));

  const std::map<VertexPath, double> all = allSimplePaths(graph, 0, 4);
  EXPECT_EQ(std::set<VertexPath>(diverse.begin(), diverse.end()).size(), diverse.size());
  for (const VertexPath& path : diverse) {
    EXPECT_EQ(all.count(path), 1u) << "not a loop-free 0-4 path";
  }
}

TEST(DiversePaths, MatchesABruteForcePenaltyMethodWithCompounding) {
  // Reference: all loop-free paths by DFS; repeatedly take the least penalised length (ties by
  // sequence) among those not yet taken, then multiply its edges' weights by 1 + penalty.
  // Integer weights times powers of 1.5 stay exact in double, so ties are real.
  constexpr double kPenalty = 0.5;
  constexpr std::size_t kM = 6;
  for (int index = 0; index < kRandomGraphs; ++index) {
    SCOPED_TRACE("graph " + std::to_string(index));
    const RoadmapGraph graph = randomGraph(index, /*integer=*/true);
    const std::size_t target = boost::num_vertices(graph) - 1;
    std::map<std::pair<std::size_t, std::size_t>, double> weight;  // lightest parallel edge
    for (auto [it, end] = boost::edges(graph); it != end; ++it) {
      const std::size_t u = boost::source(*it, graph);
      const std::size_t v = boost::target(*it, graph);
      const auto key = std::make_pair(std::min(u, v), std::max(u, v));
      const double w = boost::get(boost::edge_weight, graph, *it);
      if (weight.count(key) == 0 || w < weight[key]) weight[key] = w;
    }
    const std::map<VertexPath, double> all = allSimplePaths(graph, 0, target);
    std::vector<VertexPath> expected;
    while (expected.size() < kM) {
      std::optional<std::pair<double, VertexPath>> best;
      for (const auto& [path, unused] : all) {
        if (std::find(expected.begin(), expected.end(), path) != expected.end()) continue;
        double length = 0.0;
        for (std::size_t i = 0; i + 1 < path.size(); ++i) {
          length += weight[{std::min(path[i], path[i + 1]), std::max(path[i], path[i + 1])}];
        }
        if (!best || std::make_pair(length, path) < *best) best = std::make_pair(length, path);
      }
      if (!best) break;
      expected.push_back(best->second);
      for (const auto& e : edgesOf(best->second)) weight[e] *= 1.0 + kPenalty;
    }
    EXPECT_EQ(diversePaths(graph, 0, target, kM, kPenalty), expected);
  }
}

TEST(DiversePaths, EnumeratesEveryPathWhenMExceedsTheirNumber) {
  const RoadmapGraph graph = yenExample();
  const std::vector<VertexPath> diverse = diversePaths(graph, C, H, 20, 1.0);
  const std::map<VertexPath, double> all = allSimplePaths(graph, C, H);
  ASSERT_EQ(all.size(), 13u);
  EXPECT_EQ(diverse.size(), 13u);
  EXPECT_EQ(std::set<VertexPath>(diverse.begin(), diverse.end()).size(), 13u);
  for (const VertexPath& path : diverse) EXPECT_EQ(all.count(path), 1u);
}

TEST(DiversePaths, RejectsNegativeAndNonFinitePenalties) {
  const RoadmapGraph graph = yenExample();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::string not_a_number = errorOf([&] { diversePaths(graph, C, H, 3, nan); });
  EXPECT_THAT(not_a_number, HasSubstr("penalty"));
  EXPECT_THAT(not_a_number, HasSubstr("nan"));
  EXPECT_THAT(errorOf([&] { diversePaths(graph, C, H, 3, -0.5); }), HasSubstr("penalty -0.5"));
  EXPECT_THAT(
      errorOf([&] { diversePaths(graph, C, H, 3, std::numeric_limits<double>::infinity()); }),
      HasSubstr("penalty inf"));
}

}  // namespace
}  // namespace mcws
