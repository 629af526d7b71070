// The mcws extension module (_mcws): errors and the helpers every binding file shares; the
// bindings themselves are one file per job (robot.cpp, sampling.cpp, cloud.cpp, boundary.cpp,
// workspace.cpp, refine.cpp, envelope.cpp, reach.cpp, reach_query.cpp, reach_study.cpp).
#include <chrono>
#include <limits>

#include "bindings.h"

PYBIND11_MODULE(_mcws, m) {
  using namespace mcws::python;
  m.doc() =
      "mcws: Monte Carlo workspace analysis of robot manipulators (the C++ library's extension "
      "module; import mcws).";
  bindErrors(m);
  bindRobot(m);
  bindSampling(m);
  bindCloud(m);
  bindBoundary(m);
  bindWorkspace(m);
  bindRefine(m);
  bindEnvelope(m);
  bindReach(m);
  bindReachStudy(m);
  bindPlan(m);
  bindBehave(m);
}

namespace mcws::python {

DoubleArray doubleArray(const py::handle& value, const std::string& argument) {
  if (value.is_none()) throw UsageError(argument + ": None is not an array of numbers");
  DoubleArray array = DoubleArray::ensure(value);
  if (!array) {
    throw UsageError(argument + ": " + std::string(py::str(py::repr(value))).substr(0, 60) +
                     " is not an array of numbers");
  }
  return array;
}

void checkSignals() {
  py::gil_scoped_acquire acquire;
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
}

CancelCheck signalCheck() {
  using Clock = std::chrono::steady_clock;
  return [last = Clock::now()]() mutable {
    const Clock::time_point now = Clock::now();
    if (now - last < std::chrono::milliseconds(50)) return;
    last = now;
    checkSignals();
  };
}

Checkpoint::Checkpoint(const py::object& progress, const std::string& program,
                       const std::string& what) {
  if (progress.is_none() || (py::isinstance<py::bool_>(progress) && !progress.cast<bool>())) {
    return;
  }
  if (py::isinstance<py::bool_>(progress)) {
    line_ = std::make_unique<io::Progress>(program, what);
  } else if (PyCallable_Check(progress.ptr()) != 0) {
    callback_ = progress;
  } else {
    throw UsageError("progress: " + std::string(py::repr(progress)).substr(0, 60) +
                     " is not True, False, None or a callable (done, total)");
  }
}

void Checkpoint::operator()(std::uint64_t done, std::uint64_t total) {
  py::gil_scoped_acquire acquire;
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  if (line_) line_->update(static_cast<std::size_t>(done), static_cast<std::size_t>(total));
  if (callback_) callback_(done, total);
}

std::string shapeText(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t i = 0; i < array.ndim(); ++i) {
    text += (i ? ", " : "") + std::to_string(array.shape(i));
  }
  return text + (array.ndim() == 1 ? ",)" : ")");
}

std::string pathArgument(const py::handle& path, const std::string& argument) {
  if (!py::isinstance<py::str>(path) && !py::isinstance<py::bytes>(path) &&
      !py::hasattr(path, "__fspath__")) {
    throw py::type_error(argument + ": " + std::string(py::repr(path)) + " (" +
                         py::type::of(path).attr("__name__").cast<std::string>() +
                         ") is not a path (str, bytes or os.PathLike)");
  }
  // os.fsdecode as open() does: a bytes path b"out.pcd" is the file out.pcd.
  return py::module_::import("os").attr("fsdecode")(path).cast<std::string>();
}

std::uint64_t nonNegative(std::int64_t value, const std::string& argument) {
  if (value < 0) {
    throw UsageError(argument + ": " + std::to_string(value) +
                     " is negative (a whole number >= 0)");
  }
  return static_cast<std::uint64_t>(value);
}

int threadCount(int threads) {
  constexpr int kMaxThreads = 256;  // as the tools' --threads
  if (threads < 0 || threads > kMaxThreads) {
    throw UsageError("threads: " + std::to_string(threads) + " is not in 0 .. " +
                     std::to_string(kMaxThreads) + " (0: all cores)");
  }
  return threads;
}

py::array ownedDoubles(std::vector<double> values, std::vector<py::ssize_t> shape) {
  std::vector<py::ssize_t> strides(shape.size());
  py::ssize_t stride = sizeof(double);
  for (std::size_t i = shape.size(); i-- > 0;) {
    strides[i] = stride;
    stride *= shape[i];
  }
  auto owner = std::make_unique<std::vector<double>>(std::move(values));
  const double* data = owner->data();
  return ownedArray(std::move(owner), py::dtype::of<double>(), std::move(shape), std::move(strides),
                    data);
}

void bindErrors(py::module_& m) {
  auto& error = py::register_exception<Error>(m, "Error", PyExc_RuntimeError);
  error.attr("__doc__") =
      "A bad robot file, cloud file or argument, or a failed computation: the one-line message "
      "the mcws tools print, naming the file, field or argument and the bad value. A subclass of "
      "RuntimeError.";
  // A usage error is both an mcws.Error and a ValueError (a bad argument value).
  auto& usage = py::register_exception<UsageError>(
      m, "UsageError", py::make_tuple(error, py::handle(PyExc_ValueError)));
  usage.attr("__doc__") =
      "A bad argument value (what the tools report as a usage error, exit code 2): the message "
      "names the argument and the value. A subclass of mcws.Error and of ValueError.";
}

}  // namespace mcws::python
