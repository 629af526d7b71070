// mcws.Robot: a robot read from a .yaml or .urdf file, its forward and inverse kinematics and
// its Jacobian (the library's kinematics module, as mcws_fk and mcws_ik call it).
#include <pybind11/stl.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <optional>

#include "bindings.h"
#include "loaded_robot.h"
#include "mcws/collision/collision_checker.h"
#include "mcws/collision/collision_model.h"
#include "mcws/collision/robot_bodies.h"
#include "mcws/core/length_text.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/inverse_kinematics.h"
#include "mcws/kinematics/jacobian.h"
#include "mcws/kinematics/robot_yaml.h"
#include "positions.h"

namespace mcws::python {

namespace {

/// Largest |R^T R - I| entry of a pose argument's rotation: the IK solvers' tolerance (far above
/// the rounding of a rotation composed in double, far below any real mistake).
constexpr double kPoseRotationTolerance = 1e-9;

bool isUrdf(const std::string& path) { return std::filesystem::path(path).extension() == ".urdf"; }

/// The collision model of the robot's file, for the chain it was read with.
/// The robot's collision model as the tools load it: its chain, package path and SRDF.
CollisionModel collisionModel(const LoadedRobot& loaded) {
  return loadCollisionModel(loaded.robot, loaded.path);
}

/// Joint vectors given as (dof,) or (N, dof): the array and how many rows it holds.
struct JointRows {
  DoubleArray array;
  py::ssize_t rows{1};
  bool batched{false};

  Eigen::VectorXd row(py::ssize_t i) const {
    const py::ssize_t n = array.shape(array.ndim() - 1);
    return Eigen::Map<const Eigen::VectorXd>(array.data() + i * n, n);
  }
};

JointRows jointRows(const Robot& robot, const py::handle& q, const std::string& argument) {
  JointRows rows{doubleArray(q, argument)};
  const py::ssize_t ndim = rows.array.ndim();
  if (ndim != 1 && ndim != 2) {
    throw UsageError(argument + ": an array of shape " + shapeText(rows.array) +
                     ", not (dof,) or (N, dof) with dof = " + std::to_string(robot.dof()));
  }
  asUsageError(argument, [&] { robot.checkSize(Eigen::VectorXd(rows.array.shape(ndim - 1))); });
  rows.batched = ndim == 2;
  rows.rows = rows.batched ? rows.array.shape(0) : 1;
  return rows;
}

/// Checks row i of q as mcws_fk checks --q: finite and within the limits (`limits`), or finite.
void checkRow(const Robot& robot, const JointRows& q, py::ssize_t i, bool limits) {
  const std::string where = q.batched ? "q[" + std::to_string(i) + "]" : "q";
  const Eigen::VectorXd row = q.row(i);
  asUsageError(where, [&] {
    if (limits) {
      robot.checkJointVector(row);
    } else if (!row.allFinite()) {
      for (int j = 0; j < robot.dof(); ++j) {
        if (!std::isfinite(row[j])) {
          throw Error("joint '" + robot.joints[j].name + "' value " + std::to_string(row[j]) +
                      " is not a finite number");
        }
      }
    }
  });
}

py::array forwardKinematics(const LoadedRobot& loaded, const py::handle& q_value,
                            const std::string& frame, bool check_limits) {
  if (frame != "tool" && frame != "flange") {
    throw UsageError("frame: '" + frame + "' is not one of tool, flange");
  }
  const Robot& robot = loaded.robot;
  const JointRows q = jointRows(robot, q_value, "q");
  std::vector<double> poses(static_cast<std::size_t>(q.rows) * 16);
  {
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < q.rows; ++i) {
      checkRow(robot, q, i, check_limits);
      const ChainPoses chain = chainPoses(robot, q.row(i));
      const Eigen::Matrix4d T =
          (frame == "tool" ? chain.T_world_tool : chain.T_world_flange).matrix();
      Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(poses.data() + 16 * i) = T;
    }
  }
  if (!q.batched) return ownedDoubles(std::move(poses), {4, 4});
  return ownedDoubles(std::move(poses), {q.rows, 4, 4});
}

py::array jacobian(const LoadedRobot& loaded, const py::handle& q_value) {
  const Robot& robot = loaded.robot;
  const JointRows q = jointRows(robot, q_value, "q");
  const int dof = robot.dof();
  std::vector<double> out(static_cast<std::size_t>(q.rows) * 6 * dof);
  {
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < q.rows; ++i) {
      checkRow(robot, q, i, false);
      const Jacobian J = toolJacobian(robot, q.row(i));
      Eigen::Map<Eigen::Matrix<double, 6, Eigen::Dynamic, Eigen::RowMajor>>(
          out.data() + 6 * dof * i, 6, dof) = J;
    }
  }
  if (!q.batched) return ownedDoubles(std::move(out), {6, dof});
  return ownedDoubles(std::move(out), {q.rows, 6, dof});
}

