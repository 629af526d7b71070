#pragma once
/// \file
/// \brief The maintenance-arm patent's evaluation of candidate paths at shared nodes (steps s41 to
/// s47): node values D and P along each path, the dominant path at each node that several paths
/// pass through, the splice of its prefix into the others.

#include <cstddef>
#include <functional>
#include <vector>

#include "mcws/planning/k_shortest_paths.h"

namespace mcws {

/// \brief What one roadmap edge contributes to the node values of a path through it.
struct EdgeValues {
  double length{0.0};           ///< joint-space length of the edge [scaled joint distance]
  double probability_sum{0.0};  ///< sum of the free-state probabilities of its segments
  int segments{0};              ///< number of segments the edge is cut into (>= 1)
};

/// \brief Values of the edge between two roadmap vertices (the same in either direction).
using EdgeValuesFn = std::function<EdgeValues(std::size_t u, std::size_t v)>;

/// \brief The values of the maintenance-arm patent at one node of a path.
struct NodeValues {
  /// D (step s41): path length from the start along the path [scaled joint distance].
  double distance{0.0};
  /// P (step s42): mean of the segment free-state probabilities from the start to the node
  /// (1 at the start itself, which has no segment before it).
  double probability{1.0};
};

/// \brief Node values at every vertex of a path (element k for path[k]).
///
/// D at path[k] is the sum of the edge lengths before k; P is the sum of the edges'
/// probability_sum before k over the sum of their segments (a mean over segments, not over
/// edges); at k = 0, D = 0 and P = 1. An empty path gives no values.
/// \throws mcws::Error naming the edge when an edge has segments < 1, a negative or non-finite
/// length, or a probability_sum outside [0, segments].
std::vector<NodeValues> nodeValues(const VertexPath& path, const EdgeValuesFn& edges);

/// \brief How a path's values at a node are scored (step s45: the largest score dominates).
enum class ScoreRule {
  kLiteral,   ///< P - D, the patent's words, in the scenario's declared units
  kWeighted,  ///< P - weight * D / reference_distance
};

/// \brief Score rule and its parameters.
struct ScoreOptions {
  ScoreRule rule{ScoreRule::kWeighted};
  double weight{1.0};              ///< w of the weighted rule
  double reference_distance{1.0};  ///< D0 of the weighted rule, > 0 [scaled joint distance]
};

/// \brief The score of node values under a rule.
/// \throws mcws::Error naming the field and value, for the weighted rule only, when weight is
/// negative or not finite or reference_distance is not a finite number > 0 (the literal rule
/// ignores both fields).
double score(const NodeValues& values, const ScoreOptions& options);

/// \brief One decision at a shared node (steps s43 to s46).
struct SharedNodeDecision {
  std::size_t vertex{0};            ///< the roadmap vertex
  std::vector<std::size_t> paths;   ///< candidates through it, each with its own prefix
  std::vector<NodeValues> values;   ///< their values at the vertex before the splice (same order)
  std::vector<double> scores;       ///< their scores (same order)
  std::size_t winner{0};            ///< candidate index of the dominant path
  std::vector<std::size_t> looped;  ///< candidates whose splice made a loop, cut out
};

/// \brief Result of the evaluation: the candidates after every splice and the best path.
struct MergeResult {
  std::vector<VertexPath> paths;              ///< candidates after the splices, same indices
  std::vector<SharedNodeDecision> decisions;  ///< in the order taken
  std::size_t best{0};  ///< the dominant path at the goal (step s47): the global best path
};

/// \brief Runs steps s43 to s47 over candidate paths that share their first and last vertex.
///
/// A shared node is a vertex that two or more candidates reach through different prefixes
/// (different vertex sequences from the start). Vertices are visited in increasing
/// `order_key` (the roadmap distance from the start). At each shared node the candidate with
/// the largest score dominates (ties: the lowest index); every other candidate through the node
/// takes the dominant prefix up to it, and any loop the splice makes (a vertex that now occurs
/// twice) is cut out. Values are recomputed from the edges after every splice. The goal is the
/// last decision; when no two candidates differ, the best is candidate 0.
///
/// Details:
/// - The vertices visited are those of the input candidates except the start, ordered by
///   (`order_key`, vertex index); the goal is always visited last, whatever its key. Each visit
///   looks at the candidates as already spliced, so a vertex that a splice or cut removed from a
///   candidate no longer counts for it.
/// - The splice is winner's prefix (start .. node) + the other candidate's own suffix after the
///   node. Loops are then cut from the front: the earliest vertex along the spliced path that
///   occurs again keeps its first occurrence and everything after it, up to and including its
///   last occurrence, is dropped; then the next such vertex, until the path is simple. A cut may
///   remove the node itself from that candidate. Such candidates are listed in `looped`.
/// - Candidates whose prefix equals the winner's are listed in the decision but left as they
///   are; candidates that become identical keep their own indices.
/// - `best` is the winner of the decision at the goal; without one (all candidates are the same
///   vertex sequence by then, or start == goal) it is 0.
/// \param candidates loop-free paths, all from the same start to the same goal
/// \param edges values of every edge of the candidates (splices use no other edges)
/// \param order_key roadmap distance of a vertex from the start [scaled joint distance]
/// \param options the score rule
/// \throws mcws::Error when there are no candidates, a candidate is empty, does not share
/// candidate 0's start and goal or visits a vertex twice (each names the candidate index), an
/// order_key is not finite, an edge is bad (see nodeValues) or the options are (see score).
MergeResult mergeAtSharedNodes(const std::vector<VertexPath>& candidates, const EdgeValuesFn& edges,
                               const std::function<double(std::size_t)>& order_key,
                               const ScoreOptions& options);

}  // namespace mcws
