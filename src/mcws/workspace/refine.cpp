#include "mcws/workspace/refine.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "mcws/core/error.h"

namespace mcws {

RefineSampler::RefineSampler(const Robot& robot, const pcl::PointCloud<WorkspacePoint>& parents,
                             const RefineOptions& options)
    : rng_(options.seed),
      kinematics_(robot, options.point == SamplePoint::kTool
                             ? Eigen::Vector3d(robot.T_flange_tool.translation())
                             : Eigen::Vector3d::Zero()),
      dof_(robot.dof()),
      lower_(robot.lowerLimits()),
      upper_(robot.upperLimits()) {
  if (robot.dof() > kMaxJoints) {
    throw Error("robot '" + robot.name + "' has " + std::to_string(robot.dof()) +
                " joints; a workspace point records at most " + std::to_string(kMaxJoints));
  }
  if (parents.empty()) throw Error("no boundary points to refine");
  if (!(options.spread > 0.0 && options.spread <= 1.0)) {
    std::ostringstream msg;
    msg << "spread " << options.spread << " must lie in (0, 1] (a fraction of each joint's range)";
    throw Error(msg.str());
  }
  // Joint values are stored as float: a parent may sit a rounding step outside its limit.
  const Eigen::VectorXd tolerance = 1e-6 * (upper_ - lower_).cwiseAbs().array() + 1e-6;
  parents_.reserve(parents.size() * dof_);
  for (std::size_t p = 0; p < parents.size(); ++p) {
    for (int j = 0; j < dof_; ++j) {
      const double q = parents[p].q[j];
      if (!std::isfinite(q) || q < lower_[j] - tolerance[j] || q > upper_[j] + tolerance[j]) {
        std::ostringstream msg;
        msg.precision(10);
        msg << "point " << p << ": q" << j + 1 << " = " << q << " is outside joint '"
            << robot.joints[j].name << "' limits "
            << describeLimits(robot.joints[j], robot.length_unit)
            << " (was the cloud sampled from robot '" << robot.name << "' by mcws_sample?)";
        throw Error(msg.str());
      }
      parents_.push_back(std::clamp(q, lower_[j], upper_[j]));
    }
  }
  step_ = options.spread * (upper_ - lower_);
  for (int j = 0; j < dof_; ++j) {
    const bool pinned = parents.size() > 1 &&
                        std::all_of(parents.begin(), parents.end(), [&](const WorkspacePoint& p) {
                          return p.q[j] == parents[0].q[j];
                        });
    if (pinned) {
      step_[j] = 0.0;
      pinned_names_.push_back(robot.joints[j].name);
    }
  }
}

void RefineSampler::generate(std::uint64_t first, std::size_t count, WorkspacePoint* out) const {
  // As RobotSampler::generate: kLanes samples at a time, a partial batch padded.
  constexpr int kLanes = PointKinematics::kLanes;
  const std::size_t n_parents = parents_.size() / dof_;
  double q[kMaxJoints * kLanes], x[kLanes], y[kLanes], z[kLanes];
  for (std::size_t begin = 0; begin < count; begin += kLanes) {
    const int lanes = static_cast<int>(std::min<std::size_t>(kLanes, count - begin));
    for (int k = 0; k < kLanes; ++k) {
      const std::uint64_t index =
          first + begin + static_cast<std::uint64_t>(std::min(k, lanes - 1));
      const double* parent = &parents_[(index % n_parents) * dof_];
      for (int j = 0; j < dof_; ++j) {
        const double moved = parent[j] + step_[j] * (2.0 * rng_.uniform(index, j) - 1.0);
        q[j * kLanes + k] = std::clamp(moved, lower_[j], upper_[j]);
      }
    }
    kinematics_.positions(q, x, y, z);
    for (int k = 0; k < lanes; ++k) {
      WorkspacePoint& point = out[begin + k];
      point = WorkspacePoint();
      point.x = static_cast<float>(x[k]);
      point.y = static_cast<float>(y[k]);
      point.z = static_cast<float>(z[k]);
      for (int j = 0; j < dof_; ++j) point.q[j] = static_cast<float>(q[j * kLanes + k]);
    }
  }
}

}  // namespace mcws
