#pragma once
/// \file
/// \brief The summary of a sampled trajectory that a report (mcws_traj --json) gives.

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "mcws/kinematics/robot.h"
#include "mcws/trajectory/joint_trajectory.h"

namespace mcws {

/// \brief What a sampled trajectory does, as JSON: "robot", "length_unit", "samples", the
/// "joints" by name, each joint's "peak_velocity" [per s] and "peak_acceleration" [per s^2]
/// (largest absolute value over the samples), the tool's "tool_start" and "tool_end" positions
/// and "tool_path_length" (pathLength()) [length unit of the robot], with a "units" entry for
/// each of these numbers (jointUnits(): rad or the robot's length unit per joint).
/// \param xyz the tool positions of the samples (toolPositions()), at least one row.
nlohmann::json trajectorySummary(const Robot& robot, const SampledTrajectory& samples,
                                 const Eigen::MatrixXd& xyz);

}  // namespace mcws
