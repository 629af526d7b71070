#include "mcws/kinematics/robot_yaml.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <set>
#include <sstream>

#include "mcws/core/error.h"
#include "mcws/core/text_file.h"
#include "mcws/core/yaml_reader.h"
#include "mcws/kinematics/robot_urdf.h"

namespace mcws {
namespace {

constexpr double kDegree = M_PI / 180.0;

/// Reads one document and turns every mistake into a message with file and line.
class RobotYamlReader : YamlReader {
 public:
  explicit RobotYamlReader(std::string source) : YamlReader(std::move(source)) {}

  Robot read(const YAML::Node& root) {
    if (!root.IsMap()) fail(root, "the document must be a map of robot fields");
    checkKeys(root, "robot",
              {"name", "description", "units", "convention", "base", "tool", "joints",
               "collision"});  // collision: read by mcws::parseCollisionYaml

    Robot robot;
    robot.source = source();
    robot.name = field(root, "name", "robot");
    if (robot.name.empty()) fail(root["name"], "name: must not be empty");
    checkPrintable(root["name"], "");
    readUnits(require(root, "units", "robot"), robot);

    const std::string convention = field(root, "convention", "robot");
    if (convention != "standard" && convention != "modified") {
      fail(root["convention"],
           "convention: '" + convention + "' is not a D-H convention (standard or modified)");
    }
    if (root["base"]) robot.T_world_base = readPose(root["base"], "base");
    if (root["tool"]) robot.T_flange_tool = readPose(root["tool"], "tool");

    const YAML::Node joints = require(root, "joints", "robot");
    if (!joints.IsSequence() || joints.size() == 0) {
      fail(joints, "joints: must be a non-empty list of joints");
    }
    std::set<std::string> names;
    Eigen::Isometry3d T_previous_fixed = Eigen::Isometry3d::Identity();
    for (std::size_t i = 0; i < joints.size(); ++i) {
      const YAML::Node row = joints[i];
      const std::string where = "joint " + std::to_string(i + 1);
      if (!row.IsMap()) fail(row, where + ": must be a map of D-H fields");
      Joint joint;
      joint.name = field(row, "name", where);
      if (joint.name.empty()) fail(row["name"], where + ": name must not be empty");
      checkPrintable(row["name"], where + ": ");
      if (joint.name.find_first_of("=, \t") != std::string::npos) {
        fail(row["name"], where + ": name '" + joint.name + "' contains '=', ',' or a space");
      }
      const std::string label = where + " '" + joint.name + "'";
      checkKeys(row, label, {"name", "type", "a", "alpha", "d", "theta", "limits"});
      if (!names.insert(joint.name).second) fail(row["name"], label + ": duplicate joint name");
      const std::string type = field(row, "type", label);
      if (type == "revolute") {
        joint.type = JointType::kRevolute;
      } else if (type == "prismatic") {
        joint.type = JointType::kPrismatic;
      } else {
        fail(row["type"], label + ": type '" + type + "' is not revolute or prismatic");
      }
      const double a = number(row, "a", label);
      const double alpha = number(row, "alpha", label) * angle_scale_;
      const double d = number(row, "d", label);
      const double theta = row["theta"] ? number(row, "theta", label) * angle_scale_ : 0.0;
      readLimits(row, label, joint);

      // Motion about / along the joint frame's z axis in both conventions; see robot.h.
      joint.axis = Eigen::Vector3d::UnitZ();
      if (convention == "standard") {
        // Rz(theta + q) Tz(d) Tx(a) Rx(alpha) = Rz(q) * G, or Tz(q) * G for a prismatic joint,
        // with G = Rz(theta) Tz(d) Tx(a) Rx(alpha) fixed and applied after the motion.
        joint.T_parent_joint = T_previous_fixed;
        T_previous_fixed = dhStandard(a, alpha, d, theta);
      } else {
        // Rx(alpha) Tx(a) Rz(theta + q) Tz(d) = G * Rz(q), or G * Tz(q) when prismatic.
        joint.T_parent_joint = dhModified(a, alpha, d, theta);
      }
      robot.joints.push_back(joint);
    }
    robot.T_last_flange =
        convention == "standard" ? T_previous_fixed : Eigen::Isometry3d::Identity();
    return robot;
  }

