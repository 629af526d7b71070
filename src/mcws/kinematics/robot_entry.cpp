#include "mcws/kinematics/robot_entry.h"

#include <filesystem>
#include <system_error>

#include "mcws/core/error.h"
#include "mcws/kinematics/robot_yaml.h"

namespace mcws {
namespace {

/// The `package_path:` folders of a URDF entry, resolved against the naming file's directory.
void readPackagePath(const YamlReader& reader, const YAML::Node& node, RobotEntry& entry) {
  if (std::filesystem::path(entry.path).extension() != ".urdf") {
    reader.fail(node, "robot: package_path: needs a .urdf robot ('" + entry.file + "' is not)");
  }
  for (const std::string& folder : reader.texts(node, "robot: package_path")) {
    std::filesystem::path path(folder);
    if (path.is_relative()) path = std::filesystem::path(reader.source()).parent_path() / path;
    std::error_code ec;
    if (!std::filesystem::is_directory(path, ec)) {
      reader.fail(node, "robot: package_path: '" + folder + "' is not a folder (looked for " +
                            path.string() + ")");
    }
    entry.package_path.push_back(path.string());
  }
}

}  // namespace

RobotEntry readRobotEntry(const YamlReader& reader, const YAML::Node& node) {
  const bool map = node.IsMap();
  if (map) reader.checkKeys(node, "robot", {"file", "base", "tip", "package_path", "srdf"});
  RobotEntry entry;
  // An absent key as an undefined node: yaml-cpp's stand-in for it (a "zombie") cannot be kept.
  const auto optional = [&](const char* key) {
    return map && node[key] ? node[key] : YAML::Node(YAML::NodeType::Undefined);
  };
  // Reset, never assigned: assigning a YAML::Node rewrites the node it refers to.
  entry.file_node.reset(map ? reader.require(node, "file", "robot") : node);
  entry.base_node.reset(optional("base"));
  entry.tip_node.reset(optional("tip"));
  if (entry.base_node) entry.chain.base_link = reader.text(entry.base_node, "robot: base");
  if (entry.tip_node) entry.chain.tip_link = reader.text(entry.tip_node, "robot: tip");
  entry.file = reader.text(entry.file_node, map ? "robot: file" : "robot");
  std::filesystem::path path(entry.file);
  if (path.is_relative()) path = std::filesystem::path(reader.source()).parent_path() / path;
  std::error_code ec;  // a name too long for the file system is an error, not an exception
  if (!std::filesystem::exists(path, ec)) {
    reader.fail(entry.file_node, "robot: '" + entry.file + "' " +
                                     (ec ? "cannot be looked up: " + ec.message()
                                         : "does not exist (looked for " + path.string() + ")"));
  }
  if ((entry.base_node || entry.tip_node) && path.extension() != ".urdf") {
    const bool base = bool(entry.base_node);
    reader.fail(base ? entry.base_node : entry.tip_node,
                std::string("robot: ") + (base ? "base" : "tip") +
                    ": base and tip need a .urdf robot ('" + entry.file + "' is not)");
  }
  entry.path = path.string();
  const YAML::Node packages = optional("package_path");
  if (packages) readPackagePath(reader, packages, entry);
  if (const YAML::Node srdf = optional("srdf")) {
    const std::string file = reader.text(srdf, "robot: srdf");
    std::filesystem::path srdf_path(file);
    if (srdf_path.is_relative()) {
      srdf_path = std::filesystem::path(reader.source()).parent_path() / srdf_path;
    }
    if (!std::filesystem::is_regular_file(srdf_path, ec)) {
      reader.fail(srdf, "robot: srdf: '" + file + "' is not a file (looked for " +
                            srdf_path.string() + ")");
    }
    entry.srdf = srdf_path.string();
  }
  return entry;
}

Robot RobotEntry::load(const YamlReader& reader) const {
  try {
    Robot robot = loadRobot(path, chain);
    robot.package_path = package_path;
    robot.srdf = srdf;
    return robot;
  } catch (const UrdfChainError& e) {
    failChain(reader, e);
  }
}

void RobotEntry::failChain(const YamlReader& reader, const UrdfChainError& e) const {
  const UrdfChainError::Problem why = e.problem();
  reader.fail(why == UrdfChainError::Problem::kSeveralLeaves ? file_node
              : why == UrdfChainError::Problem::kUnknownBase ? base_node
                                                             : tip_node,
              "robot: " + e.describe("base", "tip", "robot: {file: FILE, tip: LINK}"));
}

}  // namespace mcws
