// mcws_boundary: boundary points of a workspace cloud by the local quadrant/octant test of Yin,
// Wang & Yu 2010 (section 4.3), on a plane (--plane) or in 3-D; or by the paper's baselines, the
// grid (4.1) and extremum (4.2) methods.
#include <pcl/common/common.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>

#include "common/app.h"
#include "common/flags.h"
#include "common/units.h"
#include "mcws/distributed/processes.h"
#include "mcws/distributed/tiled_boundary.h"
#include "mcws/distributed/tiled_boundary_output.h"
#include "mcws/filters/extremum_boundary.h"
#include "mcws/filters/grid_boundary.h"
#include "mcws/filters/orthant_boundary.h"
#include "mcws/filters/setting_ranges.h"
#include "mcws/filters/used_parameters.h"
#include "mcws/io/atomic_file.h"
#include "mcws/io/boundary_record.h"
#include "mcws/io/cloud_io.h"
#include "mcws/sampling/sample_report.h"

namespace {
using namespace mcws;

constexpr const char* kUsage = "mcws_boundary --input CLOUD.pcd --output BOUNDARY.pcd [options]";
constexpr const char* kSummary = R"(Keeps the points on the boundary of the sampled region.
--method orthant (default; Yin, Wang & Yu 2010): a point is a boundary point when some quadrant
(--plane) or octant (3-D) around it holds no neighbour within the radius; 2-D: in every rotation
of the local frame (a 92-degree gap between neighbours), and then (--hull-depth) only those, and
their neighbours, that lie less than a local spacing inside the convex hull of their
neighbourhood; 3-D: in the axis frame or in a frame centred on the outward direction. By default
each point's radius is twice the distance to its k-th neighbour (k = 24 in 2-D, 16 in 3-D),
which follows the density of joint-space samples; --radius fixes it, --auto-radius takes c x the
cloud's mean spacing.
--method grid (section 4.1): cells of side --cell; an occupied cell with an empty neighbour (8 in
2-D, 26 in 3-D) is a boundary cell, represented by its point nearest to the cell's mean.
--method extremum (4.2, needs --plane): in columns of width --cell along the plane's first axis,
the lowest and highest point along the second, and both points around any gap wider than --gap.
NaN points are dropped from both outputs.
The cloud must have at least 3 distinct finite points in the plane (4 in 3-D), or it has no
boundary (exit 1, for 2-D and 3-D alike); with --plane it must extend along both of the plane's
axes (a cloud flat in one of them is a --plane error, exit 2, naming the plane it lies in; a 3-D
cloud is projected). Lengths (--radius, --outer-radius, --cell, --gap) lie between a tenth of the
cloud's mean spacing and its extent in the plane, --auto-radius c such that c x spacing does,
--adaptive k below the number of distinct points, --hull-depth in [0.1, 10] or 0.
Flags' lengths are in the cloud's unit; --json gives the radius (for an adaptive radius, the
median of the points' radii) and the mean spacing in the unit the cloud records (or --unit),
named by "length_unit" and "units".
--tiles N (orthant, fixed or adaptive radius, no hull depth) reads a binary PCD in pieces and
finds the boundary one slab at a time: N slabs of equal width along the cloud's longest axis (in
the plane), each
with a halo that holds every neighbour its points search (checked point by point, widened until it
does), so the output is byte for byte the one of a run without --tiles, in memory bounded by the
largest slab and halo (and a byte a point for the flags). Under mpirun the processes share the slabs; --json then adds the halo.)";

using Filter = OrthantBoundary<WorkspacePoint>;

/// --hull-depth > 0 [local spacings]: below a tenth of a spacing only the hull's own vertices
/// stay; a neighbourhood of the recommended radius is at most about 6 spacings deep, so beyond 10
/// every candidate is kept (a band, not a boundary).
constexpr double kHullDepthRange[2] = {0.1, 10.0};

/// A configured filter and, after it ran, the parameters it used (for --json).
struct Method {
  std::string name;
  BoundaryPlane plane;
  std::shared_ptr<pcl::FilterIndices<WorkspacePoint>> filter;
  std::function<UsedParameters()> parameters;
};

