// The roadmap grown in batches on all threads is OMPL's PRM grown one milestone at a time.
#include "mcws/planning/roadmap.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <tuple>
#include <vector>

#include "mcws/planning/scenario.h"
#include "test_support.h"

namespace mcws {
namespace {

/// The roadmap's vertices and its edges (ends and weight), in the graph's order.
struct RoadmapContents {
  std::vector<Eigen::VectorXd> configurations;
  std::vector<std::tuple<std::size_t, std::size_t, double>> edges;
  std::vector<double> distance_from_start;
  RoadmapStatus status;
};

RoadmapContents grow(const Scenario& scenario, std::size_t batch, int threads, std::size_t nodes) {
  const SwayPlanningProblem& p = scenario.problem;
  const CollisionChecker checker(p.robot, p.collision);
  const MotionCertifier certifier(p.robot, checker);
  RoadmapOptions options = p.roadmap;
  options.nodes = nodes;
  options.max_nodes = 2 * nodes;
  options.batch = batch;
  omp_set_num_threads(threads);
  const Roadmap roadmap = buildRoadmap(certifier, p.robot.T_world_base, p.start, p.goal, options);
  omp_set_num_threads(omp_get_num_procs());
  RoadmapContents out{roadmap.configurations, {}, roadmap.distance_from_start, roadmap.status};
  for (auto [e, end] = boost::edges(roadmap.graph); e != end; ++e) {
    out.edges.emplace_back(boost::source(*e, roadmap.graph), boost::target(*e, roadmap.graph),
                           boost::get(boost::edge_weight, roadmap.graph, *e));
  }
  return out;
}

void expectSame(const RoadmapContents& a, const RoadmapContents& b) {
  EXPECT_EQ(a.status, b.status);
  ASSERT_EQ(a.configurations.size(), b.configurations.size());
  for (std::size_t v = 0; v < a.configurations.size(); ++v)
    EXPECT_EQ(a.configurations[v], b.configurations[v]) << "vertex " << v;
  EXPECT_EQ(a.edges, b.edges);
  EXPECT_EQ(a.distance_from_start, b.distance_from_start);
}

TEST(Roadmap, BatchesOnAllThreadsGrowOmplsRoadmapOfOneMilestoneAtATime) {
  const std::string scenarios = std::string(MCWS_ROBOTS_DIR) + "/../scenarios/";
  // The maintenance arm among the bundle (most draws and many motions collide) and the planar
  // arm beside its post; batch sizes that do and do not divide the node count.
  for (const auto& [file, nodes] :
       {std::pair{"maintenance4.yaml", test::kSanitizerShrink > 1 ? 120 : 400},
        std::pair{"planar2.yaml", 150}}) {
    SCOPED_TRACE(file);
    const Scenario scenario = loadScenario(scenarios + file);
    const RoadmapContents ompl = grow(scenario, 0, 1, static_cast<std::size_t>(nodes));
    EXPECT_GE(ompl.configurations.size(), static_cast<std::size_t>(nodes));
    EXPECT_GT(ompl.edges.size(), static_cast<std::size_t>(nodes));  // a connected roadmap
    for (const auto& [batch, threads] : {std::pair{64, 2}, {64, 1}, {7, 2}, {1, 2}}) {
      SCOPED_TRACE("batch " + std::to_string(batch) + ", threads " + std::to_string(threads));
      expectSame(ompl, grow(scenario, static_cast<std::size_t>(batch), threads,
                            static_cast<std::size_t>(nodes)));
    }
  }
}

}  // namespace
}  // namespace mcws
