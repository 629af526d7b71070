#include "mcws/planning/k_shortest_paths.h"

#include <algorithm>
#include <boost/graph/dijkstra_shortest_paths.hpp>
#include <boost/graph/filtered_graph.hpp>
#include <boost/property_map/property_map.hpp>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <utility>

#include "mcws/core/decimal.h"
#include "mcws/core/error.h"

namespace mcws {
namespace {

using Edge = boost::graph_traits<RoadmapGraph>::edge_descriptor;

/// Distance Boost's Dijkstra leaves on a vertex it did not reach (its default "infinity").
constexpr double kUnreached = std::numeric_limits<double>::max();

void checkVertex(const RoadmapGraph& graph, std::size_t vertex, const std::string& what) {
  const std::size_t n = boost::num_vertices(graph);
  if (vertex >= n) {
    throw Error(what + " " + std::to_string(vertex) + " is out of range; the graph has " +
                std::to_string(n) + " vertices");
  }
}

/// The lightest edge joining u and v (self-loop when u == v), or nullopt when there is none.
std::optional<double> lightestEdge(const RoadmapGraph& graph, std::size_t u, std::size_t v) {
  std::optional<double> lightest;
  const auto weight = boost::get(boost::edge_weight, graph);
  for (auto [it, end] = boost::out_edges(u, graph); it != end; ++it) {
    if (boost::target(*it, graph) != v) continue;
    const double w = boost::get(weight, *it);
    if (!lightest || w < *lightest) lightest = w;
  }
  return lightest;
}

/// A copy of graph with the same vertices and at most one edge per pair of distinct vertices,
/// the lightest of the parallel ones; self-loops are dropped (no loop-free path uses them).
/// \throws Error for a negative or non-finite weight (any edge, self-loops included).
RoadmapGraph simpleCopy(const RoadmapGraph& graph, const std::string& function) {
  const std::size_t n = boost::num_vertices(graph);
  const auto weight = boost::get(boost::edge_weight, graph);
  std::vector<std::tuple<std::size_t, std::size_t, double>> edges;
  edges.reserve(boost::num_edges(graph));
  for (auto [it, end] = boost::edges(graph); it != end; ++it) {
    const std::size_t u = boost::source(*it, graph);
    const std::size_t v = boost::target(*it, graph);
    const double w = boost::get(weight, *it);
    if (!std::isfinite(w) || w < 0.0) {
      throw Error(function + ": edge (" + std::to_string(u) + ", " + std::to_string(v) +
                  ") has weight " + formatNumber(w, 15) + "; weights must be finite and >= 0");
    }
    if (u != v) edges.emplace_back(std::min(u, v), std::max(u, v), w);
  }
  // Sorted by pair then weight: the first edge of each pair is its lightest.
  std::sort(edges.begin(), edges.end());
  RoadmapGraph simple(n);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const auto& [u, v, w] = edges[i];
    if (i > 0 && std::get<0>(edges[i - 1]) == u && std::get<1>(edges[i - 1]) == v) continue;
    boost::add_edge(u, v, w, simple);
  }
  return simple;
}

/// Weight of the edge u-v of a simple copy (which the caller knows exists).
double weightOf(const RoadmapGraph& simple, std::size_t u, std::size_t v) {
  return boost::get(boost::edge_weight, simple, boost::edge(u, v, simple).first);
}

/// Vertex filter: keeps the vertices not marked removed (the root path before the spur).
struct KeepVertex {
  const std::vector<char>* removed{nullptr};
  bool operator()(std::size_t v) const { return (*removed)[v] == 0; }
};

/// Edge filter: drops the edges from the spur vertex to the vertices marked forbidden (the
/// next edges of the accepted paths that share the root path).
struct KeepEdge {
  const RoadmapGraph* graph{nullptr};
  const std::vector<char>* forbidden{nullptr};
  std::size_t spur{0};
  bool operator()(const Edge& e) const {
    const std::size_t a = boost::source(e, *graph);
    const std::size_t b = boost::target(e, *graph);
    if (a == spur) return (*forbidden)[b] == 0;
    if (b == spur) return (*forbidden)[a] == 0;
    return true;
  }
};

using SpurGraph = boost::filtered_graph<RoadmapGraph, KeepEdge, KeepVertex>;

/// True when `to` can be reached from `from` along tight edges (w(x, y) + dist[y] == dist[x])
/// without entering a vertex marked on_path.
bool reachesAlongTightEdges(const SpurGraph& graph, std::size_t from, std::size_t to,
                            const std::vector<double>& dist, const std::vector<char>& on_path) {
  const auto weight = boost::get(boost::edge_weight, graph);
  std::vector<char> visited(dist.size(), 0);
  std::vector<std::size_t> stack{from};
  visited[from] = 1;
  while (!stack.empty()) {
    const std::size_t x = stack.back();
    stack.pop_back();
    if (x == to) return true;
    for (auto [it, end] = boost::out_edges(x, graph); it != end; ++it) {
      const std::size_t y = boost::target(*it, graph);
      if (visited[y] || on_path[y] || dist[y] == kUnreached) continue;
      if (boost::get(weight, *it) + dist[y] != dist[x]) continue;
      visited[y] = 1;
      stack.push_back(y);
    }
  }
  return false;
}

/// Of the shortest paths from `from` to `to` in graph, the lexicographically smallest vertex
/// sequence; nullopt when `to` is unreachable.
///
/// One Dijkstra run from `to` gives dist (distance to `to`); an edge x-y is tight when
/// w + dist[y] == dist[x], and the shortest paths are exactly the simple paths of tight edges.
/// The walk from `from` takes the smallest tight neighbour that can still reach `to` without
/// revisiting the walk: one with dist[y] < dist[x] always can (dist falls along tight edges);
/// one with dist[y] == dist[x] (a zero-weight edge) is checked by a search.
std::optional<VertexPath> smallestShortestPath(const SpurGraph& graph, std::size_t from,
                                               std::size_t to) {
  const std::size_t n = boost::num_vertices(graph);  // of the underlying graph
  std::vector<double> dist(n, kUnreached);
  const auto weight = boost::get(boost::edge_weight, graph);
  boost::dijkstra_shortest_paths(
      graph, to,
      boost::distance_map(
          boost::make_iterator_property_map(dist.begin(), boost::get(boost::vertex_index, graph)))
          .weight_map(weight));
  if (dist[from] == kUnreached) return std::nullopt;

  VertexPath path{from};
  std::vector<char> on_path(n, 0);
  on_path[from] = 1;
  std::size_t x = from;
  while (x != to) {
    std::size_t best = n;
    for (auto [it, end] = boost::out_edges(x, graph); it != end; ++it) {
      const std::size_t y = boost::target(*it, graph);
      if (y >= best || on_path[y] || dist[y] == kUnreached) continue;
      if (boost::get(weight, *it) + dist[y] != dist[x]) continue;
      if (dist[y] == dist[x] && !reachesAlongTightEdges(graph, y, to, dist, on_path)) continue;
      best = y;
    }
    // Cannot happen: the Dijkstra predecessor of x, or the first vertex of the tight path whose
    // existence the previous step checked, qualifies.
    if (best == n) return std::nullopt;
    path.push_back(best);
    on_path[best] = 1;
    x = best;
  }
  return path;
}

/// Yen's algorithm on a simple copy (validated, no parallel edges, no self-loops). The result
/// for k is a prefix of the result for k + 1: nothing below depends on k except when to stop.
std::vector<VertexPath> yen(const RoadmapGraph& graph, std::size_t source, std::size_t target,
                            std::size_t k) {
  if (k == 0) return {};
  if (source == target) return {VertexPath{source}};

  const std::size_t n = boost::num_vertices(graph);
  std::vector<char> removed(n, 0);
  std::vector<char> forbidden(n, 0);
  const auto spurGraph = [&](std::size_t spur) {
    return SpurGraph(graph, KeepEdge{&graph, &forbidden, spur}, KeepVertex{&removed});
  };

  std::optional<VertexPath> first = smallestShortestPath(spurGraph(source), source, target);
  if (!first) return {};
  std::vector<VertexPath> accepted{*first};
  std::set<VertexPath> seen{*first};                   // accepted and candidate paths
  std::set<std::pair<double, VertexPath>> candidates;  // ordered by (length, sequence)

  while (accepted.size() < k) {
    const VertexPath previous = accepted.back();
    double root_length = 0.0;  // summed source to spur, as the candidates' lengths
    for (std::size_t i = 0; i + 1 < previous.size(); ++i) {
      const std::size_t spur = previous[i];
      if (i > 0) removed[previous[i - 1]] = 1;
      std::vector<std::size_t> forbidden_now;
      for (const VertexPath& path : accepted) {
        if (path.size() > i + 1 &&
            std::equal(path.begin(), path.begin() + static_cast<std::ptrdiff_t>(i + 1),
                       previous.begin())) {
          forbidden[path[i + 1]] = 1;
          forbidden_now.push_back(path[i + 1]);
        }
      }
      if (std::optional<VertexPath> spur_path =
              smallestShortestPath(spurGraph(spur), spur, target)) {
        VertexPath candidate(previous.begin(), previous.begin() + static_cast<std::ptrdiff_t>(i));
        candidate.insert(candidate.end(), spur_path->begin(), spur_path->end());
        if (seen.insert(candidate).second) {
          double length = root_length;
          for (std::size_t j = 0; j + 1 < spur_path->size(); ++j) {
            length += weightOf(graph, (*spur_path)[j], (*spur_path)[j + 1]);
          }
          candidates.emplace(length, std::move(candidate));
        }
      }
      for (std::size_t v : forbidden_now) forbidden[v] = 0;
      root_length += weightOf(graph, previous[i], previous[i + 1]);
    }
    for (std::size_t v : previous) removed[v] = 0;

    if (candidates.empty()) break;
    accepted.push_back(candidates.begin()->second);
    candidates.erase(candidates.begin());
  }
  return accepted;
}

}  // namespace

