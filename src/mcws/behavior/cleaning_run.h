#pragma once
/// \file
/// \brief The executor of behavior_executor.h inside: one cleaning run (class CleaningRun), whose
/// parts live in files named for their job. Private to the library: include behavior_executor.h.

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mcws/behavior/behavior_executor.h"

namespace mcws {
namespace cleaning {

/// What a segment (one run of a combined behaviour) is for.
struct Segment {
  std::string combined;
  /// Started at q0: completing it counts (CB1: one disc further down, CB2: a disc cleaned, CB3:
  /// one disc back up).
  bool counted{true};
  /// On the way back (CB1, CB3): settle at the nearest state whose pose has both clamps closed
  /// (settle()) before going on.
  bool settling{false};
};

/// The basic behaviour being run.
struct Active {
  std::string behavior;
  std::string event;  // its ending event
  SimJoint joint{SimJoint::kJ1};
  SimCommand command;
  std::int64_t target_count{0};              // encoder_reached
  double hold_current{0.0}, hold_time{0.0};  // current_held [A], [s]
  std::optional<double> timeout;             // [s]
  double entered_at{0.0};                    // state entry [s]
  std::optional<double> held_since;          // current_held: when the current reached I [s]
  bool restore{false};  // restoring a pose value a fault stopped (the brush), not a transition
  /// On the way back: re-closing an open clamp instead of the state's own behaviour; the state
  /// the robot is then in.
  std::optional<std::string> reclose_to;
};

enum class Mode { kRunning, kWaitingForLink, kManual, kDone };

/// The values a component may have: one per value index, true when possible.
using ValueSet = std::vector<bool>;

/// What settle() does in a state: run the state's own behaviour; land in `to` at once (both
/// clamps grip); or close the open clamp again with `closer` and land in `to`.
struct SettleStep {
  enum Kind { kOwn, kLand, kReclose } kind{kOwn};
  std::string to;
  const BasicBehavior* closer{nullptr};
  SimJoint open{kFixedClamp};
};

/// One run of the cleaning job: runCleaningJob() is `CleaningRun(model, options, observer).run()`.
class CleaningRun {
 public:
  CleaningRun(const BehaviorModel& model, const RunOptions& options, const RunObserver& observer);

  RunSummary run();

 private:
  // ---- accessors --------------------------------------------------------------------------------
  const Segment* segment() const { return segment_ ? &*segment_ : nullptr; }
  StateMachine* machine() { return segment_ ? &machines_.at(segment_->combined) : nullptr; }
  std::string stateName() const {
    return segment_ ? machines_.at(segment_->combined).current() : std::string();
  }

  // ---- set-up, the run loop and the records (behavior_executor.cpp) -----------------------------
  void accountPhase();

  void findClampComponents();

  /// Every transition's behaviour must be something the simulator can run.
  void checkRunnable() const;

  /// The simulator command of a behaviour run. \throws naming `where`.
  SimCommand commandOf(const BehaviorRun& run, SimJoint joint, const std::string& where) const;

  double countsPerUnit(SimJoint joint) const;

  void log(const std::string& event, const std::string& behavior, const std::string& detail,
           std::optional<std::uint64_t> seq = std::nullopt);

  void notifyStep();

  /// Records a fault and its reaction; \return its index in summary_.faults.
  std::size_t react(const std::string& fault, const std::string& reaction,
                    std::optional<double> injected, std::optional<double> detected,
                    std::optional<double> resolved);

  /// Marks the faults in `open` resolved now.
  void resolve(std::vector<std::size_t>& open);

  void fireTask(const std::string& event);

  void finish(RunStatus status, const std::string& detail);

  // ---- sub-tasks and basic behaviours (cleaning_run_behaviors.cpp) ------------------------------
  void startPlanSubtask(std::size_t index);

  void startSegment(const Segment& segment, const std::string& detail,
                    const std::string& from_state = "");

  /// The segment is over: its machine is back in a final state, or (on the way back) at a state
  /// with both clamps closed.
  void endSegment(bool abandoned = false);

  /// Runs the behaviour of the current state (resume = the state is re-entered after a fault).
  void startBehavior(bool resume);

  void runBehavior(const BehaviorRun& run, bool restore,
                   std::optional<std::string> reclose_to = std::nullopt);

