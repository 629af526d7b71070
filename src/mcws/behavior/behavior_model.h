#pragma once
/// \file
/// \brief The behaviour model of Wang et al. 2018 as data: basic behaviours, combined behaviours as
/// finite state machines, and the robot's state vector (sections 1.4, 2.1, 2.2).
///
/// The file format is documented, item by item, in robots/insulator_cleaner_behaviors.yaml.
/// In short:
/// - `state_vector`: the components of the robot's pose (Table 1 of Wang et al. 2018), each with
///   its values; a component driven to positions lists them (`{home: 0 mm, extended: 155 mm}`).
///   `pose_rules` forbid poses (its Table 2): a pose breaks a rule when it matches every `when`
///   entry and misses a `require` entry.
/// - `basic_behaviors`: eq. (1), [name, (input ports), (output ports), (parameters), body];
///   `timeout` optional. The body names the actuator, the one component it changes and, for
///   each value it can set, the command and the ending event.
/// - `poses`: the pose of every FSM state. A state has one pose whichever combined behaviour
///   passes through it. checkPoseConsistency() checks that each transition's behaviour turns the
///   source pose into the target pose.
/// - `combined_behaviors`: eq. (2)-(3), M = {Q, Sigma, delta, q0, F}, as a table of transitions
///   {from, to, run, (target), event}: `run` is the behaviour run in `from` (it belongs to the
///   pair (combined behaviour, state)), `event` its ending event, which fires the transition.
///
/// Every item keeps the line of the file it came from [1-based], for messages.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "mcws/behavior/fsm.h"
#include "mcws/kinematics/robot.h"

