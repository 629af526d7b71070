// mcws_reach: the reachability map of a robot (Zacharias, Borst & Hirzinger 2007; ROS Reuleaux):
// Monte Carlo joint samples through forward kinematics into position voxels x orientation bins.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "common/app.h"
#include "common/flags.h"
#include "common/reach_args.h"
#include "mcws/collision/collision_checker.h"
#include "mcws/collision/collision_model.h"
#include "mcws/distributed/processes.h"
#include "mcws/io/atomic_file.h"
#include "mcws/io/cloud_io.h"
#include "mcws/io/pcd_stream_writer.h"
#include "mcws/reach/reach_checkpoint.h"
#include "mcws/reach/reach_map.h"
#include "mcws/reach/reach_plot.h"
#include "mcws/reach/reach_report.h"
#include "mcws/reach/reach_study.h"
#include "mcws/sampling/sample_report.h"

namespace {

using namespace mcws;

constexpr char kUsage[] =
    "mcws_reach --robot FILE --resolution LENGTH --output MAP.pcd [--map MAP.bin] [options]\n"
    "       mcws_reach --robot FILE --targets TARGETS.pcd|.csv --output HEAT.pcd [options]";

constexpr char kSummary[] =
    R"(Builds the reachability map of a robot: joint values drawn uniformly within their limits
(sample i's values depend only on --seed and i, as in mcws_sample, so the map is the same for any
--threads) are mapped by forward kinematics to the tool pose, whose point falls in a cubic voxel
of edge --resolution and whose orientation in one of --orientations x --rolls bins: the approach
direction (the tool's z axis) in Leopardi's equal-area partition of the sphere, times equal bins
of the roll about it (1 roll bin: any roll counts, as in Zacharias et al. 2007). Per occupied
voxel: the reachability index D (the share of orientation bins reached, 0..1), the best
manipulability of its samples (mcws_sample --quality explains the measure) and the sample count.
--output writes the voxel centres with fields reachability, manipulability and count (PCD;
pcl_viewer colours by them), --map the whole map for queries (binary, docs/reach_map.md),
--halfcut a picture of the slab through the base (y = 0) coloured by D, --histogram the
histogram of D. With --collision only collision-free samples count. A map from samples misses
orientation bins that inverse kinematics would find: BENCHMARKS.md tabulates its agreement with
IK against the sample count. The default 5e8 samples (about a minute on 2 cores) is where, for
the inspection arm at 10 cm and 200 directions, every IK-reachable voxel-bin pair of the check
is marked and the mean of D moves by less than 1 % when the samples are doubled; 1e7 gives a
first look.

Under mpirun (-np K, MPI builds) each process fills the map of its contiguous block of sample
indices; the maps are merged along a binary tree into rank 0 (counts add, bins unite, the best
manipulability is the larger), which writes every output: the same map, byte for byte, as one
process's. Memory per process: its map, its encoded copy while sending, or one received map
(encoded and read) while merging. --threads is then per process
(0: the cores shared among the processes on a machine).

With --checkpoint FILE a long run saves its progress: each process writes its map so far to
FILE (FILE.0, FILE.1, ... under mpirun) after every --checkpoint-every of its samples. Killed or
interrupted, the same command run again continues from each process's last checkpoint and gives
the same map as an uninterrupted run (merging is exact); a checkpoint of another run (other
robot file, grid, samples, seed, process count) is refused. The files are removed when the
outputs are written.

With --targets, a reach study instead (as ROS-Industrial REACH): each target (a point and a
surface normal from a pcl::PointNormal PCD, or a CSV: see --targets) is solved by inverse
kinematics from --ik-starts starting joint vectors, and the best solution kept: collision-free
first (the robot's collision model is used when its file has one), then the highest
manipulability. A point-and-normal target wants the tool point on the point and the tool's z
axis against the normal, its roll free; an arm with fewer joints than the target has
conditions (the 4-joint maintenance arm, whose tool always points horizontally) meets the
point exactly and the approach within --approach-tolerance. --output writes the heat map: the
targets with fields reached, score (the manipulability where reached, else 0),
manipulability, clearance (the smallest distance between any checked pair of bodies, -1 where
not measured), orientation_error and the joint values q1..q8.)";

void declareFlags(app::CommandLine& cli) {
  app::declareRobotFlags(cli, "robot description (.yaml or .urdf)");
  app::declareMapFlags(
      cli, "voxel edge: a length with unit (2cm, 0.02m, 20mm) or a number in the robot's unit");
  app::declareSharedFlags(cli);
  cli.addValue("output", "the map's voxel centres, or with --targets the heat map (PCD)");
  cli.addValue("map", "the whole map, binary (docs/reach_map.md)");
  cli.addValue("halfcut", "PNG: the slab through y = 0 coloured by D");
  cli.addValue("histogram", "PNG: histogram of D");
  cli.addSwitch("collision", "count only collision-free samples (needs collision: geometry)");
  cli.addValue("checkpoint",
               "save the map so far to FILE (FILE.RANK under mpirun) every --checkpoint-every "
               "samples; a rerun of the same command continues from it; removed at the end");
  cli.addValue("checkpoint-every", "samples per process between checkpoints (default 100000000)");
  app::declareStudyFlags(cli);
  cli.addSwitch("json", "print a JSON summary on stdout");
}

/// --checkpoint and --checkpoint-every, with the identity of the run a checkpoint records.
std::optional<ReachCheckpoint> readCheckpoint(const app::CommandLine& cli, const Robot& robot,
                                              const io::CloudProvenance& provenance,
                                              const ReachGrid& grid, const ReachSampling& sampling,
                                              std::uint64_t samples,
                                              const distributed::Processes& processes) {
  if (!cli.has("checkpoint")) {
    if (cli.has("checkpoint-every")) throw app::UsageError("--checkpoint-every needs --checkpoint");
    return std::nullopt;
  }
  return ReachCheckpoint{
      processes.distributed() ? cli.required("checkpoint") + "." + std::to_string(processes.rank())
                              : cli.required("checkpoint"),
      static_cast<std::uint64_t>(app::parseInteger(cli.text("checkpoint-every", "100000000"),
                                                   "checkpoint-every", 1,
                                                   std::numeric_limits<std::int64_t>::max())),
      checkpointRun(robot, provenance.sha256, grid, sampling, samples, cli.has("collision"),
                    processes.size(), processes.rank())};
}

/// Merges the maps of every process into rank 0's along a binary tree, sorted as one process's.
void mergeOnFirst(distributed::Processes& processes, ReachMap& map) {
  distributed::reduceToFirst(
      processes,
      [&] {
        std::ostringstream bytes;
        map.write(bytes, "{}");
        return bytes.str();
      },
      [&](const std::string& bytes) {
        std::istringstream in(bytes);
        map.merge(ReachMap::read(in, "the map of another process"));
      });
  map.sort();
}

/// Every output rendered and written under a temporary name before any is renamed; the map
/// file's header records what `summary` says of the run; the points made by `threads` threads.
void saveMapOutputs(const app::CommandLine& cli, const Robot& robot, const ReachMap& map,
                    const io::CloudProvenance& provenance, const nlohmann::json& summary,
                    int threads) {
  const std::string unit = unitName(robot.length_unit);
  io::OutputSet outputs;
  if (cli.has("halfcut"))
    io::writeWholeFile(cli.required("halfcut"), renderHalfCutPng(map, 0.0, robot.name, unit));
  if (cli.has("histogram")) {
    io::writeWholeFile(cli.required("histogram"), renderReachabilityHistogramPng(map, robot.name));
  }
  if (cli.has("map")) {
    std::ostringstream bytes;
    map.write(bytes, mapFileHeader(robot, provenance.file, provenance.sha256, summary));
    io::writeWholeFile(cli.required("map"), bytes.str());
  }
  // A part of the points at a time: a large map's points are never held whole.
  io::PcdStreamWriter<ReachPoint> cloud(cli.required("output"), map.size(), io::PcdFormat::kBinary,
                                        provenance);
  std::vector<ReachPoint, Eigen::aligned_allocator<ReachPoint>> points(
      std::min<std::size_t>(map.size(), std::size_t{1} << 16));
  for (std::size_t first = 0; first < map.size(); first += points.size()) {
    const std::size_t count = std::min(points.size(), map.size() - first);
    reachPoints(map, first, count, points.data(), threads);
    cloud.write(points.data(), count);
  }
  cloud.commit();
  outputs.commit();
}

/// The reachability map: samples through forward kinematics into voxels x orientation bins.
void runMap(const app::CommandLine& cli, const Robot& robot, const io::CloudProvenance& provenance,
            distributed::Processes& processes) {
  const std::string output = cli.required("output");
  app::checkOutputs({{"output", output},
                     {"map", cli.text("map", "")},
                     {"halfcut", cli.text("halfcut", "")},
                     {"histogram", cli.text("histogram", "")},
                     {"checkpoint", cli.text("checkpoint", "")}},
                    {{"robot", cli.required("robot")}});
  const ReachGrid grid = app::readReachGrid(cli, robot);
  ReachSampling sampling = app::readReachSampling(cli, robot);
  const std::uint64_t samples = sampling.samples;
  std::unique_ptr<CollisionChecker> checker;
  if (cli.has("collision")) {
    checker = std::make_unique<CollisionChecker>(
        robot, loadRequiredCollisionModel(robot, cli.required("robot")));
    sampling.collision = checker.get();
  }

  sampling.threads = distributed::threadsPerProcess(sampling.threads, processes);
  const distributed::Block block =
      distributed::blockOf(samples, processes.rank(), processes.size());
  sampling.first += block.begin;
  sampling.samples = block.size();

  app::Progress progress("mcws_reach", "samples");  // rank 0 reports its block
  const auto report = [&](std::uint64_t done, std::uint64_t all) {
    if (processes.rank() == 0)
      progress.update(static_cast<std::size_t>(done), static_cast<std::size_t>(all));
  };
  const std::optional<ReachCheckpoint> checkpoint =
      readCheckpoint(cli, robot, provenance, grid, sampling, samples, processes);
  std::uint64_t resumed = 0;
  // A bad flag or file on any process ends them all here; so does another robot file.
  processes.setUpDone({{"robot", provenance.sha256}});
  ReachMap map = checkpoint
                     ? buildReachMapInPieces(robot, grid, sampling, *checkpoint, report, &resumed)
                     : buildReachMap(robot, grid, sampling, report);
  std::vector<std::uint64_t> resumed_all{resumed};
  processes.sum(resumed_all);
  if (processes.distributed()) mergeOnFirst(processes, map);
  // Every checkpoint stays until rank 0 has written the outputs (a failure there keeps them).
  const auto removeCheckpoint = [&] {
    processes.barrier();
    std::error_code ignored;  // a checkpoint left behind is only refused or reused later
    if (checkpoint) std::filesystem::remove(checkpoint->path, ignored);
  };
  if (processes.rank() != 0) return removeCheckpoint();  // rank 0 writes and reports for all
  if (map.size() == 0) throw Error("no sample counted: every sample collides");

  nlohmann::json summary = mapSummary(robot, grid, sampling, samples, map, cli.has("collision"));
  summary["output"] = output;
  summary["processes"] = processes.size();
  summary["resumed_samples"] = resumed_all[0];
  saveMapOutputs(cli, robot, map, provenance, summary, sampling.threads);
  removeCheckpoint();
  addRobotNames(summary, robot);  // after the map file, whose header names the chain's links
  summary["seconds"] = progress.seconds();
  if (cli.has("json")) {
    std::cout << summary.dump() << "\n";
  } else {
    std::cerr << "[done, " << static_cast<int>(progress.seconds() * 1000) << " ms : " << map.size()
              << " voxels of edge " << grid.resolution << " " << unitName(robot.length_unit)
              << ", mean D " << summary["mean_reachability"].get<double>() << " (fraction of the "
              << map.bins().size() << " orientation bins)] -> " << output << "\n";
  }
}

/// The reach study: IK per target, the heat map and its summary.
void runStudy(const app::CommandLine& cli, const Robot& robot,
              const io::CloudProvenance& provenance) {
  const std::string output = cli.required("output");
  app::checkOutputs({{"output", output}},
                    {{"robot", cli.required("robot")}, {"targets", cli.required("targets")}});
  for (const char* flag : {"resolution", "orientations", "rolls", "samples", "no-manipulability",
                           "map", "halfcut", "histogram", "collision"}) {
    if (cli.has(flag))
      throw app::UsageError(std::string("--") + flag + " is for maps, not --targets");
  }
  const ReachStudyOptions options = app::readReachStudyOptions(cli, robot);
  const std::vector<ReachTarget> targets = app::readTargets(cli, robot);
  const std::unique_ptr<CollisionChecker> checker = app::studyChecker(cli, robot);
  app::Progress progress("mcws_reach", "targets");
  const ReachStudy study(robot, checker.get(), options);
  const std::vector<TargetReach> results =
      study.evaluate(targets, Eigen::Isometry3d::Identity(),
                     [&](std::size_t done, std::size_t all) { progress.update(done, all); });

  pcl::PointCloud<ReachTargetPoint> heat;
  for (std::size_t i = 0; i < targets.size(); ++i)
    heat.push_back(reachTargetPoint(targets[i], results[i]));
  io::PcdStreamWriter<ReachTargetPoint> cloud(output, heat.size(), io::PcdFormat::kBinary,
                                              provenance);
  cloud.write(heat.data(), heat.size());
  cloud.commit();

  nlohmann::json json = studySummary(robot, options, results, checker != nullptr);
  addRobotNames(json, robot);
  json["seconds"] = progress.seconds();
  json["output"] = output;
  const ReachSummary summary = summarize(results);
  if (cli.has("json")) {
    std::cout << json.dump() << "\n";
  } else {
    std::cerr << "[done, " << static_cast<int>(progress.seconds() * 1000)
              << " ms : " << summary.reached << " of " << summary.targets << " targets reached] -> "
              << output << "\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  distributed::Processes processes(argc, argv);
  return app::run("mcws_reach", processes, [&] {
    app::CommandLine cli(kUsage, kSummary);
    declareFlags(cli);
    if (!cli.parse(argc, argv)) return app::kExitOk;
    const Robot robot = app::readRobot(cli);
    const io::CloudProvenance provenance = robotProvenance(robot);  // recorded in the PCD
    if (cli.has("targets")) {
      if (processes.distributed())
        throw app::UsageError("--targets: a reach study runs on one process (no mpirun)");
      runStudy(cli, robot, provenance);
    } else {
      for (const char* flag : {"approach-tolerance", "ik-starts", "no-collision", "standoff"}) {
        if (cli.has(flag)) throw app::UsageError(std::string("--") + flag + " needs --targets");
      }
      runMap(cli, robot, provenance, processes);
    }
    return app::kExitOk;
  });
}
