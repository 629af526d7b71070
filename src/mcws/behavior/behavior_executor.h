#pragma once
/// \file
/// \brief Runs a cleaning job on the simulated robot: the task decomposition of Wang et al. 2018
/// (section 2.3), combined behaviours (2.2), basic behaviours (2.1) and exception handling (2.4),
/// driven by a behaviour model (behavior_model.h) over RobotSimulator (robot_simulator.h).
///
/// Three levels, as the paper's Stateflow model ("three key states, each with sub-states"):
/// - the task machine (taskMachine()): superstates CB1, CB2, CB3, FAULT and MANUAL between
///   `idle` and `done`; it moves on the plan's sub-tasks (planCleaningTask()) and on exceptions;
/// - the combined behaviour of the current sub-task: its FSM (stateMachineOf()); in each state
///   the transition's basic behaviour runs and its ending event fires the transition; the
///   sub-task is done when the FSM is back in a final state;
/// - the basic behaviour: its body's command goes to the simulator; its ending event is read
///   from the simulator's sensors every step (zero switch pressed; encoder count equal to the
///   target count, or zero; motor current >= the parameter `I` for the parameter `hold`; brush at
///   the commanded speed, or stopped); its timeout counts from the state's entry and restarts on
///   re-entry. A clamp behaviour's ending event cuts its motor (the jaws are self-locking).
///
/// Exceptions (section 2.4), each logged with its reaction:
/// - communication: every command from the ground station carries a sequence number; the robot
///   checks it (a corrupted command fails the check and is not executed) and echoes its sequence
///   number and FSM state, which the ground station compares with what it sent, resending on a
///   mismatch. The link lost: every joint stops; if the link is back within `link_wait`, the
///   interrupted behaviour runs again (state re-entered); if not, the robot returns on its own.
/// - the return to the start: first both clamps must grip, by the shortest way: a clamp that is
///   open or half released closes again when J3's encoder is at a named position (its platform
///   sits at a disc), unless the state's own behaviour is that close; with J3 mid travel the
///   interrupted behaviour finishes first. CB2 (which parks the cleaner) and CB3 (already on the
///   way up) go on to their end; from a CB1 state other than q1 (q4), CB3 runs to q1, undoing the
///   half-done move; then one CB3 per disc below the start (completed CB1 minus completed CB3).
///   The `return_start` record gives the discs to climb: those below the start, one more when
///   the CB1 in hand goes on to its end first.
/// - a behaviour timeout, or a zero switch pressed while the clamp's encoder says the jaw is
///   more than 0.5 deg open (a sensor fault, checked on both clamps at every step whatever runs,
///   so a switch stuck pressed on a closed jaw is found at once; found while the robot stands
///   still, waiting for the link or in MANUAL, it is logged then and acted on when the robot
///   would run again): every joint stops and control passes to the operator (MANUAL); the fault
///   file scripts what the operator does and when (repair and resume, resume, return), acted on
///   once the link is up; with no response left, or the link down for good, the run ends in MANUAL.
/// - commands from the ground station are not sent while the link is down; faults armed for a
///   command that never comes are reported as such at the end.
/// - an empty battery stops every joint and ends the run (status kBatteryEmpty).
/// - low battery: the alarm (once); with LowBatteryPolicy::kFinishDiscAndReturn the robot
///   finishes the disc in hand (its CB1 and CB2) and returns.
/// - interference: before each command, the behaviours' own as well as injected ones, a
///   kinematic check refuses it with a reason: the simulator's refuse() (joint limits, which are
///   the robot file's; the command kinds a joint takes) and the state-vector rules: from the pose
///   the sensors read (not the machine's state: a clamp is closed while it grips; J3-J5 at the
///   named position their encoder reads, or either of the two they lie between; the brush on
///   while it turns), every pose the robot passes through while the command runs (the commanded
///   component over every value between where it is and where the command takes it) must be
///   allowed. robots/insulator_cleaner.yaml has no collision geometry, so there is no collision
///   check. A refused command from the ground station (a wrong command) is replaced by the
///   behaviour's own; a refused own command stops every joint and ends the run (status
///   kSafetyStop, RunSummary::safety_stop names the command and the reason).
/// - the log's state descriptions ("back in q1", the command echo, "the robot is in q4") come
///   from the sensors: when they do not fit the machine's state the text says what they read.
/// - the safety invariant, at least one clamp grips the string: checked after every simulated
///   step, and before every command (a release is never sent while the other clamp's sensors say
///   it does not grip). A violation ends the run at once (status "invariant_violated", with the
///   step).
///
/// Resuming a state whose pose has the brush spinning (stopped by a fault) first spins it up
/// again: the behaviour that sets that pose value runs, then the interrupted one.
///
/// Everything is deterministic: the same model, plan, faults and configuration give the same
/// log records, bit for bit.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "mcws/behavior/behavior_model.h"
#include "mcws/behavior/fault_script.h"
#include "mcws/behavior/fsm.h"
#include "mcws/behavior/robot_simulator.h"
#include "mcws/behavior/task_plan.h"

