#include "mcws/trajectory/cartesian_line.h"

#include <cmath>
#include <sstream>

#include "mcws/core/decimal.h"
#include "mcws/core/error.h"
#include "mcws/kinematics/forward_kinematics.h"

namespace mcws {
namespace {

/// Default jump threshold for a revolute joint [rad]: at 100 Hz, 10 rad/s.
constexpr double kRevoluteStep = 0.1;
/// Default jump threshold for a prismatic joint, as a fraction of its range.
constexpr double kPrismaticStepFraction = 0.05;

Eigen::VectorXd stepLimits(const Robot& robot, const CartesianLineOptions& options) {
  if (options.max_joint_step.size() > 0) {
    if (options.max_joint_step.size() != robot.dof()) {
      throw Error("cartesian line: " + std::to_string(options.max_joint_step.size()) +
                  " joint step limits for robot '" + robot.name + "' with " +
                  std::to_string(robot.dof()) + " joints");
    }
    if (!(options.max_joint_step.array() > 0.0).all()) {
      throw Error("cartesian line: joint step limits must be positive");
    }
    return options.max_joint_step;
  }
  Eigen::VectorXd limits(robot.dof());
  for (int j = 0; j < robot.dof(); ++j) {
    const Joint& joint = robot.joints[j];
    limits[j] = joint.type == JointType::kRevolute
                    ? kRevoluteStep
                    : std::max(kPrismaticStepFraction * (joint.upper - joint.lower), 1e-12);
  }
  return limits;
}

std::string at(double t) { return "t = " + formatNumber(t) + " s"; }

}  // namespace

void differentiateSamples(SampledTrajectory& tr) {
  const int n = tr.size();
  if (n < 3) throw Error("finite differences need at least 3 samples, got " + std::to_string(n));
  tr.qd = Eigen::MatrixXd::Zero(tr.q.rows(), tr.q.cols());
  tr.qdd = Eigen::MatrixXd::Zero(tr.q.rows(), tr.q.cols());
  for (int i = 1; i + 1 < n; ++i) {
    const double h1 = tr.t[i] - tr.t[i - 1], h2 = tr.t[i + 1] - tr.t[i];
    tr.qd.row(i) = -h2 / (h1 * (h1 + h2)) * tr.q.row(i - 1) + (h2 - h1) / (h1 * h2) * tr.q.row(i) +
                   h1 / (h2 * (h1 + h2)) * tr.q.row(i + 1);
    tr.qdd.row(i) = 2.0 * (tr.q.row(i - 1) / (h1 * (h1 + h2)) - tr.q.row(i) / (h1 * h2) +
                           tr.q.row(i + 1) / (h2 * (h1 + h2)));
  }
  // The parabola through the first (last) three samples has a constant second derivative.
  tr.qdd.row(0) = tr.qdd.row(1);
  tr.qdd.row(n - 1) = tr.qdd.row(n - 2);
}

CartesianLineResult cartesianLine(const Robot& robot, const Eigen::VectorXd& q_start,
                                  const Eigen::Isometry3d& T_world_tool_goal, const IkFunction& ik,
                                  const CartesianLineOptions& options) {
  robot.checkSize(q_start);
  if (!q_start.allFinite()) throw Error("cartesian line: start joint vector is not finite");
  if (!T_world_tool_goal.matrix().allFinite()) throw Error("cartesian line: goal is not finite");
  if (!ik) throw Error("cartesian line: no IK function");
  const std::size_t count = sampleCount(options.duration, options.rate);
  if (count < 3) {
    throw Error("cartesian line: " + std::to_string(count) +
                " samples are too few; raise the rate or the duration");
  }
  const Eigen::VectorXd max_step = stepLimits(robot, options);

  const Eigen::Isometry3d T_start = toolPose(robot, q_start);
  const Eigen::Vector3d p0 = T_start.translation(), p1 = T_world_tool_goal.translation();
  const Eigen::Quaterniond r0(T_start.linear()), r1(T_world_tool_goal.linear());

  CartesianLineResult result;
  SampledTrajectory& tr = result.trajectory;
  tr.t.reserve(count);
  tr.q.resize(static_cast<Eigen::Index>(count), robot.dof());
  Eigen::VectorXd q_previous = q_start;
  for (std::size_t k = 0; k < count; ++k) {
    const double t = k + 1 == count ? options.duration : static_cast<double>(k) / options.rate;
    const double s = blend(options.profile, t / options.duration).s;
    Eigen::Isometry3d T_target = Eigen::Isometry3d::Identity();
    T_target.translation() = p0 + s * (p1 - p0);
    T_target.linear() = r0.slerp(s, r1).toRotationMatrix();
    const std::optional<Eigen::VectorXd> q = ik(T_target, q_previous);
    std::string failure;
    if (!q || q->size() != robot.dof() || !q->allFinite()) {
      const Eigen::Vector3d& p = T_target.translation();
      std::ostringstream msg;
      msg << "IK found no solution at " << at(t) << " for the tool at (" << p.x() << ", " << p.y()
          << ", " << p.z() << ") " << unitName(robot.length_unit);
      result.status = CartesianLineStatus::kIkFailed;
      failure = msg.str();
    } else {
      const Eigen::VectorXd step = (*q - q_previous).cwiseAbs();
      for (int j = 0; j < robot.dof() && failure.empty(); ++j) {
        if (step[j] <= max_step[j]) continue;
        std::ostringstream msg;
        msg << "joint '" << robot.joints[j].name << "' jumps by " << step[j]
            << (robot.joints[j].type == JointType::kRevolute
                    ? " rad"
                    : std::string(" ") + unitName(robot.length_unit))
            << " at " << at(t) << " (at most " << max_step[j] << " per sample)";
        result.status = CartesianLineStatus::kJointJump;
        failure = msg.str();
      }
    }
    if (!failure.empty()) {
      result.failure_time = t;
      result.message = failure;
      tr.q.conservativeResize(static_cast<Eigen::Index>(k), Eigen::NoChange);
      return result;
    }
    tr.t.push_back(t);
    tr.q.row(static_cast<Eigen::Index>(k)) = q->transpose();
    q_previous = *q;
  }
  differentiateSamples(tr);  // the tool starts and ends at rest: qd = 0 at both ends
  return result;
}

}  // namespace mcws
