// mcws.envelope's C++ part: the workspace envelope mesh (the library's workspace module, as
// mcws_envelope makes it), its files and its datasheet drawing's numbers.
#include <pybind11/stl.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <utility>

#include "bindings.h"
#include "loaded_robot.h"
#include "mcws/io/atomic_file.h"
#include "mcws/sampling/sample_report.h"
#include "mcws/workspace/drawing.h"
#include "mcws/workspace/envelope.h"
#include "mcws/workspace/envelope_report.h"
#include "positions.h"

namespace mcws::python {

namespace {

/// An envelope with what it was made from: the region settings, the units of its numbers and the
/// samples (the drawing's top view is theirs).
struct EnvelopeResult {
  Envelope envelope;
  MeasureOptions options;
  ResultUnits units;
  pcl::PointCloud<pcl::PointXYZ> points;
  std::optional<io::CloudProvenance> recorded;  ///< the robot of the points (pointsRecord())
};

std::unique_ptr<EnvelopeResult> makeEnvelope(const FloatRows& xyz,
                                             const std::optional<double>& alpha,
                                             const std::string& correction, int threads,
                                             const std::optional<std::string>& length_unit,
                                             const LoadedRobot* robot,
                                             const py::object& provenance) {
  MeasureOptions options = regionOptions(alpha, correction, threads);
  std::optional<io::CloudProvenance> recorded = pointsRecord(robot, provenance);
  const ResultUnits units = resultUnits(length_unit, recorded);
  const io::WorkspaceCloud::Ptr cloud = cloudOf(xyz);
  py::gil_scoped_release release;
  checkedRegion(*cloud, BoundaryPlane::k3D, false,
                "envelope() meshes a volume (measure() and boundary() take a plane)");
  pcl::PointCloud<pcl::PointXYZ> points = projectedToPlane(*cloud, BoundaryPlane::k3D);
  options.phase = [](const std::string&) { checkSignals(); };  // between the envelope's phases
  options.cancel_check = signalCheck();  // and within its triangulation and surface steps
  Envelope envelope = namingPoints([&] { return workspaceEnvelope(points, options); });
  options.phase = nullptr;
  options.cancel_check = nullptr;
  return std::make_unique<EnvelopeResult>(
      EnvelopeResult{std::move(envelope), options, units, std::move(points), std::move(recorded)});
}

py::array vertexArray(const EnvelopeResult& result) {
  const auto& vertices = result.envelope.mesh.vertices;
  std::vector<double> values;
  values.reserve(3 * vertices.size());
  for (const Eigen::Vector3d& v : vertices) values.insert(values.end(), v.data(), v.data() + 3);
  return ownedDoubles(std::move(values), {static_cast<py::ssize_t>(vertices.size()), 3});
}

py::array triangleArray(const EnvelopeResult& result) {
  const auto& triangles = result.envelope.mesh.triangles;
  py::array_t<std::uint32_t> out({static_cast<py::ssize_t>(triangles.size()), py::ssize_t{3}});
  std::uint32_t* data = out.mutable_data();
  for (const auto& t : triangles) data = std::copy(t.begin(), t.end(), data);
  return out;
}

/// The drawing's numbers at `azimuth` [deg], as mcws_envelope --json's "drawing", with "units".
std::string drawingJson(const EnvelopeResult& result, double azimuth) {
  if (!std::isfinite(azimuth)) throw UsageError("azimuth: " + number(azimuth) + " is not finite");
  py::gil_scoped_release release;
  const EnvelopeDrawing drawing = asUsageError("azimuth", [&] {
    return envelopeDrawing(result.envelope.mesh, result.points, azimuth * M_PI / 180.0);
  });
  nlohmann::json out;
  for (const ReportValue& value : drawingValues(drawing, result.units)) {
    out[value.name] = value.value;
    out["units"][value.name] = value.unit;
  }
  return out.dump();
}

/// The pictures' title and frame, as mcws_envelope names them: the robot and its tip when the
/// points' robot is known, else the file name of `source` (the tool's --input) and no frame.
std::pair<std::string, std::string> pictureNames(const EnvelopeResult& r,
                                                 const std::string& source) {
  if (r.recorded) return {r.recorded->robot, io::recordedTip(*r.recorded).value_or("")};
  return {std::filesystem::path(source).filename().string(), ""};
}

/// mcws_envelope --drawing: the datasheet drawing at `azimuth` [deg], PNG or SVG by the path's
/// extension.
void saveDrawing(const EnvelopeResult& r, const py::object& path, double azimuth,
                 const std::string& source) {
  const std::string file = pathArgument(path);
  if (!std::isfinite(azimuth)) throw UsageError("azimuth: " + number(azimuth) + " is not finite");
  const DrawingFormat format = asUsageError("path", [&] { return drawingFormatOf(file); });
  const auto [title, tip] = pictureNames(r, source);
  py::gil_scoped_release release;
  const EnvelopeDrawing drawing = asUsageError("azimuth", [&] {
    return envelopeDrawing(r.envelope.mesh, r.points, azimuth * M_PI / 180.0);
  });
  io::writeWholeFile(file,
                     renderEnvelopeDrawing(drawing, format, title, r.units.lengthName(), tip));
}

/// mcws_envelope --plot: the mesh shaded from two views, a PNG.
void savePlot(const EnvelopeResult& r, const py::object& path, const std::string& source) {
  const std::string file = pathArgument(path);
  const auto [title, tip] = pictureNames(r, source);
  py::gil_scoped_release release;
  io::writeWholeFile(file, renderEnvelopePng(r.envelope.mesh, title, r.units.lengthName(), tip));
}

constexpr char kSaveDoc[] =
    R"(Writes the mesh as mcws_envelope --output does: binary PLY, binary STL or ASCII VTK by the
extension of path (.ply, .stl, .vtk), lengths in the positions' unit; the file appears whole or
not at all. source names the cloud in the file's comment ("mcws_envelope of <source>, lengths in
<unit>", or of "robot '<robot>', tip <tip>, from <source>" when robot or provenance was given):
the tool's --input path gives the tool's bytes.

Raises mcws.Error naming the file for another extension or when it cannot be written.)";

}  // namespace