namespace mcws {

/// \brief One record of the event log.
struct LogRecord {
  double t{0.0};          ///< simulated time [s]
  std::uint64_t step{0};  ///< simulator steps taken
  int subtask{0};  ///< 1-based number of the sub-task being run (plan, then return); 0 = none
  std::string task_state;  ///< the task machine's state: idle, CB1, CB2, CB3, FAULT, MANUAL, done
  std::string combined;    ///< the sub-task's combined behaviour ("" when none)
  std::string state;       ///< its FSM state (q1, q2, ...; "" when none)
  std::string event;       ///< what happened (see the list in mcws_behave --help)
  std::string behavior;    ///< the basic behaviour concerned ("" when none)
  std::optional<std::uint64_t> seq;  ///< the command's sequence number, for command records
  int disc{0};                       ///< discs below the start: completed CB1 minus completed CB3
  std::string detail;                ///< human-readable text
};

/// \brief What the executor is doing at one simulated step, for a timeline row.
struct StepContext {
  int subtask{0};
  std::string task_state, combined, state, behavior;
  int disc{0};
};

/// \brief A fault (injected or detected) and what the robot did about it, with three times.
struct FaultReaction {
  std::string fault;  ///< link_down, timeout, corrupt_command, wrong_command, battery_low, ...
  /// When the fault file injected it [s]; none for a condition the robot met on its own (a
  /// low or empty battery, a timeout with no injected fault behind it).
  std::optional<double> injected_t;
  /// When the robot noticed it [s]; none when it never did (a wrong command that passed the
  /// check, a fault armed for a command that never came).
  std::optional<double> detected_t;
  /// When the reaction ended [s]: the robot resumed, the operator acted, the command was
  /// resent or replaced, or the return the fault caused reached the start; none when the run
  /// ended first.
  std::optional<double> resolved_t;
  std::string reaction;  ///< text
};

/// \brief Where in the run something happened: the simulator's step and time, the sub-task, the
/// combined behaviour and its state, the basic behaviour.
struct RunPlace {
  std::uint64_t step{0};
  double t{0.0};  ///< [s]
  int subtask{0};
  std::string combined, state, behavior;
};

/// \brief A command of the robot's own behaviours that the interference check refused: the run
/// stops there (status kSafetyStop).
struct SafetyStop : RunPlace {
  std::string command;  ///< "J6 spin 300 rpm"
  std::string reason;   ///< why the check refused it (the pose rule, the joint limit, ...)
  std::string message;  ///< "step 1234 (t = 12.34 s): refused BB_Brush's command ..."
};

/// \brief The step at which the safety invariant failed.
struct InvariantViolation : RunPlace {
  std::string message;  ///< "step 1234 (t = 12.34 s): both clamps open ..."
};

/// \brief How a run ended.
enum class RunStatus {
  kCompleted,          ///< every sub-task of the plan done; the robot is back at the start
  kReturned,           ///< returned to the start before the plan was done (a fault)
  kHaltedInManual,     ///< control handed to the operator, no scripted response left
  kInvariantViolated,  ///< both clamps open at some step
  kTimeLimit,          ///< the simulated time limit was reached
  kBatteryEmpty,       ///< the battery ran empty: the robot stopped, hanging on the string
  kSafetyStop,         ///< a behaviour's own command was refused: every joint stopped
};
/// \brief "completed", "returned", "halted_in_manual", "invariant_violated", "time_limit",
/// "battery_empty", "safety_stop".
const char* runStatusName(RunStatus status);

/// \brief The result of a run.
struct RunSummary {
  RunStatus status{RunStatus::kCompleted};
  int discs_requested{0};
  int discs_cleaned{0};            ///< CB2 sub-tasks completed
  int final_disc{0};               ///< discs below the start at the end (0 = back at the start)
  std::vector<Subtask> plan;       ///< the plan that was run
  int subtasks_completed{0};       ///< plan and return sub-tasks brought to their final state
  std::size_t behaviors_run{0};    ///< basic behaviours that ended on their event
  std::uint64_t commands_sent{0};  ///< sequence numbers used
  double duration_s{0.0};          ///< simulated time at the end [s]
  std::uint64_t steps{0};
  std::vector<FaultReaction> faults;
  std::optional<InvariantViolation> violation;  ///< set when status is kInvariantViolated
  std::optional<SafetyStop> safety_stop;        ///< set when status is kSafetyStop
  double battery_voltage_end{0.0};              ///< [V]
  double battery_charge_used{0.0};              ///< [A h]
  std::optional<double> battery_alarm_t;        ///< when the low-battery alarm was raised [s]
  /// Simulated time spent in phase I (CB1, CB3: J1-J3 move) and phase II (CB2: J4-J6) [s].
  double phase_one_s{0.0}, phase_two_s{0.0};
};

/// \brief What a run is given besides the model.
struct RunOptions {
  int insulators{0};   ///< discs to clean: the worker's confirmed number (required, >= 1)
  FaultScript faults;  ///< injected faults, operator responses, policies (default: none)
  /// The simulator; simulatorConfigFor() by default (RunOptions::forModel()).
  RobotSimulatorConfig simulator;
  /// Simulated time limit [s]: a day; a 200-disc job takes about 8.5 h, a 28-disc one 1.2 h.
  double max_time_s{86400.0};
  /// \brief Options for `model` and `insulators`: simulatorConfigFor(model, insulators).
  static RunOptions forModel(const BehaviorModel& model, int insulators);
};

/// \brief The simulator for a model and a number of discs: the model's disc pitch, the moving
/// clamp two pitches below the fixed one, grip positions 0 .. insulators + 2 (the tower-end
/// fitting, the discs, and the positions the moving clamp takes below the last disc); the rest
/// the RobotSimulatorConfig defaults.
RobotSimulatorConfig simulatorConfigFor(const BehaviorModel& model, int insulators);

/// \brief Receives the run as it happens; both calls are optional.
struct RunObserver {
  std::function<void(const LogRecord&)> on_log;
  /// Called after every simulated step (and once at time 0 before the first).
  std::function<void(const SimSnapshot&, const StepContext&)> on_step;
};

/// \brief The task-level machine: idle -> CB1 <-> CB2 -> CB3 -> done, FAULT and MANUAL
/// superstates entered from CB1..CB3 on `link_lost` and `hand_over` (a behaviour timeout or a
/// sensor disagreement) and left by `resume_CB<k>` (to the superstate that was interrupted). A
/// refused own command ends the run where it is (RunStatus::kSafetyStop).
StateMachine taskMachine();

/// \brief Runs `options.insulators` discs of the cleaning job on the simulated robot.
/// \param model a model that passes validateBehaviorModel() (it is validated again here).
/// \throws mcws::Error naming the item for a model the simulator cannot run (an event with no
///   sensor behind it, a current_held behaviour without parameters I and hold, an actuator that
///   is not J1..J6), bad options, or a bad simulator configuration. A violated invariant is not
///   an exception: it is the run's status.
RunSummary runCleaningJob(const BehaviorModel& model, const RunOptions& options,
                          const RunObserver& observer = {});

}  // namespace mcws
