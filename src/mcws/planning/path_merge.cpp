#include "mcws/planning/path_merge.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <string>
#include <utility>

#include "mcws/core/decimal.h"
#include "mcws/core/error.h"

namespace mcws {
namespace {

std::string edgeName(std::size_t u, std::size_t v) {
  return "edge (" + std::to_string(u) + ", " + std::to_string(v) + ")";
}

/// The values of edge (u, v), checked: segments >= 1, a finite length >= 0, and a probability
/// sum in [0, segments] (each segment's probability is in [0, 1]).
EdgeValues checkedEdge(const EdgeValuesFn& edges, std::size_t u, std::size_t v) {
  const EdgeValues e = edges(u, v);
  if (e.segments < 1) {
    throw Error(edgeName(u, v) + ": segments " + std::to_string(e.segments) + " is not >= 1");
  }
  if (!std::isfinite(e.length) || e.length < 0.0) {
    throw Error(edgeName(u, v) + ": length " + formatNumber(e.length) +
                " is not a finite number >= 0");
  }
  if (!std::isfinite(e.probability_sum) || e.probability_sum < 0.0 ||
      e.probability_sum > static_cast<double>(e.segments)) {
    throw Error(edgeName(u, v) + ": probability_sum " + formatNumber(e.probability_sum) +
                " is not in [0, segments = " + std::to_string(e.segments) + "]");
  }
  return e;
}

/// Node values at path[0] .. path[count - 1] (count <= path.size()).
std::vector<NodeValues> prefixValues(const VertexPath& path, std::size_t count,
                                     const EdgeValuesFn& edges) {
  std::vector<NodeValues> values;
  values.reserve(count);
  double distance = 0.0;
  double probability_sum = 0.0;
  std::int64_t segments = 0;
  for (std::size_t k = 0; k < count; ++k) {
    if (k > 0) {
      const EdgeValues e = checkedEdge(edges, path[k - 1], path[k]);
      distance += e.length;
      probability_sum += e.probability_sum;
      segments += e.segments;
    }
    NodeValues node;
    node.distance = distance;
    node.probability = segments == 0 ? 1.0 : probability_sum / static_cast<double>(segments);
    values.push_back(node);
  }
  return values;
}

void checkOptions(const ScoreOptions& options) {
  if (options.rule != ScoreRule::kWeighted) return;
  if (!std::isfinite(options.weight) || options.weight < 0.0) {
    throw Error("score options: weight " + formatNumber(options.weight) +
                " is not a finite number >= 0");
  }
  if (!std::isfinite(options.reference_distance) || options.reference_distance <= 0.0) {
    throw Error("score options: reference_distance " + formatNumber(options.reference_distance) +
                " is not a finite number > 0");
  }
}

double uncheckedScore(const NodeValues& values, const ScoreOptions& options) {
  if (options.rule == ScoreRule::kLiteral) return values.probability - values.distance;
  return values.probability - options.weight * values.distance / options.reference_distance;
}

/// Cuts the loops out of a path: for the earliest vertex along the path that occurs again, keeps
/// its first occurrence and drops everything after it up to and including its last occurrence;
/// then the same for the next vertex along the path, until every vertex occurs once.
/// \return whether anything was cut.
bool cutLoops(VertexPath* path) {
  bool cut = false;
  for (std::size_t i = 0; i < path->size(); ++i) {
    const auto first = path->begin() + static_cast<std::ptrdiff_t>(i);
    const auto last = std::find(path->rbegin(), path->rend(), *first).base() - 1;
    if (last != first) {
      path->erase(first + 1, last + 1);
      cut = true;
    }
  }
  return cut;
}

/// Whether the first n vertices of a and of b are the same sequence (n <= both sizes).
bool samePrefix(const VertexPath& a, std::size_t n_a, const VertexPath& b, std::size_t n_b) {
  return n_a == n_b &&
         std::equal(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(n_a), b.begin());
}

/// The candidates checked: at least one, none empty, all from candidate 0's start to its goal,
/// no vertex twice, every edge's values valid.
void checkCandidates(const std::vector<VertexPath>& candidates, const EdgeValuesFn& edges,
                     const std::string& where) {
  if (candidates.empty()) throw Error(where + "no candidate paths");
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const VertexPath& path = candidates[i];
    const std::string name = "candidate " + std::to_string(i);
    if (path.empty()) throw Error(where + name + " is empty");
    if (path.front() != candidates[0].front()) {
      throw Error(where + name + " starts at vertex " + std::to_string(path.front()) +
                  ", not at vertex " + std::to_string(candidates[0].front()) + " as candidate 0");
    }
    if (path.back() != candidates[0].back()) {
      throw Error(where + name + " ends at vertex " + std::to_string(path.back()) +
                  ", not at vertex " + std::to_string(candidates[0].back()) + " as candidate 0");
    }
    std::set<std::size_t> seen;
    for (std::size_t v : path) {
      if (!seen.insert(v).second) {
        throw Error(where + name + " visits vertex " + std::to_string(v) + " twice");
      }
    }
    prefixValues(path, path.size(), edges);  // checks every edge; splices only reuse these edges
  }
}

/// Visit order: the vertices other than the start and the goal by (order_key, index), then the
/// goal.
std::vector<std::size_t> visitOrder(const std::vector<VertexPath>& candidates,
                                    const std::function<double(std::size_t)>& order_key,
                                    const std::string& where) {
  const std::size_t start = candidates[0].front();
  const std::size_t goal = candidates[0].back();
  std::set<std::size_t> vertices;
  for (const VertexPath& path : candidates) vertices.insert(path.begin(), path.end());
  vertices.erase(start);
  vertices.erase(goal);
  std::vector<std::pair<double, std::size_t>> keyed;
  keyed.reserve(vertices.size());
  for (std::size_t v : vertices) {
    const double key = order_key(v);
    if (!std::isfinite(key)) {
      throw Error(where + "order_key of vertex " + std::to_string(v) + " is " + formatNumber(key) +
                  ", not a finite number");
    }
    keyed.emplace_back(key, v);
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::size_t> order;
  order.reserve(keyed.size() + 1);
  for (const auto& [key, v] : keyed) order.push_back(v);
  if (goal != start) order.push_back(goal);
  return order;
}

/// The paths through a vertex (ascending index) and the length of each one's prefix up to it.
struct PathsThrough {
  std::vector<std::size_t> paths;
  std::vector<std::size_t> prefix_size;
};

PathsThrough pathsThrough(const std::vector<VertexPath>& paths, std::size_t v) {
  PathsThrough through;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    const VertexPath& path = paths[i];
    const auto it = std::find(path.begin(), path.end(), v);
    if (it == path.end()) continue;
    through.paths.push_back(i);
    through.prefix_size.push_back(static_cast<std::size_t>(it - path.begin()) + 1);
  }
  return through;
}

/// Whether two or more of the paths reach the vertex by different prefixes.
bool shared(const std::vector<VertexPath>& paths, const PathsThrough& through) {
  for (std::size_t j = 1; j < through.paths.size(); ++j) {
    if (!samePrefix(paths[through.paths[0]], through.prefix_size[0], paths[through.paths[j]],
                    through.prefix_size[j])) {
      return true;
    }
  }
  return false;
}

/// The decision at shared vertex v: each path's values and score there, the best score wins
/// (the lowest index among equal scores); `winner` receives its position in `through`.
SharedNodeDecision decide(const std::vector<VertexPath>& paths, std::size_t v,
                          const PathsThrough& through, const EdgeValuesFn& edges,
                          const ScoreOptions& options, std::size_t& winner) {
  SharedNodeDecision decision;
  decision.vertex = v;
  decision.paths = through.paths;
  winner = 0;
  for (std::size_t j = 0; j < through.paths.size(); ++j) {
    const NodeValues values =
        prefixValues(paths[through.paths[j]], through.prefix_size[j], edges).back();
    decision.values.push_back(values);
    decision.scores.push_back(uncheckedScore(values, options));
    if (decision.scores[j] > decision.scores[winner]) winner = j;
  }
  decision.winner = through.paths[winner];
  return decision;
}

/// The winner's prefix up to the vertex put in place of the other paths' prefixes, loops cut
/// (the paths where a loop was cut are added to decision.looped).
void splice(std::vector<VertexPath>& paths, const PathsThrough& through, std::size_t winner,
            SharedNodeDecision& decision) {
  const VertexPath& won = paths[decision.winner];
  const VertexPath prefix(won.begin(),
                          won.begin() + static_cast<std::ptrdiff_t>(through.prefix_size[winner]));
  for (std::size_t j = 0; j < through.paths.size(); ++j) {
    VertexPath& path = paths[through.paths[j]];
    if (samePrefix(path, through.prefix_size[j], prefix, prefix.size())) continue;
    VertexPath spliced = prefix;
    spliced.insert(spliced.end(),
                   path.begin() + static_cast<std::ptrdiff_t>(through.prefix_size[j]), path.end());
    if (cutLoops(&spliced)) decision.looped.push_back(through.paths[j]);
    path = std::move(spliced);
  }
}

}  // namespace

