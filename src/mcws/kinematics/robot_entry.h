#pragma once
/// \file
/// \brief A robot named by another YAML file (a planning scenario, a behaviour model): its file
/// and, for a URDF, the chain to read.

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "mcws/core/yaml_reader.h"
#include "mcws/kinematics/robot.h"
#include "mcws/kinematics/robot_urdf.h"

namespace mcws {

/// \brief The `robot:` entry of a YAML file, as read by readRobotEntry().
struct RobotEntry {
  std::string file;                ///< as written
  std::string path;                ///< resolved against the naming file's directory
  UrdfChainOptions chain;          ///< the `base:` and `tip:` links (empty when not given)
  YAML::Node file_node;            ///< where the file is named, for messages
  YAML::Node base_node, tip_node;  ///< the `base:` and `tip:` values (undefined when absent)
  /// The `package_path:` folders, resolved against the naming file's directory: where package://
  /// mesh URIs are looked for first (Robot::package_path).
  std::vector<std::string> package_path;
  /// The `srdf:` file, resolved against the naming file's directory (Robot::srdf); empty for none.
  std::string srdf;

  /// \brief loadRobot(path, chain), with Robot::package_path and Robot::srdf set. \param reader the
  /// naming file's reader, for messages. \throws mcws::Error as loadRobot(); for a UrdfChainError,
  /// "source:line: robot: tip: 'hand'
  ///   is not a link of robot 'arm' in arm.urdf" at the line of the key it concerns, or
  ///   "source:line: robot: arm.urdf: link 'world' has 2 leaf links below it (tool0, ee_link):
  ///   choose one with robot: {file: FILE, tip: LINK}" at the file's line.
  Robot load(const YamlReader& reader) const;

  /// \brief Throws the UrdfChainError `e` of loading this entry as load() words it.
  [[noreturn]] void failChain(const YamlReader& reader, const UrdfChainError& e) const;
};

/// \brief Reads a `robot:` entry: either the robot file alone, or a map choosing a URDF's chain,
/// the same choice as the tools' --base and --tip:
/// \code{.yaml}
/// robot: ../robots/arm.urdf
/// robot: {file: ../robots/arm.urdf, base: base_link, tip: tool0}   # base, tip optional
/// robot: {file: arm/urdf/arm.urdf, package_path: [ws/src]}         # a folder or a list
/// robot: {file: arm.urdf, srdf: arm.srdf}   # <disable_collisions> pairs the checks skip
/// \endcode
/// A relative file is resolved against the directory of the reader's source.
/// \param reader the naming file's reader (its source and messages).
/// \param node the value of `robot:`.
/// \throws mcws::Error "source:line: robot: ..." for a list or an empty value, an unknown key, a
///   missing `file:`, an empty link name, a file that does not exist, `base:`, `tip:` or
///   `package_path:` with a robot file that is not `.urdf`, a `package_path:` entry that is not
///   a folder, an `srdf:` that is not a file.
RobotEntry readRobotEntry(const YamlReader& reader, const YAML::Node& node);

}  // namespace mcws