/// JSON of the parameters a method used, lengths in `units`, with their "units".
nlohmann::json parametersJson(const UsedParameters& used, const ResultUnits& units) {
  nlohmann::json out, unit;
  for (const auto& [key, value] : used.lengths) {
    out[key] = units.length(value);
    unit[key] = units.lengthName();
  }
  out["units"] = unit;
  for (const auto& [key, count] : used.counts) out[key] = count;
  return out;
}

void addFlags(app::CommandLine& cli) {
  cli.addValue("input", "workspace cloud (PCD)");
  cli.addValue("output", "boundary points (PCD)");
  cli.addValue("interior", "also write the interior points here");
  cli.addValue("plane", "xy | xz | yz: work in that plane (default 3-D)");
  cli.addValue("method", "orthant (default) | grid | extremum");
  cli.addValue("radius", "orthant: fixed search radius r [length unit]");
  cli.addValue("auto-radius", "orthant: r = c x mean spacing (default: c automatic)");
  cli.addValue("adaptive", "orthant: k, per-point r = 2 x distance to k-th neighbour (default)");
  cli.addValue("outer-radius",
               "orthant: the paper's second stage at R: a length > r with --radius/--auto-radius, "
               "else a factor > 1 of each point's radius");
  cli.addValue("min-gap",
               "orthant, 2-D: empty sector that makes a boundary point, 90..179 deg (default 92)");
  cli.addValue("hull-depth",
               "orthant, 2-D: keep points less than t local spacings inside the convex hull of "
               "their neighbourhood; 0 = off (default 1)");
  cli.addValue("cell",
               "grid: cell side, extremum: column width dL [length unit] (default: from N and "
               "spacing)");
  cli.addValue("gap",
               "extremum: a larger gap inside a column is an inner boundary [length unit] "
               "(default: from the density)");
  cli.addValue("threads", "orthant: worker threads, 0 = all cores (default 0)");
  cli.addValue("tiles",
               "orthant: find the boundary in N slabs with halos, in bounded memory (binary PCD; "
               "shared among mpirun's processes)");
  cli.addSwitch("tree-search",
                "orthant: search every point in the kd-tree, not the cell grid (same result, "
                "slower; for comparison)");
  app::declareUnitFlag(cli);
  cli.addSwitch("json", "print a JSON summary on stdout");
}

/// Usage error for flags of another method.
void rejectFlags(const app::CommandLine& cli, const std::string& method,
                 std::initializer_list<const char*> flags) {
  for (const char* flag : flags) {
    if (cli.has(flag)) {
      throw app::UsageError("--" + std::string(flag) + " does not apply to --method " + method);
    }
  }
}

/// The filter's recommended settings, changed by the flags given.
Method orthantMethod(const app::CommandLine& cli, BoundaryPlane plane, int threads) {
  rejectFlags(cli, "orthant", {"cell", "gap"});
  if (cli.has("radius") + cli.has("auto-radius") + cli.has("adaptive") > 1) {
    throw app::UsageError("give at most one of --radius, --auto-radius, --adaptive");
  }
  if (plane == BoundaryPlane::k3D && cli.has("hull-depth")) {
    throw app::UsageError("--hull-depth works in a plane: give --plane xy, xz or yz");
  }
  auto boundary = std::make_shared<Filter>(true);
  boundary->setPlane(plane);
  if (cli.has("adaptive")) {
    const auto k = app::parseInteger(cli.required("adaptive"), "adaptive", 1, 1000);
    boundary->setAdaptiveRadius(static_cast<int>(k), Filter::kRecommendedScale);
  }
  if (cli.has("auto-radius"))
    boundary->setAutoRadius(app::parsePositive(cli.required("auto-radius"), "auto-radius"));
  if (cli.has("radius"))
    boundary->setRadiusSearch(app::parsePositive(cli.required("radius"), "radius"));
  if (cli.has("outer-radius")) {
    boundary->setOuterRadius(app::parsePositive(cli.required("outer-radius"), "outer-radius"));
  }
  if (cli.has("min-gap")) {
    const double gap = app::parseNumber(cli.required("min-gap"), "min-gap");
    if (!(gap >= 90.0 && gap < 180.0)) {
      throw app::UsageError("--min-gap: " + cli.required("min-gap") + " is not in [90, 180) deg");
    }
    boundary->setMinimumGap(gap * M_PI / 180.0);
  }
  if (cli.has("hull-depth")) {
    const double depth = app::parseNonNegative(cli.required("hull-depth"), "hull-depth");
    if (depth != 0.0 && !(depth >= kHullDepthRange[0] && depth <= kHullDepthRange[1])) {
      throw app::UsageError("--hull-depth: " + cli.required("hull-depth") +
                            " is not 0 (off) or in [0.1, 10] local spacings");
    }
    boundary->setHullDepth(depth);
  }
  boundary->setNumberOfThreads(threads);
  boundary->setGridSearch(!cli.has("tree-search"));
  return {"orthant", plane, boundary, [boundary] { return usedParameters(*boundary); }};
}

