#pragma once
/// \file
/// \brief Robot descriptions in YAML (the format: docs/robot-files.md).

#include <string>

#include "mcws/kinematics/robot.h"

namespace mcws {

/// \brief Reads a robot description file.
/// \param path a `.yaml`/`.yml` robot file, or a `.urdf` file: then the chain from the root link
///   to the single leaf, read by loadRobotUrdf() (robot_urdf.h), lengths in metres.
/// \return the robot, lengths in the file's length unit, angles converted to [rad].
/// \throws mcws::Error naming the file, line, joint and field of any mistake: missing or
///   unreadable file, YAML syntax, unknown key, missing field, wrong type, NaN or infinite
///   number, unknown unit, convention or joint type, limits in the wrong order, duplicate names.
Robot loadRobot(const std::string& path);

/// \brief Parses a robot description held in a string.
/// \param text the YAML text.
/// \param source name used in error messages (usually the file name).
/// \throws mcws::Error as loadRobot().
Robot parseRobotYaml(const std::string& text, const std::string& source);

}  // namespace mcws
