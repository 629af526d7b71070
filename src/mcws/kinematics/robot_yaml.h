#pragma once
/// \file
/// \brief Robot descriptions in YAML (the format: docs/robot-files.md).

#include <string>

#include "mcws/kinematics/robot.h"
#include "mcws/kinematics/robot_urdf.h"

namespace mcws {

/// \brief Reads a robot description file.
/// \param path a `.yaml`/`.yml` robot file, or a `.urdf` file: then the chain from the root link
///   to the single leaf, or the chain `chain` names, read by loadRobotUrdf() (robot_urdf.h),
///   lengths in metres.
/// \param chain the base and tip links of a URDF robot (empty: the whole tree's chain).
/// \return the robot, lengths in the file's length unit, angles converted to [rad].
/// \throws mcws::Error naming the file, line, joint and field of any mistake: missing or
///   unreadable file, YAML syntax, unknown key, missing field, wrong type, NaN or infinite
///   number, unknown unit, convention or joint type, limits in the wrong order, duplicate names;
///   a base or tip link given for a robot file that is not `.urdf`; UrdfChainError for a chain
///   the URDF does not have.
Robot loadRobot(const std::string& path, const UrdfChainOptions& chain = {});

/// \brief Parses a robot description held in a string.
/// \param text the YAML text.
/// \param source name used in error messages (usually the file name).
/// \throws mcws::Error as loadRobot().
Robot parseRobotYaml(const std::string& text, const std::string& source);

}  // namespace mcws
