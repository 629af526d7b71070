// Monte Carlo sampling throughput: forward kinematics of the sampler with file writing excluded,
// and the streaming PCD writer alone. Run: build/bench/bench_sampler (see BENCHMARKS.md).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/robot_yaml.h"
#include "mcws/sampling/sampler.h"

namespace {

const char* const kRobots[] = {"deicing", "ta1400", "inspection6"};
constexpr std::size_t kBatch = 1u << 20;

void BM_SampleForwardKinematics(benchmark::State& state) {
  const std::string name = kRobots[state.range(0)];
  const mcws::Robot robot = mcws::loadRobot(std::string(MCWS_ROBOTS_DIR) + "/" + name + ".yaml");
  const mcws::RobotSampler sampler(robot, {});
  std::vector<mcws::WorkspacePoint, Eigen::aligned_allocator<mcws::WorkspacePoint>> out(kBatch);
  std::uint64_t first = 0;
  for (auto _ : state) {
    mcws::generateParallel(sampler, first, kBatch, out.data(), static_cast<int>(state.range(1)));
    benchmark::DoNotOptimize(out.data());
    first += kBatch;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBatch));
  state.SetLabel(name);
}
BENCHMARK(BM_SampleForwardKinematics)
    ->ArgsProduct({{0, 1, 2}, {1, 2}})
    ->ArgNames({"robot", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The general chain (toolPose: 4x4 products, Eigen AngleAxis per joint) on the same random joint
// values, one thread: what the sampling kernel is compared with.
void BM_ChainToolPose(benchmark::State& state) {
  const std::string name = kRobots[state.range(0)];
  const mcws::Robot robot = mcws::loadRobot(std::string(MCWS_ROBOTS_DIR) + "/" + name + ".yaml");
  const mcws::CounterRng rng(1);
  Eigen::VectorXd q(robot.dof());
  std::uint64_t index = 0;
  for (auto _ : state) {
    for (int j = 0; j < robot.dof(); ++j) {
      q[j] = robot.joints[j].lower +
             (robot.joints[j].upper - robot.joints[j].lower) * rng.uniform(index, j);
    }
    benchmark::DoNotOptimize(mcws::toolPose(robot, q).translation());
    ++index;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
  state.SetLabel(name);
}
BENCHMARK(BM_ChainToolPose)->DenseRange(0, 2);

void BM_PcdStreamWriter(benchmark::State& state) {
  std::vector<mcws::WorkspacePoint, Eigen::aligned_allocator<mcws::WorkspacePoint>> points(kBatch);
  const std::string path =
      std::getenv("MCWS_BENCH_DIR")
          ? std::string(std::getenv("MCWS_BENCH_DIR")) + "/mcws_bench_writer.pcd"
          : "/tmp/mcws_bench_writer.pcd";
  for (auto _ : state) {
    mcws::io::PcdStreamWriter<mcws::WorkspacePoint> writer(path, 8 * kBatch);
    for (int k = 0; k < 8; ++k) writer.write(points.data(), kBatch);
    writer.commit();
  }
  std::remove(path.c_str());
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * 8 * kBatch * 48));
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * 8 * kBatch));
}
BENCHMARK(BM_PcdStreamWriter)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
