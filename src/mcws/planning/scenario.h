#pragma once
/// \file
/// \brief Planning scenarios for the maintenance-arm patent's planner (`scenarios/*.yaml`): the
/// robot and its obstacles, the start and goal, how the base sways, the planner's settings.

#include <string>

#include "mcws/planning/sway_planner.h"

namespace mcws {

/// \brief A scenario file as read.
struct Scenario {
  std::string name;
  std::string source;      ///< the scenario file
  std::string robot_path;  ///< the robot file it names, resolved
  SwayPlanningProblem problem;
  std::string distance_unit;  ///< how D is measured, e.g. "1/rad, 1/cm" scales, for reports
};

/// \brief Parses a scenario document.
///
/// \code{.yaml}
/// name: maintenance4
/// robot: ../robots/maintenance4.yaml    # relative to the scenario file; needs collision:
/// # or, choosing a URDF's chain as the tools' --base and --tip do (readRobotEntry()):
/// # robot: {file: ../robots/arm.urdf, base: base_link, tip: tool0}  # base, tip optional
/// start: [0 rad, 0 cm, 0 rad, 0 cm]      # every joint value carries its unit; pi allowed
/// goal: [pi rad, 10 cm, 0.5236 rad, 10 cm]
/// joint_scale: [1, 1, 1, 1]              # D = sqrt(sum (scale_i dq_i)^2), dq in rad and the
///                                        # robot's length unit
/// base: {xyz: [0 cm, 0 cm, -20 cm], rpy: [180 deg, 0 deg, 0 deg]}  # optional measured pose
/// sway:
///   pivot: [0 cm, 0 cm, 25 cm]           # a point of the line (world)
///   line: [1, 0, 0]                      # the line's direction (world)
///   swing: 2 deg                         # sigma of the roll about the line
///   slide: 1 cm                          # sigma of the slide along the line
///   covariance: {length: cm, angle: deg, matrix: [[...6 numbers], ...6 rows]}  # optional
///   confidence: 0.95
///   poses: 100                           # n
///   seed: 1
/// planner:
///   candidates: 10                       # m
///   diversity: 0.5                       # penalty of diversePaths()
///   roadmap_nodes: 400
///   max_roadmap_nodes: 3200
///   neighbours: 10
///   roadmap_seed: 1
///   segment_length: 0.5                  # [scaled joint distance]
///   rule: weighted                       # or literal
///   weight: 1
///   acceptance: whole_path               # or patent_p (P >= threshold)
///   max_collision_probability: 0.05      # whole_path: the largest upper end of the 95 % Wilson
///                                        # interval of the whole-path collision rate
///   threshold: 0.9                       # patent_p: the least P
///   allow_goal_shift: false              # may a base shift free a goal in collision?
///   base_step: 5 cm
///   base_range: 30 cm
///   padding: auto                        # or a length, e.g. 3 cm
/// validation: {poses: 10000}
/// \endcode
/// \throws mcws::Error "file:line: field: ..." for a missing or unknown field, a value of the
///   wrong kind or unit, a negative sigma, a covariance that is not positive semi-definite, a
///   confidence outside (0, 1), n or m zero, an acceptance other than whole_path or patent_p, a
///   max_collision_probability outside (0, 1), an allow_goal_shift other than true or false, a
///   start or goal outside the joint limits or of the wrong length, a robot file that does not
///   exist or has no collision geometry, a `robot:` base or tip the robot file does not have
///   (readRobotEntry(), RobotEntry::load()).
Scenario parseScenario(const std::string& text, const std::string& source);

/// \brief parseScenario() of a file. \throws mcws::Error when it cannot be read.
Scenario loadScenario(const std::string& path);

/// \brief A value with its unit, "pi rad", "-pi/6 rad", "30 deg", "10 cm", "0.1 m", converted
/// to rad (for an angle) or to `length_unit`. \param want 'a' for an angle, 'l' for a length.
/// \throws mcws::Error (without file and line) naming the text.
double parseQuantity(const std::string& text, char want, LengthUnit length_unit);

}  // namespace mcws
