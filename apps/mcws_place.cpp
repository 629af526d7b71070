// mcws_place: where to put the robot's base (stop the line robot) so its arm reaches a set of
// targets: candidate base positions scored from the reachability map, the best confirmed by IK.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "common/app.h"
#include "common/flags.h"
#include "common/reach_args.h"
#include "mcws/collision/collision_checker.h"
#include "mcws/collision/robot_bodies.h"
#include "mcws/io/atomic_file.h"
#include "mcws/io/cloud_io.h"
#include "mcws/io/pcd_stream_writer.h"
#include "mcws/reach/base_placement.h"
#include "mcws/reach/map_cache.h"
#include "mcws/reach/placement_map.h"
#include "mcws/reach/reach_report.h"
#include "mcws/sampling/sample_report.h"
#include "mcws/sampling/sampler.h"

namespace {

using namespace mcws;

constexpr char kUsage[] =
    R"(mcws_place --robot FILE --targets TARGETS.pcd|.csv --along "X0 X1 STEP" (--map MAP.bin | --resolution LENGTH) --output BASES.pcd [options])";

constexpr char kSummary[] =
    R"(Finds where to put the robot's base so its arm reaches the targets: the whole robot (base,
links, tool) is moved by every offset of the grid --along (x) x --across (y) x --up (z), each
"first last step" in the robot's length unit, while the environment of its collision model
stays where it is (the power-line robot stopping at points of its conductor). Each position is
scored from the reachability map (--map from mcws_reach, or one built here from --resolution
and --samples; the map built here counts samples free of self-collision, the environment being
left to IK): the share of the targets whose voxel and approach-direction bin the map marks
reached, and their mean best manipulability. The map is an estimate (a voxel partly inside the
reach counts; too few samples miss bins; its manipulability is the best of a voxel's samples),
so every position whose map share is within --confirm-margin of the best (default 0.1, a
fraction of the targets: with 20 targets, every position the map says reaches at most 2 fewer
than the best), and the --confirm best by the map (default 0; all: every position), are solved
by inverse kinematics with the collision model, as mcws_reach --targets does; the best position
is the confirmed one with the most targets reached, then the best mean score. A map built here
(no --map) takes as long as mcws_reach takes for it, much longer with a mesh collision model;
the tool says so with an estimate after its first samples, and shows progress. It is kept in the
map cache (--map-cache) and reused by every later run whose map inputs are the same (the robot
file, its collision model and meshes, --base/--tip, --resolution, --orientations, --rolls,
--samples, --seed, the manipulability flags, --no-collision); a cached map is also a --map file.
After a store the cache's oldest maps are removed until they take at most 2 GiB
(MCWS_MAP_CACHE_LIMIT_MB, in MiB, 0: no limit; docs/place.md).
--output writes the candidate bases (where the base frame lands) with fields map_share,
map_score, ik_share and ik_score (-1: not confirmed); --plot the share reached against the
offset along x.)";

void declareFlags(app::CommandLine& cli) {
  app::declareRobotFlags(cli, "robot description (.yaml or .urdf)");
  cli.addValue("along", "\"first last step\": base offsets along x [robot length unit]");
  cli.addValue("across", "\"first last step\": base offsets along y (default 0 only)");
  cli.addValue("up", "\"first last step\": base offsets along z (default 0 only)");
  cli.addValue("map",
               "the robot's reachability map (mcws_reach --map, without --collision), made from "
               "this very --robot file (its SHA-256 is in the map's header)");
  app::declareMapFlags(cli,
                       "voxel edge of a map built here (without --map): a length with unit "
                       "(2cm, 0.02m, 20mm) or a number in the robot's unit");
  cli.addValue("map-cache",
               "folder where a map built here is kept and reused, or off (default "
               "$XDG_CACHE_HOME/mcws/reach-maps, else ~/.cache/mcws/reach-maps)");
  app::declareSharedFlags(cli);
  app::declareStudyFlags(cli);
  cli.addValue("confirm-margin",
               "confirm by IK every position whose map share is at least the best less this "
               "[fraction of the targets, 0..1] (default 0.1)");
  cli.addValue("confirm",
               "also confirm the best N by the map, whatever their share: a number "
               "(default 0) or all");
  cli.addValue("output", "candidate bases with map_share, map_score, ik_share, ik_score (PCD)");
  cli.addValue("plot", "PNG: targets reached against the offset along x");
  cli.addSwitch("json", "print a JSON summary on stdout");
}