namespace mcws {

/// \brief An input or output port of a basic behaviour: `<PortName>: <PortType>`.
struct Port {
  std::string name;
  std::string type;
  int line{0};
};

/// \brief A parameter of a basic behaviour, "1.5 A": value 1.5 in unit "A".
///
/// Units: A, mA, V, s, ms, mm, deg, rpm, mm/s, deg/s, N.
struct Parameter {
  std::string name;
  double value{0.0};  ///< in `unit`
  std::string unit;
  int line{0};
};

/// \brief One value a basic behaviour can set, with the command that sets it and the sensor
/// event that ends the behaviour.
struct BehaviorTarget {
  std::string value;    ///< a value of the changed component ("closed", "upper_shed", "on")
  std::string command;  ///< close, release, move_to (the component's position), spin, stop
  std::string ends_on;  ///< an event of BehaviorModel::events
  int line{0};
};

/// \brief The body of a basic behaviour: actuator, changed component, targets.
struct BehaviorBody {
  std::string actuator;              ///< J1..J6: a joint of the robot file
  std::vector<std::string> changes;  ///< the components it changes (valid: exactly one)
  std::vector<BehaviorTarget> targets;
  int line{0};
  int changes_line{0};
  /// \brief The target setting `value`; nullptr when the behaviour cannot set it.
  const BehaviorTarget* target(const std::string& value) const;
};

/// \brief A basic behaviour (section 2.1, eq. (1)).
struct BasicBehavior {
  std::string name;
  std::vector<Port> input_ports, output_ports;
  std::vector<Parameter> parameters;
  std::optional<double> timeout_s;  ///< [s]; exceeded = mechanism or sensor fault
  BehaviorBody body;
  int line{0};
  /// \brief The parameter called `name`; nullptr when there is none.
  const Parameter* parameter(const std::string& name) const;
};

/// \brief delta(from, event) = to, with the behaviour run in `from`.
struct Transition {
  std::string from, to;
  std::string behavior;  ///< the basic behaviour run in `from`
  std::string target;    ///< the value it sets; "" = the behaviour's only target
  std::string event;     ///< the behaviour's ending event, which fires the transition
  int line{0};
};

/// \brief A combined behaviour CB(BB1..BBn, M) (section 2.2, eq. (2)-(3)).
struct CombinedBehavior {
  std::string name;
  std::string description;
  std::vector<std::string> states;      ///< Q, in file order
  std::string initial;                  ///< q0; "" when the file gives none
  std::vector<std::string> finals;      ///< F
  std::vector<Transition> transitions;  ///< delta, in file order
  int line{0};
  int states_line{0}, initial_line{0}, final_line{0};
  /// \brief Sigma of this machine: the events of its transitions, first use first.
  std::vector<std::string> events() const;
  /// \brief The first transition out of `state` (the behaviour run there); nullptr if none.
  const Transition* transitionFrom(const std::string& state) const;
};

/// \brief One component of the state vector (Table 1 of Wang et al. 2018).
struct StateComponent {
  std::string name;      ///< fixed_clamp, moving_clamp, j3, j4, j5, brush
  std::string actuator;  ///< the joint that drives it
  std::vector<std::string> values;
  /// One joint value per value for a component with named positions (in `position_unit`,
  /// the robot file's mm or deg), empty otherwise.
  std::vector<double> positions;
  std::string position_unit;  ///< "mm", "deg" or ""
  int line{0};
  /// \brief Index of `value` in values; -1 when it is not one.
  int indexOf(const std::string& value) const;
};

/// \brief A pose: one value index per component, in StateVectorSpec::components order.
using Pose = std::vector<int>;

/// \brief A pose rule entry: the component is one of `values`.
struct PoseCondition {
  std::size_t component{0};
  std::vector<int> values;
  bool matches(const Pose& pose) const;
};

/// \brief A rule of allowed poses: a pose matching all of `when` must match all of `require`.
struct PoseRule {
  std::string name;
  std::vector<PoseCondition> when, require;
  int line{0};
  /// \brief Whether `pose` breaks the rule.
  bool brokenBy(const Pose& pose) const;
};

/// \brief The state vector: components and the rules that forbid poses (Tables 1-2 of
/// Wang et al. 2018).
struct StateVectorSpec {
  std::vector<StateComponent> components;
  std::vector<PoseRule> rules;
  int line{0};
  /// \brief Number of poses, the product of the components' value counts (96 for the robot).
  std::size_t combinations() const;
  /// \brief The first rule `pose` breaks; nullptr when the pose is allowed.
  const PoseRule* brokenRule(const Pose& pose) const;
  bool allowed(const Pose& pose) const { return brokenRule(pose) == nullptr; }
  /// \brief All allowed poses, the first component varying slowest.
  std::vector<Pose> allowedPoses() const;
  /// \brief Index of the component called `name`; -1 when there is none.
  int componentIndex(const std::string& name) const;
  /// \brief "fixed_clamp=closed moving_clamp=open j3=home ...".
  std::string describe(const Pose& pose) const;
};

/// \brief The pose of an FSM state.
struct StatePose {
  std::string state;
  Pose pose;
  int line{0};
};

/// \brief The string's discs. The number of discs is a run parameter, not part of the model.
struct InsulatorSpec {
  std::string type;                                                 ///< "XWP2-160"
  double pitch_mm{0.0};                                             ///< structure height [mm]
  double upper_shed_diameter_mm{0.0}, lower_shed_diameter_mm{0.0};  ///< [mm]
  int line{0};
};

/// \brief A sensor event of Sigma.
struct EventSpec {
  std::string name;
  std::string description;
  int line{0};
};

/// \brief A behaviour model file as read.
struct BehaviorModel {
  std::string source;  ///< the file (or the name given to parseBehaviorModel)
  std::string name;
  /// the robot file named by `robot:` (or by `robot: {file: F, base: LINK, tip: LINK}`, which
  /// chooses a URDF's chain: readRobotEntry()), resolved; "" when none
  std::string robot_path;
  std::optional<Robot> robot;  ///< loaded from robot_path
  int robot_line{0};
  InsulatorSpec insulator;
  std::vector<EventSpec> events;
  StateVectorSpec state_vector;
  std::vector<BasicBehavior> behaviors;
  std::vector<StatePose> poses;
  std::vector<CombinedBehavior> combined;

