#include "mcws/workspace/refine.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "mcws/core/error.h"

namespace mcws {

RefineSampler::RefineSampler(const Robot& robot, const pcl::PointCloud<WorkspacePoint>& parents,
                             const RefineOptions& options)
    : rng_(options.seed),
      kinematics_(samplePointKinematics(robot, options.point)),
      dof_(robot.dof()),
      lower_(robot.lowerLimits()),
      upper_(robot.upperLimits()) {
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
  if (options.fixed) {
    std::vector<bool> pinned(dof_, false);
    for (const auto& [name, value] : *options.fixed) {
      const int j = robot.jointIndex(name);
      const Joint& joint = robot.joints[j];
      std::ostringstream msg;
      msg.precision(10);
      if (pinned[j]) throw Error("joint '" + name + "' is fixed twice");
      pinned[j] = true;
      if (!std::isfinite(value) || value < joint.lower || value > joint.upper) {
        msg << "fixed value " << value << " of joint '" << name << "' is outside its limits "
            << describeLimits(joint, robot.length_unit);
        throw Error(msg.str());
      }
      // The parents hold the value as a float.
      const float stored = static_cast<float>(value);
      for (std::size_t p = 0; p < parents.size(); ++p) {
        if (parents[p].q[j] != stored) {
          msg << "point " << p << ": q" << j + 1 << " = " << parents[p].q[j] << " but joint '"
              << name << "' was fixed at " << value << " when the cloud was sampled";
          throw Error(msg.str());
        }
        parents_[p * dof_ + j] = value;
      }
      step_[j] = 0.0;
      pinned_names_.push_back(name);
    }
    return;
  }
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
  generateFromJointValues(kinematics_, first, count, out,
                          [this](std::uint64_t index, double* q) { jointValues(index, q); });
}

void RefineSampler::jointValues(std::uint64_t index, double* q) const {
  const double* parent = &parents_[(index % (parents_.size() / dof_)) * dof_];
  for (int j = 0; j < dof_; ++j) {
    const double moved = parent[j] + step_[j] * (2.0 * rng_.uniform(index, j) - 1.0);
    q[j] = std::clamp(moved, lower_[j], upper_[j]);
  }
}

}  // namespace mcws