Method gridMethod(const app::CommandLine& cli, BoundaryPlane plane) {
  rejectFlags(cli, "grid",
              {"radius", "auto-radius", "adaptive", "outer-radius", "min-gap", "hull-depth",
               "threads", "gap", "tree-search", "tiles"});
  auto grid = std::make_shared<GridBoundary<WorkspacePoint>>(true);
  grid->setPlane(plane);
  if (cli.has("cell")) grid->setCellSize(app::parsePositive(cli.required("cell"), "cell"));
  return {"grid", plane, grid, [grid] { return usedParameters(*grid); }};
}

Method extremumMethod(const app::CommandLine& cli, BoundaryPlane plane) {
  rejectFlags(cli, "extremum",
              {"radius", "auto-radius", "adaptive", "outer-radius", "min-gap", "hull-depth",
               "threads", "tree-search", "tiles"});
  if (plane == BoundaryPlane::k3D) {
    throw app::UsageError("--method extremum works in a plane: give --plane xy, xz or yz");
  }
  auto extremum = std::make_shared<ExtremumBoundary<WorkspacePoint>>(true);
  extremum->setPlane(plane);
  if (cli.has("cell")) extremum->setColumnWidth(app::parsePositive(cli.required("cell"), "cell"));
  if (cli.has("gap")) extremum->setGapThreshold(app::parsePositive(cli.required("gap"), "gap"));
  return {"extremum", plane, extremum, [extremum] { return usedParameters(*extremum); }};
}

/// The method named by --method (default orthant), set up from its flags.
Method methodFromFlags(const app::CommandLine& cli, int threads) {
  const BoundaryPlane plane = app::readPlane(cli);
  const std::string name =
      app::parseChoice(cli.text("method", "orthant"), "method", {"orthant", "grid", "extremum"});
  if (name == "grid") return gridMethod(cli, plane);
  if (name == "extremum") return extremumMethod(cli, plane);
  return orthantMethod(cli, plane, threads);
}

/// Usage error unless --flag's value lies in `range` (boundarySettingRanges()).
void requireWithin(const app::CommandLine& cli, const char* flag, const SettingRange& range) {
  if (range.contains(app::parseNumber(cli.required(flag), flag))) return;
  throw app::UsageError("--" + std::string(flag) + ": " + cli.required(flag) + " is not in " +
                        (range.open_low ? "(" : "[") + app::shortNumber(range.low) + ", " +
                        app::shortNumber(range.high) + "] " + range.unit + " (" + range.why + ")");
}

/// Whether a flag given has a range in the cloud's mean spacings (checkFlagsAgainstCloud), so
/// that the cloud is summarised with its spacing, a pass over every point the default run skips.
bool needsSpacing(const app::CommandLine& cli) {
  for (const char* flag : {"cell", "gap", "radius", "auto-radius", "outer-radius"}) {
    if (cli.has(flag)) return true;
  }
  return false;
}

/// Checks the numeric flags against the cloud they work on (boundarySettingRanges()). A value
/// the filter would reject is a usage error naming its flag, never a filter's error.
void checkFlagsAgainstCloud(const app::CommandLine& cli, const Method& method,
                            const CloudSummary& cloud) {
  BoundarySettings settings;
  settings.baseline = method.name != "orthant";
  settings.plane = method.plane;
  if (!settings.baseline) {
    settings.adaptive_neighbours =
        static_cast<const Filter&>(*method.filter).getAdaptiveNeighbours();
    if (cli.has("radius")) settings.radius = app::parseNumber(cli.required("radius"), "radius");
    if (cli.has("auto-radius"))
      settings.auto_radius_factor = app::parseNumber(cli.required("auto-radius"), "auto-radius");
  }
  const BoundarySettingRanges ranges = boundarySettingRanges(cloud, settings);
  const std::pair<const char*, std::optional<SettingRange>> flags[] = {
      {"adaptive", ranges.adaptive},
      {"cell", ranges.cell},
      {"gap", ranges.gap},
      {"radius", ranges.radius},
      {"auto-radius", ranges.auto_radius},
      {"outer-radius", ranges.outer_radius}};
  for (const auto& [flag, range] : flags) {
    if (cli.has(flag) && range) requireWithin(cli, flag, *range);
  }
}

