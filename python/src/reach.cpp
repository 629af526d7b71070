// mcws.reach_map and mcws.ReachMap: reachability maps (the library's reach module, as mcws_reach
// builds, writes and reads them), their voxels as NumPy arrays and queries.
#include <pybind11/stl.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "bindings.h"
#include "loaded_robot.h"
#include "mcws/collision/collision_checker.h"
#include "mcws/io/atomic_file.h"
#include "mcws/io/pcd_stream_writer.h"
#include "mcws/reach/reach_map.h"
#include "mcws/reach/reach_plot.h"
#include "mcws/reach/reach_report.h"
#include "mcws/sampling/sample_report.h"
#include "mcws/sampling/sampler.h"
#include "reach_map_result.h"
#include "reach_query.h"
#include "sample_array.h"

namespace mcws::python {

ReachGrid mapGrid(const MapArguments& a) {
  ReachGrid grid;
  grid.resolution = a.resolution;
  grid.directions = a.orientations;
  grid.rolls = a.rolls;
  if (!(a.resolution > 0.0 && std::isfinite(a.resolution))) {
    throw UsageError("resolution: " + py::str(py::float_(a.resolution)).cast<std::string>() +
                     " is not a positive length");
  }
  for (const auto& [name, value] :
       {std::pair{"orientations", a.orientations}, {"rolls", a.rolls}}) {
    if (value < 1 || value > 65536) {
      throw UsageError(std::string(name) + ": " + std::to_string(value) + " is not in 1 .. 65536");
    }
  }
  asUsageError("orientations", [&] { grid.check(); });
  return grid;
}

ReachSampling mapSampling(const Robot& robot, const MapArguments& a,
                          const CollisionChecker* checker) {
  if (a.samples < 1) throw UsageError("samples: " + std::to_string(a.samples) + " is not >= 1");
  ReachSampling sampling;
  sampling.samples = static_cast<std::uint64_t>(a.samples);
  sampling.seed = nonNegative(a.seed, "seed");
  sampling.threads = threadCount(a.threads);
  sampling.manipulability = a.manipulability;
  if (!a.manipulability && (a.quality_task || a.length)) {
    throw UsageError("quality_task and length need manipulability=True");
  }
  sampling.quality = qualityOptions(robot, a.quality_task, a.length);
  sampling.collision = checker;
  return sampling;
}

std::unique_ptr<MapResult> buildMap(const LoadedRobot& loaded, const MapArguments& a,
                                    const CollisionChecker* checker, Checkpoint& checkpoint) {
  const Robot& robot = loaded.robot;
  const ReachGrid grid = mapGrid(a);
  const ReachSampling sampling = mapSampling(robot, a, checker);
  const io::CloudProvenance provenance = robotProvenance(robot);
  auto result = std::make_unique<MapResult>();
  {
    py::gil_scoped_release release;
    // Between chunks of samples, on the calling thread.
    try {
      result->map = buildReachMap(robot, grid, sampling, std::ref(checkpoint));
    } catch (const UsageError&) {
      throw;
    } catch (const Error& e) {  // a point beyond the grid's range: "give a coarser --resolution"
      std::string text = e.what();
      const std::string flag = "--resolution";
      const std::size_t at = text.rfind(flag);
      if (at == std::string::npos) throw;
      text.replace(at, flag.size(), "resolution");
      throw UsageError("resolution: " + text);
    }
  }
  if (result->map.size() == 0) throw Error("no sample counted: every sample collides");
  nlohmann::json summary =
      mapSummary(robot, grid, sampling, sampling.samples, result->map, checker != nullptr);
  result->header = mapFileHeader(robot, provenance.file, provenance.sha256, summary);
  addRobotNames(summary, robot);  // after the header, as mcws_reach --json
  result->summary = summary.dump();
  result->source = "reach_map()";
  return result;
}

namespace {

std::unique_ptr<MapResult> loadMap(const py::object& path_value) {
  const std::string path = pathArgument(path_value);
  auto result = std::make_unique<MapResult>();
  py::gil_scoped_release release;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the reachability map");
  std::string header;
  result->map = ReachMap::read(in, path, &header);
  // The header read holds the grid's members too, which write() adds again: the rest is what
  // mapFileHeader() gave (a compact JSON object, sorted: the same text again).
  nlohmann::json members = nlohmann::json::parse(header, nullptr, false);
  if (!members.is_object()) throw Error(path + ": the reachability map's header is not JSON");
  for (const char* grid : {"resolution", "directions", "rolls", "voxels", "words"}) {
    members.erase(grid);
  }
  result->header = members.dump();
  result->summary = "null";
  result->source = path;
  return result;
}

/// The file's bytes: the map and its header, as mcws_reach --map writes them.
void saveMap(const MapResult& r, const py::object& path_value) {
  const std::string path = pathArgument(path_value);
  py::gil_scoped_release release;
  std::ostringstream bytes;
  r.map.write(bytes, r.header);
  io::writeWholeFile(path, bytes.str());
}

/// A text member of the map file's header ("robot", "length_unit", ...), "" when it has none.
std::string headerText(const MapResult& r, const char* key) {
  const nlohmann::json h = nlohmann::json::parse(r.header, nullptr, false);
  return h.is_object() && h.contains(key) && h[key].is_string() ? h[key].get<std::string>()
                                                                : std::string();
}

/// mcws_reach --halfcut (`histogram` false) or --histogram: a PNG titled with the robot's name
/// the header records, lengths in its unit.
void savePicture(const MapResult& r, const py::object& path_value, bool histogram) {
  const std::string path = pathArgument(path_value);
  const std::string robot = headerText(r, "robot"), unit = headerText(r, "length_unit");
  py::gil_scoped_release release;
  io::writeWholeFile(path, histogram ? renderReachabilityHistogramPng(r.map, robot)
                                     : renderHalfCutPng(r.map, 0.0, robot, unit));
}

/// The voxel centres with reachability, manipulability and count, as mcws_reach --output writes
/// them; the robot the header names recorded as the tool records it.
void savePoints(const MapResult& r, const py::object& path_value) {
  const std::string path = pathArgument(path_value);
  const auto text = [&](const char* key) { return headerText(r, key); };
  const io::CloudProvenance provenance(text("robot"), text("robot_file"), text("robot_sha256"),
                                       text("length_unit"));
  py::gil_scoped_release release;
  const auto points = reachPoints(r.map);
  io::PcdStreamWriter<ReachPoint> cloud(path, points.size(), io::PcdFormat::kBinary, provenance);
  cloud.write(points.data(), points.size());
  cloud.commit();
}

py::array voxelArray(const ReachMap& map, bool centres) {
  const std::size_t n = map.size();
  std::vector<double> values;
  values.reserve(3 * n);
  for (std::size_t v = 0; v < n; ++v) {
    const Eigen::Vector3i index = map.voxel(v);
    const Eigen::Vector3d value = centres ? map.voxelCentre(index) : index.cast<double>();
    values.insert(values.end(), value.data(), value.data() + 3);
  }
  py::array out = ownedDoubles(std::move(values), {static_cast<py::ssize_t>(n), 3});
  return centres ? out : out.attr("astype")("int32");
}

template <typename T, typename Value>
py::array_t<T> perVoxel(const ReachMap& map, Value&& value) {
  py::array_t<T> out(static_cast<py::ssize_t>(map.size()));
  T* data = out.mutable_data();
  for (std::size_t v = 0; v < map.size(); ++v) data[v] = static_cast<T>(value(v));
  return out;
}

}  // namespace

void bindReach(py::module_& m) {
  py::class_<MapResult>(m, "_ReachMap", "mcws.ReachMap's C++ part (see mcws.ReachMap).")
      .def_static("load", &loadMap, py::arg("path"))
      .def("save", &saveMap, py::arg("path"))
      .def("save_points", &savePoints, py::arg("path"))
      .def(
          "save_halfcut",
          [](const MapResult& r, const py::object& path) { savePicture(r, path, false); },
          py::arg("path"))
      .def(
          "save_histogram",
          [](const MapResult& r, const py::object& path) { savePicture(r, path, true); },
          py::arg("path"))
      .def("header", [](const MapResult& r) { return r.header; })
      .def("summary", [](const MapResult& r) { return r.summary; })
      .def("grid",
           [](const MapResult& r) {
             const ReachGrid& g = r.map.grid();
             return py::make_tuple(g.resolution, g.directions, g.rolls);
           })
      .def("__len__", [](const MapResult& r) { return r.map.size(); })
      .def("voxels", [](const MapResult& r) { return voxelArray(r.map, false); })
      .def("centres", [](const MapResult& r) { return voxelArray(r.map, true); })
      .def("reachability",
           [](const MapResult& r) {
             return perVoxel<double>(r.map, [&](std::size_t v) { return r.map.reachability(v); });
           })
      .def("manipulability",
           [](const MapResult& r) {
             return perVoxel<float>(r.map,
                                    [&](std::size_t v) { return r.map.bestManipulability(v); });
           })
      .def("count",
           [](const MapResult& r) {
             return perVoxel<std::uint64_t>(r.map, [&](std::size_t v) { return r.map.count(v); });
           })
      .def(
          "query",
          [](const MapResult& r, const py::handle& points, const py::handle& directions) {
            return queryMap(r.map, points, directions);
          },
          py::arg("points"), py::arg("directions").none(true));
  m.def(
      "_reach_map",
      [](const LoadedRobot& robot, double resolution, std::int64_t samples, std::int64_t seed,
         int threads, int orientations, int rolls, bool manipulability, bool collision,
         const std::optional<std::string>& quality_task, const std::optional<double>& length,
         const py::object& progress) {
        Checkpoint checkpoint(progress, "mcws.reach_map", "samples");
        const std::unique_ptr<CollisionChecker> checker =
            collision ? collisionChecker(robot) : nullptr;
        return buildMap(robot,
                        {resolution, samples, seed, threads, orientations, rolls, manipulability,
                         quality_task, length},
                        checker.get(), checkpoint);
      },
      "mcws.reach_map's C++ part.", py::arg("robot"), py::arg("resolution"), py::arg("samples"),
      py::arg("seed"), py::arg("threads"), py::arg("orientations"), py::arg("rolls"),
      py::arg("manipulability"), py::arg("collision"), py::arg("quality_task").none(true),
      py::arg("length").none(true), py::arg("progress"));
}

}  // namespace mcws::python
