#include "mcws/planning/scenario_sections.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "mcws/collision/collision_model.h"
#include "mcws/core/decimal.h"
#include "mcws/core/error.h"
#include "mcws/kinematics/robot_entry.h"
#include "mcws/planning/scenario.h"

namespace mcws {

namespace {

/// An unsigned plain decimal number (the sign is read before it, once).
bool plainNumber(const std::string& text, double& value) {
  return parseDecimal(text, value, false);
}

/// A number, "pi", "2pi", "2*pi", "pi/6", "-3*pi/4"; false when the text is none of these.
bool parseExpression(std::string text, double& value) {
  double sign = 1.0;
  if (!text.empty() && (text[0] == '-' || text[0] == '+')) {
    if (text[0] == '-') sign = -1.0;
    text.erase(0, 1);
  }
  double divisor = 1.0;
  if (const auto slash = text.find('/'); slash != std::string::npos) {
    if (!plainNumber(text.substr(slash + 1), divisor) || divisor == 0.0) return false;
    text = text.substr(0, slash);
  }
  double factor = 1.0;
  if (text.size() >= 2 && text.compare(text.size() - 2, 2, "pi") == 0) {
    factor = M_PI;
    text.erase(text.size() - 2);
    if (!text.empty() && text.back() == '*') {
      text.pop_back();
      if (text.empty()) return false;  // "*pi"
    }
    if (text.empty()) text = "1";
  }
  double number = 0.0;
  if (!plainNumber(text, number)) return false;
  value = sign * number * factor / divisor;
  return std::isfinite(value);
}

}  // namespace

void ScenarioSectionReader::readRobot(const YAML::Node& node, std::string& robot_path,
                                      SwayPlanningProblem& problem) {
  const RobotEntry entry = readRobotEntry(*this, node);
  robot_path = entry.path;
  problem.robot = entry.load(*this);
  problem.collision = loadCollisionModel(problem.robot, robot_path);
  if (!hasGeometry(problem.collision)) {
    fail(entry.file_node, "robot: '" + entry.file + "' has no collision geometry (collision: key)");
  }
  unit_ = problem.robot.length_unit;
}

std::string ScenarioSectionReader::readJointScale(const YAML::Node& scale,
                                                  SwayPlanningProblem& problem) {
  const int dof = problem.robot.dof();
  problem.roadmap.joint_scale = Eigen::VectorXd::Ones(dof);
  if (scale) {
    if (!scale.IsSequence() || static_cast<int>(scale.size()) != dof) {
      fail(scale, "joint_scale: must list " + std::to_string(dof) + " numbers, one per joint");
    }
    for (int j = 0; j < dof; ++j) {
      problem.roadmap.joint_scale[j] =
          number(scale[j], "joint_scale[" + std::to_string(j + 1) + "]");
      if (!(problem.roadmap.joint_scale[j] > 0.0)) {
        fail(scale[j],
             "joint_scale[" + std::to_string(j + 1) + "]: " + scale[j].Scalar() + " must be > 0");
      }
    }
  }
  std::ostringstream unit;
  for (int j = 0; j < dof; ++j) {
    unit << (j ? ", " : "") << problem.roadmap.joint_scale[j] << "/"
         << (problem.robot.joints[j].type == JointType::kRevolute ? "rad" : unitName(unit_));
  }
  return "sqrt(sum (s_i dq_i)^2) with s = " + unit.str();
}

std::string ScenarioSectionReader::readProblem(const YAML::Node& root, const std::string& where,
                                               std::string& robot_path,
                                               SwayPlanningProblem& problem, bool goal) {
  readRobot(require(root, "robot", where), robot_path, problem);
  if (const YAML::Node base = root["base"]) problem.robot.T_world_base = pose(base, "base");
  problem.start = joints(require(root, "start", where), "start", problem.robot);
  problem.goal = goal ? joints(require(root, "goal", where), "goal", problem.robot) : problem.start;
  const std::string distance_unit = readJointScale(root["joint_scale"], problem);
  readSway(require(root, "sway", where), problem);
  if (const YAML::Node planner = root["planner"]) readPlanner(planner, problem);
  if (const YAML::Node validation = root["validation"]) readValidation(validation, problem);
  return distance_unit;
}

void ScenarioSectionReader::readValidation(const YAML::Node& validation,
                                           SwayPlanningProblem& problem) {
  checkKeys(validation, "validation", {"poses"});
  if (validation["poses"])
    problem.validation_poses = count(validation["poses"], "validation: poses");
}

double ScenarioSectionReader::number(const YAML::Node& node, const std::string& field) const {
  const std::string value = scalar(node, field);
  double out = 0.0;
  if (!parseExpression(value, out)) fail(node, field + ": '" + value + "' is not a number");
  return out;
}

std::size_t ScenarioSectionReader::count(const YAML::Node& node, const std::string& field,
                                         std::size_t least, std::size_t most) const {
  const double value = number(node, field);
  if (value < static_cast<double>(least) || value != std::floor(value) ||
      value > static_cast<double>(most)) {
    fail(node, field + ": " + node.Scalar() + " must be a whole number from " +
                   std::to_string(least) + " to " + std::to_string(most));
  }
  return static_cast<std::size_t>(value);
}

std::uint64_t ScenarioSectionReader::seedOf(const YAML::Node& node,
                                            const std::string& field) const {
  const double value = number(node, field);
  if (value < 0.0 || value != std::floor(value) || value > 9e15) {
    fail(node, field + ": " + node.Scalar() + " must be a whole number >= 0");
  }
  return static_cast<std::uint64_t>(value);
}

double ScenarioSectionReader::quantity(const YAML::Node& node, char want,
                                       const std::string& field) const {
  try {
    return parseQuantity(scalar(node, field), want, unit_);
  } catch (const Error& e) {
    fail(node, field + ": " + e.what());
  }
}

Eigen::VectorXd ScenarioSectionReader::joints(const YAML::Node& node, const std::string& field,
                                              const Robot& robot) {
  if (!node.IsSequence()) fail(node, field + ": must be a list of joint values with units");
  if (static_cast<int>(node.size()) != robot.dof()) {
    fail(node, field + ": has " + std::to_string(node.size()) + " values; robot '" + robot.name +
                   "' has " + std::to_string(robot.dof()) + " joints");
  }
  Eigen::VectorXd q(robot.dof());
  for (int j = 0; j < robot.dof(); ++j) {
    const Joint& joint = robot.joints[j];
    const bool revolute = joint.type == JointType::kRevolute;
    q[j] = quantity(node[j], revolute ? 'a' : 'l',
                    field + "[" + std::to_string(j + 1) + "] (joint '" + joint.name + "', " +
                        jointTypeName(joint.type) + ")");
    if (q[j] < joint.lower - 1e-9 || q[j] > joint.upper + 1e-9) {
      fail(node[j], field + ": joint '" + joint.name + "' value " + node[j].Scalar() +
                        " is outside its limits " + describeLimits(joint, unit_));
    }
    q[j] = std::clamp(q[j], joint.lower, joint.upper);
  }
  return q;
}

Eigen::Vector3d ScenarioSectionReader::vector3(const YAML::Node& node, char want,
                                               const std::string& field) const {
  if (!node.IsSequence() || node.size() != 3) fail(node, field + ": must list 3 values");
  Eigen::Vector3d v;
  for (int k = 0; k < 3; ++k) {
    v[k] = want == 'n' ? number(node[k], field) : quantity(node[k], want, field);
  }
  return v;
}

Eigen::Isometry3d ScenarioSectionReader::pose(const YAML::Node& node,
                                              const std::string& field) const {
  checkKeys(node, field, {"xyz", "rpy"});
  const Eigen::Vector3d xyz =
      node["xyz"] ? vector3(node["xyz"], 'l', field + ": xyz") : Eigen::Vector3d::Zero();
  const Eigen::Vector3d rpy =
      node["rpy"] ? vector3(node["rpy"], 'a', field + ": rpy") : Eigen::Vector3d::Zero();
  return poseFromXyzRpy(xyz, rpy);
}

double ScenarioSectionReader::nonNegative(const YAML::Node& node, char want,
                                          const std::string& field, const std::string& what) const {
  const double value = quantity(node, want, field);
  if (value < 0.0) fail(node, field + ": " + what + node.Scalar() + " must be >= 0");
  return value;
}

double ScenarioSectionReader::sigma(const YAML::Node& node, char want,
                                    const std::string& field) const {
  return nonNegative(node, want, field, "sigma ");
}

void ScenarioSectionReader::readSway(const YAML::Node& node, SwayPlanningProblem& problem) {
  checkKeys(node, "sway",
            {"pivot", "line", "swing", "slide", "covariance", "confidence", "poses", "seed"});
  SwayModel& sway = problem.sway;
  sway.pivot = vector3(require(node, "pivot", "sway"), 'l', "sway: pivot");
  sway.line_direction = vector3(require(node, "line", "sway"), 'n', "sway: line");
  if (sway.line_direction.norm() == 0.0) fail(node["line"], "sway: line: must not be zero");
  sway.covariance.setZero();
  if (const YAML::Node swing = node["swing"]) {
    sway.covariance(3, 3) += std::pow(sigma(swing, 'a', "sway: swing"), 2);
  }
  if (const YAML::Node slide = node["slide"]) {
    sway.covariance(0, 0) += std::pow(sigma(slide, 'l', "sway: slide"), 2);
  }
  if (const YAML::Node covariance = node["covariance"]) readCovariance(covariance, sway);
  if (const YAML::Node confidence = node["confidence"]) {
    sway.confidence = number(confidence, "sway: confidence");
    if (!(sway.confidence > 0.0 && sway.confidence < 1.0)) {
      fail(confidence, "sway: confidence " + confidence.Scalar() + " is outside (0, 1)");
    }
  }
  if (const YAML::Node poses = node["poses"]) problem.base_poses = count(poses, "sway: poses");
  if (const YAML::Node seed = node["seed"]) problem.seed = seedOf(seed, "sway: seed");
  try {
    SwaySampler check(sway);  // positive semi-definite, symmetric
  } catch (const Error& e) {
    fail(node["covariance"] ? node["covariance"] : node, e.what());
  }
}

void ScenarioSectionReader::readCovariance(const YAML::Node& node, SwayModel& sway) {
  checkKeys(node, "sway: covariance", {"length", "angle", "matrix"});
  const std::string length = scalar(require(node, "length", "sway: covariance"), "length");
  const std::string angle = scalar(require(node, "angle", "sway: covariance"), "angle");
  double length_scale = 0.0, angle_scale = 0.0;
  try {
    length_scale = parseQuantity("1 " + length, 'l', unit_);
    angle_scale = parseQuantity("1 " + angle, 'a', unit_);
  } catch (const Error& e) {
    fail(node, std::string("sway: covariance: ") + e.what());
  }
  const YAML::Node matrix = require(node, "matrix", "sway: covariance");
  if (!matrix.IsSequence() || matrix.size() != 6) {
    fail(matrix, "sway: covariance: matrix must have 6 rows (x, y, z, roll, pitch, yaw)");
  }
  for (int r = 0; r < 6; ++r) {
    if (!matrix[r].IsSequence() || matrix[r].size() != 6) {
      fail(matrix[r], "sway: covariance: row " + std::to_string(r + 1) + " must have 6 numbers");
    }
    for (int c = 0; c < 6; ++c) {
      const double scale =
          (r < 3 ? length_scale : angle_scale) * (c < 3 ? length_scale : angle_scale);
      sway.covariance(r, c) += number(matrix[r][c], "sway: covariance") * scale;
    }
  }
  for (int k = 0; k < 6; ++k) {
    if (sway.covariance(k, k) < 0.0) {
      fail(matrix[k], "sway: covariance: variance " + formatNumber(sway.covariance(k, k)) +
                          " of row " + std::to_string(k + 1) + " is negative");
    }
  }
}

void ScenarioSectionReader::readPlanner(const YAML::Node& node, SwayPlanningProblem& problem) {
  checkKeys(node, "planner",
            {"candidates", "diversity", "roadmap_nodes", "max_roadmap_nodes", "neighbours",
             "roadmap_seed", "segment_length", "rule", "weight", "acceptance",
             "max_collision_probability", "threshold", "threshold_on", "allow_goal_shift",
             "base_step", "base_range", "padding"});
  readSearch(node, problem);
  readRule(node, problem);
  readAcceptance(node, problem);
  readBaseShift(node, problem);
}

void ScenarioSectionReader::readSearch(const YAML::Node& node, SwayPlanningProblem& problem) {
  if (node["candidates"]) problem.candidates = count(node["candidates"], "planner: candidates");
  if (node["diversity"]) problem.diversity = nonNegative(node["diversity"], "planner: diversity");
  if (node["roadmap_nodes"])
    problem.roadmap.nodes = count(node["roadmap_nodes"], "planner: roadmap_nodes");
  if (node["max_roadmap_nodes"])
    problem.roadmap.max_nodes = count(node["max_roadmap_nodes"], "planner: max_roadmap_nodes");
  problem.roadmap.max_nodes = std::max(problem.roadmap.max_nodes, problem.roadmap.nodes);
  if (node["neighbours"])
    problem.roadmap.neighbours =
        static_cast<unsigned>(count(node["neighbours"], "planner: neighbours"));
  if (node["roadmap_seed"])
    problem.roadmap.seed = seedOf(node["roadmap_seed"], "planner: roadmap_seed");
  if (node["segment_length"]) {
    problem.segment_length = number(node["segment_length"], "planner: segment_length");
    if (!(problem.segment_length > 0.0))
      fail(node["segment_length"],
           "planner: segment_length " + node["segment_length"].Scalar() + " must be > 0");
  }
}

void ScenarioSectionReader::readRule(const YAML::Node& node, SwayPlanningProblem& problem) {
  if (const YAML::Node rule = node["rule"]) {
    const std::string name = scalar(rule, "planner: rule");
    if (name == "literal") {
      problem.score.rule = ScoreRule::kLiteral;
    } else if (name == "weighted") {
      problem.score.rule = ScoreRule::kWeighted;
    } else {
      fail(rule, "planner: rule '" + name + "' is not literal or weighted");
    }
  }
  if (node["weight"]) problem.score.weight = nonNegative(node["weight"], "planner: weight");
}

void ScenarioSectionReader::readAcceptance(const YAML::Node& node, SwayPlanningProblem& problem) {
  if (const YAML::Node threshold = node["threshold"]) {
    problem.threshold = number(threshold, "planner: threshold");
    if (problem.threshold < 0.0 || problem.threshold > 1.0) {
      fail(threshold, "planner: threshold " + threshold.Scalar() + " is outside [0, 1]");
    }
  }
  if (const YAML::Node on = node["threshold_on"]) {
    // The old switch between P and the whole-path free fraction as a point estimate.
    fail(on,
         "planner: threshold_on is no longer read: acceptance: whole_path (the default, "
         "with max_collision_probability) or acceptance: patent_p (with threshold)");
  }
  if (const YAML::Node acceptance = node["acceptance"]) {
    const std::string name = scalar(acceptance, "planner: acceptance");
    if (name == "whole_path") {
      problem.acceptance = Acceptance::kWholePath;
    } else if (name == "patent_p") {
      problem.acceptance = Acceptance::kPatentP;
    } else {
      fail(acceptance, "planner: acceptance '" + name + "' is not whole_path or patent_p");
    }
  }
  if (const YAML::Node most = node["max_collision_probability"]) {
    problem.max_collision_probability = number(most, "planner: max_collision_probability");
    if (!(problem.max_collision_probability > 0.0 && problem.max_collision_probability < 1.0)) {
      fail(most, "planner: max_collision_probability " + most.Scalar() +
                     " is outside (0, 1) (a fraction, e.g. 0.05)");
    }
  }
}

void ScenarioSectionReader::readBaseShift(const YAML::Node& node, SwayPlanningProblem& problem) {
  if (const YAML::Node shift = node["allow_goal_shift"]) {
    const std::string value = scalar(shift, "planner: allow_goal_shift");
    if (value != "true" && value != "false") {
      fail(shift, "planner: allow_goal_shift '" + value + "' is not true or false");
    }
    problem.allow_goal_shift = value == "true";
  }
  if (node["base_step"])
    problem.base_step = nonNegative(node["base_step"], 'l', "planner: base_step", "");
  if (node["base_range"])
    problem.base_range = nonNegative(node["base_range"], 'l', "planner: base_range", "");
  if (const YAML::Node padding = node["padding"]) {
    problem.padding = padding.IsScalar() && padding.Scalar() == "auto"
                          ? -1.0
                          : nonNegative(padding, 'l', "planner: padding", "");
  }
}

double ScenarioSectionReader::nonNegative(const YAML::Node& node, const std::string& field) const {
  const double value = number(node, field);
  if (value < 0.0) fail(node, field + ": " + node.Scalar() + " must be >= 0");
  return value;
}

double parseQuantity(const std::string& text, char want, LengthUnit length_unit) {
  std::istringstream words(text);
  std::string value, unit, extra;
  words >> value >> unit;
  if (value.empty() || unit.empty() || (words >> extra)) {
    throw Error("'" + text + "' is not a value and a unit (e.g. 'pi rad', '30 deg', '10 cm')");
  }
  double number = 0.0;
  if (!parseExpression(value, number)) throw Error("'" + value + "' is not a number (or pi)");
  if (unit == "rad" || unit == "deg") {
    if (want != 'a') throw Error("'" + text + "' is an angle; a length is needed (m, cm, mm)");
    return unit == "rad" ? number : number * M_PI / 180.0;
  }
  const LengthUnit units[] = {LengthUnit::kMetre, LengthUnit::kCentimetre, LengthUnit::kMillimetre};
  for (LengthUnit u : units) {
    if (unit == unitName(u)) {
      if (want != 'l') throw Error("'" + text + "' is a length; an angle is needed (rad, deg)");
      return number * unitInMetres(u) / unitInMetres(length_unit);
    }
  }
  throw Error("unknown unit '" + unit + "' in '" + text + "' (rad, deg, m, cm, mm)");
}

}  // namespace mcws
