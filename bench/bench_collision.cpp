// Collision-checked sampling throughput (file writing excluded): LabelledRobotSampler through
// generateParallel on ta1400 with capsules and with triangle meshes, and what the exact capsule
// test and the bounding-sphere broad phase each save. Run: build/bench/bench_collision (see
// BENCHMARKS.md).
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "mcws/collision/collision_sampler.h"
#include "mcws/kinematics/robot_yaml.h"

namespace {

constexpr std::size_t kBatch = 1u << 17;

/// range(0): 0 ta1400 (capsules), 1 ta1400_mesh; range(1): threads; range(2): 0 default,
/// 1 capsules through fcl::collide, 2 no bounding spheres.
void BM_LabelledSampling(benchmark::State& state) {
  const std::string name = state.range(0) == 0 ? "ta1400" : "ta1400_mesh";
  const std::string path = std::string(MCWS_ROBOTS_DIR) + "/" + name + ".yaml";
  const mcws::Robot robot = mcws::loadRobot(path);
  mcws::CollisionCheckerOptions options;
  options.exact_capsules = state.range(2) != 1;
  options.bounding_spheres = state.range(2) != 2;
  const mcws::CollisionChecker checker(robot, mcws::loadCollisionModel(robot, path), options);
  const mcws::LabelledRobotSampler sampler(robot, {}, checker);
  const std::size_t batch = state.range(0) == 0 ? kBatch : kBatch / 8;
  std::vector<mcws::WorkspacePoint, Eigen::aligned_allocator<mcws::WorkspacePoint>> out(batch);
  std::uint64_t first = 0;
  for (auto _ : state) {
    mcws::generateParallel(sampler, first, batch, out.data(), static_cast<int>(state.range(1)));
    benchmark::DoNotOptimize(out.data());
    first += batch;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * batch));
  state.SetLabel(name + (state.range(2) == 1   ? " fcl-capsules"
                         : state.range(2) == 2 ? " no-bounding-spheres"
                                               : ""));
}
BENCHMARK(BM_LabelledSampling)
    ->ArgsProduct({{0, 1}, {1, 2}, {0}})
    ->Args({0, 1, 1})
    ->Args({0, 1, 2})
    ->Args({1, 1, 2})
    ->ArgNames({"mesh", "threads", "variant"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