/// Checks both destinations before any work, so that neither is written when the other cannot
/// be.
void checkOutputs(const app::CommandLine& cli) {
  app::checkOutputs({{"output", cli.required("output")}, {"interior", cli.text("interior", "")}},
                    {{"input", cli.required("input")}});
}

/// Writes the boundary and, with --interior, the finite points that are not on it: both or
/// neither.
/// Both record the robot the input records, if any, and the input (io::boundaryProvenance()).
void saveOutputs(const app::CommandLine& cli, const io::WorkspaceCloud& cloud,
                 const pcl::Indices& kept, const pcl::Indices& removed, pcl::Indices& interior) {
  const std::string output = cli.required("output");
  const std::optional<io::CloudProvenance> robot =
      io::boundaryProvenance(cli.required("input"), cloud.size(), kept.size());
  io::OutputSet outputs;
  io::writeCloud(cloud, kept, output, robot);
  if (cli.has("interior")) {
    for (const auto i : removed) {
      if (pcl::isFinite(cloud[i])) interior.push_back(i);
    }
    io::writeCloud(cloud, interior, cli.required("interior"), robot);
  }
  outputs.commit();
}

/// Prints the run's summary: one JSON object with --json, else a line on stderr.
void report(const app::CommandLine& cli, nlohmann::json summary, const ResultUnits& units,
            const app::Progress& clock) {
  summary["length_unit"] = units.lengthName();
  addRecordedRobotNames(summary, io::readProvenance(cli.required("input")));
  summary["units"]["seconds"] = "s";
  if (cli.has("json")) {
    std::cout << summary.dump() << "\n";
  } else {
    std::cerr << "[done, " << static_cast<int>(clock.seconds() * 1000)
              << " ms : " << summary["boundary"] << " of " << summary["points"]
              << " points on the boundary] -> " << summary["output"].get<std::string>() << "\n";
  }
}

/// The common part of both summaries.
nlohmann::json summaryOf(const app::CommandLine& cli, const Method& method, std::uint64_t points,
                         std::uint64_t boundary, const app::Progress& clock) {
  return {{"input", cli.required("input")},
          {"output", cli.required("output")},
          {"method", method.name},
          {"plane", boundaryPlaneName(method.plane)},
          {"points", points},
          {"boundary", boundary},
          {"seconds", clock.seconds()}};
}

/// --tiles: the boundary slab by slab (distributed::tiledBoundary()), the outputs written by rank 0
/// in one more pass over the input. The flags a tiled run cannot take.
void checkTiledMethod(const app::CommandLine& cli, const Method& method) {
  if (method.name != "orthant") throw app::UsageError("--tiles works with --method orthant");
  if (cli.has("auto-radius")) {
    throw app::UsageError(
        "--auto-radius needs the whole cloud's spacing: with --tiles give --radius or --adaptive");
  }
  if (static_cast<const Filter&>(*method.filter).getHullDepth() > 0.0) {
    throw app::UsageError(
        "--tiles: the hull-depth stage looks past the neighbourhood of a point; give "
        "--hull-depth 0 with --plane");
  }
}