void bindEnvelope(py::module_& m) {
  py::class_<EnvelopeResult>(m, "_Envelope", "mcws.envelope's C++ part (see mcws.Envelope).")
      .def("summary",
           [](const EnvelopeResult& r) {
             nlohmann::json out = envelopeSummary(r.envelope, r.options, std::nullopt, r.units);
             addRecordedRobotNames(out, r.recorded);
             return out.dump();
           })
      .def("vertices", &vertexArray)
      .def("triangles", &triangleArray)
      .def(
          "save",
          [](const EnvelopeResult& r, const py::object& path, const std::string& source) {
            const std::string file = pathArgument(path);
            py::gil_scoped_release release;
            saveSurface(r.envelope.mesh, file, io::describeCloud(source, r.recorded),
                        r.units.lengthName());
          },
          kSaveDoc, py::arg("path"), py::arg("source"))
      .def("drawing", &drawingJson, py::arg("azimuth"))
      .def("save_drawing", &saveDrawing, py::arg("path"), py::arg("azimuth"), py::arg("source"))
      .def("save_plot", &savePlot, py::arg("path"), py::arg("source"));
  m.def("_envelope", &makeEnvelope,
        "mcws.envelope's C++ part: the envelope of float32 (N, 3) positions.", py::arg("xyz"),
        py::arg("alpha").none(true), py::arg("correction"), py::arg("threads"),
        py::arg("length_unit").none(true), py::arg("robot").none(true),
        py::arg("provenance").none(true));
}

}  // namespace mcws::python