/// The values of "first last step" (one value, first, when the flag is absent).
std::vector<double> steps(const app::CommandLine& cli, const std::string& flag) {
  if (!cli.has(flag)) return {0.0};
  const Eigen::VectorXd v = app::parseNumberList(cli.required(flag), flag);
  if (v.size() != 3) {
    throw app::UsageError("--" + flag + ": " + std::to_string(v.size()) +
                          " values given, 3 wanted (first last step)");
  }
  if (!(v[2] > 0.0) || v[1] < v[0]) {
    std::ostringstream msg;
    msg << "--" << flag << ": step " << v[2] << " is not positive or last " << v[1]
        << " is below first " << v[0];
    throw app::UsageError(msg.str());
  }
  const double count = std::floor((v[1] - v[0]) / v[2] + 1e-9) + 1.0;
  if (!(count <= 1e5)) {  // also catches an overflow to infinity
    std::ostringstream msg;
    msg << "--" << flag << ": " << count << " positions, at most 100000";
    throw app::UsageError(msg.str());
  }
  std::vector<double> values;
  for (int k = 0; k < static_cast<int>(count); ++k) values.push_back(v[0] + k * v[2]);
  return values;
}

std::vector<Eigen::Vector3d> offsets(const app::CommandLine& cli) {
  const std::vector<double> xs = steps(cli, "along"), ys = steps(cli, "across"),
                            zs = steps(cli, "up");
  if (xs.size() * ys.size() * zs.size() > 1000000) {
    throw app::UsageError("--along x --across x --up: more than 1000000 base positions");
  }
  return offsetGrid(xs, ys, zs);
}

/// --confirm and --confirm-margin.
PlacementOptions readPlacementOptions(const app::CommandLine& cli) {
  PlacementOptions placement;
  const std::string confirm = cli.text("confirm", "0");
  placement.confirm =
      confirm == "all" ? -1 : static_cast<int>(app::parseInteger(confirm, "confirm", 0, 1000000));
  placement.confirm_margin =
      app::parseNonNegative(cli.text("confirm-margin", "0.1"), "confirm-margin");
  if (placement.confirm_margin > 1.0) {
    throw app::UsageError("--confirm-margin: " + cli.required("confirm-margin") +
                          " is above 1 (a fraction of the targets)");
  }
  return placement;
}

/// The cache directory of --map-cache: a folder, "off" (none) or, without the flag, the default
/// (empty when HOME is not set either).
std::string mapCacheDirectory(const app::CommandLine& cli) {
  if (!cli.has("map-cache")) {
    const std::string directory = defaultMapCacheDirectory();
    if (directory.empty())
      std::cerr << "mcws_place: neither XDG_CACHE_HOME nor HOME is set: no map cache\n";
    return directory;
  }
  const std::string directory = cli.required("map-cache");
  if (directory.empty()) throw app::UsageError("--map-cache: empty (a folder, or off)");
  return directory == "off" ? std::string() : directory;
}

