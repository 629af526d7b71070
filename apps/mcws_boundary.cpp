// mcws_boundary: boundary points of a workspace cloud by the local quadrant/octant test of Yin,
// Wang & Yu 2010 (section 4.3), on a plane (--plane) or in 3-D; or by the paper's baselines, the
// grid (4.1) and extremum (4.2) methods.
#include <pcl/common/common.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "common/app.h"
#include "common/cloud_io.h"
#include "common/flags.h"
#include "mcws/filters/extremum_boundary.h"
#include "mcws/filters/grid_boundary.h"
#include "mcws/filters/orthant_boundary.h"
#include "mcws/io/atomic_file.h"

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
NaN points are dropped from both outputs.)";

using Filter = OrthantBoundary<WorkspacePoint>;

/// A configured filter and, after it ran, the parameters it used (for --json).
struct Method {
  std::string name;
  BoundaryPlane plane;
  std::shared_ptr<pcl::FilterIndices<WorkspacePoint>> filter;
  std::function<nlohmann::json()> parameters;
};

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
  cli.addSwitch("tree-search",
                "orthant: search every point in the kd-tree, not the cell grid (same result, "
                "slower; for comparison)");
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
Method orthantMethod(const app::CommandLine& cli, BoundaryPlane plane) {
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
    boundary->setHullDepth(app::parseNonNegative(cli.required("hull-depth"), "hull-depth"));
  }
  boundary->setNumberOfThreads(app::readThreads(cli));
  boundary->setGridSearch(!cli.has("tree-search"));
  return {"orthant", plane, boundary, [boundary] {
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
  if (cli.has("cell")) grid->setCellSize(app::parsePositive(cli.required("cell"), "cell"));
  return {"grid", plane, grid, [grid] {
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
  if (cli.has("cell")) extremum->setColumnWidth(app::parsePositive(cli.required("cell"), "cell"));
  if (cli.has("gap")) extremum->setGapThreshold(app::parsePositive(cli.required("gap"), "gap"));
  return {"extremum", plane, extremum, [extremum] {
            return nlohmann::json{{"cell", extremum->usedColumnWidth()},
                                  {"gap", extremum->usedGapThreshold()},
                                  {"spacing", extremum->usedSpacing()},
                                  {"columns", extremum->columns()}};
          }};
}

/// The method named by --method (default orthant), set up from its flags.
Method methodFromFlags(const app::CommandLine& cli) {
  const BoundaryPlane plane = app::readPlane(cli);
  const std::string name =
      app::parseChoice(cli.text("method", "orthant"), "method", {"orthant", "grid", "extremum"});
  if (name == "grid") return gridMethod(cli, plane);
  if (name == "extremum") return extremumMethod(cli, plane);
  return orthantMethod(cli, plane);
}

/// Checks both destinations before any work, so that neither is written when the other cannot
/// be.
void checkOutputs(const app::CommandLine& cli) {
  if (cli.has("interior") && cli.required("interior") == cli.required("output")) {
    throw app::UsageError("--interior and --output name the same file");
  }
  app::checkOutputs({{"output", cli.required("output")}, {"interior", cli.text("interior", "")}},
                    {{"input", cli.required("input")}});
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
    app::CommandLine cli(kUsage, kSummary);
    addFlags(cli);
    if (!cli.parse(argc, argv)) return app::kExitOk;
    const std::string input = cli.required("input"), output = cli.required("output");
    const Method method = methodFromFlags(cli);
    checkOutputs(cli);

    app::Progress clock("mcws_boundary", "points");
    const app::WorkspaceCloud::Ptr cloud = app::loadCloud(input);
    if (method.plane == BoundaryPlane::k3D) app::requireVolume(*cloud, input);
    method.filter->setInputCloud(cloud);
    pcl::Indices kept, interior;
    method.filter->filter(kept);
    saveOutputs(cli, *cloud, kept, *method.filter->getRemovedIndices(), interior);

    nlohmann::json summary = {{"input", input},
                              {"output", output},
                              {"method", method.name},
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