/// A (4, 4) homogeneous pose with a last row of 0 0 0 1.
Eigen::Isometry3d poseArgument(const py::handle& value) {
  const DoubleArray array = doubleArray(value, "pose");
  if (array.ndim() != 2 || array.shape(0) != 4 || array.shape(1) != 4) {
    throw UsageError("pose: an array of shape " + shapeText(array) + ", not (4, 4)");
  }
  return checkedPose(Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(array.data()),
                     "pose");
}

py::object inverseKinematics(const LoadedRobot& loaded, const py::handle& pose,
                             const py::handle& q0_value, bool position_only, bool free_roll,
                             double tolerance, std::int64_t seed) {
  const Robot& robot = loaded.robot;
  const Eigen::Isometry3d T_target = poseArgument(pose);
  Eigen::VectorXd q0 = 0.5 * (robot.lowerLimits() + robot.upperLimits());  // as mcws_ik
  if (!q0_value.is_none()) {
    const JointRows rows = jointRows(robot, q0_value, "q0");
    if (rows.batched) throw UsageError("q0: give one joint vector, of shape (dof,)");
    checkRow(robot, rows, 0, false);
    q0 = rows.row(0);
  }
  if (position_only && free_roll) {
    throw UsageError("position_only and free_roll exclude each other");
  }
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) {
    throw UsageError("tolerance: " + std::to_string(tolerance) + " is not a positive number");
  }
  IkOptions options;
  options.position_only = position_only;
  options.free_roll = free_roll;
  options.position_tolerance = tolerance;
  options.seed = nonNegative(seed, "seed");
  IkResult result;
  {
    py::gil_scoped_release release;
    result = asUsageError("pose", [&] { return solveIk(robot, T_target, q0, options); });
  }
  if (!result.converged()) return py::none();
  return ownedDoubles(std::vector<double>(result.q.data(), result.q.data() + result.q.size()),
                      {robot.dof()});
}

py::array limits(const Robot& robot) {
  std::vector<double> values;
  for (const Joint& joint : robot.joints) {
    values.push_back(joint.lower);
    values.push_back(joint.upper);
  }
  return ownedDoubles(std::move(values), {robot.dof(), 2});
}

std::vector<std::string> jointNames(const Robot& robot) {
  std::vector<std::string> names;
  for (const Joint& joint : robot.joints) names.push_back(joint.name);
  return names;
}

std::vector<std::string> jointTypes(const Robot& robot) {
  std::vector<std::string> types;
  for (const Joint& joint : robot.joints) types.push_back(jointTypeName(joint.type));
  return types;
}

constexpr char kRobotDoc[] = R"(A serial robot arm read from a robot file.

Robot(path, *, base=None, tip=None, package_path=None, srdf=None)

path: a robot description, .yaml (docs/robot-files.md) or .urdf (str or os.PathLike).
base, tip: URDF only: the first and last link of the chain to read (default: the tree's root to
    its one leaf), as the tools' --base and --tip.
package_path: URDF only: a folder, or a list of folders, holding ROS packages for the
    package:// mesh URIs, searched before ROS_PACKAGE_PATH and the folders above the URDF, as
    the tools' --package-path.
srdf: an SRDF file whose <disable_collisions> link pairs the collision checks skip, as --srdf.

Lengths are in the robot file's length unit (.length_unit: "m", "cm" or "mm"; URDF: "m"), joint
values in rad (revolute joints) or in that length unit (prismatic joints): see .joint_units.

Raises mcws.Error naming the file, line, joint or field (missing or unreadable file, a mistake in
it), mcws.UsageError for base, tip or package_path with a file that is not a .urdf, a
package_path that is not a folder or an srdf that is not a file.)";

constexpr char kFkDoc[] =
    R"(Forward kinematics: the pose of the tool (or flange) frame in the world frame.

q: joint values [rad | length unit] (see .joint_units), shape (dof,) or (N, dof), any float dtype.
frame: "tool" (default) or "flange" (the end of the bare arm).
check_limits: refuse joint values outside the joint limits (default True, as mcws_fk; False: as
    mcws_fk --ignore-limits).

Returns the homogeneous 4x4 pose, shape (4, 4), or (N, 4, 4) for (N, dof): rotation
dimensionless, translation (last column) in .length_unit. The same numbers as mcws_fk --json.

