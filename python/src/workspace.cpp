// mcws.measure's C++ part, the Delaunay area or volume (the library's workspace module), called as
// mcws_measure calls it, and what the region bindings share (positions.h): positions handed over as
// float32 (N, 3), as a PCD file holds them, checked as the tools check their input.
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <sstream>

#include "bindings.h"
#include "loaded_robot.h"
#include "mcws/filters/boundary_geometry.h"
#include "mcws/io/cloud_io.h"
#include "mcws/sampling/sample_report.h"
#include "mcws/sampling/sampler.h"
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
CloudSummary checkedRegion(const io::WorkspaceCloud& cloud, BoundaryPlane plane, bool spacing,
                           const std::string& flat_hint) {
  const CloudSummary region =
      summarizeCloud(cloud, plane, spacing ? SummaryDetail::kSpacing : SummaryDetail::kCounts);
  requireRegionPoints(region, kPoints);
  if (plane == BoundaryPlane::k3D) requireVolumeHinted(cloud, kPoints, flat_hint);
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

ResultUnits resultUnits(const std::optional<std::string>& length_unit,
                        const std::optional<io::CloudProvenance>& recorded) {
  if (!length_unit) {
    // A record's unit was checked when it was read (one of m, cm, mm).
    if (recorded) return ResultUnits(lengthUnitNamed(recorded->length_unit), std::nullopt);
    return ResultUnits(std::nullopt, std::nullopt);
  }
  const std::optional<LengthUnit> unit = lengthUnitNamed(*length_unit);
  if (!unit) throw UsageError("length_unit: '" + *length_unit + "' is not one of m, cm, mm");
  if (recorded && recorded->length_unit != *length_unit) {
    throw UsageError("length_unit: '" + *length_unit + "' is not '" + recorded->length_unit +
                     "', the unit of the points' robot (robot or provenance)");
  }
  return ResultUnits(unit, std::nullopt);
}

std::optional<io::CloudProvenance> pointsRecord(const LoadedRobot* robot,
                                                const py::object& provenance) {
  if (!provenance.is_none()) return provenanceFromDict(provenance.cast<py::dict>());
  if (!robot) return std::nullopt;
  io::CloudProvenance recorded = robotProvenance(robot->robot);
  recorded.sampling = io::SamplingRecord{};  // point "tool", no collision labels, no joint fixed
  return recorded;
}

namespace {

/// measure()'s settings beyond the region's (mcws_measure's --method, --leave-one-out,
/// --triangulate, --boundary, --column-width).
struct MeasureChoices {
  std::string method{"delaunay"};
  std::optional<std::string> leave_one_out, triangulate;
  std::optional<FloatRows> boundary;  ///< the boundary points, for the column method
  std::optional<double> column_width;
};

/// `text` if it is one of `choices`. \throws UsageError "name: 'x' is not a or b" otherwise.
std::string choice(const std::string& text, const char* name, const char* first,
                   const char* second) {
  if (text == first || text == second) return text;
  throw UsageError(std::string(name) + ": '" + text + "' is not " + first + " or " + second);
}

/// The choices checked as mcws_measure checks its flags, into `options`.
void applyChoices(const MeasureChoices& c, BoundaryPlane plane, const std::optional<double>& alpha,
                  const std::string& correction, int threads, MeasureOptions& options) {
  choice(c.method, "method", "delaunay", "column");
  if (c.method == "column" && (plane == BoundaryPlane::k3D || !c.boundary))
    throw UsageError("method 'column' measures an area: give plane and boundary");
  if (c.boundary && plane == BoundaryPlane::k3D)
    throw UsageError("boundary: the column cross-check measures an area: give plane");
  if (c.column_width && !c.boundary)
    throw UsageError("column_width applies to the column method: give boundary");
  if (c.method == "column") {
    const std::pair<const char*, bool> given[] = {{"alpha", alpha.has_value()},
                                                  {"correction", correction != "efron"},
                                                  {"leave_one_out", c.leave_one_out.has_value()},
                                                  {"threads", threads != 0},
                                                  {"triangulate", c.triangulate.has_value()}};
    for (const auto& [name, is_given] : given) {
      if (is_given) throw UsageError(std::string(name) + " does not apply to method 'column'");
    }
  }
  options.leave_one_out =
      choice(c.leave_one_out.value_or("star"), "leave_one_out", "star", "reinsert") == "star"
          ? LeaveOneOut::kStar
          : LeaveOneOut::kRemoveAndReinsert;
  options.shell = choice(c.triangulate.value_or("shell"), "triangulate", "shell", "all") == "shell";
  if (c.column_width && !std::isfinite(*c.column_width)) {
    throw UsageError("column_width: " + number(*c.column_width) + " is not a finite length");
  }
  if (c.column_width && *c.column_width < 0.0) {
    throw UsageError("column_width: " + number(*c.column_width) + " is less than 0");
  }
}

/// The column method's area of the boundary points, checked as mcws_measure checks --boundary
/// (points of the cloud, a region) and --column-width (0 or between a tenth of the cloud's mean
/// spacing and its extent).
ColumnArea columnOf(const MeasureChoices& c, const io::WorkspaceCloud& cloud,
                    const CloudSummary& summary, BoundaryPlane plane) {
  const double width = c.column_width.value_or(0.0);
  if (width != 0.0) {
    const LengthRange length = parameterLengths(summary);
    if (!(width >= length.min && width <= length.max)) {
      throw UsageError("column_width: " + number(width) + " is not 0 or in [" + number(length.min) +
                       ", " + number(length.max) +
                       "] [length unit] (a tenth of the points' mean spacing " +
                       number(*summary.spacing) + " to their extent)");
    }
  }
  const io::WorkspaceCloud::Ptr boundary = cloudOf(*c.boundary);
  if (const std::optional<std::size_t> i = firstPointNotIn(*boundary, cloud)) {
    const auto& p = (*boundary)[*i];
    throw Error("boundary: point " + std::to_string(*i) + " (" + number(p.x) + ", " + number(p.y) +
                ", " + number(p.z) + ") is not one of points: a boundary of " + "another cloud?");
  }
  requireRegionPoints(summarizeCloud(*boundary, plane), "boundary");
  return columnArea(projectedToPlane(*boundary, plane), width);
}

std::string measureJson(const FloatRows& xyz, const std::optional<std::string>& plane_name,
                        const std::optional<double>& alpha, const std::string& correction,
                        int threads, const std::optional<std::string>& length_unit,
                        const LoadedRobot* robot, const py::object& provenance,
                        const MeasureChoices& choices) {
  const BoundaryPlane plane = planeOf(plane_name);
  MeasureOptions options = regionOptions(alpha, correction, threads);
  applyChoices(choices, plane, alpha, correction, threads, options);
  options.phase = [](const std::string&) { checkSignals(); };  // Ctrl-C between phases
  options.cancel_check = signalCheck();  // and within them (the library's loops and insertion)
  const std::optional<io::CloudProvenance> recorded = pointsRecord(robot, provenance);
  const ResultUnits units = resultUnits(length_unit, recorded);
  const io::WorkspaceCloud::Ptr cloud = cloudOf(xyz);
  py::gil_scoped_release release;
  const CloudSummary summary = checkedRegion(*cloud, plane, choices.column_width.value_or(0) > 0);
  std::optional<ColumnArea> column;
  if (choices.boundary) column = columnOf(choices, *cloud, summary, plane);
  const int dimensions = boundaryDimensions(plane);
  nlohmann::json out;
  if (choices.method == "delaunay") {
    const pcl::PointCloud<pcl::PointXYZ> region = projectedToPlane(*cloud, plane);
    const RegionMeasure measured =
        namingPoints([&] { return delaunayMeasure(region, dimensions, options); });
    out = regionMeasureJson(measured, options, dimensions, units);
    if (column) addColumnCrossCheck(out, *column, units);
  } else {
    out = columnAreaJson(*column, units);
  }
  out["plane"] = boundaryPlaneName(plane);
  out["method"] = choices.method;
  out["length_unit"] = units.lengthName();
  addRecordedRobotNames(out, recorded);
  return out.dump();
}

}  // namespace

void bindWorkspace(py::module_& m) {
  m.def(
      "_measure",
      [](const FloatRows& xyz, const std::optional<std::string>& plane,
         const std::optional<double>& alpha, const std::string& correction, int threads,
         const std::optional<std::string>& length_unit, const LoadedRobot* robot,
         const py::object& provenance, const std::string& method,
         const std::optional<std::string>& leave_one_out,
         const std::optional<std::string>& triangulate, const std::optional<FloatRows>& boundary,
         const std::optional<double>& column_width) {
        return measureJson(xyz, plane, alpha, correction, threads, length_unit, robot, provenance,
                           {method, leave_one_out, triangulate, boundary, column_width});
      },
      "mcws.measure's C++ part: mcws_measure's JSON for float32 (N, 3) positions.", py::arg("xyz"),
      py::arg("plane").none(true), py::arg("alpha").none(true), py::arg("correction"),
      py::arg("threads"), py::arg("length_unit").none(true), py::arg("robot").none(true),
      py::arg("provenance").none(true), py::arg("method"), py::arg("leave_one_out").none(true),
      py::arg("triangulate").none(true), py::arg("boundary").none(true),
      py::arg("column_width").none(true));
}

}  // namespace mcws::python
