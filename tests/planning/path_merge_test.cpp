#include "mcws/planning/path_merge.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "mcws/core/error.h"

namespace mcws {
namespace {

using ::testing::ElementsAre;
using ::testing::IsEmpty;

// Sums and quotients of a few decimals: the hand-worked values agree to rounding.
constexpr double kExact = 1e-12;

// Undirected edge values keyed on (min(u, v), max(u, v)).
using EdgeMap = std::map<std::pair<std::size_t, std::size_t>, EdgeValues>;

void addEdge(EdgeMap* map, std::size_t u, std::size_t v, double length, int segments,
             double probability_sum) {
  EdgeValues e;
  e.length = length;
  e.segments = segments;
  e.probability_sum = probability_sum;
  (*map)[{std::min(u, v), std::max(u, v)}] = e;
}

EdgeValuesFn edgeFn(const EdgeMap& map) {
  return [map](std::size_t u, std::size_t v) { return map.at({std::min(u, v), std::max(u, v)}); };
}

// Roadmap distance of every vertex from the start (Bellman-Ford over the edge map): the
// order_key the planner passes.
std::function<double(std::size_t)> roadmapDistance(const EdgeMap& map, std::size_t start) {
  std::map<std::size_t, double> distance;
  for (const auto& [uv, e] : map) {
    distance[uv.first] = std::numeric_limits<double>::infinity();
    distance[uv.second] = std::numeric_limits<double>::infinity();
  }
  distance[start] = 0.0;
  for (std::size_t round = 0; round < distance.size(); ++round) {
    for (const auto& [uv, e] : map) {
      const auto [u, v] = uv;
      distance[v] = std::min(distance[v], distance[u] + e.length);
      distance[u] = std::min(distance[u], distance[v] + e.length);
    }
  }
  return [distance](std::size_t v) { return distance.at(v); };
}

ScoreOptions literal() {
  ScoreOptions options;
  options.rule = ScoreRule::kLiteral;
  return options;
}

ScoreOptions weighted(double weight, double reference_distance) {
  ScoreOptions options;
  options.rule = ScoreRule::kWeighted;
  options.weight = weight;
  options.reference_distance = reference_distance;
  return options;
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

// ---------------------------------------------------------------------------------------------
// Figure 3 of the maintenance-arm patent: a solid path (candidate 0) and a dashed path
// (candidate 1) cross at X1, then at X2, and meet again at the goal.
//
//   solid  S -a- X1 -b- X2 -c- G
//   dashed S -d- X1 -e- X2 -f- G
//
// Edges (length, segments, probability sum):
//   S-a  0.25  2 1.0    S-d  0.375 3 3.0
//   a-X1 0.25  2 1.0    d-X1 0.375 3 2.7
//   X1-b 0.25  2 2.0    X1-e 0.25  2 1.0
//   b-X2 0.25  2 2.0    e-X2 0.25  2 1.0
//   X2-c 0.5   4 4.0    X2-f 0.125 1 0.5
//   c-G  0.5   4 4.0    f-G  0.125 1 0.5
// Roadmap distances: a .25, d .375, X1 .5, b = e .75, X2 1, f 1.125, G 1.25, c 1.5.
//
// Literal rule, score = P - D:
// X1: solid  D = 0.5,  P = 2/4 = 0.5,      score 0
//     dashed D = 0.75, P = 5.7/6 = 0.95,   score 0.2    -> dashed wins (fig. 3a);
//     solid becomes S d X1 b X2 c G (fig. 3b).
// X2: solid  D = 1.25, P = 9.7/10 = 0.97,  score -0.28  -> solid wins on its own X1-b-X2;
//     dashed D = 1.25, P = 7.7/10 = 0.77,  score -0.48
//     dashed becomes S d X1 b X2 f G (fig. 3c).
// G:  solid  D = 2.25, P = 17.7/18,        score 17.7/18 - 2.25 = -1.26666...
//     dashed D = 1.5,  P = 10.7/12,        score 10.7/12 - 1.5  = -0.60833...  -> dashed wins.
// Best: dashed (1), both end as S d X1 b X2 f G.
// ---------------------------------------------------------------------------------------------
namespace fig3 {

enum : std::size_t {
  kS = 0,
  kG = 1,
  kX1 = 2,
  kX2 = 3,
  kA = 4,
  kB = 5,
  kC = 6,
  kD = 7,
  kE = 8,
  kF = 9
};

EdgeMap edges() {
  EdgeMap map;
  addEdge(&map, kS, kA, 0.25, 2, 1.0);
  addEdge(&map, kA, kX1, 0.25, 2, 1.0);
  addEdge(&map, kX1, kB, 0.25, 2, 2.0);
  addEdge(&map, kB, kX2, 0.25, 2, 2.0);
  addEdge(&map, kX2, kC, 0.5, 4, 4.0);
  addEdge(&map, kC, kG, 0.5, 4, 4.0);
  addEdge(&map, kS, kD, 0.375, 3, 3.0);
  addEdge(&map, kD, kX1, 0.375, 3, 2.7);
  addEdge(&map, kX1, kE, 0.25, 2, 1.0);
  addEdge(&map, kE, kX2, 0.25, 2, 1.0);
  addEdge(&map, kX2, kF, 0.125, 1, 0.5);
  addEdge(&map, kF, kG, 0.125, 1, 0.5);
  return map;
}

const std::vector<VertexPath> kCandidates = {{kS, kA, kX1, kB, kX2, kC, kG},
                                             {kS, kD, kX1, kE, kX2, kF, kG}};

void expectResult(const MergeResult& result) {
  ASSERT_EQ(result.decisions.size(), 3u);

  const SharedNodeDecision& x1 = result.decisions[0];
  EXPECT_EQ(x1.vertex, kX1);
  EXPECT_THAT(x1.paths, ElementsAre(0u, 1u));
  ASSERT_EQ(x1.values.size(), 2u);
  EXPECT_NEAR(x1.values[0].distance, 0.5, kExact);
  EXPECT_NEAR(x1.values[0].probability, 0.5, kExact);
  EXPECT_NEAR(x1.values[1].distance, 0.75, kExact);
  EXPECT_NEAR(x1.values[1].probability, 0.95, kExact);
  ASSERT_EQ(x1.scores.size(), 2u);
  EXPECT_NEAR(x1.scores[0], 0.0, kExact);
  EXPECT_NEAR(x1.scores[1], 0.2, kExact);
  EXPECT_EQ(x1.winner, 1u);
  EXPECT_THAT(x1.looped, IsEmpty());

  const SharedNodeDecision& x2 = result.decisions[1];
  EXPECT_EQ(x2.vertex, kX2);
  EXPECT_THAT(x2.paths, ElementsAre(0u, 1u));
  ASSERT_EQ(x2.values.size(), 2u);
  EXPECT_NEAR(x2.values[0].distance, 1.25, kExact);
  EXPECT_NEAR(x2.values[0].probability, 0.97, kExact);
  EXPECT_NEAR(x2.values[1].distance, 1.25, kExact);
  EXPECT_NEAR(x2.values[1].probability, 0.77, kExact);
  ASSERT_EQ(x2.scores.size(), 2u);
  EXPECT_NEAR(x2.scores[0], -0.28, kExact);
  EXPECT_NEAR(x2.scores[1], -0.48, kExact);
  EXPECT_EQ(x2.winner, 0u);
  EXPECT_THAT(x2.looped, IsEmpty());

  const SharedNodeDecision& goal = result.decisions[2];
  EXPECT_EQ(goal.vertex, kG);
  EXPECT_THAT(goal.paths, ElementsAre(0u, 1u));
  ASSERT_EQ(goal.values.size(), 2u);
  EXPECT_NEAR(goal.values[0].distance, 2.25, kExact);
  EXPECT_NEAR(goal.values[0].probability, 17.7 / 18.0, kExact);
  EXPECT_NEAR(goal.values[1].distance, 1.5, kExact);
  EXPECT_NEAR(goal.values[1].probability, 10.7 / 12.0, kExact);
  ASSERT_EQ(goal.scores.size(), 2u);
  EXPECT_NEAR(goal.scores[0], 17.7 / 18.0 - 2.25, kExact);
  EXPECT_NEAR(goal.scores[1], 10.7 / 12.0 - 1.5, kExact);
  EXPECT_EQ(goal.winner, 1u);
  EXPECT_THAT(goal.looped, IsEmpty());

  EXPECT_EQ(result.best, 1u);
  ASSERT_EQ(result.paths.size(), 2u);
  EXPECT_THAT(result.paths[0], ElementsAre(kS, kD, kX1, kB, kX2, kF, kG));
  EXPECT_THAT(result.paths[1], ElementsAre(kS, kD, kX1, kB, kX2, kF, kG));
}

}  // namespace fig3

TEST(MergeAtSharedNodes, FigureThreeADifferentPathWinsAtEachCrossing) {
  const EdgeMap map = fig3::edges();
  const MergeResult result =
      mergeAtSharedNodes(fig3::kCandidates, edgeFn(map), roadmapDistance(map, fig3::kS), literal());
  fig3::expectResult(result);
}

TEST(MergeAtSharedNodes, VisitsTheGoalLastWhateverItsKey) {
  // With every key 0 the ties go by vertex index, which would put G (1) before X1 (2) and X2 (3);
  // the goal still comes last, so the decisions are those of Figure 3.
  const EdgeMap map = fig3::edges();
  const MergeResult result = mergeAtSharedNodes(
      fig3::kCandidates, edgeFn(map), [](std::size_t) { return 0.0; }, literal());
  fig3::expectResult(result);
}

// ---------------------------------------------------------------------------------------------
TEST(NodeValues, HandWorkedThreeEdgePath) {
  // 0 -(0.5, 1 segment, sum 0.5)- 1 -(1.25, 3 segments, sum 2.4)- 2 -(0.75, 2 segments, sum 1.1)- 3
  //   k = 0: D = 0,    P = 1
  //   k = 1: D = 0.5,  P = 0.5 / 1
  //   k = 2: D = 1.75, P = 2.9 / 4 = 0.725
  //   k = 3: D = 2.5,  P = 4.0 / 6 = 0.6666... (the mean of the edge means would be 0.6166...)
  EdgeMap map;
  addEdge(&map, 0, 1, 0.5, 1, 0.5);
  addEdge(&map, 1, 2, 1.25, 3, 2.4);
  addEdge(&map, 2, 3, 0.75, 2, 1.1);

  const std::vector<NodeValues> values = nodeValues({0, 1, 2, 3}, edgeFn(map));
  ASSERT_EQ(values.size(), 4u);
  EXPECT_EQ(values[0].distance, 0.0);
  EXPECT_EQ(values[0].probability, 1.0);
  EXPECT_NEAR(values[1].distance, 0.5, kExact);
  EXPECT_NEAR(values[1].probability, 0.5, kExact);
  EXPECT_NEAR(values[2].distance, 1.75, kExact);
  EXPECT_NEAR(values[2].probability, 0.725, kExact);
  EXPECT_NEAR(values[3].distance, 2.5, kExact);
  EXPECT_NEAR(values[3].probability, 4.0 / 6.0, kExact);

  // Backwards: 3 -> 2 -> 1 -> 0 through the same edges.
  //   D = 0, 0.75, 2.0, 2.5;  P = 1, 1.1 / 2, 3.5 / 5, 4.0 / 6
  const std::vector<NodeValues> back = nodeValues({3, 2, 1, 0}, edgeFn(map));
  ASSERT_EQ(back.size(), 4u);
  EXPECT_NEAR(back[1].distance, 0.75, kExact);
  EXPECT_NEAR(back[1].probability, 0.55, kExact);
  EXPECT_NEAR(back[2].distance, 2.0, kExact);
  EXPECT_NEAR(back[2].probability, 0.7, kExact);
  EXPECT_NEAR(back[3].distance, 2.5, kExact);
  EXPECT_NEAR(back[3].probability, 4.0 / 6.0, kExact);
}

TEST(NodeValues, SingleVertexAndEmptyPath) {
  const EdgeMap map;
  const std::vector<NodeValues> one = nodeValues({7}, edgeFn(map));
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].distance, 0.0);
  EXPECT_EQ(one[0].probability, 1.0);
  EXPECT_THAT(nodeValues({}, edgeFn(map)), IsEmpty());
}

// ---------------------------------------------------------------------------------------------
TEST(MergeAtSharedNodes, CutsTheLoopASpliceMakes) {
  // candidate 0: S - x - v - G        candidate 1: S - a - v - y - x - G
  // Edges: S-x 0.4 2 2.0, x-v 0.05 1 1, v-G 0.5 1 1, S-a 0.05 1 0.25, a-v 0.05 1 0.25,
  //        v-y 0.1 1 1, y-x 0.1 1 1, x-G 0.2 1 0.5.
  // Roadmap distances: a .05, v .1, x .15 (through v), y .2, G .35: v comes before x although x
  // comes before v on candidate 0.
  // v: candidate 0 D = 0.45, P = 3/3 = 1,    score 0.55  -> wins
  //    candidate 1 D = 0.1,  P = 0.5/2 = .25, score 0.15
  //    splice: S x v + y x G = S x v y x G, x twice -> S x G (looped).
  // x: both reach it by S x: not shared.  y: on no candidate now.
  // G: candidate 0 S x v G: D = 0.95, P = 4/4 = 1,     score 0.05
  //    candidate 1 S x G:   D = 0.6,  P = 2.5/3,       score 2.5/3 - 0.6 = 0.2333...  -> wins
  // x has the smaller index, v the smaller key: visiting by index would decide at x instead.
  enum : std::size_t { kS = 0, kG = 1, kX = 2, kV = 3, kA = 4, kY = 5 };
  EdgeMap map;
  addEdge(&map, kS, kX, 0.4, 2, 2.0);
  addEdge(&map, kX, kV, 0.05, 1, 1.0);
  addEdge(&map, kV, kG, 0.5, 1, 1.0);
  addEdge(&map, kS, kA, 0.05, 1, 0.25);
  addEdge(&map, kA, kV, 0.05, 1, 0.25);
  addEdge(&map, kV, kY, 0.1, 1, 1.0);
  addEdge(&map, kY, kX, 0.1, 1, 1.0);
  addEdge(&map, kX, kG, 0.2, 1, 0.5);

  const MergeResult result = mergeAtSharedNodes({{kS, kX, kV, kG}, {kS, kA, kV, kY, kX, kG}},
                                                edgeFn(map), roadmapDistance(map, kS), literal());
  ASSERT_EQ(result.decisions.size(), 2u);
  const SharedNodeDecision& v = result.decisions[0];
  EXPECT_EQ(v.vertex, kV);
  EXPECT_THAT(v.paths, ElementsAre(0u, 1u));
  ASSERT_EQ(v.scores.size(), 2u);
  EXPECT_NEAR(v.scores[0], 0.55, kExact);
  EXPECT_NEAR(v.scores[1], 0.15, kExact);
  EXPECT_EQ(v.winner, 0u);
  EXPECT_THAT(v.looped, ElementsAre(1u));

  const SharedNodeDecision& goal = result.decisions[1];
  EXPECT_EQ(goal.vertex, kG);
  ASSERT_EQ(goal.scores.size(), 2u);
  EXPECT_NEAR(goal.scores[0], 0.05, kExact);
  EXPECT_NEAR(goal.scores[1], 2.5 / 3.0 - 0.6, kExact);
  EXPECT_EQ(goal.winner, 1u);
  EXPECT_THAT(goal.looped, IsEmpty());

  EXPECT_EQ(result.best, 1u);
  EXPECT_THAT(result.paths[0], ElementsAre(kS, kX, kG));
  EXPECT_THAT(result.paths[1], ElementsAre(kS, kX, kG));
}

TEST(MergeAtSharedNodes, CutsLoopsFromTheEarliestRepeatedVertex) {
  // candidate 0: S - x1 - x2 - v - G     candidate 1: S - a - v - p - x1 - q - x2 - G
  // Every edge has 1 segment of probability 1 except S-a and a-v (0.25 each); lengths 0.05
  // except S-x1 0.3, v-G 0.1, x2-G 0.1. Roadmap distances: a .05, v .1, x2 = p .15,
  // x1 = q = G .2.
  // v: candidate 0 D = 0.4, P = 1, score 0.6 (wins); candidate 1 D = 0.1, P = 0.25, score 0.15.
  //    splice: S x1 x2 v p x1 q x2 G. x1 is the earliest repeated vertex: cut x2 v p x1
  //    -> S x1 q x2 G (cutting x2's loop first would have given S x1 x2 G and no decision at x2).
  // x2: candidate 0 by S x1 x2 (D 0.35, score 0.65, wins), candidate 1 by S x1 q x2 (D 0.4,
  //    score 0.6) -> candidate 1 becomes S x1 x2 G.
  // G: candidate 0 D 0.5 score 0.5; candidate 1 D 0.45 score 0.55 (wins).
  enum : std::size_t { kS = 0, kG = 1, kV = 2, kX1 = 3, kX2 = 4, kA = 5, kP = 6, kQ = 7 };
  EdgeMap map;
  addEdge(&map, kS, kA, 0.05, 1, 0.25);
  addEdge(&map, kA, kV, 0.05, 1, 0.25);
  addEdge(&map, kS, kX1, 0.3, 1, 1.0);
  addEdge(&map, kX1, kX2, 0.05, 1, 1.0);
  addEdge(&map, kX2, kV, 0.05, 1, 1.0);
  addEdge(&map, kV, kG, 0.1, 1, 1.0);
  addEdge(&map, kV, kP, 0.05, 1, 1.0);
  addEdge(&map, kP, kX1, 0.05, 1, 1.0);
  addEdge(&map, kX1, kQ, 0.05, 1, 1.0);
  addEdge(&map, kQ, kX2, 0.05, 1, 1.0);
  addEdge(&map, kX2, kG, 0.1, 1, 1.0);

  const MergeResult result =
      mergeAtSharedNodes({{kS, kX1, kX2, kV, kG}, {kS, kA, kV, kP, kX1, kQ, kX2, kG}}, edgeFn(map),
                         roadmapDistance(map, kS), literal());
  ASSERT_EQ(result.decisions.size(), 3u);
  EXPECT_EQ(result.decisions[0].vertex, kV);
  EXPECT_EQ(result.decisions[0].winner, 0u);
  EXPECT_THAT(result.decisions[0].looped, ElementsAre(1u));

  const SharedNodeDecision& x2 = result.decisions[1];
  EXPECT_EQ(x2.vertex, kX2);
  ASSERT_EQ(x2.values.size(), 2u);
  EXPECT_NEAR(x2.values[0].distance, 0.35, kExact);
  EXPECT_NEAR(x2.values[1].distance, 0.4, kExact);
  EXPECT_NEAR(x2.scores[0], 0.65, kExact);
  EXPECT_NEAR(x2.scores[1], 0.6, kExact);
  EXPECT_EQ(x2.winner, 0u);
  EXPECT_THAT(x2.looped, IsEmpty());

  EXPECT_EQ(result.decisions[2].vertex, kG);
  EXPECT_EQ(result.decisions[2].winner, 1u);
  EXPECT_EQ(result.best, 1u);
  EXPECT_THAT(result.paths[0], ElementsAre(kS, kX1, kX2, kG));
  EXPECT_THAT(result.paths[1], ElementsAre(kS, kX1, kX2, kG));
}

// ---------------------------------------------------------------------------------------------
// Two paths meeting at the goal:
//   candidate 0, short and risky: S-r 0.25 2 1.0, r-G 0.25 2 1.4       -> D 0.5,   P 2.4/4 = 0.6
//   candidate 1, long and safe:   S-s1 0.25, s1-s2 0.25, s2-G 0.375, each 1 segment of 1
//                                                                       -> D 0.875, P 1
//   literal P - D:               0.6 - 0.5 = 0.1        1 - 0.875 = 0.125  -> long wins
//   weighted P - 2 D / 0.5:      0.6 - 2.0 = -1.4       1 - 3.5 = -2.5     -> short wins
enum : std::size_t { kRiskS = 0, kRiskG = 1, kRiskR = 2, kSafe1 = 3, kSafe2 = 4 };

EdgeMap riskyAndSafeEdges() {
  EdgeMap map;
  addEdge(&map, kRiskS, kRiskR, 0.25, 2, 1.0);
  addEdge(&map, kRiskR, kRiskG, 0.25, 2, 1.4);
  addEdge(&map, kRiskS, kSafe1, 0.25, 1, 1.0);
  addEdge(&map, kSafe1, kSafe2, 0.25, 1, 1.0);
  addEdge(&map, kSafe2, kRiskG, 0.375, 1, 1.0);
  return map;
}

TEST(Score, LiteralAndWeightedRulesChooseDifferently) {
  const EdgeMap map = riskyAndSafeEdges();
  const std::vector<VertexPath> candidates = {{kRiskS, kRiskR, kRiskG},
                                              {kRiskS, kSafe1, kSafe2, kRiskG}};

  const MergeResult by_literal =
      mergeAtSharedNodes(candidates, edgeFn(map), roadmapDistance(map, kRiskS), literal());
  ASSERT_EQ(by_literal.decisions.size(), 1u);
  EXPECT_EQ(by_literal.decisions[0].vertex, kRiskG);
  EXPECT_NEAR(by_literal.decisions[0].scores[0], 0.1, kExact);
  EXPECT_NEAR(by_literal.decisions[0].scores[1], 0.125, kExact);
  EXPECT_EQ(by_literal.best, 1u);
  EXPECT_EQ(by_literal.paths[0], candidates[1]);

  const MergeResult by_weight =
      mergeAtSharedNodes(candidates, edgeFn(map), roadmapDistance(map, kRiskS), weighted(2, 0.5));
  ASSERT_EQ(by_weight.decisions.size(), 1u);
  EXPECT_NEAR(by_weight.decisions[0].scores[0], -1.4, kExact);
  EXPECT_NEAR(by_weight.decisions[0].scores[1], -2.5, kExact);
  EXPECT_EQ(by_weight.best, 0u);
  EXPECT_EQ(by_weight.paths[1], candidates[0]);
}

TEST(Score, DocumentedFormulas) {
  NodeValues values;
  values.distance = 0.875;
  values.probability = 1.0;
  EXPECT_NEAR(score(values, literal()), 0.125, kExact);
  EXPECT_NEAR(score(values, weighted(2.0, 0.5)), -2.5, kExact);
  EXPECT_NEAR(score(values, weighted(0.0, 0.5)), 1.0, kExact);  // w = 0: P alone
}

// ---------------------------------------------------------------------------------------------
TEST(MergeAtSharedNodes, IdenticalCandidatesHaveNoSharedNode) {
  EdgeMap map;
  addEdge(&map, 0, 2, 1.0, 1, 0.5);
  addEdge(&map, 2, 1, 1.0, 1, 0.5);
  const std::vector<VertexPath> same = {{0, 2, 1}, {0, 2, 1}, {0, 2, 1}};
  const MergeResult result = mergeAtSharedNodes(same, edgeFn(map), roadmapDistance(map, 0), {});
  EXPECT_THAT(result.decisions, IsEmpty());
  EXPECT_EQ(result.best, 0u);
  EXPECT_EQ(result.paths, same);

  const MergeResult single =
      mergeAtSharedNodes({{0, 2, 1}}, edgeFn(map), roadmapDistance(map, 0), {});
  EXPECT_THAT(single.decisions, IsEmpty());
  EXPECT_EQ(single.best, 0u);
  ASSERT_EQ(single.paths.size(), 1u);
  EXPECT_THAT(single.paths[0], ElementsAre(0u, 2u, 1u));

  // Start = goal: nothing to decide.
  const MergeResult still =
      mergeAtSharedNodes({{5}, {5}}, edgeFn(map), [](std::size_t) { return 0.0; }, {});
  EXPECT_THAT(still.decisions, IsEmpty());
  EXPECT_EQ(still.best, 0u);
}

TEST(MergeAtSharedNodes, CandidatesThatBecomeIdenticalBeforeTheGoalKeepTheirIndices) {
  // candidates 0 and 2: S a X G; candidate 1: S b X G.
  // X: 0 and 2 by S a X: D 1, P 0.5, score -0.5; 1 by S b X: D 1, P 1, score 0 -> 1 wins.
  // All three are then S b X G: no decision at G, best 0.
  enum : std::size_t { kS = 0, kG = 1, kX = 2, kA = 3, kB = 4 };
  EdgeMap map;
  addEdge(&map, kS, kA, 0.5, 1, 0.5);
  addEdge(&map, kA, kX, 0.5, 1, 0.5);
  addEdge(&map, kS, kB, 0.5, 1, 1.0);
  addEdge(&map, kB, kX, 0.5, 1, 1.0);
  addEdge(&map, kX, kG, 1.0, 1, 1.0);
  const MergeResult result =
      mergeAtSharedNodes({{kS, kA, kX, kG}, {kS, kB, kX, kG}, {kS, kA, kX, kG}}, edgeFn(map),
                         roadmapDistance(map, kS), literal());
  ASSERT_EQ(result.decisions.size(), 1u);
  const SharedNodeDecision& x = result.decisions[0];
  EXPECT_EQ(x.vertex, kX);
  EXPECT_THAT(x.paths, ElementsAre(0u, 1u, 2u));
  ASSERT_EQ(x.scores.size(), 3u);
  EXPECT_NEAR(x.scores[0], -0.5, kExact);
  EXPECT_NEAR(x.scores[1], 0.0, kExact);
  EXPECT_NEAR(x.scores[2], -0.5, kExact);
  EXPECT_EQ(x.winner, 1u);
  EXPECT_EQ(result.best, 0u);
  ASSERT_EQ(result.paths.size(), 3u);
  for (const VertexPath& path : result.paths) EXPECT_THAT(path, ElementsAre(kS, kB, kX, kG));
}

TEST(MergeAtSharedNodes, EqualScoresGoToTheLowestIndex) {
  // S a G and S b G with the same edge values: D 2, P 0.75 on both.
  EdgeMap map;
  addEdge(&map, 0, 2, 1.0, 2, 1.5);
  addEdge(&map, 2, 1, 1.0, 2, 1.5);
  addEdge(&map, 0, 3, 1.0, 2, 1.5);
  addEdge(&map, 3, 1, 1.0, 2, 1.5);
  const MergeResult result =
      mergeAtSharedNodes({{0, 3, 1}, {0, 2, 1}}, edgeFn(map), roadmapDistance(map, 0), literal());
  ASSERT_EQ(result.decisions.size(), 1u);
  EXPECT_EQ(result.decisions[0].scores[0], result.decisions[0].scores[1]);
  EXPECT_NEAR(result.decisions[0].scores[0], 0.75 - 2.0, kExact);
  EXPECT_EQ(result.decisions[0].winner, 0u);
  EXPECT_EQ(result.best, 0u);
  EXPECT_THAT(result.paths[1], ElementsAre(0u, 3u, 1u));
}

// ---------------------------------------------------------------------------------------------
TEST(MergeAtSharedNodes, RejectsBadCandidates) {
  EdgeMap map;
  addEdge(&map, 0, 1, 1.0, 1, 1.0);
  addEdge(&map, 0, 2, 1.0, 1, 1.0);
  addEdge(&map, 2, 1, 1.0, 1, 1.0);
  const EdgeValuesFn edges = edgeFn(map);
  const auto key = roadmapDistance(map, 0);
  const ScoreOptions options;

  EXPECT_EQ(errorOf([&] { mergeAtSharedNodes({}, edges, key, options); }),
            "mergeAtSharedNodes: no candidate paths");
  EXPECT_EQ(errorOf([&] {
              mergeAtSharedNodes({{0, 1}, {}}, edges, key, options);
            }),
            "mergeAtSharedNodes: candidate 1 is empty");
  EXPECT_EQ(errorOf([&] {
              mergeAtSharedNodes({{0, 1}, {2, 1}}, edges, key, options);
            }),
            "mergeAtSharedNodes: candidate 1 starts at vertex 2, not at vertex 0 as candidate 0");
  EXPECT_EQ(errorOf([&] {
              mergeAtSharedNodes({{0, 2, 1}, {0, 2}}, edges, key, options);
            }),
            "mergeAtSharedNodes: candidate 1 ends at vertex 2, not at vertex 1 as candidate 0");
  EXPECT_EQ(errorOf([&] {
              mergeAtSharedNodes({{0, 1}, {0, 2, 0, 1}}, edges, key, options);
            }),
            "mergeAtSharedNodes: candidate 1 visits vertex 0 twice");
  EXPECT_EQ(errorOf([&] {
              mergeAtSharedNodes(
                  {{0, 2, 1}}, edges,
                  [](std::size_t) { return std::numeric_limits<double>::quiet_NaN(); }, options);
            }),
            "mergeAtSharedNodes: order_key of vertex 2 is nan, not a finite number");
}

TEST(Score, RejectsBadWeightedOptions) {
  const NodeValues values;
  EXPECT_EQ(errorOf([&] { score(values, weighted(-1.0, 1.0)); }),
            "score options: weight -1 is not a finite number >= 0");
  EXPECT_EQ(errorOf([&] { score(values, weighted(std::numeric_limits<double>::infinity(), 1.0)); }),
            "score options: weight inf is not a finite number >= 0");
  EXPECT_EQ(errorOf([&] { score(values, weighted(1.0, 0.0)); }),
            "score options: reference_distance 0 is not a finite number > 0");
  EXPECT_EQ(errorOf([&] { score(values, weighted(1.0, -2.5)); }),
            "score options: reference_distance -2.5 is not a finite number > 0");

  // The merge checks the options before anything else, even with nothing to decide.
  EdgeMap map;
  addEdge(&map, 0, 1, 1.0, 1, 1.0);
  EXPECT_EQ(
      errorOf([&] {
        mergeAtSharedNodes({{0, 1}}, edgeFn(map), roadmapDistance(map, 0), weighted(1.0, 0.0));
      }),
      "score options: reference_distance 0 is not a finite number > 0");

  // The literal rule does not use weight and reference_distance.
  ScoreOptions unused = literal();
  unused.weight = -1.0;
  unused.reference_distance = 0.0;
  EXPECT_NO_THROW(score(values, unused));
}

TEST(NodeValues, RejectsBadEdges) {
  EdgeMap map;
  addEdge(&map, 3, 4, 1.0, 0, 0.0);
  addEdge(&map, 4, 5, -1.0, 1, 1.0);
  addEdge(&map, 5, 6, 1.0, 2, 2.5);
  EXPECT_EQ(errorOf([&] {
              nodeValues({4, 3}, edgeFn(map));
            }),
            "edge (4, 3): segments 0 is not >= 1");
  EXPECT_EQ(errorOf([&] {
              nodeValues({4, 5}, edgeFn(map));
            }),
            "edge (4, 5): length -1 is not a finite number >= 0");
  EXPECT_EQ(errorOf([&] {
              nodeValues({5, 6}, edgeFn(map));
            }),
            "edge (5, 6): probability_sum 2.5 is not in [0, segments = 2]");
  // The merge checks every edge of every candidate, shared node or not.
  EXPECT_EQ(errorOf([&] {
              mergeAtSharedNodes({{3, 4}}, edgeFn(map), [](std::size_t) { return 0.0; }, {});
            }),
            "edge (3, 4): segments 0 is not >= 1");
}

}  // namespace
}  // namespace mcws
