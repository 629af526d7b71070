#pragma once
/// \file
/// \brief Straight-line tool motion in Cartesian space through inverse kinematics (the camera
/// sweeps of Liu, Han, Xu & Li 2021).

#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <string>

#include "mcws/kinematics/robot.h"
#include "mcws/trajectory/joint_trajectory.h"

namespace mcws {

/// \brief An inverse-kinematics solver: a joint vector [rad | length unit] putting the tool at
/// `T_world_tool_target` (lengths in the robot's unit), searched from `q_seed`, or std::nullopt
/// when it finds none. For example, with solveIk() of inverse_kinematics.h:
/// \code
/// IkFunction ik = [&](const Eigen::Isometry3d& T, const Eigen::VectorXd& seed)
///     -> std::optional<Eigen::VectorXd> {
///   const IkResult r = solveIk(robot, T, seed);
///   if (!r.converged()) return std::nullopt;
///   return r.q;
/// };
/// \endcode
using IkFunction = std::function<std::optional<Eigen::VectorXd>(
    const Eigen::Isometry3d& T_world_tool_target, const Eigen::VectorXd& q_seed)>;

/// \brief Timing and safety of a straight-line move.
struct CartesianLineOptions {
  double duration{1.0};                        ///< [s], > 0
  double rate{100.0};                          ///< samples per second [Hz], > 0
  TimeProfile profile{TimeProfile::kQuintic};  ///< progress along the line over time
  /// Largest change of joint j between two samples [rad | length unit]; larger steps are a jump
  /// (another IK branch, a singularity). Empty: 0.1 rad for revolute joints, 5% of the joint's
  /// range for prismatic ones.
  Eigen::VectorXd max_joint_step;
};

/// \brief How a straight-line move ended.
enum class CartesianLineStatus {
  kSuccess,    ///< every sample solved, no jump
  kIkFailed,   ///< the IK function found no solution for a sample
  kJointJump,  ///< a joint moved more than max_joint_step between two samples
};

/// \brief The sampled move, or where and why it stopped.
struct CartesianLineResult {
  CartesianLineStatus status{CartesianLineStatus::kSuccess};
  double failure_time{0.0};  ///< [s], time of the sample that failed
  std::string message;       ///< one line naming the time (and joint) when status != kSuccess
  /// On success, every sample: q from IK; qd and qdd by second-order finite differences
  /// (non-uniform three-point formulas); qd = 0 at both ends, where the tool is at rest. On
  /// failure, the samples before the failing one (q only).
  SampledTrajectory trajectory;
};

/// \brief Moves the tool on the straight line from its pose at `q_start` to `T_world_tool_goal`.
///
/// At sample time t (t = k / rate and the duration, as sampleTrajectory()) with
/// s = blend(profile, t / duration).s, the target position is p0 + s (p1 - p0) and the target
/// orientation the quaternion slerp from R0 to R1 at s. Each sample's IK is seeded with the
/// previous sample's solution (the first with q_start).
/// \param robot the arm (lengths in its unit).
/// \param q_start start joint vector; the line starts at toolPose(robot, q_start).
/// \param T_world_tool_goal end pose of the tool.
/// \param ik the solver.
/// \throws mcws::Error for bad options or q_start of the wrong size; IK failures and jumps are
///   results, not exceptions.
CartesianLineResult cartesianLine(const Robot& robot, const Eigen::VectorXd& q_start,
                                  const Eigen::Isometry3d& T_world_tool_goal, const IkFunction& ik,
                                  const CartesianLineOptions& options = {});

/// \brief Fills `qd` and `qdd` of a trajectory from its `t` and `q` by non-uniform three-point
/// finite differences (second order); qd is set to 0 at both ends. Needs at least 3 samples.
void differentiateSamples(SampledTrajectory& trajectory);

}  // namespace mcws
