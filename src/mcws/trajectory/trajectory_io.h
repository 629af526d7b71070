#pragma once
/// \file
/// \brief Sampled trajectories as CSV text and as a PNG picture (gnuplot).

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <string>

#include "mcws/kinematics/robot.h"
#include "mcws/trajectory/joint_trajectory.h"

namespace mcws {

/// \brief Tool positions toolPose(robot, q).translation() of every sample (samples x 3) [length
/// unit of the robot].
Eigen::MatrixXd toolPositions(const Robot& robot, const SampledTrajectory& trajectory);

/// \brief The trajectory as CSV: a header line, then one line per sample.
///
/// Columns, each name ending in its unit: `t_s` [s]; one per joint position, named by the joint
/// and its unit (`j1_rad`, or `slide_cm` for a prismatic joint in a cm robot); the velocities
/// `j1_rad_per_s`, ... [per s]; the accelerations `j1_rad_per_s2`, ... [per s^2]; the tool
/// position `x_mm`, `y_mm`, `z_mm` [length unit of the robot]. Numbers with 12 significant digits.
/// \throws mcws::Error when the trajectory does not fit the robot.
std::string trajectoryCsv(const Robot& robot, const SampledTrajectory& trajectory);

/// \brief The text of trajectoryCsv() in pieces of at most `rows` samples (the header line goes
/// with the first), each handed to `sink` with the number of samples written so far: a file of a
/// million samples (300 MB) is written without holding it as one string.
/// \throws mcws::Error when the trajectory does not fit the robot, and what `sink` throws.
void writeTrajectoryCsv(const Robot& robot, const SampledTrajectory& trajectory,
                        const std::function<void(const std::string& piece, std::size_t done)>& sink,
                        std::size_t rows = 65536);

/// \brief Renders the trajectory as a PNG with gnuplot: joint positions, velocities and
/// accelerations over time (as Fig. 5 of Liu, Han, Xu & Li 2021) and the tool path in 3-D (as its
/// Fig. 6).
/// \param title first line of the picture.
/// \return the PNG file's bytes.
/// \throws mcws::Error when gnuplot is missing or fails (its first message line).
std::string renderTrajectoryPng(const Robot& robot, const SampledTrajectory& trajectory,
                                const std::string& title);

}  // namespace mcws