// s41 (D) and s42 (P):
// "将在同一条非碰撞路径上的节点构型与初始构型之间所有路径段的第二自由状态概率相加
// 除以路径段数目，获得节点构型与初始构型之间的第一自由状态概率" (sum the segment probabilities
// between the start and the node along the path and divide by the number of segments).
std::vector<NodeValues> nodeValues(const VertexPath& path, const EdgeValuesFn& edges) {
  return prefixValues(path, path.size(), edges);
}

double score(const NodeValues& values, const ScoreOptions& options) {
  checkOptions(options);
  return uncheckedScore(values, options);
}

MergeResult mergeAtSharedNodes(const std::vector<VertexPath>& candidates, const EdgeValuesFn& edges,
                               const std::function<double(std::size_t)>& order_key,
                               const ScoreOptions& options) {
  const std::string where = "mergeAtSharedNodes: ";
  checkOptions(options);
  checkCandidates(candidates, edges, where);
  const std::size_t goal = candidates[0].back();
  MergeResult result;
  result.paths = candidates;
  for (std::size_t v : visitOrder(candidates, order_key, where)) {
    // s43/s44: "判断节点构型是否有2条或2条以上非碰撞路径经过；如果否，则判断下一个节点构型" (does
    // the node have two or more paths through it? if not, go to the next node).
    const PathsThrough through = pathsThrough(result.paths, v);
    if (!shared(result.paths, through)) continue;
    // s45: "选择出第一自由状态概率与欧氏距离数学差值最大的非碰撞路径作为优势路径" (the path whose
    // free-state probability minus distance is largest is the dominant path).
    std::size_t winner = 0;
    SharedNodeDecision decision = decide(result.paths, v, through, edges, options, winner);
    // s46:
    // "用优势路径上同一节点构型与初始构型之间的所有节点对非优势路经上...的节点进行替换，替换后非
    // 优势路经上剩余的所有节点处的欧氏距离值和自由状态概率值重新计算" (the dominant path's nodes
    // from the start to this node replace the other paths' ones; their later values are
    // recomputed, here from the edges whenever they are needed).
    splice(result.paths, through, winner, decision);
    result.decisions.push_back(std::move(decision));
  }
  // s47: "将在目标节点处选出的优势路径作为全局最优路径" (the dominant path at the goal is the
  // global best path).
  const bool decided_at_goal = !result.decisions.empty() && result.decisions.back().vertex == goal;
  result.best = decided_at_goal ? result.decisions.back().winner : 0;
  return result;
}

}  // namespace mcws
