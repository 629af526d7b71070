// mcws_boundary: boundary points of a workspace cloud by the local quadrant/octant test of
// seed 000 (section 4.3), on a plane (--plane) or in 3-D; or by the paper's baselines, the grid
// (4.1) and extremum (4.2) methods.
#include <pcl/common/common.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "common/app.h"
#include "common/cloud_io.h"
#include "mcws/filters/extremum_boundary.h"
#include "mcws/filters/grid_boundary.h"
#include "mcws/filters/orthant_boundary.h"
#include "mcws/io/atomic_file.h"

namespace {
using namespace mcws;

// 90 degrees is seed 000's quadrant. 92 trades a little recall for precision: on uniform disks
// of 1e5 and 1e6 points, precision 0.991 and recall 0.982-0.984 (BENCHMARKS.md).
constexpr int kDefaultGapDegrees = 92;

/// A configured filter and, after it ran, the parameters it used (for --json).
struct Method {
  BoundaryPlane plane;
  std::shared_ptr<pcl::FilterIndices<WorkspacePoint>> filter;
  std::function<nlohmann::json()> parameters;
};

void addFlags(app::CommandLine& cli) {
  cli.add()("input", app::po::value<std::string>(), "workspace cloud (PCD)")(
      "output", app::po::value<std::string>(), "boundary points (PCD)")(
      "interior", app::po::value<std::string>(), "also write the interior points here")(
      "plane", app::po::value<std::string>(), "xy | xz | yz: work in that plane (default 3-D)")(
      "method", app::po::value<std::string>(), "orthant (default) | grid | extremum")(
      "radius", app::po::value<std::string>(), "orthant: fixed search radius r [length unit]")(
      "auto-radius", app::po::value<std::string>(),
      "orthant: r = c x mean spacing (default: c automatic)")(
      "adaptive", app::po::value<std::string>(),
      "orthant: k, per-point r = 2 x distance to k-th neighbour (default)")(
      "outer-radius", app::po::value<std::string>(),
      "orthant: seed 000's second stage at R: a length > r with --radius/--auto-radius, else a "
      "factor > 1 of each point's radius")(
      "min-gap", app::po::value<std::string>(),
      "orthant, 2-D: empty sector that makes a boundary point, 90..179 deg (default 92)")(
      "hull-depth", app::po::value<std::string>(),
      "orthant, 2-D: keep points less than t local spacings inside the convex hull of their "
      "neighbourhood; 0 = off (default 1)")(
      "cell", app::po::value<std::string>(),
      "grid: cell side, extremum: column width dL [length unit] (default: from N and spacing)")(
      "gap", app::po::value<std::string>(),
      "extremum: a larger gap inside a column is an inner boundary [length unit] (default: "
      "from the density)")("threads", app::po::value<std::string>(),
                           "orthant: worker threads, 0 = all cores (default 0)")(
      "tree-search",
      "orthant: search every point in the kd-tree, not the cell grid (same "
      "result, slower; for comparison)")("json", "print a JSON summary on stdout");
}

double positive(const app::CommandLine& cli, const std::string& flag) {
  const double value = app::parseNumber(cli.required(flag), flag);
  if (!(value > 0.0))
    throw app::UsageError("--" + flag + ": must be positive, not " + cli.required(flag));
  return value;
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

Method orthantMethod(const app::CommandLine& cli, BoundaryPlane plane) {
  rejectFlags(cli, "orthant", {"cell", "gap"});
  auto boundary = std::make_shared<OrthantBoundary<WorkspacePoint>>(true);
  boundary->setPlane(plane);
  if (cli.has("radius") + cli.has("auto-radius") + cli.has("adaptive") > 1) {
    throw app::UsageError("give at most one of --radius, --auto-radius, --adaptive");
  }
  const int default_k = plane == BoundaryPlane::k3D ? 16 : 24;
  boundary->setAdaptiveRadius(
      static_cast<int>(
          app::parseInteger(cli.text("adaptive", std::to_string(default_k)), "adaptive", 1, 1000)),
      2.0);
  if (cli.has("auto-radius")) boundary->setAutoRadius(positive(cli, "auto-radius"));
  if (cli.has("radius")) boundary->setRadiusSearch(positive(cli, "radius"));
  if (cli.has("outer-radius")) boundary->setOuterRadius(positive(cli, "outer-radius"));
  const double gap =
      app::parseNumber(cli.text("min-gap", std::to_string(kDefaultGapDegrees)), "min-gap");
  if (!(gap >= 90.0 && gap < 180.0))
    throw app::UsageError("--min-gap: must be in [90, 180), not " + cli.text("min-gap", ""));
  boundary->setMinimumGap(gap * M_PI / 180.0);
  if (plane == BoundaryPlane::k3D && cli.has("hull-depth")) {
    throw app::UsageError("--hull-depth works in a plane: give --plane xy, xz or yz");
  }
  if (plane != BoundaryPlane::k3D) {
    const double depth = app::parseNumber(cli.text("hull-depth", "1"), "hull-depth");
    if (!(depth >= 0.0 && std::isfinite(depth))) {
      throw app::UsageError("--hull-depth: must be 0 (off) or positive, not " +
                            cli.text("hull-depth", ""));
    }
    boundary->setHullDepth(depth);
  }
  boundary->setNumberOfThreads(app::parseInteger(cli.text("threads", "0"), "threads", 0, 256));
  boundary->setGridSearch(!cli.has("tree-search"));
  return {plane, boundary, [boundary] {
            return nlohmann::json{{"radius", boundary->usedRadius()},
                                  {"spacing", boundary->usedSpacing()}};
          }};
}

Method gridMethod(const app::CommandLine& cli, BoundaryPlane plane) {
  rejectFlags(cli, "grid",
              {"radius", "auto-radius", "adaptive", "outer-radius", "min-gap", "hull-depth",
               "threads", "gap", "tree-search"});
  auto grid = std::make_shared<GridBoundary<WorkspacePoint>>(true);
  grid->setPlane(plane);
  if (cli.has("cell")) grid->setCellSize(positive(cli, "cell"));
  return {plane, grid, [grid] {
            return nlohmann::json{{"cell", grid->usedCellSize()},
                                  {"spacing", grid->usedSpacing()},
                                  {"occupied_cells", grid->occupiedCells()},
                                  {"boundary_cells", grid->boundaryCells()}};
          }};
}

Method extremumMethod(const app::CommandLine& cli, BoundaryPlane plane) {
  rejectFlags(cli, "extremum",
              {"radius", "auto-radius", "adaptive", "outer-radius", "min-gap", "hull-depth",
               "threads", "tree-search"});
  if (plane == BoundaryPlane::k3D) {
    throw app::UsageError("--method extremum works in a plane: give --plane xy, xz or yz");
  }
  auto extremum = std::make_shared<ExtremumBoundary<WorkspacePoint>>(true);
  extremum->setPlane(plane);
  if (cli.has("cell")) extremum->setColumnWidth(positive(cli, "cell"));
  if (cli.has("gap")) extremum->setGapThreshold(positive(cli, "gap"));
  return {plane, extremum, [extremum] {
            return nlohmann::json{{"cell", extremum->usedColumnWidth()},
                                  {"gap", extremum->usedGapThreshold()},
                                  {"spacing", extremum->usedSpacing()},
                                  {"columns", extremum->columns()}};
          }};
}

/// The method named by --method (default orthant), set up from its flags.
Method methodFromFlags(const app::CommandLine& cli, std::string& name) {
  BoundaryPlane plane = BoundaryPlane::k3D;
  try {
    if (cli.has("plane")) plane = parseBoundaryPlane(cli.required("plane"));
  } catch (const Error& e) {
    throw app::UsageError(std::string("--plane: ") + e.what());
  }
  name = cli.text("method", "orthant");
  if (name == "orthant") return orthantMethod(cli, plane);
  if (name == "grid") return gridMethod(cli, plane);
  if (name == "extremum") return extremumMethod(cli, plane);
  throw app::UsageError("--method: unknown method '" + name + "' (known: orthant, grid, extremum)");
}

/// Writes the boundary and, with --interior, the finite points that are not on it: both or
/// neither.
void saveOutputs(const app::CommandLine& cli, const app::WorkspaceCloud& cloud,
                 const pcl::Indices& kept, const pcl::Indices& removed, pcl::Indices& interior) {
  const std::string output = cli.required("output");
  app::saveCloud(cloud, kept, output);
  if (!cli.has("interior")) return;
  for (const auto i : removed) {
    if (pcl::isFinite(cloud[i])) interior.push_back(i);
  }
  try {
    app::saveCloud(cloud, interior, cli.required("interior"));
  } catch (...) {
    std::remove(output.c_str());  // all or nothing
    throw;
  }
}
}  // namespace

int main(int argc, char** argv) {
  return app::run("mcws_boundary", [&] {
    app::CommandLine cli(
        "mcws_boundary --input CLOUD.pcd --output BOUNDARY.pcd [options]",
        "Keeps the points on the boundary of the sampled region. --method orthant (default, seed\n"
        "000's test): a point is a boundary point when some quadrant (--plane) or octant (3-D)\n"
        "around it holds no neighbour within the radius; 2-D: in every rotation of the local\n"
        "frame (a 90-degree gap between neighbours), and then (--hull-depth) only those, and "
        "their\n"
        "neighbours, that lie less than a local spacing inside the convex hull of their\n"
        "neighbourhood; 3-D: in the axis frame or in a frame centred on the outward direction.\n"
        "By default each point's radius is twice the distance to its k-th neighbour (k = 24 in\n"
        "2-D, 16 in 3-D), which follows the density of joint-space samples; --radius fixes it,\n"
        "--auto-radius takes c x the cloud's mean spacing.\n"
        "--method grid (seed 000, 4.1): cells of side --cell; an occupied cell with an empty\n"
        "neighbour (8 in 2-D, 26 in 3-D) is a boundary cell, represented by its point nearest to\n"
        "the cell's mean. --method extremum (4.2, needs --plane): in columns of width --cell "
        "along\n"
        "the plane's first axis, the lowest and highest point along the second, and both points\n"
        "around any gap wider than --gap.\n"
        "NaN points are dropped from both outputs.");
    addFlags(cli);
    if (!cli.parse(argc, argv)) return app::kExitOk;

    const std::string input = cli.required("input"), output = cli.required("output");
    std::string name;
    const Method method = methodFromFlags(cli, name);
    // Both destinations are checked before any work, so neither is written when the other cannot
    // be.
    io::checkOutputPath(output);
    if (cli.has("interior")) {
      if (cli.required("interior") == output) {
        throw app::UsageError("--interior and --output name the same file");
      }
      io::checkOutputPath(cli.required("interior"));
    }
    app::Progress clock("mcws_boundary", "points");
    const app::WorkspaceCloud::Ptr cloud = app::loadCloud(input);
    const BoundaryPlane plane =
        cli.has("plane") ? parseBoundaryPlane(cli.required("plane")) : BoundaryPlane::k3D;
    if (plane == BoundaryPlane::k3D) app::requireVolume(*cloud, input);
    method.filter->setInputCloud(cloud);
    pcl::Indices kept, interior;
    method.filter->filter(kept);
    saveOutputs(cli, *cloud, kept, *method.filter->getRemovedIndices(), interior);

    nlohmann::json summary = {{"input", input},
                              {"output", output},
                              {"method", name},
                              {"plane", boundaryPlaneName(method.plane)},
                              {"points", cloud->size()},
                              {"boundary", kept.size()},
                              {"seconds", clock.seconds()}};
    summary.update(method.parameters());
    if (cli.has("interior")) summary["interior"] = interior.size();
    if (cli.has("json")) {
      std::cout << summary.dump() << "\n";
    } else {
      std::cerr << "[done, " << static_cast<int>(clock.seconds() * 1000) << " ms : " << kept.size()
                << " of " << cloud->size() << " points on the boundary] -> " << output << "\n";
    }
    return app::kExitOk;
  });
}
