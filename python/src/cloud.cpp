// mcws.read_pcd, mcws.read_provenance and the writer behind mcws.write_pcd: PCD files through the
// library's checked reader (mcws::io::readPcd) and streaming writer (mcws::io::PcdStreamWriter),
// the robot a cloud comes from recorded in its header.
#include <pybind11/stl.h>

#include <cstring>
#include <optional>
#include <type_traits>

#include "bindings.h"
#include "loaded_robot.h"
#include "mcws/io/cloud_io.h"
#include "mcws/io/pcd_stream_writer.h"
#include "mcws/io/provenance.h"
#include "mcws/sampling/sampler.h"
#include "point_layout.h"
#include "positions.h"

namespace mcws::python {

namespace {

/// A structured dtype of a file's fields at their offsets in its records (PCL's padding fields
/// "_" left out).
py::dtype fileDtype(const pcl::PCLPointCloud2& blob, const std::string& path) {
  py::list names, formats, offsets;
  for (const pcl::PCLPointField& field : blob.fields) {
    if (field.name == "_") continue;
    std::string format = numpyFormat(field.datatype);
    if (format.empty()) {
      throw Error("'" + path + "': field '" + field.name + "' has a type NumPy is not given");
    }
    if (field.count > 1) format = "(" + std::to_string(field.count) + ",)" + format;
    names.append(field.name);
    formats.append(format);
    offsets.append(field.offset);
  }
  try {
    return py::dtype(names, formats, offsets, blob.point_step);
  } catch (const py::error_already_set& e) {  // a name twice, overlapping fields
    throw Error("'" + path + "': its fields make no NumPy record: " + e.what());
  }
}

py::array readPcdArray(const py::object& path_value) {
  const std::string path = pathArgument(path_value);
  auto blob = std::make_unique<pcl::PCLPointCloud2>();
  {
    py::gil_scoped_release release;
    *blob = io::readPcd(path);
  }
  const py::dtype dtype = fileDtype(*blob, path);
  const auto points = static_cast<py::ssize_t>(blob->width) * blob->height;
  const void* data = blob->data.data();
  const auto step = static_cast<py::ssize_t>(blob->point_step);
  return ownedArray(std::move(blob), dtype, {points}, {step}, data);
}

py::dict samplingDict(const io::SamplingRecord& sampling) {
  py::dict fix;
  for (const auto& [name, value] : sampling.fixed) fix[py::str(name)] = value;
  py::dict out;
  out["point"] = sampling.point;
  out["collision"] = sampling.collision;
  out["fix"] = fix;
  return out;
}

py::object provenanceDict(const std::optional<io::CloudProvenance>& provenance) {
  if (!provenance) return py::none();
  py::dict out;
  out["robot"] = provenance->robot;
  out["file"] = provenance->file;
  out["sha256"] = provenance->sha256;
  out["length_unit"] = provenance->length_unit;
  if (!provenance->tip_link.empty()) {  // a URDF robot's chain
    out["base_link"] = provenance->base_link;
    out["tip_link"] = provenance->tip_link;
  }
  if (provenance->sampling) out["sampling"] = samplingDict(*provenance->sampling);
  if (provenance->input) {
    py::dict input;
    input["points"] = provenance->input->points;
    input["sha256"] = provenance->input->sha256;
    input["boundary_points"] = provenance->input->boundary_points;
    out["input"] = input;
  }
  return out;
}

/// Writes `points` (records of pointDtype<PointT>(joints)) as binary PCD, q beyond the first
/// `joints` written as 0 whatever the hidden bytes hold.
template <typename PointT>
void writePoints(const std::string& path, const py::array& points, int joints,
                 const std::optional<io::CloudProvenance>& provenance) {
  const auto n = static_cast<std::size_t>(points.shape(0));
  const auto* records = static_cast<const char*>(points.data());
  py::gil_scoped_release release;
  io::PcdStreamWriter<PointT> writer(path, n, io::PcdFormat::kBinary, provenance);
  constexpr std::size_t kPiece = std::size_t{1} << 16;
  std::vector<PointT, Eigen::aligned_allocator<PointT>> piece;
  for (std::size_t begin = 0; begin < n; begin += kPiece) {
    piece.resize(std::min(kPiece, n - begin));
    std::memcpy(static_cast<void*>(piece.data()), records + begin * sizeof(PointT),
                piece.size() * sizeof(PointT));
    for (PointT& point : piece) std::fill(point.q + joints, point.q + kMaxJoints, 0.0f);
    writer.write(piece.data(), piece.size());
  }
  writer.commit();
}

/// The record of `robot` for points drawn as `sampling` says (None: sample()'s defaults, point
/// "tool", no collision labels, no joint fixed), checked as mcws_sample checks its flags.
io::CloudProvenance robotRecord(const LoadedRobot& robot, const py::object& sampling) {
  io::CloudProvenance provenance = robotProvenance(robot.robot);
  provenance.sampling = io::SamplingRecord{};
  if (sampling.is_none()) return provenance;
  try {
    provenance.sampling = samplingFromDict(sampling, "sampling", true);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  if (provenance.sampling->point != "tool" && provenance.sampling->point != "flange") {
    throw UsageError("sampling.point: '" + provenance.sampling->point +
                     "' is not one of tool, flange");
  }
  RobotSamplerOptions options;
  options.fixed = provenance.sampling->fixed;
  asUsageError("sampling.fix", [&] {
    const RobotSampler check(robot.robot, options);  // an unknown joint, a value off its limits
  });
  return asUsageError(
      "sampling", [&] { return io::parseProvenanceComment(io::provenanceComment(provenance)); });
}

void writePcdArray(const py::object& path_value, const py::array& points, bool quality, int joints,
                   const LoadedRobot* robot, const py::object& provenance_value,
                   const py::object& sampling) {
  const std::string path = pathArgument(path_value);
  const py::dtype layout =
      quality ? pointDtype<QualityPoint>(joints) : pointDtype<WorkspacePoint>(joints);
  if (points.ndim() != 1 || !points.dtype().equal(layout) ||
      !(points.flags() & py::array::c_style)) {
    throw UsageError("points: not a C-ordered 1-D array of the layout _point_dtype(" +
                     std::to_string(joints) + ", " + (quality ? "True" : "False") + ")");
  }
  if (points.shape(0) == 0) {  // as read_pcd() and the tools refuse a cloud without points
    throw UsageError("points: none given (a cloud file holds at least one point)");
  }
  if (!sampling.is_none() && !robot) {
    throw UsageError("sampling: give robot too (a provenance records its own sampling)");
  }
  std::optional<io::CloudProvenance> provenance;
  if (robot) provenance = robotRecord(*robot, sampling);
  if (!provenance_value.is_none()) {
    if (!py::isinstance<py::dict>(provenance_value)) {
      throw UsageError("provenance: give a dict as read_provenance() returns, or None");
    }
    provenance = provenanceFromDict(provenance_value);
  }
  if (quality) {
    writePoints<QualityPoint>(path, points, joints, provenance);
  } else {
    writePoints<WorkspacePoint>(path, points, joints, provenance);
  }
}

constexpr char kReadPcdDoc[] =
    R"(Reads a PCD file (ascii, binary or binary_compressed) through mcws's checked reader.

path: the file (str or os.PathLike).

Returns a NumPy structured array, one record per point, with the file's fields as they are (for
a cloud of mcws_sample: x y z [length unit, see read_provenance()], q1..q8 [rad | length unit],
label, and manipulability, inverse_condition when sampled with quality), viewing the data read
(no copy).

Raises mcws.Error naming the file (and the line) when it is missing, unreadable, not a PCD file
the reader accepts (the checks of mcws_boundary & co.), or holds no points.)";

constexpr char kReadProvenanceDoc[] =
    R"(The robot a cloud file records in its header (its "# mcws" line), or None.

Returns a dict: robot (name), file (the robot file's base name), sha256 (of the robot file),
length_unit (of the cloud's coordinates: "m", "cm", "mm"), and when recorded base_link and
tip_link (a URDF robot's chain: the points are the tip link's origin in the base link's frame),
sampling
({"point": "tool"|"flange", "collision": bool, "fix": {joint: value [rad | length unit]}}) and
input ({"points", "sha256", "boundary_points"} of a boundary's input cloud). None for clouds of
other tools and of sample_shape().

Raises mcws.Error naming the file as read_pcd() does for a bad header.)";

}  // namespace

namespace {

/// What a message calls a value: its repr and type, "'0.5' (str)".
std::string described(const py::handle& value) {
  return std::string(py::repr(value)) + " (" +
         py::type::of(value).attr("__name__").cast<std::string>() + ")";
}

/// dict[key] as T. \throws Error naming `where` + key for a missing key or a value that is not
/// `kind`.
template <typename T>
T entry(const py::dict& dict, const char* key, const std::string& where, const char* kind) {
  if (!dict.contains(key)) throw Error("no key '" + where + key + "'");
  const py::object value = dict[key];
  // A bool is an int to Python, but no count; a str no bool.
  const bool refused =
      (std::is_integral_v<T> && !std::is_same_v<T, bool> && py::isinstance<py::bool_>(value)) ||
      (std::is_same_v<T, std::string> && !py::isinstance<py::str>(value));
  try {
    if (!refused) return value.cast<T>();
  } catch (const py::cast_error&) {
  }
  throw Error(where + key + ": " + described(value) + " is not " + kind);
}

}  // namespace

io::SamplingRecord samplingFromDict(const py::handle& value, const std::string& where,
                                    bool defaults) {
  if (!py::isinstance<py::dict>(value)) {
    throw Error(where + ": " + described(value) + " is not a dict (point, collision, fix)");
  }
  const auto dict = py::reinterpret_borrow<py::dict>(value);
  const std::string at = where + ".";
  io::SamplingRecord record;
  if (!defaults || dict.contains("point"))
    record.point = entry<std::string>(dict, "point", at, "a str (tool or flange)");
  if (!defaults || dict.contains("collision"))
    record.collision = entry<bool>(dict, "collision", at, "a bool");
  if (!defaults || dict.contains("fix")) {
    if (!dict.contains("fix")) throw Error("no key '" + at + "fix'");
    const py::object fix = dict["fix"];
    if (!py::isinstance<py::dict>(fix)) {
      throw Error(at + "fix: " + described(fix) + " is not a dict joint name -> value");
    }
    for (const auto& [name, joint_value] : py::reinterpret_borrow<py::dict>(fix)) {
      if (!py::isinstance<py::str>(name)) {
        throw Error(at + "fix: joint name " + described(name) + " is not a str");
      }
      const std::string joint = name.cast<std::string>();
      const py::dict one;
      one[name] = joint_value;
      record.fixed.emplace_back(
          joint, entry<double>(one, joint.c_str(), at + "fix.", "a number [rad | length unit]"));
    }
  }
  for (const auto& [key, unused] : dict) {
    const std::string name = py::str(key);
    if (name != "point" && name != "collision" && name != "fix") {
      throw Error(at + name + ": not a key of a sampling record (point, collision, fix)");
    }
  }
  return record;
}

io::CloudProvenance provenanceFromDict(const py::dict& dict) {
  return asUsageError("provenance", [&] {
    const char* text = "a str";
    io::CloudProvenance provenance(entry<std::string>(dict, "robot", "", text),
                                   entry<std::string>(dict, "file", "", text),
                                   entry<std::string>(dict, "sha256", "", text),
                                   entry<std::string>(dict, "length_unit", "", text));
    if (dict.contains("base_link"))
      provenance.base_link = entry<std::string>(dict, "base_link", "", text);
    if (dict.contains("tip_link"))
      provenance.tip_link = entry<std::string>(dict, "tip_link", "", text);
    if (dict.contains("sampling") && !dict["sampling"].is_none()) {
      provenance.sampling = samplingFromDict(dict["sampling"], "sampling", false);
    }
    if (dict.contains("input") && !dict["input"].is_none()) {
      if (!py::isinstance<py::dict>(dict["input"])) {
        throw Error("input: " + described(dict["input"]) +
                    " is not a dict (points, sha256, boundary_points)");
      }
      const auto input = dict["input"].cast<py::dict>();
      const char* count = "a whole number >= 0";
      provenance.input =
          io::InputCloud{entry<std::uint64_t>(input, "points", "input.", count),
                         entry<std::string>(input, "sha256", "input.", text),
                         entry<std::uint64_t>(input, "boundary_points", "input.", count)};
    }
    // What a header records must read back: the same checks as a file's line.
    return io::parseProvenanceComment(io::provenanceComment(provenance));
  });
}

void bindCloud(py::module_& m) {
  m.def("read_pcd", &readPcdArray, kReadPcdDoc, py::arg("path"));
  m.def(
      "read_provenance",
      [](const py::object& path) { return provenanceDict(io::readProvenance(pathArgument(path))); },
      kReadProvenanceDoc, py::arg("path"));
  m.def("_write_points", &writePcdArray,
        "Writes records of _point_dtype(joints, quality) as binary PCD (mcws.write_pcd's C++ "
        "part).",
        py::arg("path"), py::arg("points"), py::arg("quality"), py::arg("joints"),
        py::arg("robot").none(true), py::arg("provenance").none(true),
        py::arg("sampling").none(true));
}

}  // namespace mcws::python