  const BasicBehavior* behavior(const std::string& name) const;             ///< nullptr if none
  const CombinedBehavior* combinedBehavior(const std::string& name) const;  ///< nullptr if none
  const EventSpec* event(const std::string& name) const;                    ///< nullptr if none
  const StatePose* poseOf(const std::string& state) const;                  ///< nullptr if none
};

/// \brief The stem of the file `mcws_behave --dot` writes the task machine to ("task.dot").
inline constexpr char kTaskDiagramName[] = "task";

/// \brief Why `name` cannot be the stem of a file written into an output directory (a combined
/// behaviour's name is: `<dir>/<name>.dot`), or nothing when it can.
///
/// Refused: an empty name; a '/' or '\\' (a path, not a name); a leading '.' (".", ".." and
/// hidden files); a control byte (0x00-0x1f, 0x7f); more than 200 bytes (a file name has at most
/// 255 with its extension).
std::optional<std::string> fileStemProblem(const std::string& name);

/// \brief `name` in single quotes for a one-line message, control bytes, '\\', the quote and
/// bytes >= 0x80 written as \xNN.
std::string quotedName(const std::string& name);

/// \brief Parses a behaviour model document.
/// \param text the YAML text.
/// \param source the file name used in messages; a relative `robot:` is resolved against its
///   directory, and the robot file is loaded.
/// \throws mcws::Error "source:line: item: ..." for YAML syntax, an unknown or duplicate key, a
///   missing mandatory field (name, body, ...), a value of the wrong kind or unit, a pose or rule
///   naming an unknown component or value, a pose missing a component, a missing robot file, a
///   combined behaviour's name that cannot be a file name (fileStemProblem()) or that equals
///   kTaskDiagramName or another combined behaviour's name ignoring ASCII case (their diagrams
///   would overwrite each other on a case-insensitive file system).
///   Everything about how the items fit together is left to validateBehaviorModel().
BehaviorModel parseBehaviorModel(const std::string& text, const std::string& source);

/// \brief parseBehaviorModel() of a file. \throws mcws::Error when it cannot be read.
BehaviorModel loadBehaviorModel(const std::string& path);

/// \brief Sizes of one combined behaviour, for reports.
struct CombinedBehaviorCounts {
  std::string name;
  std::size_t states{0}, transitions{0}, events{0};
};

/// \brief What validateBehaviorModel() counted.
struct ValidationReport {
  std::size_t combinations{0};     ///< poses of the state vector (96)
  std::size_t allowed_poses{0};    ///< poses breaking no rule
  std::size_t forbidden_poses{0};  ///< combinations - allowed_poses
  std::size_t states{0};           ///< FSM states with a pose
  std::size_t poses_used{0};       ///< distinct poses of those states
  std::size_t behaviors{0};        ///< basic behaviours
  std::size_t events{0};           ///< events of Sigma
  std::vector<CombinedBehaviorCounts> combined;
  /// \brief The counts as text, one line each: "state vector: 96 combinations, 17 allowed, 79
  ///   forbidden", "CB1: 6 states, 6 transitions, 4 events", ...
  std::string summary() const;
};

/// \brief Checks that a model's items fit together.
///
/// In order: the state vector (values unique; with a robot file, every actuator is one of its
/// joints, positions carry the joint's unit and lie within its limits); the basic behaviours
/// (each changes exactly one component, driven by its actuator; its targets are values of that
/// component; known commands, `move_to` only to a named position; ending events exist); every
/// pose is allowed by the rules; the combined behaviours (names unique; Q non-empty without
/// repeats, each state with a pose; q0 given and in Q; F given and in Q; every transition
/// between states of Q, running an existing behaviour with a target it can set, on an existing
/// event that is that target's ending event; one behaviour per (combined behaviour, state); no
/// two transitions on the same event from one state; every state reachable from q0; from every
/// state a way back to F).
/// \return the counts to print.
/// \throws mcws::Error "source:line: item: ..." naming the item and its line, at the first
///   problem found.
ValidationReport validateBehaviorModel(const BehaviorModel& model);

/// \brief A transition whose behaviour does not turn the source pose into the target pose.
struct PoseFinding {
  std::string combined;  ///< the combined behaviour
  Transition transition;
  Pose reached;         ///< the source pose with the behaviour's change applied
  std::string message;  ///< "source:line: CB1: q6 -> q1: ..."
};

/// \brief Static pose check of a validated model, separate from validateBehaviorModel(): for
/// every transition, applies the behaviour's one change to the source state's pose and compares
/// with the target state's pose.
///
/// The shipped model has no findings. The literal CB1 of Wang et al. 2018 (the fixed clamp closes
/// at q6 -> q1) has one: BB_UG_Clamp leaves the moving clamp open, so the robot reaches "q1" with
/// one clamp closed and the next CB1 step (fixed clamp releases) opens both. The literal model is
/// structurally valid; at run time the executor's safety invariant rejects it.
/// \throws mcws::Error as resolveRun() for a model that does not validate.
std::vector<PoseFinding> checkPoseConsistency(const BehaviorModel& model);

/// \brief What a transition's behaviour does, resolved against the model.
struct BehaviorRun {
  const BasicBehavior* behavior{nullptr};
  const BehaviorTarget* target{nullptr};  ///< command and ending event
  std::size_t component{0};               ///< index into state_vector.components
  int value{0};                           ///< the value index it sets
  /// The joint target of a `move_to` [mm or deg, the component's position_unit].
  std::optional<double> position;
};

/// \brief Resolves a transition of `model` (its behaviour, target, changed component, value,
/// and the position of a `move_to`).
/// \throws mcws::Error naming the transition's line when the behaviour, target or component
///   does not exist (validateBehaviorModel() rejects such models first).
BehaviorRun resolveRun(const BehaviorModel& model, const Transition& transition);

/// \brief The pose after running `run` from `pose`: the changed component set to run.value.
Pose applyRun(const BehaviorRun& run, Pose pose);

/// \brief The state machine of a combined behaviour: Q, Sigma, delta, q0, F, each edge
/// labelled "<behaviour>[ <target>]\n<event>".
/// \throws mcws::Error as the StateMachine builders (a model that does not validate).
StateMachine stateMachineOf(const CombinedBehavior& combined);

}  // namespace mcws
