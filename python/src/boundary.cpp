// mcws.boundary's C++ part: the boundary filters of filters/ (the orthant test, and the paper's
// grid and extremum baselines), set up and checked as mcws_boundary sets up and checks them from
// its flags, on positions handed over as float32 (N, 3), as a PCD file holds them.
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "bindings.h"
#include "mcws/distributed/processes.h"
#include "mcws/distributed/tiled_boundary.h"
#include "mcws/filters/extremum_boundary.h"
#include "mcws/filters/grid_boundary.h"
#include "mcws/filters/orthant_boundary.h"
#include "mcws/filters/setting_ranges.h"
#include "positions.h"

namespace mcws::python {

namespace {

using OrthantFilter = OrthantBoundary<WorkspacePoint>;

/// The settings of mcws_boundary, as its flags: a value for each flag given, none for the others.
struct BoundaryArguments {
  std::string method{"orthant"};
  std::optional<double> radius, auto_radius, outer_radius, min_gap, hull_depth, cell, gap;
  std::optional<int> adaptive;
  int threads{0};
};

/// A configured filter, and what its settings are checked against (boundarySettingRanges()).
struct BoundaryMethod {
  std::shared_ptr<pcl::FilterIndices<WorkspacePoint>> filter;
  BoundarySettings settings;
};

/// UsageError "name: value is not in [low, high] unit (why)" unless `range` holds `value`.
void requireInRange(const char* name, double value, const SettingRange& range) {
  if (range.contains(value)) return;
  throw UsageError(std::string(name) + ": " + number(value) + " is not in " +
                   (range.open_low ? "(" : "[") + number(range.low) + ", " + number(range.high) +
                   "] " + range.unit + " (" + range.why + ")");
}

/// UsageError "name: value is not a positive number" unless it is one (a length setting).
void requirePositive(const char* name, const std::optional<double>& value) {
  if (value && !(*value > 0.0 && std::isfinite(*value))) {
    throw UsageError(std::string(name) + ": " + number(*value) + " is not a positive number");
  }
}

/// UsageError "name does not apply to method M" for each setting of another method given.
void rejectSettings(const BoundaryArguments& a,
                    std::initializer_list<std::pair<const char*, bool>> given) {
  for (const auto& [name, is_given] : given) {
    if (is_given) throw UsageError(std::string(name) + " does not apply to method " + a.method);
  }
}

BoundaryMethod orthantMethod(BoundaryPlane plane, const BoundaryArguments& a) {
  rejectSettings(a, {{"cell", a.cell.has_value()}, {"gap", a.gap.has_value()}});
  if (!!a.radius + !!a.auto_radius + !!a.adaptive > 1) {
    throw UsageError("give at most one of radius, auto_radius, adaptive");
  }
  if (plane == BoundaryPlane::k3D && a.hull_depth) {
    throw UsageError("hull_depth works in a plane: give plane 'xy', 'xz' or 'yz'");
  }
  auto filter = std::make_shared<OrthantFilter>(true);
  filter->setPlane(plane);
  if (a.adaptive) {
    if (*a.adaptive < 1 || *a.adaptive > 1000) {
      throw UsageError("adaptive: " + std::to_string(*a.adaptive) + " is not in 1 .. 1000");
    }
    filter->setAdaptiveRadius(*a.adaptive, OrthantFilter::kRecommendedScale);
  }
  requirePositive("radius", a.radius);
  requirePositive("auto_radius", a.auto_radius);
  requirePositive("outer_radius", a.outer_radius);
  if (a.auto_radius) filter->setAutoRadius(*a.auto_radius);
  if (a.radius) filter->setRadiusSearch(*a.radius);
  if (a.outer_radius) filter->setOuterRadius(*a.outer_radius);
  if (a.min_gap) {
    if (!(*a.min_gap >= 90.0 && *a.min_gap < 180.0)) {
      throw UsageError("min_gap: " + number(*a.min_gap) + " is not in [90, 180) deg");
    }
    filter->setMinimumGap(*a.min_gap * M_PI / 180.0);
  }
  if (a.hull_depth) {
    const double depth = *a.hull_depth;
    if (depth != 0.0 && !(depth >= 0.1 && depth <= 10.0)) {
      throw UsageError("hull_depth: " + number(depth) +
                       " is not 0 (off) or in [0.1, 10] local spacings");
    }
    filter->setHullDepth(depth);
  }
  filter->setNumberOfThreads(threadCount(a.threads));
  BoundarySettings settings;
  settings.plane = plane;
  settings.adaptive_neighbours = filter->getAdaptiveNeighbours();
  settings.radius = a.radius.value_or(0.0);
  settings.auto_radius_factor = a.auto_radius.value_or(0.0);
  return {filter, settings};
}

/// The orthant method's settings, which the baselines do not take (as mcws_boundary's flags).
void rejectOrthantSettings(const BoundaryArguments& a) {
  rejectSettings(a, {{"radius", a.radius.has_value()},
                     {"auto_radius", a.auto_radius.has_value()},
                     {"adaptive", a.adaptive.has_value()},
                     {"outer_radius", a.outer_radius.has_value()},
                     {"min_gap", a.min_gap.has_value()},
                     {"hull_depth", a.hull_depth.has_value()},
                     {"threads", a.threads != 0}});
}

/// The grid (section 4.1) or extremum (4.2) method of Yin, Wang & Yu 2010.
BoundaryMethod baselineMethod(BoundaryPlane plane, const BoundaryArguments& a) {
  rejectOrthantSettings(a);
  BoundarySettings settings;
  settings.baseline = true;
  settings.plane = plane;
  if (a.method == "grid") {
    rejectSettings(a, {{"gap", a.gap.has_value()}});
    requirePositive("cell", a.cell);
    auto grid = std::make_shared<GridBoundary<WorkspacePoint>>(true);
    grid->setPlane(plane);
    if (a.cell) grid->setCellSize(*a.cell);
    return {grid, settings};
  }
  if (plane == BoundaryPlane::k3D) {
    throw UsageError("method extremum works in a plane: give plane 'xy', 'xz' or 'yz'");
  }
  requirePositive("cell", a.cell);
  requirePositive("gap", a.gap);
  auto extremum = std::make_shared<ExtremumBoundary<WorkspacePoint>>(true);
  extremum->setPlane(plane);
  if (a.cell) extremum->setColumnWidth(*a.cell);
  if (a.gap) extremum->setGapThreshold(*a.gap);
  return {extremum, settings};
}

BoundaryMethod boundaryMethod(BoundaryPlane plane, const BoundaryArguments& a) {
  if (a.method == "orthant") return orthantMethod(plane, a);
  if (a.method == "grid" || a.method == "extremum") return baselineMethod(plane, a);
  throw UsageError("method: '" + a.method + "' is not one of orthant, grid, extremum");
}

/// The settings checked against the cloud they work on, as mcws_boundary checks its flags: a
/// value the filter would reject is a UsageError naming the setting.
void checkAgainstCloud(const BoundaryArguments& a, const BoundaryMethod& method,
                       const CloudSummary& region) {
  const BoundarySettingRanges ranges = boundarySettingRanges(region, method.settings);
  if (a.adaptive) requireInRange("adaptive", *a.adaptive, ranges.adaptive);
  const std::pair<const char*, std::optional<double>> lengths[] = {
      {"cell", a.cell},
      {"gap", a.gap},
      {"radius", a.radius},
      {"auto_radius", a.auto_radius},
      {"outer_radius", a.outer_radius}};
  const std::optional<SettingRange>* length_ranges[] = {&ranges.cell, &ranges.gap, &ranges.radius,
                                                        &ranges.auto_radius, &ranges.outer_radius};
  for (int i = 0; i < 5; ++i) {
    if (lengths[i].second && *length_ranges[i]) {
      requireInRange(lengths[i].first, *lengths[i].second, **length_ranges[i]);
    }
  }
}

py::array boundaryMask(const FloatRows& xyz, const std::optional<std::string>& plane_name,
                       const BoundaryArguments& arguments) {
  const BoundaryPlane plane = planeOf(plane_name);
  const BoundaryMethod method = boundaryMethod(plane, arguments);
  const io::WorkspaceCloud::Ptr cloud = cloudOf(xyz);
  pcl::Indices kept;
  {
    py::gil_scoped_release release;
    const BoundaryArguments& a = arguments;
    // The length settings' ranges are in the cloud's mean spacings: only then is it measured.
    const bool spacing = a.radius || a.auto_radius || a.outer_radius || a.cell || a.gap;
    checkAgainstCloud(a, method, checkedRegion(*cloud, plane, spacing));
    method.filter->setInputCloud(cloud);
    method.filter->filter(kept);
  }
  py::array_t<bool> out(static_cast<py::ssize_t>(cloud->size()));
  bool* flags = out.mutable_data();
  std::fill(flags, flags + cloud->size(), false);
  for (const pcl::index_t i : kept) flags[i] = true;
  return out;
}

/// The settings a tiled run cannot take, as mcws_boundary --tiles refuses them.
void checkTiledMethod(const BoundaryArguments& a, const BoundaryMethod& method) {
  if (a.method != "orthant") throw UsageError("tiles works with method 'orthant'");
  if (a.auto_radius) {
    throw UsageError(
        "auto_radius needs the whole cloud's spacing: with tiles give radius or adaptive");
  }
  if (static_cast<const OrthantFilter&>(*method.filter).getHullDepth() > 0.0) {
    throw UsageError(
        "tiles: the hull-depth stage looks past the neighbourhood of a point; give "
        "hull_depth=0 with a plane");
  }
}

/// mcws_boundary --tiles on the binary PCD file at `path`: the file read in pieces, the boundary
/// found one slab at a time (distributed::tiledBoundary(), on this process alone), checked as the
/// tool checks it; a mask over the file's points.
py::array tiledBoundaryMask(const std::string& path, const std::optional<std::string>& plane_name,
                            const BoundaryArguments& a, int tiles, const py::object& progress) {
  if (tiles < 1 || tiles > 100000) {
    throw UsageError("tiles: " + std::to_string(tiles) + " is not in 1 .. 100000");
  }
  const BoundaryPlane plane = planeOf(plane_name);
  const BoundaryMethod method = boundaryMethod(plane, a);
  checkTiledMethod(a, method);
  Checkpoint checkpoint(progress, "mcws.boundary", "slabs");
  distributed::TiledBoundary found;
  {
    py::gil_scoped_release release;
    io::PcdPointReader reader(path);
    const distributed::FileSummary file = distributed::summarizeFile(reader, plane);
    file.range.check(path);
    requireRegionPoints(file.cloud, path);
    if (plane == BoundaryPlane::k3D) requireVolumeHinted(file.range, path, "give plane");
    asUsageError("plane", [&] { requirePlaneFits(file.cloud, path); });
    CloudSummary region = file.cloud;
    if (a.radius || a.outer_radius) region.spacing = distributed::boundingBoxSpacing(region);
    checkAgainstCloud(a, method, region);
    const auto make = [&] {
      return std::static_pointer_cast<OrthantFilter>(boundaryMethod(plane, a).filter);
    };
    const distributed::Processes alone;
    found = distributed::tiledBoundary(
        reader, file, tiles, make, a.threads, alone,
        [&](std::size_t done, std::size_t all) { checkpoint(done, all); });
  }
  py::array_t<bool> out(static_cast<py::ssize_t>(found.boundary.size()));
  std::copy(found.boundary.begin(), found.boundary.end(), out.mutable_data());
  return out;
}

}  // namespace

void bindBoundary(py::module_& m) {
  m.def(
      "_boundary",
      [](const FloatRows& xyz, const std::optional<std::string>& plane, const std::string& method,
         std::optional<double> radius, std::optional<double> auto_radius,
         std::optional<int> adaptive, std::optional<double> outer_radius,
         std::optional<double> min_gap, std::optional<double> hull_depth,
         std::optional<double> cell, std::optional<double> gap, int threads) {
        return boundaryMask(xyz, plane,
                            {method, radius, auto_radius, outer_radius, min_gap, hull_depth, cell,
                             gap, adaptive, threads});
      },
      "mcws.boundary's C++ part: the boundary of float32 (N, 3) positions, as a mask.",
      py::arg("xyz"), py::arg("plane").none(true), py::arg("method"), py::arg("radius").none(true),
      py::arg("auto_radius").none(true), py::arg("adaptive").none(true),
      py::arg("outer_radius").none(true), py::arg("min_gap").none(true),
      py::arg("hull_depth").none(true), py::arg("cell").none(true), py::arg("gap").none(true),
      py::arg("threads"));
  m.def(
      "_boundary_tiled",
      [](const std::string& path, const std::optional<std::string>& plane,
         const std::string& method, std::optional<double> radius, std::optional<double> auto_radius,
         std::optional<int> adaptive, std::optional<double> outer_radius,
         std::optional<double> min_gap, std::optional<double> hull_depth,
         std::optional<double> cell, std::optional<double> gap, int threads, int tiles,
         const py::object& progress) {
        return tiledBoundaryMask(path, plane,
                                 {method, radius, auto_radius, outer_radius, min_gap, hull_depth,
                                  cell, gap, adaptive, threads},
                                 tiles, progress);
      },
      "mcws.boundary's C++ part with tiles: the boundary of a binary PCD file, slab by slab.",
      py::arg("path"), py::arg("plane").none(true), py::arg("method"), py::arg("radius").none(true),
      py::arg("auto_radius").none(true), py::arg("adaptive").none(true),
      py::arg("outer_radius").none(true), py::arg("min_gap").none(true),
      py::arg("hull_depth").none(true), py::arg("cell").none(true), py::arg("gap").none(true),
      py::arg("threads"), py::arg("tiles"), py::arg("progress").none(true));
}

}  // namespace mcws::python
