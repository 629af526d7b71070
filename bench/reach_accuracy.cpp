// How accurate a reachability map from samples is: a map of inspection6 (Liu, Han, Xu & Li 2021)
// against inverse kinematics on voxel-centre x orientation-bin pairs, and how the mean
// reachability index converges as the sample count doubles.
// Usage: reach_accuracy [--resolution MM (100)] [--pairs P (2000)] [--from N (1000000)]
//                       [--to N (256000000)] [--threads T (0)] [--ik-rolls R (8)]
//                       [--ik-restarts K (20)]
// A pair is IK-reachable when solveIk reaches the voxel centre with the approach (tool z) along
// the bin's centre direction at one of the rolls tried; the map marks it reachable when a
// sample fell in that voxel with its approach in that bin. Agreement = share of the IK-reachable
// pairs the map marks; false positives = share of the pairs the map marks that IK does not reach
// at the centre (the voxel or bin is only partly reachable).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "mcws/core/counter_rng.h"
#include "mcws/kinematics/inverse_kinematics.h"
#include "mcws/kinematics/robot_yaml.h"
#include "mcws/reach/reach_map.h"

namespace {

struct Pair {
  Eigen::Vector3d centre;
  int bin;
  bool ik_reachable;
};

}  // namespace

int main(int argc, char** argv) {
  double resolution = 100.0;
  int pairs = 2000, threads = 0, rolls = 8, restarts = 20;
  std::uint64_t from = 1000000, to = 256000000;
  for (int k = 1; k + 1 < argc; k += 2) {
    const std::string flag = argv[k];
    const char* value = argv[k + 1];
    if (flag == "--resolution")
      resolution = std::atof(value);
    else if (flag == "--pairs")
      pairs = std::atoi(value);
    else if (flag == "--from")
      from = std::strtoull(value, nullptr, 10);
    else if (flag == "--to")
      to = std::strtoull(value, nullptr, 10);
    else if (flag == "--threads")
      threads = std::atoi(value);
    else if (flag == "--ik-rolls")
      rolls = std::atoi(value);
    else if (flag == "--ik-restarts")
      restarts = std::atoi(value);
    else {
      std::fprintf(stderr, "reach_accuracy: unknown flag %s\n", flag.c_str());
      return 2;
    }
  }
  const mcws::Robot robot = mcws::loadRobot(std::string(MCWS_ROBOTS_DIR) + "/inspection6.yaml");
  mcws::ReachGrid grid;
  grid.resolution = resolution;
  grid.directions = 200;
  grid.rolls = 1;
  const mcws::ReachMap shape(grid);

  // Voxel centres uniform among the grid's voxels within the chain's length of the shoulder,
  // orientation bins uniform: a seeded, reproducible reference set.
  const double reach = mcws::chainLengthScale(robot);
  const Eigen::Vector3d shoulder = robot.joints[0].T_parent_joint.translation();
  const mcws::CounterRng rng(2026);
  std::vector<Pair> reference;
  for (std::uint64_t i = 0; static_cast<int>(reference.size()) < pairs; ++i) {
    Eigen::Vector3d p;
    for (int a = 0; a < 3; ++a) p[a] = shoulder[a] + reach * (2.0 * rng.uniform(i, a) - 1.0);
    if ((p - shoulder).norm() > reach) continue;
    const Eigen::Vector3d centre = shape.voxelCentre(shape.voxelOf(p));
    const int bin = std::min(shape.bins().size() - 1,
                             static_cast<int>(rng.uniform(i, 3) * shape.bins().size()));
    reference.push_back({centre, bin, false});
  }
  const auto ik_start = std::chrono::steady_clock::now();
  const mcws::IkSolver solver(robot);
  int ik_reachable = 0;
#pragma omp parallel for schedule(dynamic) reduction(+ : ik_reachable)
  for (int i = 0; i < pairs; ++i) {
    Pair& pair = reference[i];
    const Eigen::Matrix3d R0 = shape.bins().centre(pair.bin);
    for (int roll = 0; roll < rolls && !pair.ik_reachable; ++roll) {
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.linear() = R0 * Eigen::AngleAxisd(roll * 2.0 * M_PI / rolls, Eigen::Vector3d::UnitZ());
      T.translation() = pair.centre;
      mcws::IkOptions options;
      options.position_tolerance = 1e-3;  // mm
      options.orientation_tolerance = 1e-5;
      options.restarts = restarts;
      options.seed = static_cast<std::uint64_t>(i) * rolls + roll + 1;
      pair.ik_reachable = solver.solve(T, Eigen::VectorXd::Zero(robot.dof()), options).converged();
    }
    ik_reachable += pair.ik_reachable;
  }
  const double ik_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - ik_start).count();
  std::printf(
      "inspection6, resolution %.0f mm, %d directions x 1 roll, %d pairs: %d IK-reachable "
      "(IK at %d rolls, %d restarts each: %.1f s)\n\n",
      resolution, grid.directions, pairs, ik_reachable, rolls, restarts, ik_seconds);
  std::printf(
      "| samples N | voxels | mean D | mean D change from N/2 | agreement (IK-reachable "
      "pairs marked) | false positives (marked, not IK-reachable at the centre) | map s |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|\n");

  mcws::ReachMap map(grid);
  std::uint64_t done = 0;
  double previous_mean = 0.0;
  for (std::uint64_t n = from; n <= to; n *= 2) {
    mcws::ReachSampling sampling;
    sampling.first = done;
    sampling.samples = n - done;
    sampling.threads = threads;
    sampling.manipulability = false;
    const auto start = std::chrono::steady_clock::now();
    map.merge(mcws::buildReachMap(robot, grid, sampling));
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    done = n;
    int marked_reachable = 0, marked = 0, marked_unreachable = 0;
    for (const Pair& pair : reference) {
      const long v = map.find(pair.centre);
      const bool on = v >= 0 && map.reached(static_cast<std::size_t>(v), pair.bin);
      marked += on;
      marked_reachable += on && pair.ik_reachable;
      marked_unreachable += on && !pair.ik_reachable;
    }
    const double mean = map.meanReachability();
    char change[32] = "-";
    if (previous_mean > 0.0)
      std::snprintf(change, sizeof change, "%+.2f %%", 100.0 * (mean / previous_mean - 1.0));
    std::printf("| %.3g | %zu | %.4f | %s | %.2f %% | %.2f %% | %.1f |\n", static_cast<double>(n),
                map.size(), mean, change, 100.0 * marked_reachable / std::max(1, ik_reachable),
                100.0 * marked_unreachable / std::max(1, marked), seconds);
    std::fflush(stdout);
    previous_mean = mean;
  }
  return 0;
}
