#include "common/reach_args.h"

#include <cmath>
#include <limits>

#include "common/flags.h"
#include "mcws/collision/robot_bodies.h"
#include "mcws/reach/targets_file.h"

namespace mcws::app {

void declareMapFlags(CommandLine& cli, const char* resolution_help) {
  cli.addValue("resolution", resolution_help);
  cli.addValue("orientations", "approach-direction bins on the sphere (default 200)");
  cli.addValue("rolls", "roll bins about the approach (default 1: any roll)");
  cli.addValue("samples", "joint samples of the map (default 500000000)");
  cli.addSwitch("no-manipulability", "skip the Jacobian (faster; the field is 0)");
}

void declareSharedFlags(CommandLine& cli) {
  declareQualityFlags(cli);
  cli.addValue("seed", "random seed, a whole number >= 0 (default 1)");
  cli.addValue("threads", "worker threads, 0 = all cores (default 0)");
}

void declareStudyFlags(CommandLine& cli) {
  cli.addValue("targets",
               "targets as PCD with normals (pcl::PointNormal) or CSV with the header "
               "x,y,z,normal_x,normal_y,normal_z or x,y,z,roll,pitch,yaw (rad)");
  cli.addValue("standoff",
               "distance of the tool point from each target's surface, along the normal: a length "
               "with unit or a number in the robot's unit (default 0)");
  cli.addValue("approach-tolerance",
               "largest accepted approach (or orientation) error of a target, with unit: 5deg, "
               "0.1rad (default 0: exact)");
  cli.addValue("ik-starts", "IK starting joint vectors per target (default 4)");
  cli.addSwitch("no-collision",
                "ignore the robot's collision model (when solving targets, and in a map "
                "mcws_place builds)");
}

ReachGrid readReachGrid(const CommandLine& cli, const Robot& robot) {
  ReachGrid grid;
  grid.resolution = parseLength(cli.required("resolution"), "resolution", robot.length_unit);
  grid.directions =
      static_cast<int>(parseInteger(cli.text("orientations", "200"), "orientations", 1, 65536));
  grid.rolls = static_cast<int>(parseInteger(cli.text("rolls", "1"), "rolls", 1, 65536));
  asUsageError("orientations", [&] { grid.check(); });
  return grid;
}

ReachSampling readReachSampling(const CommandLine& cli, const Robot& robot) {
  ReachSampling sampling;
  sampling.samples = static_cast<std::uint64_t>(parseInteger(
      cli.text("samples", "500000000"), "samples", 1, std::numeric_limits<std::int64_t>::max()));
  sampling.seed = readSeed(cli);
  sampling.threads = readThreads(cli);
  sampling.manipulability = !cli.has("no-manipulability");
  sampling.quality = readQualityOptions(cli, robot);
  return sampling;
}

ReachStudyOptions readReachStudyOptions(const CommandLine& cli, const Robot& robot) {
  ReachStudyOptions options;
  options.approach_tolerance =
      parseAngle(cli.text("approach-tolerance", "0"), "approach-tolerance");
  if (options.approach_tolerance > M_PI) {
    throw UsageError("--approach-tolerance: " + cli.required("approach-tolerance") +
                     " is more than 180deg");
  }
  options.starts = static_cast<int>(parseInteger(cli.text("ik-starts", "4"), "ik-starts", 1, 1000));
  options.ik.seed = readSeed(cli);
  options.threads = readThreads(cli);
  options.quality = readQualityOptions(cli, robot);
  return options;
}

std::vector<ReachTarget> readTargets(const CommandLine& cli, const Robot& robot) {
  std::vector<ReachTarget> targets = loadTargets(cli.required("targets"));
  if (cli.has("standoff")) {
    applyStandoff(targets,
                  parseLength(cli.required("standoff"), "standoff", robot.length_unit, true));
  }
  return targets;
}

std::unique_ptr<CollisionChecker> studyChecker(const CommandLine& cli, const Robot& robot,
                                               bool environment) {
  if (cli.has("no-collision")) return nullptr;
  return checkerIfModelled(robot, cli.required("robot"), environment);
}

}  // namespace mcws::app
