#pragma once
/// \file
/// \brief Loop-free shortest paths through a roadmap: Yen's k shortest paths, and a set of diverse
/// candidate paths for step s30 of the maintenance-arm patent (paths that split and re-merge, as in
/// its Figure 3).

#include <boost/graph/adjacency_list.hpp>
#include <cstddef>
#include <vector>

namespace mcws {

/// \brief An undirected roadmap with edge lengths (e.g. a copy of OMPL's PRM roadmap whose
/// weights are scaled joint-space distances). Vertex descriptors are indices 0 .. n-1.
using RoadmapGraph =
    boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS, boost::no_property,
                          boost::property<boost::edge_weight_t, double>>;

/// \brief A path through a roadmap: vertex indices, source first, target last.
using VertexPath = std::vector<std::size_t>;

/// \brief Sum of the edge weights along a path (0 for a single vertex or an empty path).
///
/// Where parallel edges join two consecutive vertices, the lightest one counts (the edge
/// kShortestPaths uses). The weights are summed from source to target.
/// \throws mcws::Error for a vertex index out of range, or when two consecutive vertices are not
/// joined by an edge.
double pathLength(const RoadmapGraph& graph, const VertexPath& path);

/// \brief The k shortest loop-free paths from source to target, shortest first (Yen, "Finding
/// the k shortest loopless paths in a network", Management Science 17(11), 1971), built on
/// Boost.Graph's dijkstra_shortest_paths over a filtered_graph.
///
/// - A path is its vertex sequence. Parallel edges count once, as the lightest of them;
///   self-loops are ignored (no loop-free path uses one), though their weights are checked.
/// - Order: by length (weights summed from source to target), equal lengths by lexicographic
///   vertex sequence. Each spur path is the lexicographically smallest of the shortest ones, so
///   the result is exactly the first k loop-free paths in that order whenever the sums are exact
///   in double (e.g. integer weights); otherwise it is so up to rounding of equal lengths.
/// - The result for k is a prefix of the result for k + 1.
/// - source == target gives the single path {source}; k = 0 gives none.
/// \return fewer than k paths when the graph has fewer; none when target is unreachable.
/// \throws mcws::Error for a vertex index out of range or a negative or non-finite weight.
std::vector<VertexPath> kShortestPaths(const RoadmapGraph& graph, std::size_t source,
                                       std::size_t target, std::size_t k);

/// \brief m distinct loop-free paths that share parts and differ elsewhere.
///
/// Diversity rule (the penalty method): after each accepted path, the weight of every edge it
/// uses is multiplied by (1 + penalty); the next path is the shortest loop-free path under the
/// penalised weights that is not already accepted (found with kShortestPaths, so it is always
/// distinct). An edge on several accepted paths is multiplied once per path, so its penalty
/// compounds. Ties and parallel edges are treated as in kShortestPaths (the lightest parallel
/// edge is the one penalised). penalty = 0 gives Yen's k shortest paths exactly. Fewer than m
/// paths come back when the graph has fewer loop-free paths; an edge whose penalised weight
/// overflows to infinity is no longer used. Cost: m runs of Yen's algorithm, the j-th for j paths.
/// \param penalty relative weight increase per use, >= 0 [dimensionless]
/// \throws mcws::Error as kShortestPaths, or for a negative or non-finite penalty.
std::vector<VertexPath> diversePaths(const RoadmapGraph& graph, std::size_t source,
                                     std::size_t target, std::size_t m, double penalty);

}  // namespace mcws
