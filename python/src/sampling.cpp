// mcws.sample and mcws.sample_shape: Monte Carlo workspace samples (the library's sampling
// module, as mcws_sample draws them) handed to NumPy without a copy.
#include <pybind11/stl.h>

#include <cstdint>
#include <optional>

#include "bindings.h"
#include "loaded_robot.h"
#include "mcws/collision/collision_checker.h"
#include "mcws/collision/collision_sampler.h"
#include "mcws/reach/quality.h"
#include "mcws/reach/quality_sampler.h"
#include "mcws/sampling/sampler.h"
#include "sample_array.h"

namespace mcws::python {

std::size_t sampleCount(std::int64_t n) {
  if (n < 0) throw UsageError("n: " + std::to_string(n) + " is negative");
  // The most points of the largest layout an array can address (a vector's max_size()).
  constexpr std::int64_t kMost = PTRDIFF_MAX / sizeof(QualityPoint);
  if (n > kMost) {
    throw UsageError("n: " + std::to_string(n) + " samples are more than an array can hold (" +
                     std::to_string(kMost) + ")");
  }
  return static_cast<std::size_t>(n);
}

std::vector<std::pair<std::string, double>> fixedJoints(const py::handle& fix) {
  std::vector<std::pair<std::string, double>> fixed;
  if (fix.is_none()) return fixed;
  if (!py::isinstance<py::dict>(fix)) {
    throw UsageError("fix: give a dict of joint name -> value [rad | length unit]");
  }
  for (const auto& [name, value] : py::reinterpret_borrow<py::dict>(fix)) {
    if (!py::isinstance<py::str>(name)) {
      throw UsageError("fix: joint name " + std::string(py::repr(name)) + " is not a str");
    }
    double number = 0.0;
    try {
      number = py::cast<double>(value);
    } catch (const py::cast_error&) {
      throw UsageError("fix: " + py::cast<std::string>(name) + " = " +
                       std::string(py::repr(value)) + " is not a number");
    }
    fixed.emplace_back(py::cast<std::string>(name), number);
  }
  return fixed;
}

SamplePoint samplePoint(const std::string& point) {
  if (point != "tool" && point != "flange") {
    throw UsageError("point: '" + point + "' is not one of tool, flange");
  }
  return point == "tool" ? SamplePoint::kTool : SamplePoint::kFlange;
}

QualityOptions qualityOptions(const Robot& robot, const std::optional<std::string>& task,
                              const std::optional<double>& length) {
  QualityOptions quality = defaultQualityOptions(robot);
  if (task) quality.task = asUsageError("quality_task", [&] { return parseQualityTask(*task); });
  if (length) {
    quality.characteristic_length = *length;
    asUsageError("length", [&] { quality.check(); });
  }
  return quality;
}

namespace {

py::array sample(const LoadedRobot& loaded, std::int64_t n, std::int64_t seed, int threads,
                 const py::object& fix, bool collision, bool quality, const std::string& point,
                 const std::optional<std::string>& quality_task,
                 const std::optional<double>& length, const py::object& progress) {
  const Robot& robot = loaded.robot;
  Checkpoint checkpoint(progress, "mcws.sample", "samples");
  const std::size_t samples = sampleCount(n);
  RobotSamplerOptions options;
  options.seed = nonNegative(seed, "seed");
  threads = threadCount(threads);
  options.point = samplePoint(point);
  options.fixed = fixedJoints(fix);
  if (!quality && (quality_task || length)) {
    throw UsageError("quality_task and length need quality=True");
  }
  if (robot.dof() > kMaxJoints) {
    throw Error(loaded.path + ": robot '" + robot.name + "' has " + std::to_string(robot.dof()) +
                " joints; a workspace point records at most " + std::to_string(kMaxJoints));
  }
  std::unique_ptr<CollisionChecker> checker;
  if (collision) checker = collisionChecker(loaded);
  const auto generator = asUsageError("fix", [&]() -> std::unique_ptr<PointGenerator> {
    if (checker) return std::make_unique<LabelledRobotSampler>(robot, options, *checker);
    return std::make_unique<RobotSampler>(robot, options);
  });
  if (!quality) return samplePoints(*generator, samples, threads, robot.dof(), checkpoint);
  const QualitySampler measured(robot, options, *generator,
                                qualityOptions(robot, quality_task, length));
  return samplePoints(measured, samples, threads, robot.dof(), checkpoint);
}

py::array sampleShape(const std::string& name, std::int64_t n, std::int64_t seed, int threads,
                      const py::object& progress) {
  Checkpoint checkpoint(progress, "mcws.sample_shape", "samples");
  const std::size_t samples = sampleCount(n);
  const Shape shape = asUsageError("shape", [&] { return parseShape(name); });
  const ShapeSampler generator(shape, nonNegative(seed, "seed"));
  return samplePoints(generator, samples, threadCount(threads), 0, checkpoint);
}

constexpr char kSampleDoc[] =
    R"(Monte Carlo workspace samples of a robot, as mcws_sample writes them.

robot: an mcws.Robot.
n: number of samples (int >= 0).
seed: random seed, a whole number >= 0 (mcws_sample's default is 1). Sample i's joint values
    depend on the seed and i only.
threads: worker threads, 0 = all cores. The result is the same bytes for any thread count.
fix: joints pinned instead of sampled, a dict joint name -> value [rad | length unit], as
    mcws_sample --fix name=value.
collision: label each sample by its collision status under the robot file's collision model
    (0 free, 1 link-link, 2 tool-link, 3 environment), as mcws_sample --collision.
quality: add the fields manipulability and inverse_condition, as mcws_sample --quality.
point: "tool" (default) or "flange": which point's position to record.
quality_task: "position" or "full" (as --quality-task; default: full for 6 or more joints).
length: the characteristic length L of quality_task "full" [length unit] (as --length).
progress: True for progress lines on stderr as mcws_sample writes them, or a callable called
    with (samples done, n) every 65536 samples, on the calling thread; None: silent.

Returns a NumPy structured array of n records (the C++ points themselves, no copy) with the fields
of mcws_sample's PCD: x, y, z (float32, [length unit], the robot's .length_unit), q1 .. q<dof>
(float32, [rad | length unit], see .joint_units), label (uint32), and with quality=True
manipulability (float32, [length unit^k] for "position", [1] for "full") and inverse_condition
(float32, [1]). The same values as mcws_sample with the same arguments. The GIL is released
while sampling; Ctrl-C interrupts (KeyboardInterrupt).

Raises mcws.UsageError for a bad n, seed, threads, point, quality_task or length, an unknown joint
in fix or a value outside its limits; mcws.Error for collision=True on a robot file without
collision geometry.)";

constexpr char kSampleShapeDoc[] =
    R"(Uniform samples of a validation shape of known area or volume (mcws_sample --shape).

shape: "disk" (unit disk, z = 0, area pi), "annulus" (0.5 <= r <= 1, z = 0, area 0.75 pi),
    "ball" (unit ball, volume 4 pi / 3) or "box" (unit cube [-0.5, 0.5]^3, volume 1).
n: number of samples (int >= 0).
seed: random seed, a whole number >= 0.
threads: worker threads, 0 = all cores (the result does not depend on it).
progress: as sample()'s.

Returns a structured array with fields x, y, z (float32, dimensionless: the shapes have no
recorded length unit) and label (uint32, 0), the points mcws_sample --shape writes.

Raises mcws.UsageError for an unknown shape (naming the known ones) or a bad n, seed, threads.)";

}  // namespace