Raises mcws.UsageError for a q of the wrong shape or dof, a value that is not finite or (with
check_limits) outside its joint's limits (the message names the row, the joint and its limits).)";

constexpr char kJacobianDoc[] = R"(The geometric Jacobian of the tool point, in the world frame.

q: joint values [rad | length unit], shape (dof,) or (N, dof); limits are not checked.

Returns shape (6, dof), or (N, 6, dof): column i maps joint i's rate to the tool's twist, rows
0-2 the tool point's linear velocity [length unit / rad] (revolute) or [1] (prismatic), rows 3-5
the angular velocity [1] (revolute) or 0 (prismatic).

Raises mcws.UsageError for a q of the wrong shape or dof or a value that is not finite.)";

constexpr char kIkDoc[] =
    R"(Inverse kinematics: joint values within the limits that put the tool at a pose.

pose: the wanted tool pose, a homogeneous 4x4 array, translation in .length_unit; its rotation
    must be orthonormal.
q0: the first guess [rad | length unit], shape (dof,) (default: the middle of the limits, as
    mcws_ik).
position_only: match the tool point only (arms with fewer than 6 joints).
free_roll: match the tool point and the direction of the tool's z axis only.
tolerance: largest accepted position error [length unit] (default 1e-6); the orientation
    tolerance is 1e-6 rad.
seed: seed of the random restarts, a whole number >= 0 (default 1, as mcws_ik).

Returns the joint values [rad | length unit], shape (dof,), or None when the pose is not reached
(unreachable, or every attempt stalled): the damped-least-squares solver of mcws_ik.

Raises mcws.UsageError for a pose that is not (4, 4), finite, with a last row 0 0 0 1 and an
orthonormal rotation, or a bad q0, tolerance or seed.)";

}  // namespace

Eigen::Isometry3d checkedPose(const Eigen::Matrix4d& M, const std::string& argument) {
  if (!M.allFinite()) throw UsageError(argument + ": holds a value that is not a finite number");
  if (M.row(3) != Eigen::RowVector4d(0, 0, 0, 1)) {
    throw UsageError(argument + ": last row is " + number(M(3, 0)) + " " + number(M(3, 1)) + " " +
                     number(M(3, 2)) + " " + number(M(3, 3)) + ", not 0 0 0 1");
  }
  // The check of the solvers' targets (solveIk's): orthonormal to rounding, not a reflection.
  const Eigen::Matrix3d R = M.topLeftCorner<3, 3>();
  const double deviation = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!(deviation <= kPoseRotationTolerance) || R.determinant() < 0.0) {
    throw UsageError(argument + ": the rotation is not orthonormal (|R^T R - I| = " +
                     number(deviation) + ", det R = " + number(R.determinant()) + ")");
  }
  Eigen::Isometry3d T;
  T.matrix() = M;
  return T;
}

LoadedRobot loadRobotFile(const std::string& path, const std::string& base, const std::string& tip,
                          const std::vector<std::string>& package_path, const std::string& srdf) {
  const bool chain = !base.empty() || !tip.empty();
  if (chain && !isUrdf(path))
    throw UsageError("base and tip need a .urdf robot, not '" + path + "'");
  if (!package_path.empty() && !isUrdf(path))
    throw UsageError("package_path needs a .urdf robot, not '" + path + "'");
  std::error_code ec;
  for (const std::string& folder : package_path) {
    if (!std::filesystem::is_directory(folder, ec))
      throw UsageError("package_path: '" + folder + "' is not a folder");
  }
  if (!srdf.empty() && !std::filesystem::is_regular_file(srdf, ec))
    throw UsageError("srdf: '" + srdf + "' is not a file");
  LoadedRobot loaded;
  loaded.path = path;
  loaded.chain = {base, tip};
  loaded.robot = chain ? loadRobotUrdf(path, loaded.chain) : loadRobot(path);
  loaded.robot.package_path = package_path;
  loaded.robot.srdf = srdf;
  return loaded;
}

std::unique_ptr<CollisionChecker> collisionCheckerIfModelled(const LoadedRobot& loaded,
                                                             bool environment) {
  CollisionModel model = collisionModel(loaded);
  if (!environment) model = robotBodiesOnly(std::move(model));
  if (!hasGeometry(model)) return nullptr;
  return std::make_unique<CollisionChecker>(loaded.robot, model);
}

std::unique_ptr<CollisionChecker> collisionChecker(const LoadedRobot& loaded) {
  const CollisionModel model = collisionModel(loaded);
  if (!hasGeometry(model)) {
    throw Error(loaded.path + ": has no collision geometry " +
                (isUrdf(loaded.path) ? "(no <collision> element on a link of its chain)"
                                     : "(collision: key)"));
  }
  return std::make_unique<CollisionChecker>(loaded.robot, model);
}

