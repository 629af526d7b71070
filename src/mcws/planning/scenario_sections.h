#pragma once
/// \file
/// \brief The sections a planning scenario shares with the files built on it (a study): the
/// robot and its collision model, joint values with units, poses, the sway, the planner and the
/// validation. For the readers that link yaml-cpp.

#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <set>
#include <string>

#include "mcws/core/length_unit.h"
#include "mcws/core/yaml_reader.h"
#include "mcws/planning/sway_planner.h"

namespace mcws {

/// \brief Reads the scenario's sections (see parseScenario() for their fields); every mistake
/// "file:line: field: ...". Quantities carry their units ("10 cm", "pi rad") and are converted
/// to the robot's length unit once readRobot() has read it.
class ScenarioSectionReader : public YamlReader {
 public:
  explicit ScenarioSectionReader(std::string source) : YamlReader(std::move(source)) {}

  /// The robot (`robot: FILE`, or a map choosing a URDF's chain: readRobotEntry()) and its
  /// collision model, of the same chain, into `problem`; the robot file's path into
  /// `robot_path`; sets the length unit of the quantities read after it.
  /// \throws mcws::Error also for a robot without collision geometry.
  void readRobot(const YAML::Node& node, std::string& robot_path, SwayPlanningProblem& problem);
  /// `joint_scale` (absent: all 1) into problem.roadmap.joint_scale; returns the distance's
  /// unit in words ("sqrt(sum (s_i dq_i)^2) with s = 1/rad, 1/cm").
  std::string readJointScale(const YAML::Node& node, SwayPlanningProblem& problem);
  /// The sections of a planning problem in `root` (a map; `where` names it in messages):
  /// robot, base (optional), start, goal (when `goal`), joint_scale, sway, planner and
  /// validation (optional); returns the distance's unit (readJointScale()).
  std::string readProblem(const YAML::Node& root, const std::string& where, std::string& robot_path,
                          SwayPlanningProblem& problem, bool goal);
  /// The `validation` section ({poses: N}).
  void readValidation(const YAML::Node& node, SwayPlanningProblem& problem);
  /// The length unit quantities are converted to (the robot's).
  LengthUnit lengthUnit() const { return unit_; }
  /// The largest count read by count() unless it names another.
  static constexpr std::size_t kMaxCount = 1000000000;
  double number(const YAML::Node& node, const std::string& field) const;
  /// A whole number from `least` to `most`; else fails with "field: VALUE must be a whole number
  /// from LEAST to MOST".
  std::size_t count(const YAML::Node& node, const std::string& field, std::size_t least = 1,
                    std::size_t most = kMaxCount) const;
  std::uint64_t seedOf(const YAML::Node& node, const std::string& field) const;
  double quantity(const YAML::Node& node, char want, const std::string& field) const;
  /// Joint values with units, one per joint, within the limits.
  Eigen::VectorXd joints(const YAML::Node& node, const std::string& field, const Robot& robot);
  Eigen::Vector3d vector3(const YAML::Node& node, char want, const std::string& field) const;
  Eigen::Isometry3d pose(const YAML::Node& node, const std::string& field) const;
  /// A quantity that must not be negative; `what` names it in the message ("sigma", ...).
  double nonNegative(const YAML::Node& node, char want, const std::string& field,
                     const std::string& what) const;
  double sigma(const YAML::Node& node, char want, const std::string& field) const;
  void readSway(const YAML::Node& node, SwayPlanningProblem& problem);
  void readCovariance(const YAML::Node& node, SwayModel& sway);
  void readPlanner(const YAML::Node& node, SwayPlanningProblem& problem);
  /// The planner's paths and roadmap: candidates, diversity, roadmap sizes and seed, segments.
  void readSearch(const YAML::Node& node, SwayPlanningProblem& problem);
  /// The score at shared nodes: rule and weight.
  void readRule(const YAML::Node& node, SwayPlanningProblem& problem);
  /// Step s50's criterion: acceptance, threshold, max_collision_probability.
  void readAcceptance(const YAML::Node& node, SwayPlanningProblem& problem);
  /// Step s70's base shift: allow_goal_shift, base_step, base_range, and the comparison's padding.
  void readBaseShift(const YAML::Node& node, SwayPlanningProblem& problem);
  double nonNegative(const YAML::Node& node, const std::string& field) const;

 private:
  LengthUnit unit_{LengthUnit::kMetre};
};

}  // namespace mcws