 private:
  /// Throws unless the name `node` holds has no control byte (mcws::hasControlByte()); `where`
  /// starts the message ("" or "joint 2: ").
  void checkPrintable(const YAML::Node& node, const std::string& where) const {
    if (hasControlByte(node.Scalar())) {
      fail(node, where + "name '" + escapedControlBytes(node.Scalar()) +
                     "' holds a control byte (names are printable text)");
    }
  }

  /// The single value of field `key` of `map`, possibly empty.
  std::string field(const YAML::Node& map, const std::string& key, const std::string& where) const {
    const YAML::Node node = require(map, key, where);
    if (!node.IsScalar()) fail(node, where + ": field '" + key + "' must be a single value");
    return node.Scalar();
  }

  double number(const YAML::Node& map, const std::string& key, const std::string& where) const {
    return finiteNumber(require(map, key, where), where + ": field '" + key + "'");
  }

  void readUnits(const YAML::Node& units, Robot& robot) {
    if (!units.IsMap()) fail(units, "units: must be a map with 'length' and 'angle'");
    checkKeys(units, "units", {"length", "angle"});
    const std::string length = field(units, "length", "units");
    const std::optional<LengthUnit> unit = lengthUnitNamed(length);
    if (!unit) fail(units["length"], "units: length unit '" + length + "' is not m, cm or mm");
    robot.length_unit = *unit;
    const std::string angle = field(units, "angle", "units");
    if (angle == "deg") {
      angle_scale_ = kDegree;
    } else if (angle == "rad") {
      angle_scale_ = 1.0;
    } else {
      fail(units["angle"], "units: angle unit '" + angle + "' is not deg or rad");
    }
  }

  Eigen::Vector3d vector3(const YAML::Node& map, const std::string& key,
                          const std::string& where) const {
    const YAML::Node node = map[key];
    if (!node) return Eigen::Vector3d::Zero();
    if (!node.IsSequence() || node.size() != 3)
      fail(node, where + ": " + key + " must be [x, y, z]");
    Eigen::Vector3d v;
    for (int k = 0; k < 3; ++k) v[k] = finiteNumber(node[k], where + ": " + key);
    return v;
  }

  Eigen::Isometry3d readPose(const YAML::Node& node, const std::string& where) const {
    if (!node.IsMap()) fail(node, where + ": must be a map with 'xyz' and/or 'rpy'");
    checkKeys(node, where, {"xyz", "rpy"});
    return poseFromXyzRpy(vector3(node, "xyz", where), vector3(node, "rpy", where) * angle_scale_);
  }

  void readLimits(const YAML::Node& row, const std::string& label, Joint& joint) const {
    const YAML::Node limits = require(row, "limits", label);
    if (!limits.IsSequence() || limits.size() != 2) {
      fail(limits, label + ": limits must be [min, max]");
    }
    const double scale = joint.type == JointType::kRevolute ? angle_scale_ : 1.0;
    const double lower = finiteNumber(limits[0], label + ": limits min");
    const double upper = finiteNumber(limits[1], label + ": limits max");
    if (lower > upper) {
      std::ostringstream msg;
      msg << label << ": limits min " << lower << " is greater than max " << upper;
      fail(limits, msg.str());
    }
    joint.lower = lower * scale;
    joint.upper = upper * scale;
  }

  double angle_scale_{kDegree};
};

}  // namespace

Robot parseRobotYaml(const std::string& text, const std::string& source) {
  return RobotYamlReader(source).read(loadYamlDocument(text, source, "a robot file"));
}

Robot loadRobot(const std::string& path, const UrdfChainOptions& chain) {
  if (std::filesystem::path(path).extension() == ".urdf") return loadRobotUrdf(path, chain);
  if (!chain.base_link.empty() || !chain.tip_link.empty()) {
    throw Error(path +
                ": a base or tip link is chosen only in a .urdf robot (a D-H robot's chain "
                "is its joints)");
  }
  // The file name is recorded in every cloud of the robot (mcws::io::CloudProvenance).
  checkPrintableName(std::filesystem::path(path).filename().string(), "robot file");
  return parseRobotYaml(readTextFile(path, "robot file"), path);
}

}  // namespace mcws
