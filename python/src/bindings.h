#pragma once
/// \file
/// \brief What the binding files of the mcws Python module (_mcws) share: one function per file
/// that adds its part to the module, argument checks that raise mcws.UsageError, and NumPy arrays
/// that own a C++ buffer (no copy of large results).
///
/// The bindings call the library (src/mcws/..., filters/) only, never the tools' code (apps/).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "mcws/core/cancel_check.h"
#include "mcws/core/error.h"
#include "mcws/io/progress.h"

namespace mcws::python {

namespace py = pybind11;

/// \brief mcws.Error and mcws.UsageError, translated from mcws::Error and mcws::UsageError.
void bindErrors(py::module_& m);
/// \brief mcws.Robot: loading, forward and inverse kinematics, the Jacobian.
void bindRobot(py::module_& m);
/// \brief mcws.sample, mcws.sample_shape and the point layout they return.
void bindSampling(py::module_& m);
/// \brief mcws.read_pcd, mcws.read_provenance and the writer behind mcws.write_pcd.
void bindCloud(py::module_& m);
/// \brief The C++ part of mcws.boundary.
void bindBoundary(py::module_& m);
/// \brief The C++ part of mcws.measure.
void bindWorkspace(py::module_& m);
/// \brief The C++ part of mcws.refine.
void bindRefine(py::module_& m);
/// \brief The C++ part of mcws.envelope.
void bindEnvelope(py::module_& m);
/// \brief mcws.reach_map's C++ part and the map class behind mcws.ReachMap.
void bindReach(py::module_& m);
/// \brief mcws.reach_study's and mcws.place's C++ parts.
void bindReachStudy(py::module_& m);
/// \brief mcws.plan's C++ part.
void bindPlan(py::module_& m);
/// \brief mcws.behave's C++ part.
void bindBehave(py::module_& m);

/// \brief Raises KeyboardInterrupt (throws py::error_already_set) when Ctrl-C was pressed: called
/// with the GIL released, on the thread that released it (a library's progress or phase
/// callback, between pieces of a long computation), it takes the GIL for the look.
void checkSignals();

/// \brief A library CancelCheck for a call made with the GIL released: checkSignals() at most
/// every 50 ms (the library calls it every few milliseconds of work), so Ctrl-C ends the call
/// with KeyboardInterrupt and nothing is returned. Only on the thread that released the GIL.
CancelCheck signalCheck();

/// \brief What a long call does between its pieces of work (chunks of samples, targets,
/// positions): raises KeyboardInterrupt on Ctrl-C (checkSignals()) and reports its progress as
/// the call's `progress` argument asks: None or False nothing, True a line on stderr as the tools
/// write it ("mcws.sample: 45% (4500000/10000000 samples)", for calls over a second, at most
/// twice a second), a callable called with (done, total) on the calling thread (what it raises
/// ends the call).
class Checkpoint {
 public:
  /// \param program the function's name on the stderr line; \param what what is counted.
  /// \throws UsageError for a `progress` of another kind.
  Checkpoint(const py::object& progress, const std::string& program, const std::string& what);
  /// \brief Called with the GIL released, on the thread that released it.
  void operator()(std::uint64_t done, std::uint64_t total);

 private:
  py::object callback_;  ///< None, or the callable
  std::unique_ptr<io::Progress> line_;
};

/// \brief A float64, C-ordered array: what array arguments of any float dtype and memory layout
/// are converted to (once, and only when they are not one already).
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// \brief `value` as a DoubleArray. \throws UsageError "argument: ..." when NumPy cannot make
/// numbers of it.
DoubleArray doubleArray(const py::handle& value, const std::string& argument);

/// \brief An array's shape as Python writes it: "(4, 2)", "(3,)".
std::string shapeText(const py::array& array);

/// \brief A path argument (str, bytes or os.PathLike) as a string, bytes decoded as os.fsdecode
/// decodes them. \throws TypeError (py::type_error) naming `argument` for another type.
std::string pathArgument(const py::handle& path, const std::string& argument = "path");

/// \brief A homogeneous pose checked as Robot.ik checks its pose (the IK solvers' check): finite,
/// a last row of 0 0 0 1, a rotation orthonormal to 1e-9 and not a reflection.
/// \throws UsageError "argument: ..." saying what is wrong.
Eigen::Isometry3d checkedPose(const Eigen::Matrix4d& M, const std::string& argument);

/// \brief A whole number >= 0 (a seed). \throws UsageError naming `argument` and the value.
std::uint64_t nonNegative(std::int64_t value, const std::string& argument);

/// \brief A thread count: 0 (all cores) .. 256. \throws UsageError naming the value.
int threadCount(int threads);

/// \brief A NumPy array viewing `data`, whose buffer `owner` holds: the array frees `owner` when
/// it is collected, so a result reaches Python without a copy.
template <typename Owner>
py::array ownedArray(std::unique_ptr<Owner> owner, const py::dtype& dtype,
                     std::vector<py::ssize_t> shape, std::vector<py::ssize_t> strides,
                     const void* data) {
  py::capsule capsule(owner.get(), [](void* p) { delete static_cast<Owner*>(p); });
  owner.release();  // the capsule owns it now
  return py::array(dtype, std::move(shape), std::move(strides), data, capsule);
}

/// \brief A float64 array of `shape` (C order) that owns `values`.
py::array ownedDoubles(std::vector<double> values, std::vector<py::ssize_t> shape);

}  // namespace mcws::python
