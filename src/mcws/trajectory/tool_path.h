#pragma once
/// \file
/// \brief The tool's path: a straight tool line followed by inverse kinematics, and the length
/// of a sampled path.

#include <Eigen/Geometry>

#include "mcws/kinematics/robot.h"
#include "mcws/trajectory/cartesian_line.h"
#include "mcws/trajectory/joint_trajectory.h"

namespace mcws {

/// \brief The straight tool line from the pose of `q_start` to `T_goal` (cartesianLine()), each
/// sample solved by solveIk() seeded with the previous one, with 2 restarts (seeded so, a restart
/// means a new branch).
/// \throws mcws::Error with cartesianLine()'s message when the line cannot be followed.
SampledTrajectory ikToolLine(const Robot& robot, const Eigen::VectorXd& q_start,
                             const Eigen::Isometry3d& T_goal, const CartesianLineOptions& options);

/// \brief The length of the polyline through the rows of `xyz` (toolPositions()) [length unit].
double pathLength(const Eigen::MatrixXd& xyz);

}  // namespace mcws
