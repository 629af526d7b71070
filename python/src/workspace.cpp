// The C++ parts of mcws.boundary and mcws.measure: the orthant boundary filter (filters/) and the
// Delaunay area or volume (the library's workspace module), called as mcws_boundary and
// mcws_measure call them, on positions handed over as float32 (N, 3), as a PCD file holds them.
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <sstream>

#include "bindings.h"
#include "mcws/filters/boundary_geometry.h"
#include "mcws/filters/orthant_boundary.h"
#include "mcws/filters/setting_ranges.h"
#include "mcws/io/cloud_io.h"
#include "mcws/workspace/measure.h"
#include "mcws/workspace/measure_report.h"
#include "positions.h"

namespace mcws::python {

io::WorkspaceCloud::Ptr cloudOf(const FloatRows& xyz) {
  if (xyz.ndim() != 2 || xyz.shape(1) != 3) throw UsageError("points: not an (N, 3) array");
  auto cloud = std::make_shared<io::WorkspaceCloud>();
  cloud->resize(static_cast<std::size_t>(xyz.shape(0)));
  const float* p = xyz.data();
  for (auto& point : *cloud) {
    point.x = *p++;
    point.y = *p++;
    point.z = *p++;
  }
  cloud->is_dense = false;
  return cloud;
}

BoundaryPlane planeOf(const std::optional<std::string>& name) {
  if (!name) return BoundaryPlane::k3D;
  return asUsageError("plane", [&] { return parseBoundaryPlane(*name); });
}

std::string number(double value) {
  std::ostringstream text;
  text.precision(6);
  text << value;
  return text.str();
}

/// The cloud checked as mcws_boundary and mcws_measure check theirs, and summarised.
CloudSummary checkedRegion(const io::WorkspaceCloud& cloud, BoundaryPlane plane, bool spacing) {
  const CloudSummary region =
      summarizeCloud(cloud, plane, spacing ? SummaryDetail::kSpacing : SummaryDetail::kCounts);
  requireRegionPoints(region, kPoints);
  if (plane == BoundaryPlane::k3D) io::requireVolume(cloud, kPoints);
  asUsageError("plane", [&] { requirePlaneFits(region, kPoints); });
  return region;
}

MeasureOptions regionOptions(const std::optional<double>& alpha, const std::string& correction,
                             int threads) {
  MeasureOptions options;
  if (correction != "efron" && correction != "none") {
    throw UsageError("correction: '" + correction + "' is not one of efron, none");
  }
  options.edge_correction = correction == "efron";
  options.alpha_factor = alpha.value_or(options.edge_correction ? 3.0 : 5.0);  // as the tools
  if (!(options.alpha_factor >= 1.0 && options.alpha_factor <= 1000.0)) {
    throw UsageError("alpha: " + number(options.alpha_factor) +
                     " is not in [1, 1000] local spacings");
  }
  options.threads = threadCount(threads);
  return options;
}

ResultUnits resultUnits(const std::optional<std::string>& length_unit) {
  if (!length_unit) return ResultUnits(std::nullopt, std::nullopt);
  const std::optional<LengthUnit> unit = lengthUnitNamed(*length_unit);
  if (!unit) throw UsageError("length_unit: '" + *length_unit + "' is not one of m, cm, mm");
  return ResultUnits(unit, std::nullopt);
}

namespace {

using Filter = OrthantBoundary<WorkspacePoint>;

/// UsageError "name: value is not in [low, high] unit (why)" unless `range` holds `value`.
void requireWithin(const char* name, double value, const SettingRange& range) {
  if (range.contains(value)) return;
  throw UsageError(std::string(name) + ": " + number(value) + " is not in " +
                   (range.open_low ? "(" : "[") + number(range.low) + ", " + number(range.high) +
                   "] " + range.unit + " (" + range.why + ")");
}

/// The settings of mcws_boundary's orthant method, as its flags.
struct OrthantSettings {
  std::optional<double> radius, auto_radius, outer_radius, min_gap, hull_depth;
  std::optional<int> adaptive;
  int threads{0};
};

std::shared_ptr<Filter> orthantFilter(BoundaryPlane plane, const OrthantSettings& s) {
  if (!!s.radius + !!s.auto_radius + !!s.adaptive > 1) {
    throw UsageError("give at most one of radius, auto_radius, adaptive");
  }
  if (plane == BoundaryPlane::k3D && s.hull_depth) {
    throw UsageError("hull_depth works in a plane: give plane 'xy', 'xz' or 'yz'");
  }
  auto filter = std::make_shared<Filter>(true);
  filter->setPlane(plane);
  if (s.adaptive) {
    if (*s.adaptive < 1 || *s.adaptive > 1000) {
      throw UsageError("adaptive: " + std::to_string(*s.adaptive) + " is not in 1 .. 1000");
    }
    filter->setAdaptiveRadius(*s.adaptive, Filter::kRecommendedScale);
  }
  for (const auto& [name, value] : {std::pair{"radius", s.radius},
                                    {"auto_radius", s.auto_radius},
                                    {"outer_radius", s.outer_radius}}) {
    if (value && !(*value > 0.0 && std::isfinite(*value))) {
      throw UsageError(std::string(name) + ": " + number(*value) + " is not a positive number");
    }
  }
  if (s.auto_radius) filter->setAutoRadius(*s.auto_radius);
  if (s.radius) filter->setRadiusSearch(*s.radius);
  if (s.outer_radius) filter->setOuterRadius(*s.outer_radius);
  if (s.min_gap) {
    if (!(*s.min_gap >= 90.0 && *s.min_gap < 180.0)) {
      throw UsageError("min_gap: " + number(*s.min_gap) + " is not in [90, 180) deg");
    }
    filter->setMinimumGap(*s.min_gap * M_PI / 180.0);
  }
  if (s.hull_depth) {
    const double depth = *s.hull_depth;
    if (depth != 0.0 && !(depth >= 0.1 && depth <= 10.0)) {
      throw UsageError("hull_depth: " + number(depth) +
                       " is not 0 (off) or in [0.1, 10] local spacings");
    }
    filter->setHullDepth(depth);
  }
  filter->setNumberOfThreads(threadCount(s.threads));
  return filter;
}

py::array boundaryMask(const FloatRows& xyz, const std::optional<std::string>& plane_name,
                       const OrthantSettings& settings) {
  const BoundaryPlane plane = planeOf(plane_name);
  const std::shared_ptr<Filter> filter = orthantFilter(plane, settings);
  const io::WorkspaceCloud::Ptr cloud = cloudOf(xyz);
  pcl::Indices kept;
  {
    py::gil_scoped_release release;
    const bool spacing = settings.radius || settings.auto_radius || settings.outer_radius;
    const CloudSummary region = checkedRegion(*cloud, plane, spacing);
    BoundarySettings ranges_for;
    ranges_for.plane = plane;
    ranges_for.adaptive_neighbours = filter->getAdaptiveNeighbours();
    ranges_for.radius = settings.radius.value_or(0.0);
    ranges_for.auto_radius_factor = settings.auto_radius.value_or(0.0);
    const BoundarySettingRanges ranges = boundarySettingRanges(region, ranges_for);
    if (settings.adaptive) requireWithin("adaptive", *settings.adaptive, ranges.adaptive);
    const std::pair<const char*, std::optional<double>> lengths[] = {
        {"radius", settings.radius},
        {"auto_radius", settings.auto_radius},
        {"outer_radius", settings.outer_radius}};
    const std::optional<SettingRange>* length_ranges[] = {&ranges.radius, &ranges.auto_radius,
                                                          &ranges.outer_radius};
    for (int i = 0; i < 3; ++i) {
      if (lengths[i].second && *length_ranges[i]) {
        requireWithin(lengths[i].first, *lengths[i].second, **length_ranges[i]);
      }
    }
    filter->setInputCloud(cloud);
    filter->filter(kept);
  }
  py::array_t<bool> out(static_cast<py::ssize_t>(cloud->size()));
  bool* flags = out.mutable_data();
  std::fill(flags, flags + cloud->size(), false);
  for (const pcl::index_t i : kept) flags[i] = true;
  return out;
}

std::string measureJson(const FloatRows& xyz, const std::optional<std::string>& plane_name,
                        const std::optional<double>& alpha, const std::string& correction,
                        int threads, const std::optional<std::string>& length_unit) {
  const BoundaryPlane plane = planeOf(plane_name);
  MeasureOptions options = regionOptions(alpha, correction, threads);
  options.phase = [](const std::string&) { checkSignals(); };  // Ctrl-C between phases
  const ResultUnits units = resultUnits(length_unit);
  const io::WorkspaceCloud::Ptr cloud = cloudOf(xyz);
  py::gil_scoped_release release;
  checkedRegion(*cloud, plane, false);
  const int dimensions = boundaryDimensions(plane);
  const pcl::PointCloud<pcl::PointXYZ> region = projectedToPlane(*cloud, plane);
  const RegionMeasure measured =
      namingPoints([&] { return delaunayMeasure(region, dimensions, options); });
  nlohmann::json out = regionMeasureJson(measured, options, dimensions, units);
  out["plane"] = boundaryPlaneName(plane);
  out["method"] = "delaunay";
  out["length_unit"] = units.lengthName();
  return out.dump();
}

}  // namespace

void bindWorkspace(py::module_& m) {
  m.def(
      "_boundary",
      [](const FloatRows& xyz, const std::optional<std::string>& plane,
         std::optional<double> radius, std::optional<double> auto_radius,
         std::optional<int> adaptive, std::optional<double> outer_radius,
         std::optional<double> min_gap, std::optional<double> hull_depth, int threads) {
        return boundaryMask(
            xyz, plane,
            {radius, auto_radius, outer_radius, min_gap, hull_depth, adaptive, threads});
      },
      "mcws.boundary's C++ part: the orthant boundary of float32 (N, 3) positions, as a mask.",
      py::arg("xyz"), py::arg("plane").none(true), py::arg("radius").none(true),
      py::arg("auto_radius").none(true), py::arg("adaptive").none(true),
      py::arg("outer_radius").none(true), py::arg("min_gap").none(true),
      py::arg("hull_depth").none(true), py::arg("threads"));
  m.def("_measure", &measureJson,
        "mcws.measure's C++ part: mcws_measure's JSON for float32 (N, 3) positions.",
        py::arg("xyz"), py::arg("plane").none(true), py::arg("alpha").none(true),
        py::arg("correction"), py::arg("threads"), py::arg("length_unit").none(true));
}

}  // namespace mcws::python
