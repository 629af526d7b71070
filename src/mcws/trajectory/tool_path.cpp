#include "mcws/trajectory/tool_path.h"

#include <optional>
#include <utility>

#include "mcws/core/error.h"
#include "mcws/kinematics/inverse_kinematics.h"

namespace mcws {

SampledTrajectory ikToolLine(const Robot& robot, const Eigen::VectorXd& q_start,
                             const Eigen::Isometry3d& T_goal, const CartesianLineOptions& options) {
  IkOptions ik_options;
  ik_options.restarts = 2;  // seeded with the previous sample: a restart means a new branch
  const IkFunction ik = [&](const Eigen::Isometry3d& T, const Eigen::VectorXd& seed) {
    const IkResult r = solveIk(robot, T, seed, ik_options);
    return r.converged() ? std::optional<Eigen::VectorXd>(r.q) : std::nullopt;
  };
  CartesianLineResult result = cartesianLine(robot, q_start, T_goal, ik, options);
  if (result.status != CartesianLineStatus::kSuccess) throw Error(result.message);
  return std::move(result.trajectory);
}

double pathLength(const Eigen::MatrixXd& xyz) {
  double length = 0.0;
  for (Eigen::Index i = 1; i < xyz.rows(); ++i) length += (xyz.row(i) - xyz.row(i - 1)).norm();
  return length;
}

}  // namespace mcws
