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

std::string measureJson(const FloatRows& xyz, const std::optional<std::string>& plane_name,
                        const std::optional<double>& alpha, const std::string& correction,
                        int threads, const std::optional<std::string>& length_unit,
                        const LoadedRobot* robot, const py::object& provenance) {
  const BoundaryPlane plane = planeOf(plane_name);
  MeasureOptions options = regionOptions(alpha, correction, threads);
  options.phase = [](const std::string&) { checkSignals(); };  // Ctrl-C between phases
  options.cancel_check = signalCheck();  // and within them (the library's loops and insertion)
  const std::optional<io::CloudProvenance> recorded = pointsRecord(robot, provenance);
  const ResultUnits units = resultUnits(length_unit, recorded);
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
  addRecordedRobotNames(out, recorded);
  return out.dump();
}

}  // namespace

void bindWorkspace(py::module_& m) {
  m.def("_measure", &measureJson,
        "mcws.measure's C++ part: mcws_measure's JSON for float32 (N, 3) positions.",
        py::arg("xyz"), py::arg("plane").none(true), py::arg("alpha").none(true),
        py::arg("correction"), py::arg("threads"), py::arg("length_unit").none(true),
        py::arg("robot").none(true), py::arg("provenance").none(true));
}

}  // namespace mcws::python