  /// Before resuming `state`: a pose value that stopping every joint undid (a spinning brush)
  /// is set again first. \return whether a restoring behaviour was started.
  bool restorePose(const std::string& state);

  bool endingEventSeen(Active& a);

  void superviseBehavior();

  void stopAll();

  // ---- sending commands, the command check, safety stops (cleaning_run_commands.cpp) ------------
  /// Sends a behaviour's command; \return false when it was refused (control handed over).
  bool send(const SimCommand& command, const std::string& behavior);

  std::optional<InjectedFault> takeFault(FaultKind kind);

  /// Where the run is now, in `behavior`.
  RunPlace place(const std::string& behavior) const;

  /// A behaviour's own command was refused: every joint stops and the run ends there.
  void safetyStop(const SimCommand& command, const std::string& behavior,
                  const std::string& reason);

  /// Why releasing a clamp would leave the robot hanging by neither (the other clamp does not
  /// grip, as its sensors say), or nothing.
  std::optional<std::string> opensBothClamps(const SimCommand& command) const;

  bool checkInvariant();

  /// Stops the run on the safety invariant (never both clamps open): broken at this step, or
  /// about to be by a command.
  void violate(const std::string& what);

  // ---- the pose the sensors read and the interference check (cleaning_run_interference.cpp) -----
  /// The values a positioned component (named positions, the robot's units) may have with its
  /// joint anywhere in [lo, hi]: every named position in the interval, and the nearest one on
  /// either side of each end that is not a named position (the joint is between them).
  static ValueSet valuesSpanned(const StateComponent& c, double lo, double hi);

  /// The commands with which the model's behaviours set each value of component `k`.
  std::vector<std::vector<std::string>> commandsSetting(std::size_t k) const;

  /// The pose the sensors read, per component the values it may have: a clamp's value is the
  /// one its close behaviour sets while it grips, its release's otherwise; a positioned joint's
  /// the named position its encoder reads, or the two it lies between; the brush's the value of
  /// its spin while it turns, of its stop at rest. A component the sensors cannot name may have
  /// any value.
  std::vector<ValueSet> sensedPose() const;

  /// "fixed_clamp=closed moving_clamp=open j3=home|extended ...".
  std::string describePose(const std::vector<ValueSet>& pose) const;

  /// The first pose of the product of `pose`'s value sets that a rule forbids, with the rule.
  std::optional<std::pair<Pose, const PoseRule*>> forbiddenPose(
      const std::vector<ValueSet>& pose) const;

  /// The FSM state whose pose the sensors read, when exactly one state's pose fits.
  std::optional<std::string> sensedState(const std::vector<ValueSet>& pose) const;

  /// Whether the pose of `state` is one the sensors allow (a joint between two named positions
  /// allows either).
  bool sensorsFit(const std::string& state) const;

  /// For the log: `claim` (e.g. "back in q1") when the sensors fit the pose of `state`, else
  /// "the machine is back in q1, but the sensors read q6 (fixed_clamp=closed ...)".
  std::string sensedText(const std::string& claim, const std::string& state) const;

  /// Why `command` must not be sent now, or nothing: the simulator's refuse() (joint limits,
  /// command kinds), a release while the other clamp does not grip, and the pose rules: every
  /// pose the robot may pass through while the command runs, from the pose the sensors read
  /// (not the machine's state) with the commanded component over the values between where it
  /// is and where the command takes it, must be allowed.
  std::optional<std::string> interference(const SimCommand& command) const;

  // ---- faults and exceptions (cleaning_run_faults.cpp) ------------------------------------------
  void applyFaults();

  void superviseLink();

  /// Control to the operator (MANUAL), with the next scripted response if there is one.
  /// \param detected when the fault was found [s]; now when not given.
  void handOver(const std::string& fault, const std::string& what, std::optional<double> injected,
                std::optional<double> detected = std::nullopt);

  void superviseOperator();

  void superviseBattery();

  /// A zero switch that reads pressed while its clamp's encoder says the jaw is more than half
  /// a degree open: a sensor fault, like a timeout (seed section 2.4 (2)). Checked on both
  /// clamps at every step, whatever runs: a switch stuck pressed on a closed jaw shows at once.
  /// \return the clamp and the text.
  std::optional<std::pair<SimJoint, std::string>> sensorMismatch() const;