/// The map of the map flags, built here with its progress and time estimate.
ReachMap buildMapHere(const Robot& robot, const ReachGrid& grid, const ReachSampling& sampling,
                      const ReachMapCache& cache) {
  std::cerr << "mcws_place: no --map: building a reachability map here from " << sampling.samples
            << " samples" << (sampling.collision ? ", each checked for self-collision" : "")
            << (cache.enabled() ? " (will be cached at " + cache.path() + ")"
                                : std::string(" (mcws_reach --map MAP.bin builds one to pass as "
                                              "--map)"))
            << "\n";
  app::Progress progress("mcws_place", "map samples");
  // The time estimate from the second chunk's rate (the first chunk, a few hundred samples a
  // thread, is timed mostly for its start-up: threads, tables, first touches).
  int chunks = 0;
  double first_seconds = 0.0;
  std::uint64_t first_done = 0;
  return buildReachMap(robot, grid, sampling, [&](std::uint64_t done, std::uint64_t all) {
    if (++chunks == 1) {
      first_seconds = progress.seconds();
      first_done = done;
    } else if (chunks == 2) {
      const double rate = static_cast<double>(done - first_done) /
                          std::max(progress.seconds() - first_seconds, 1e-9);
      std::cerr << "mcws_place: the map will take about "
                << app::shortNumber(progress.seconds() + static_cast<double>(all - done) / rate)
                << " s in all (" << app::shortNumber(rate) << " samples a second)\n";
    }
    progress.update(static_cast<std::size_t>(done), static_cast<std::size_t>(all));
  });
}

/// The map from --map (checked against the robot), or the one of the map flags: from the map
/// cache when it holds it, else built here (and then stored in the cache). `cache_json` receives
/// what the cache did (null with --map).
ReachMap loadOrBuildMap(const app::CommandLine& cli, const Robot& robot, nlohmann::json& about,
                        nlohmann::json& cache_json) {
  if (cli.has("map")) {
    for (const char* flag :
         {"resolution", "orientations", "rolls", "samples", "no-manipulability", "map-cache"}) {
      if (cli.has(flag))
        throw app::UsageError(std::string("--") + flag +
                              " is for a map built here, not with --map");
    }
    const std::string path = cli.required("map");
    std::uint64_t samples = 0;
    ReachMap map = readPlacementMap(
        path, robot, cli.required("robot"),
        qualitySummary(app::readQualityOptions(cli, robot), robot).dump(), samples);
    about = {{"source", path}, {"samples", samples}};
    return map;
  }
  if (!cli.has("resolution")) throw app::UsageError("missing --map or --resolution");
  const ReachGrid grid = app::readReachGrid(cli, robot);
  ReachSampling sampling = app::readReachSampling(cli, robot);
  const std::string directory = mapCacheDirectory(cli);
  // The self-collision model (checkerIfModelled()'s, without the environment): part of the key.
  std::optional<CollisionModel> self;
  if (!cli.has("no-collision")) {
    self = robotBodiesOnly(loadCollisionModel(robot, cli.required("robot")));
    if (!hasGeometry(*self)) self.reset();
  }
  const ReachMapCache cache(directory, robot, grid, sampling, self ? &*self : nullptr);
  cache_json = {{"directory", cache.enabled() ? nlohmann::json(directory) : nlohmann::json()},
                {"path", cache.enabled() ? nlohmann::json(cache.path()) : nlohmann::json()},
                {"reused", false},
                {"stored", false}};
  CachedMapInfo info;
  if (std::optional<ReachMap> cached = cache.load(std::cerr, "mcws_place", &info)) {
    std::cerr << "mcws_place: reusing the cached map " << cache.path() << " (built "
              << info.built_utc << " from " << info.samples << " samples in "
              << app::shortNumber(info.build_seconds) << " s)\n";
    cache_json["reused"] = true;
    about = {{"source", "cache"},
             {"samples", info.samples},
             {"self_collision", info.self_collision},
             {"built_utc", info.built_utc}};
    return std::move(*cached);
  }
  const std::unique_ptr<CollisionChecker> checker =
      self ? std::make_unique<CollisionChecker>(robot, *self) : nullptr;
  sampling.collision = checker.get();
  const app::Progress clock("mcws_place", "");
  ReachMap map = buildMapHere(robot, grid, sampling, cache);
  cache_json["stored"] = cache.store(map, clock.seconds(), std::cerr, "mcws_place");
  about = {
      {"source", "built"}, {"samples", sampling.samples}, {"self_collision", self.has_value()}};
  return map;
}