void bindRobot(py::module_& m) {
  m.def(
      "_parse_length",
      [](const std::string& text, const std::string& name, const LoadedRobot& robot,
         bool allow_zero) {
        return lengthFromText(text, name, robot.robot.length_unit, allow_zero);
      },
      "A length argument written with its unit (\"2cm\", \"0.5m\"; a bare number in the robot's "
      "unit) in the robot's length unit, as the tools read their length flags.",
      py::arg("text"), py::arg("name"), py::arg("robot"), py::arg("allow_zero"));
  py::class_<LoadedRobot>(m, "Robot", kRobotDoc)
      .def(py::init([](const py::object& path, const std::optional<std::string>& base,
                       const std::optional<std::string>& tip, const py::object& package_path,
                       const py::object& srdf) {
             std::vector<std::string> folders;
             if (py::isinstance<py::str>(package_path) || py::isinstance<py::bytes>(package_path) ||
                 py::hasattr(package_path, "__fspath__")) {
               folders.push_back(pathArgument(package_path, "package_path"));
             } else if (!package_path.is_none()) {
               if (!py::isinstance<py::iterable>(package_path)) {
                 throw py::type_error(
                     "package_path: " + std::string(py::repr(package_path)) + " (" +
                     py::type::of(package_path).attr("__name__").cast<std::string>() +
                     ") is neither a folder (str or os.PathLike) nor a list of folders");
               }
               for (const py::handle folder : package_path) {
                 folders.push_back(pathArgument(folder, "package_path"));
               }
             }
             return loadRobotFile(pathArgument(path), base.value_or(""), tip.value_or(""), folders,
                                  srdf.is_none() ? "" : pathArgument(srdf, "srdf"));
           }),
           py::arg("path"), py::kw_only(), py::arg("base") = py::none(),
           py::arg("tip") = py::none(), py::arg("package_path") = py::none(),
           py::arg("srdf") = py::none())
      .def_property_readonly(
          "name", [](const LoadedRobot& r) { return r.robot.name; }, "The robot's name (str).")
      .def_property_readonly(
          "path", [](const LoadedRobot& r) { return r.path; }, "The file it was read from (str).")
      .def_property_readonly(
          "dof", [](const LoadedRobot& r) { return r.robot.dof(); }, "Number of joints (int).")
      .def_property_readonly(
          "joint_names", [](const LoadedRobot& r) { return jointNames(r.robot); },
          "Joint names, base to tip (list of str).")
      .def_property_readonly(
          "joint_types", [](const LoadedRobot& r) { return jointTypes(r.robot); },
          "\"revolute\" or \"prismatic\" for each joint (list of str).")
      .def_property_readonly(
          "joint_units", [](const LoadedRobot& r) { return jointUnits(r.robot); },
          "The unit of each joint's value: \"rad\" (revolute) or .length_unit (prismatic).")
      .def_property_readonly(
          "limits", [](const LoadedRobot& r) { return limits(r.robot); },
          "Joint limits, shape (dof, 2) float64, columns lower and upper, in .joint_units (rad "
          "for revolute joints, even when the file gives degrees; .length_unit for prismatic).")
      .def_property_readonly(
          "length_unit", [](const LoadedRobot& r) { return unitName(r.robot.length_unit); },
          "The unit of every length of the robot and of its results: \"m\", \"cm\" or \"mm\".")
      .def_property_readonly(
          "has_collision_model",
          [](const LoadedRobot& r) { return hasGeometry(collisionModel(r)); },
          "True when the file has collision geometry (a YAML collision: key with shapes, URDF "
          "<collision> elements on the chain's links), so that sample(collision=True) works. "
          "Raises mcws.Error for a malformed collision model.")
      .def("fk", &forwardKinematics, kFkDoc, py::arg("q"), py::arg("frame") = "tool",
           py::arg("check_limits") = true)
      .def("jacobian", &jacobian, kJacobianDoc, py::arg("q"))
      .def("ik", &inverseKinematics, kIkDoc, py::arg("pose"), py::arg("q0") = py::none(),
           py::arg("position_only") = false, py::kw_only(), py::arg("free_roll") = false,
           py::arg("tolerance") = 1e-6, py::arg("seed") = 1)
      .def("__repr__", [](const LoadedRobot& r) {
        return "mcws.Robot('" + r.path + "': " + r.robot.name + ", " +
               std::to_string(r.robot.dof()) + " joints, lengths in " +
               unitName(r.robot.length_unit) + ")";
      });
}

}  // namespace mcws::python