int runTiled(const app::CommandLine& cli, distributed::Processes& processes) {
  const std::string input = cli.required("input"), output = cli.required("output");
  const int tiles = static_cast<int>(app::parseInteger(cli.required("tiles"), "tiles", 1, 100000));
  const int threads = distributed::threadsPerProcess(app::readThreads(cli), processes);
  const Method method = methodFromFlags(cli, threads);
  checkTiledMethod(cli, method);
  const auto& prototype = static_cast<const Filter&>(*method.filter);
  if (processes.rank() == 0) checkOutputs(cli);
  const ResultUnits units = app::readResultUnits(cli, io::recordedUnit(input), input);
  app::Progress clock("mcws_boundary", "slabs");
  io::PcdPointReader reader(input);
  const distributed::FileSummary file = distributed::summarizeFile(reader, method.plane);
  file.range.check(input);
  requireRegionPoints(file.cloud, input);
  if (method.plane == BoundaryPlane::k3D) io::requireVolume(file.range, input);
  app::asUsageError("plane", [&] { requirePlaneFits(file.cloud, input); });
  CloudSummary region = file.cloud;
  if (needsSpacing(cli)) {
    // The ranges of the length flags only: the whole cloud's spacing needs all of it.
    region.spacing = distributed::boundingBoxSpacing(region);
  }
  checkFlagsAgainstCloud(cli, method, region);
  if (region.finite > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw Error(input + ": " + std::to_string(region.finite) +
                " finite points, more than the 2^31 - 1 a PCD output holds");
  }
  // The same file on every process: its size and what the first pass saw of it.
  processes.setUpDone({{"input", distributed::fileFingerprint(reader, file)}});

  const auto make = [&] {
    return std::static_pointer_cast<Filter>(methodFromFlags(cli, threads).filter);
  };
  const distributed::TiledBoundary found = distributed::tiledBoundary(
      reader, file, tiles, make, threads, processes,
      [&](std::size_t done, std::size_t all) { clock.update(done, all); });
  if (processes.rank() != 0) return app::kExitOk;

  const bool with_interior = cli.has("interior");
  const std::uint64_t interior = file.cloud.finite - found.kept;
  distributed::writeTiledBoundary(reader, found, output, cli.text("interior", ""), interior,
                                  io::boundaryProvenance(input, reader.size(), found.kept));

  nlohmann::json summary = summaryOf(cli, method, reader.size(), found.kept, clock);
  summary.update(parametersJson(
      {{{"radius", prototype.getRadiusMode() == RadiusMode::kFixed ? prototype.getRadiusSearch()
                                                                   : found.median_radius},
        {"halo", found.largest_halo}},
       {}},
      units));
  summary["tiles"] = tiles;
  summary["processes"] = processes.size();
  summary["largest_tile_points"] = found.largest_tile;
  summary["reloaded_tiles"] = found.reloaded_tiles;
  if (with_interior) summary["interior"] = interior;
  report(cli, summary, units, clock);
  return app::kExitOk;
}
}  // namespace

int main(int argc, char** argv) {
  distributed::Processes processes(argc, argv);
  return app::run("mcws_boundary", processes, [&] {
    app::CommandLine cli(kUsage, kSummary);
    addFlags(cli);
    if (!cli.parse(argc, argv)) return app::kExitOk;
    if (cli.has("tiles")) return runTiled(cli, processes);
    if (processes.distributed()) {
      throw app::UsageError("several processes (mpirun) share a boundary only with --tiles N");
    }
    const std::string input = cli.required("input"), output = cli.required("output");
    const Method method = methodFromFlags(cli, app::readThreads(cli));
    checkOutputs(cli);
    const ResultUnits units = app::readResultUnits(cli, io::recordedUnit(input), input);

    app::Progress clock("mcws_boundary", "points");
    const io::WorkspaceCloud::Ptr cloud = io::readCloud(input);
    const CloudSummary region = summarizeCloud(
        *cloud, method.plane, needsSpacing(cli) ? SummaryDetail::kSpacing : SummaryDetail::kCounts);
    requireRegionPoints(region, input);
    if (method.plane == BoundaryPlane::k3D) io::requireVolume(*cloud, input);
    app::asUsageError("plane", [&] { requirePlaneFits(region, input); });
    checkFlagsAgainstCloud(cli, method, region);
    method.filter->setInputCloud(cloud);
    pcl::Indices kept, interior;
    method.filter->filter(kept);
    saveOutputs(cli, *cloud, kept, *method.filter->getRemovedIndices(), interior);

    nlohmann::json summary = summaryOf(cli, method, cloud->size(), kept.size(), clock);
    summary.update(parametersJson(method.parameters(), units));
    if (cli.has("interior")) summary["interior"] = interior.size();
    report(cli, summary, units, clock);
    return app::kExitOk;
  });
}