void bindSampling(py::module_& m) {
  m.def("sample", &sample, kSampleDoc, py::arg("robot"), py::arg("n"), py::arg("seed") = 0,
        py::arg("threads") = 0, py::arg("fix") = py::none(), py::arg("collision") = false,
        py::arg("quality") = false, py::kw_only(), py::arg("point") = "tool",
        py::arg("quality_task") = py::none(), py::arg("length") = py::none(),
        py::arg("progress") = py::none());
  m.def("sample_shape", &sampleShape, kSampleShapeDoc, py::arg("shape"), py::arg("n"),
        py::arg("seed") = 0, py::arg("threads") = 0, py::kw_only(),
        py::arg("progress") = py::none());
  m.def(
      "_point_dtype",
      [](int joints, bool quality) {
        if (joints < 0 || joints > kMaxJoints) {
          throw UsageError("joints: " + std::to_string(joints) + " is not in 0 .. " +
                           std::to_string(kMaxJoints));
        }
        return quality ? pointDtype<QualityPoint>(joints) : pointDtype<WorkspacePoint>(joints);
      },
      "The record layout of sample() (and of write_pcd's input): fields x y z q1..q<joints> "
      "label [manipulability inverse_condition] at the offsets of the C++ point.",
      py::arg("joints"), py::arg("quality"));
}

}  // namespace mcws::python
