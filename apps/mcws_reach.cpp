// mcws_reach: the reachability map of a robot (Zacharias, Borst & Hirzinger 2007; ROS Reuleaux):
// Monte Carlo joint samples through forward kinematics into position voxels x orientation bins.
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "common/app.h"
#include "common/flags.h"
#include "mcws/collision/collision_checker.h"
#include "mcws/collision/collision_model.h"
#include "mcws/io/atomic_file.h"
#include "mcws/io/pcd_stream_writer.h"
#include "mcws/reach/reach_map.h"
#include "mcws/reach/reach_plot.h"

namespace {

using namespace mcws;

constexpr char kUsage[] =
    "mcws_reach --robot FILE --resolution LENGTH --output MAP.pcd [--map MAP.bin] [options]";

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
first look.)";

void declareFlags(app::CommandLine& cli) {
  cli.addValue("robot", "robot description (.yaml or .urdf)");
  cli.addValue("resolution",
               "voxel edge: a length with unit (2cm, 0.02m, 20mm) or a number in the robot's unit");
  cli.addValue("orientations", "approach-direction bins on the sphere (default 200)");
  cli.addValue("rolls", "roll bins about the approach (default 1: any roll)");
  cli.addValue("samples", "joint samples (default 500000000; see above)");
  cli.addValue("seed", "random seed, a whole number >= 0 (default 1)");
  cli.addValue("threads", "worker threads, 0 = all cores (default 0)");
  cli.addValue("output", "voxel centres with reachability, manipulability, count (PCD)");
  cli.addValue("map", "the whole map, binary (docs/reach_map.md)");
  cli.addValue("halfcut", "PNG: the slab through y = 0 coloured by D");
  cli.addValue("histogram", "PNG: histogram of D");
  cli.addValue("quality-task", "position | full: how manipulability is measured (mcws_sample)");
  cli.addValue("length",
               "characteristic length of --quality-task full: a length with unit or a number in "
               "the robot's unit");
  cli.addSwitch("no-manipulability", "skip the Jacobian (faster; the field is 0)");
  cli.addSwitch("collision", "count only collision-free samples (needs collision: geometry)");
  cli.addSwitch("json", "print a JSON summary on stdout");
}

ReachGrid gridFromFlags(const app::CommandLine& cli, const Robot& robot) {
  ReachGrid grid;
  grid.resolution = app::parseLength(cli.required("resolution"), "resolution", robot.length_unit);
  grid.directions = static_cast<int>(
      app::parseInteger(cli.text("orientations", "200"), "orientations", 1, 65536));
  grid.rolls = static_cast<int>(app::parseInteger(cli.text("rolls", "1"), "rolls", 1, 65536));
  app::asUsageError("orientations", [&] { grid.check(); });
  return grid;
}

/// One output written under a temporary name, renamed when every output is ready.
struct PendingFile {
  std::unique_ptr<io::AtomicFile> file;
  void write(const std::string& path, const std::string& bytes) {
    file = std::make_unique<io::AtomicFile>(path);
    file->write(bytes.data(), bytes.size());
  }
};

}  // namespace

int main(int argc, char** argv) {
  return app::run("mcws_reach", [&] {
    app::CommandLine cli(kUsage, kSummary);
    declareFlags(cli);
    if (!cli.parse(argc, argv)) return app::kExitOk;

    const std::uint64_t samples = static_cast<std::uint64_t>(app::parseInteger(
        cli.text("samples", "500000000"), "samples", 1, std::numeric_limits<std::int64_t>::max()));
    const std::string output = cli.required("output");
    for (const char* flag : {"output", "map", "halfcut", "histogram"}) {
      if (cli.has(flag)) io::checkOutputPath(cli.required(flag));
    }
    const Robot robot = app::readRobot(cli);
    const ReachGrid grid = gridFromFlags(cli, robot);

    ReachSampling sampling;
    sampling.samples = samples;
    sampling.seed = app::readSeed(cli);
    sampling.threads = app::readThreads(cli);
    sampling.manipulability = !cli.has("no-manipulability");
    sampling.quality = app::readQualityOptions(cli, robot);
    std::unique_ptr<CollisionChecker> checker;
    if (cli.has("collision")) {
      checker = std::make_unique<CollisionChecker>(
          robot, loadRequiredCollisionModel(robot, cli.required("robot")));
      sampling.collision = checker.get();
    }

    app::Progress progress("mcws_reach", "samples");
    const ReachMap map =
        buildReachMap(robot, grid, sampling, [&](std::uint64_t done, std::uint64_t all) {
          progress.update(static_cast<std::size_t>(done), static_cast<std::size_t>(all));
        });
    if (map.size() == 0) throw Error("no sample counted: every sample collides");

    const std::string unit = unitName(robot.length_unit);
    const double voxel_volume = std::pow(grid.resolution, 3);
    nlohmann::json summary = {
        {"robot", robot.name},
        {"length_unit", unit},
        {"resolution", grid.resolution},
        {"orientations", grid.directions},
        {"rolls", grid.rolls},
        {"orientation_bins", map.bins().size()},
        {"direction_partition", "EQ (Leopardi 2006), approach = tool z axis"},
        {"samples", samples},
        {"samples_counted", map.samples()},
        {"seed", sampling.seed},
        {"voxels", map.size()},
        {"occupied_volume", static_cast<double>(map.size()) * voxel_volume},
        {"occupied_volume_unit", unit + "^3"},
        {"mean_reachability", map.meanReachability()},
        {"manipulability",
         sampling.manipulability
             ? nlohmann::json{{"task", qualityTaskName(sampling.quality.task)},
                              {"characteristic_length", sampling.quality.characteristic_length}}
             : nlohmann::json(nullptr)},
        {"collision", cli.has("collision")},
        {"output", output}};

    // Every output is rendered and written under a temporary name before any is renamed.
    PendingFile halfcut, histogram, map_file;
    if (cli.has("halfcut"))
      halfcut.write(cli.required("halfcut"), renderHalfCutPng(map, 0.0, robot.name, unit));
    if (cli.has("histogram"))
      histogram.write(cli.required("histogram"), renderReachabilityHistogramPng(map, robot.name));
    if (cli.has("map")) {
      std::ostringstream bytes;
      map.write(bytes, nlohmann::json{{"robot", robot.name},
                                      {"length_unit", unit},
                                      {"samples", samples},
                                      {"seed", sampling.seed},
                                      {"collision", cli.has("collision")}}
                           .dump());
      map_file.write(cli.required("map"), bytes.str());
    }
    const auto points = reachPoints(map);
    io::PcdStreamWriter<ReachPoint> cloud(output, points.size());
    cloud.write(points.data(), points.size());
    cloud.commit();
    for (PendingFile* file : {&halfcut, &histogram, &map_file}) {
      if (file->file) file->file->commit();
    }
    summary["seconds"] = progress.seconds();
    if (cli.has("json")) {
      std::cout << summary.dump() << "\n";
    } else {
      std::cerr << "[done, " << static_cast<int>(progress.seconds() * 1000)
                << " ms : " << map.size() << " voxels, mean D "
                << summary["mean_reachability"].get<double>() << "] -> " << output << "\n";
    }
    return app::kExitOk;
  });
}
