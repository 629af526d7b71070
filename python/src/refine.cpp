// mcws.refine's C++ part: boundary refinement (the library's workspace module, RefineSampler, as
// mcws_refine draws its new samples), with collision labels as mcws_refine --collision gives them.
#include <pybind11/stl.h>

#include <cstring>
#include <optional>

#include "bindings.h"
#include "loaded_robot.h"
#include "mcws/collision/collision_checker.h"
#include "mcws/collision/collision_sampler.h"
#include "mcws/workspace/refine.h"
#include "sample_array.h"

namespace mcws::python {

namespace {

/// The records of WorkspacePoint layout (mcws._point_dtype(joints, False)) as a cloud.
pcl::PointCloud<WorkspacePoint> parentCloud(const py::array& records) {
  if (records.ndim() != 1 || records.itemsize() != sizeof(WorkspacePoint) ||
      !(records.flags() & py::array::c_style)) {
    throw UsageError("boundary_points: not packed as workspace points (mcws._point_dtype)");
  }
  pcl::PointCloud<WorkspacePoint> cloud;
  cloud.resize(static_cast<std::size_t>(records.shape(0)));
  if (!cloud.empty())
    std::memcpy(cloud.data(), records.data(), cloud.size() * sizeof(WorkspacePoint));
  return cloud;
}

/// Refuses parents with a joint value beyond the robot's dof (a file's q1..q8 hold 0 there): the
/// points of a robot with more joints.
void checkJointsBeyond(const pcl::PointCloud<WorkspacePoint>& parents, int joints,
                       const Robot& robot) {
  for (std::size_t i = 0; i < parents.size(); ++i) {
    for (int j = robot.dof(); j < joints; ++j) {
      if (parents[i].q[j] == 0.0f) continue;
      throw UsageError(
          "boundary_points: point " + std::to_string(i) + " has q" + std::to_string(j + 1) + " = " +
          py::str(py::float_(parents[i].q[j])).cast<std::string>() + ", but robot '" + robot.name +
          "' has " + std::to_string(robot.dof()) + " joints: points of a robot with more joints");
    }
  }
}

py::array refine(const LoadedRobot& loaded, const py::array& records, int joints, std::int64_t n,
                 std::int64_t seed, int threads, double spread, const std::string& point,
                 const py::object& fix, bool collision, const py::object& progress) {
  const Robot& robot = loaded.robot;
  Checkpoint checkpoint(progress, "mcws.refine", "samples");
  const std::size_t samples = sampleCount(n);
  if (joints < robot.dof()) {
    throw UsageError("boundary_points: has no field 'q" + std::to_string(joints + 1) +
                     "' (robot '" + robot.name + "' has " + std::to_string(robot.dof()) +
                     " joints; give the points sample() or read_pcd() returns)");
  }
  RefineOptions options;
  options.seed = nonNegative(seed, "seed");
  threads = threadCount(threads);
  if (!(spread > 0.0 && spread <= 1.0)) {
    throw UsageError("spread: " + py::str(py::float_(spread)).cast<std::string>() +
                     " is not in (0, 1]");
  }
  options.spread = spread;
  options.point = samplePoint(point);
  if (!fix.is_none()) options.fixed = fixedJoints(fix);
  const pcl::PointCloud<WorkspacePoint> parents = parentCloud(records);
  checkJointsBeyond(parents, joints, robot);
  const std::string checked = fix.is_none() ? "boundary_points" : "boundary_points and fix";
  const RefineSampler refined =
      asUsageError(checked, [&] { return RefineSampler(robot, parents, options); });
  if (!collision) return samplePoints(refined, samples, threads, robot.dof(), checkpoint);
  const std::unique_ptr<CollisionChecker> checker = collisionChecker(loaded);
  const LabelledSampler<RefineSampler> labelled(refined, *checker);
  return samplePoints(labelled, samples, threads, robot.dof(), checkpoint);
}

}  // namespace

void bindRefine(py::module_& m) {
  m.def("_refine", &refine,
        "mcws.refine's C++ part: n new samples near the joint values of boundary points packed "
        "as _point_dtype(joints, False).",
        py::arg("robot"), py::arg("records"), py::arg("joints"), py::arg("n"), py::arg("seed"),
        py::arg("threads"), py::arg("spread"), py::arg("point"), py::arg("fix").none(true),
        py::arg("collision"), py::arg("progress"));
}

}  // namespace mcws::python