void printTable(const std::vector<BaseCandidate>& candidates, int best, std::size_t targets,
                const std::string& unit, const PlacementOptions& placement) {
  std::cerr << "offset x y z [" << unit << "]   map share   IK share   (fractions of the "
            << targets << " targets)\n";
  for (const BaseCandidate& c : candidates) {
    std::cerr << std::setw(8) << c.offset.x() << ' ' << std::setw(8) << c.offset.y() << ' '
              << std::setw(8) << c.offset.z() << "   " << std::setw(9) << c.map_share << "   "
              << (c.confirmed ? std::to_string(c.ik.share_reached) : std::string("-")) << "\n";
  }
  const auto confirmed = std::count_if(candidates.begin(), candidates.end(),
                                       [](const BaseCandidate& c) { return c.confirmed; });
  std::cerr << confirmed << " of " << candidates.size()
            << " positions confirmed by IK: those within a map share of "
            << placement.confirm_margin << " (fraction of the targets) of the best";
  if (placement.confirm != 0) {
    std::cerr << ", and the "
              << (placement.confirm < 0 ? std::string("all") : std::to_string(placement.confirm))
              << " best by the map";
  }
  std::cerr << "\n";
  if (best >= 0) {
    const BaseCandidate& b = candidates[static_cast<std::size_t>(best)];
    std::cerr << "best: move the base by (" << b.offset.transpose() << ") " << unit << ": "
              << b.ik.reached << " of " << targets << " targets reached\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  return app::run("mcws_place", [&] {
    app::CommandLine cli(kUsage, kSummary);
    declareFlags(cli);
    if (!cli.parse(argc, argv)) return app::kExitOk;
    const app::Progress clock("mcws_place", "");  // the whole run's seconds
    const std::string output = cli.required("output");
    app::checkOutputs({{"output", output}, {"plot", cli.text("plot", "")}},
                      {{"robot", cli.required("robot")},
                       {"targets", cli.required("targets")},
                       {"map", cli.text("map", "")}});
    if (!cli.has("along")) throw app::UsageError("missing --along");
    const std::vector<Eigen::Vector3d> moves = offsets(cli);
    PlacementOptions placement = readPlacementOptions(cli);
    const Robot robot = app::readRobot(cli);
    const ReachStudyOptions options = app::readReachStudyOptions(cli, robot);
    placement.approach_tolerance = options.approach_tolerance;
    const std::vector<ReachTarget> targets = app::readTargets(cli, robot);

    nlohmann::json map_about, map_cache;
    const ReachMap map = loadOrBuildMap(cli, robot, map_about, map_cache);
    const std::unique_ptr<CollisionChecker> checker = app::studyChecker(cli, robot);
    const ReachStudy study(robot, checker.get(), options);
    app::Progress progress("mcws_place", "positions confirmed");
    const std::vector<BaseCandidate> candidates =
        placeBase(map, study, targets, moves, placement,
                  [&](std::size_t done, std::size_t all) { progress.update(done, all); });
    const int best = bestCandidate(candidates);

    const std::string unit = unitName(robot.length_unit);
    io::OutputSet outputs;
    if (cli.has("plot")) {
      io::writeWholeFile(cli.required("plot"), renderPlacementPng(candidates, robot.name, unit));
    }
    const std::vector<BasePoint> points = basePoints(candidates, robot.T_world_base);
    // The robot (and so the positions' length unit) recorded, as mcws_reach's clouds.
    io::PcdStreamWriter<BasePoint> cloud(output, points.size(), io::PcdFormat::kBinary,
                                         robotProvenance(robot));
    cloud.write(points.data(), points.size());
    cloud.commit();
    outputs.commit();

    if (cli.has("json")) {
      nlohmann::json json = placementSummary(robot, targets.size(), map, map_about, options,
                                             checker != nullptr, candidates, best);
      addRobotNames(json, robot);
      json["confirmation"] = confirmationJson(placement, candidates);
      if (!map_cache.is_null()) json["map_cache"] = map_cache;  // none with --map
      json["seconds"] = clock.seconds();
      json["output"] = output;
      std::cout << json.dump() << "\n";
    } else {
      printTable(candidates, best, targets.size(), unit, placement);
    }
    return app::kExitOk;
  });
}
