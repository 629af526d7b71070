#pragma once
/// \file
/// \brief A power-line study file (`studies/*.yaml`): the robot, the line it works on (conductors
/// and fittings), the work targets, the stops along the line, and the settings of each stage of
/// mcws_study (workspace, reach, placement, planning under sway).

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mcws/behavior/behavior_model.h"
#include "mcws/collision/collision_model.h"
#include "mcws/planning/sway_planner.h"
#include "mcws/reach/reach_map.h"
#include "mcws/reach/reach_study.h"

namespace mcws {

/// \brief A conductor: a polyline of points with a radius, each segment a capsule [length unit].
struct Conductor {
  std::string name;
  std::vector<Eigen::Vector3d> points;  ///< world [length unit], at least two
  double radius{0.0};                   ///< [length unit]
};

/// \brief A named work target.
struct StudyTarget {
  std::string name;  ///< "spacer_3": the file's name and the point's index from 1, or the pose's
  ReachTarget target;
};

/// \brief Settings of the workspace stage (mcws_sample, mcws_boundary, mcws_measure,
/// mcws_envelope with their defaults otherwise).
struct StudyWorkspace {
  std::size_t samples{20000};
  /// New samples near the boundary points' configurations (mcws_refine --samples), 0 to 10^9;
  /// 0 (the default): none (no refined cloud; the volume with the edge correction). Else the
  /// volume and envelope are those of the refined cloud, without the edge correction (its
  /// samples lie on the edge), as mcws_measure --correction none measures it.
  std::size_t refine{0};
  double alpha{3.0};    ///< [local spacings] (mcws_measure --alpha)
  double azimuth{0.0};  ///< the drawing's side view [rad] (mcws_envelope --azimuth)
};

/// \brief Settings of the reach stage (mcws_reach --map, mcws_reach --targets, mcws_place).
struct StudyReach {
  ReachGrid grid;                  ///< resolution [length unit], directions, rolls
  std::uint64_t samples{200000};   ///< map samples, 1 to 2^53 (mcws_place --samples)
  double approach_tolerance{0.0};  ///< [rad]
  int ik_starts{4};                ///< 1 to 1000 (mcws_place --ik-starts)
  std::size_t plan_targets{0};  ///< targets planned at the chosen stop (the first reached); 0 all
};

/// \brief The scan of P against the base offset at the chosen stop (mcws_plan --plot-offsets):
/// each planned target planned again with the base shifted along the line by -range, ...,
/// +range, step apart, the goal kept in joint space. range 0: no scan.
struct StudyOffsets {
  double range{0.0};  ///< largest shift either way [length unit]
  double step{0.0};   ///< [length unit]
};

/// \brief The optional behaviour rehearsal (mcws_behave): the cleaning job of a behaviour model.
struct StudyBehaviour {
  std::string model;  ///< the model file, resolved; empty: no rehearsal
  int insulators{0};  ///< discs of the job, 1 to 200
  /// The model as read from `model` when the study was read: validated (as mcws_behave
  /// --check) and its job set up for `insulators` discs; unset when there is no rehearsal.
  std::optional<BehaviorModel> loaded;
};

/// \brief A study file as read.
struct Study {
  std::string name;
  std::string source;      ///< the study file
  std::string robot_path;  ///< the robot file it names, resolved
  /// The files read: the study, the robot, the targets files, the behaviour model and its robot.
  std::vector<std::string> inputs;
  /// The robot (its T_world_base the measured pose at stop 0), its collision model with the
  /// study's line as environment, start, sway, planner and validation as a scenario's; goal
  /// unset (each target's is found by IK).
  SwayPlanningProblem problem;
  std::string distance_unit;  ///< how D is measured (Scenario::distance_unit)
  std::vector<Conductor> conductors;
  std::vector<BodySpec> fittings;  ///< one shape each, world frame
  /// How many objects the robot file's own environment had (replaced by the line).
  std::size_t replaced_environment{0};
  std::vector<StudyTarget> targets;
  std::vector<double> stops;  ///< base offsets along the sway's line direction [length unit]
  std::uint64_t seed{1};      ///< of the workspace samples, the reach map and the IK starts
  StudyWorkspace workspace;
  StudyReach reach;
  StudyOffsets offsets;
  StudyBehaviour behaviour;
};

/// \brief Parses a study document.
///
/// \code{.yaml}
/// name: maintenance4 on a two-conductor line
/// robot: ../robots/maintenance4.yaml     # as a scenario's robot (needs collision geometry)
/// seed: 1                                # workspace samples, reach map, IK starts
/// line:                                  # replaces the robot file's own environment
///   conductors:                          # polylines with radii; each segment a capsule
///     - {name: conductor_a, radius: 1.5 cm, points: [[-300 cm, 0 cm, 25 cm], [300 cm, 0 cm, 25
///     cm]]}
///   fittings:                            # spacers, dampers, clamps: the shapes of a robot
///     - {name: spacer, type: box, size: [6, 4, 76], xyz: [50, -35, -10]}  # file's environment:
///                                        # numbers in the robot's length unit, angles in deg
/// targets:                               # a targets file (PCD with normals, CSV) or poses;
///   - {file: ../robots/maintenance4_spacer_targets.pcd, name: spacer, standoff: 5 cm}
///                                        # standoff: the tool point that far off the surface
///   - {name: clamp, point: [0 cm, -33 cm, -40 cm], normal: [0, 1, 0]}
/// stops: {from: -20 cm, to: 60 cm, step: 10 cm}   # base offsets along the sway's line
/// start: [0 rad, 0 cm, 0 rad, 0 cm]
/// joint_scale: [1, 1, 1, 1]
/// sway: {...}                            # as a scenario's
/// planner: {...}
/// validation: {poses: 2000}
/// workspace: {samples: 20000, refine: 20000, alpha: 3, azimuth: 0 deg}
/// reach: {resolution: 4 cm, samples: 200000, orientations: 50, rolls: 1,
///         approach_tolerance: 5 deg, ik_starts: 4, plan_targets: 2}
/// offsets: {range: 10 cm, step: 5 cm}   # optional: P against the base offset at the stop
/// behaviour: {model: ../robots/insulator_cleaner_behaviors.yaml, insulators: 3}  # optional
/// \endcode
/// \throws mcws::Error "file:line: field: ..." for a mistake in any section (as parseScenario()
///   for the scenario's sections), an unknown fitting type, a conductor with fewer than two
///   points or a radius not > 0, a targets file that cannot be read, an empty stop range (step
///   not > 0 or to below from), a robot without collision geometry, a count outside its range
///   ("reach: samples: 0 must be a whole number from 1 to 9007199254740992"), a behaviour model
///   that cannot be read, is not valid or cannot run the job ("behaviour: model: <model
///   file>[:line]: <why>").
Study parseStudy(const std::string& text, const std::string& source);

/// \brief parseStudy() of a file. \throws mcws::Error when it cannot be read.
Study loadStudy(const std::string& path);

/// \brief The line's objects as collision bodies in the world: one body per conductor (a
/// capsule per segment), one per fitting.
std::vector<BodySpec> lineBodies(const Study& study);

}  // namespace mcws