  /// The sensor check while the robot runs; \return false when it handed control to the
  /// operator. A disagreement already found while the robot stood still keeps its time.
  bool superviseSensors();

  /// The sensor check while the robot stands still (waiting for the link, or in MANUAL): a
  /// disagreement is logged when it shows and handled when the robot runs again.
  void noteSensors();

  /// When the fault file broke the sensor a behaviour on `joint` waits for [s], if it did.
  std::optional<double> sensorFaultAt(SimJoint joint) const;

  // ---- the return to the start (cleaning_run_return.cpp) ----------------------------------------
  /// Back to the start: the interrupted behaviour is finished first (it may have half moved a
  /// jaw: the state's pose is not what the robot has), then CB1 goes on to the next state with
  /// both clamps closed, CB2 and CB3 to their end; CB3 from a CB1 state other than q1 undoes
  /// the half-done move; then one CB3 per disc below the start.
  void startReturn(const std::string& why);

  /// The joint value class of J3 its encoder reads exactly (home, extended), or -1 mid-travel.
  int j3Class() const;

  /// settle()'s decision in `state` of the current CB1 or CB3, the clamps gripping as given and
  /// J3 in position class `j3` (-1: mid travel).
  SettleStep settleStep(const std::string& state, bool fixed, bool moving, int j3) const;

  /// On the way back in CB1 or CB3: reach a state whose pose has both clamps closed by the
  /// shortest safe way. Both clamps gripping: the robot is there. One clamp open (or half
  /// released) with J3 at a named position, so that its platform sits at a disc: close it again
  /// (the clamp's close behaviour) unless the state's own behaviour is that very close; J3 mid
  /// travel: finish the state's own behaviour first, then settle again.
  void settle();

  /// Whether a return starting now brings the CB1 in hand to its end (settle() runs its own
  /// behaviours until it is back in a final state), so that it counts one disc more to climb.
  /// Follows settle()'s decisions from the sensed clamps and J3, then from each state's pose.
  bool returnCompletesCb1();

  /// The robot holds the string with both clamps in state `to` of the current CB1 or CB3
  /// (`reversal`: reached by closing a clamp again, not by the machine's own transitions).
  void landOn(const std::string& to, bool reversal);

  void endSegmentForReturn();

  /// Back at the start: completed when every disc was cleaned, returned otherwise.
  RunStatus endStatus() const;

  const BehaviorModel& model_;
  const RunOptions& options_;
  const RunObserver& observer_;
  RobotSimulator sim_;
  StateMachine task_ = taskMachine();
  std::map<std::string, StateMachine> machines_;
  int fixed_component_{-1}, moving_component_{-1};
  RunSummary summary_;

  Mode mode_{Mode::kRunning};
  std::size_t plan_index_{0};
  std::optional<Segment> segment_;
  std::optional<Active> active_;
  int subtask_{0};
  int disc_{0};
  std::uint64_t seq_{0};
  bool returning_{false};
  bool return_after_disc_{false};
  bool battery_alarm_{false};

  std::vector<InjectedFault> faults_;
  std::size_t next_fault_{0};
  std::vector<InjectedFault> pending_;  // corrupt and wrong commands waiting for a command
  std::vector<double> link_back_at_;
  bool link_down_for_good_{false};
  bool link_loss_noted_{false};  // a loss during MANUAL or the return was reported
  double drain_{0.0};
  double link_lost_at_{0.0};
  std::optional<double> mismatch_seen_at_;    // a sensor disagreement found while standing still
  bool mismatch_handed_over_{false};          // the present disagreement is the operator's already
  std::optional<double> outage_injected_at_;  // when the present (or last) outage began [s]
  std::array<std::optional<double>, 2> switch_fault_at_;  // J1's, J2's zero-switch fault [s]
  std::vector<std::size_t> until_link_;                   // faults resolved when the link is back
  std::vector<std::size_t> until_operator_;               // faults resolved when the operator acts
  std::vector<std::size_t> until_start_;  // faults resolved when the return reaches the start
  std::optional<OperatorResponse> response_;
  double response_at_{0.0};
  std::size_t next_response_{0};
};

}  // namespace cleaning
}  // namespace mcws