double pathLength(const RoadmapGraph& graph, const VertexPath& path) {
  const std::size_t n = boost::num_vertices(graph);
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (path[i] >= n) {
      throw Error("pathLength: vertex " + std::to_string(path[i]) + " at position " +
                  std::to_string(i) + " is out of range; the graph has " + std::to_string(n) +
                  " vertices");
    }
  }
  double length = 0.0;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const std::optional<double> w = lightestEdge(graph, path[i], path[i + 1]);
    if (!w) {
      throw Error("pathLength: vertices " + std::to_string(path[i]) + " and " +
                  std::to_string(path[i + 1]) + " (positions " + std::to_string(i) + " and " +
                  std::to_string(i + 1) + ") are not joined by an edge");
    }
    length += *w;
  }
  return length;
}

std::vector<VertexPath> kShortestPaths(const RoadmapGraph& graph, std::size_t source,
                                       std::size_t target, std::size_t k) {
  checkVertex(graph, source, "kShortestPaths: source vertex");
  checkVertex(graph, target, "kShortestPaths: target vertex");
  return yen(simpleCopy(graph, "kShortestPaths"), source, target, k);
}

std::vector<VertexPath> diversePaths(const RoadmapGraph& graph, std::size_t source,
                                     std::size_t target, std::size_t m, double penalty) {
  checkVertex(graph, source, "diversePaths: source vertex");
  checkVertex(graph, target, "diversePaths: target vertex");
  if (!std::isfinite(penalty) || penalty < 0.0) {
    throw Error("diversePaths: penalty " + formatNumber(penalty, 15) + " must be finite and >= 0");
  }
  RoadmapGraph penalised = simpleCopy(graph, "diversePaths");
  const auto weight = boost::get(boost::edge_weight, penalised);

  std::vector<VertexPath> accepted;
  std::set<VertexPath> accepted_set;
  while (accepted.size() < m) {
    // The first accepted.size() + 1 distinct paths hold at least one not yet accepted.
    const std::vector<VertexPath> ranked = yen(penalised, source, target, accepted.size() + 1);
    const auto next = std::find_if(ranked.begin(), ranked.end(), [&](const VertexPath& path) {
      return accepted_set.count(path) == 0;
    });
    if (next == ranked.end()) break;
    accepted.push_back(*next);
    accepted_set.insert(*next);
    for (std::size_t i = 0; i + 1 < next->size(); ++i) {
      const Edge e = boost::edge((*next)[i], (*next)[i + 1], penalised).first;
      boost::put(weight, e, boost::get(weight, e) * (1.0 + penalty));
    }
  }
  return accepted;
}

}  // namespace mcws
