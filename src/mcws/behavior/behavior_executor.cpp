#include "mcws/behavior/behavior_executor.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <sstream>
#include <utility>

#include "mcws/core/error.h"

namespace mcws {
namespace {

/// The sensor events the simulator can raise, and the joints that have the sensor.
bool eventFitsJoint(const std::string& event, SimJoint joint) {
  const bool clamp = joint == kFixedClamp || joint == kMovingClamp;
  if (event == "zero_switch") return clamp;
  if (event == "current_held") return clamp;
  if (event == "encoder_reached") return !clamp && joint != SimJoint::kJ6;
  if (event == "encoder_zero") return joint != SimJoint::kJ6;
  if (event == "speed_reached" || event == "speed_zero") return joint == SimJoint::kJ6;
  return false;
}

std::string number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

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

class CleaningRun {
 public:
  CleaningRun(const BehaviorModel& model, const RunOptions& options, const RunObserver& observer)
      : model_(model), options_(options), observer_(observer), sim_(options.simulator) {
    validateBehaviorModel(model_);
    if (options_.insulators < 1) {
      throw Error("insulators: " + std::to_string(options_.insulators) + " discs; must be >= 1");
    }
    if (!(options_.max_time_s > 0.0)) {
      throw Error("max_time: " + number(options_.max_time_s) + " s; must be > 0");
    }
    summary_.plan = planCleaningTask(options_.insulators);
    summary_.discs_requested = options_.insulators;
    for (const char* name : {"CB1", "CB2", "CB3"}) {
      const CombinedBehavior* cb = model_.combinedBehavior(name);
      if (!cb) throw Error(model_.source + ": the task plan needs a combined behaviour " + name);
      machines_.emplace(name, stateMachineOf(*cb));
    }
    findClampComponents();
    checkRunnable();
    faults_ = options_.faults.faults;
  }

  RunSummary run() {
    log("run_start", "",
        std::to_string(options_.insulators) + " discs, " + std::to_string(summary_.plan.size()) +
            " sub-tasks");
    notifyStep();
    applyFaults();  // those at time 0 act on the first command
    startPlanSubtask(0);
    while (mode_ != Mode::kDone) {
      if (sim_.time() >= options_.max_time_s) {
        finish(RunStatus::kTimeLimit,
               "simulated time limit " + number(options_.max_time_s) + " s reached");
        break;
      }
      applyFaults();
      superviseLink();
      superviseOperator();
      if (mode_ == Mode::kRunning) {
        superviseSensors();
      } else if (mode_ != Mode::kDone) {
        noteSensors();
      }
      if (mode_ == Mode::kDone) break;
      sim_.step();
      accountPhase();
      notifyStep();
      if (!checkInvariant()) break;
      if (sim_.snapshot().battery_charge <= 0.0) {
        stopAll();
        react("battery_empty", "every joint stopped: the robot hangs on the string", std::nullopt,
              sim_.time(), std::nullopt);
        finish(RunStatus::kBatteryEmpty, "the battery is empty");
        break;
      }
      superviseBattery();
      if (mode_ == Mode::kRunning && active_) superviseBehavior();
    }
    const SimSnapshot& s = sim_.snapshot();
    summary_.duration_s = s.time;
    summary_.steps = s.step;
    summary_.final_disc = disc_;
    summary_.commands_sent = seq_;
    summary_.battery_voltage_end = s.battery_voltage;
    summary_.battery_charge_used =
        options_.simulator.battery.capacity * options_.simulator.battery.initial_charge -
        s.battery_charge;
    return summary_;
  }

 private:
  // ---- set-up ---------------------------------------------------------------------------------

  void findClampComponents() {
    const StateVectorSpec& spec = model_.state_vector;
    for (std::size_t k = 0; k < spec.components.size(); ++k) {
      const StateComponent& c = spec.components[k];
      if (c.actuator == "J1") fixed_component_ = static_cast<int>(k);
      if (c.actuator == "J2") moving_component_ = static_cast<int>(k);
    }
    for (const int k : {fixed_component_, moving_component_}) {
      if (k < 0 || spec.components[k].indexOf("closed") < 0) {
        throw Error(model_.source +
                    ": the state vector needs a component driven by J1 and one by "
                    "J2, each with a value 'closed' (the two clamps)");
      }
    }
  }

  /// Every transition's behaviour must be something the simulator can run.
  void checkRunnable() const {
    for (const CombinedBehavior& cb : model_.combined) {
      for (const Transition& t : cb.transitions) {
        const BehaviorRun run = resolveRun(model_, t);
        const std::string where = model_.source + ":" + std::to_string(t.line) + ": " + cb.name +
                                  ": " + t.from + " -> " + t.to + ": " + t.behavior;
        SimJoint joint;
        try {
          joint = simJointFromName(run.behavior->body.actuator);
        } catch (const Error& e) {
          throw Error(where + ": " + e.what());
        }
        if (!eventFitsJoint(run.target->ends_on, joint)) {
          throw Error(where + ": the simulator has no sensor for event '" + run.target->ends_on +
                      "' on " + simJointName(joint));
        }
        commandOf(run, joint, where);  // throws for missing or mis-united parameters
      }
    }
  }

  /// The simulator command of a behaviour run. \throws naming `where`.
  SimCommand commandOf(const BehaviorRun& run, SimJoint joint, const std::string& where) const {
    const std::string& kind = run.target->command;
    const Parameter* speed = run.behavior->parameter("speed");
    if (kind == "close") return SimCommand::close(joint);
    if (kind == "release") return SimCommand::release(joint);
    if (kind == "stop") return SimCommand::stop(joint);
    if (kind == "move_to") {
      if (!run.position) throw Error(where + ": move_to without a position");
      double cruise = 0.0;
      if (speed) {
        const std::string unit = joint == SimJoint::kJ5 ? "deg/s" : "mm/s";
        if (speed->unit != unit) {
          throw Error(where + ": parameter speed is in " + speed->unit + "; " +
                      simJointName(joint) + " needs " + unit);
        }
        cruise = speed->value;
      }
      return SimCommand::moveTo(joint, *run.position, cruise);
    }
    if (kind == "spin") {
      if (!speed || speed->unit != "rpm") {
        throw Error(where + ": spin needs a parameter speed in rpm");
      }
      return SimCommand::spin(speed->value);
    }
    throw Error(where + ": command '" + kind + "' is not one the simulator takes");
  }

  // ---- logging --------------------------------------------------------------------------------

  const Segment* segment() const { return segment_ ? &*segment_ : nullptr; }
  StateMachine* machine() { return segment_ ? &machines_.at(segment_->combined) : nullptr; }
  std::string stateName() const {
    return segment_ ? machines_.at(segment_->combined).current() : std::string();
  }

  void log(const std::string& event, const std::string& behavior, const std::string& detail,
           std::optional<std::uint64_t> seq = std::nullopt) {
    if (!observer_.on_log) return;
    LogRecord r;
    r.t = sim_.time();
    r.step = sim_.snapshot().step;
    r.subtask = subtask_;
    r.task_state = task_.current();
    r.combined = segment_ ? segment_->combined : "";
    r.state = stateName();
    r.event = event;
    r.behavior = behavior;
    r.seq = seq;
    r.disc = disc_;
    r.detail = detail;
    observer_.on_log(r);
  }

  void notifyStep() {
    if (!observer_.on_step) return;
    StepContext c;
    c.subtask = subtask_;
    c.task_state = task_.current();
    c.combined = segment_ ? segment_->combined : "";
    c.state = stateName();
    c.behavior = active_ ? active_->behavior : "";
    c.disc = disc_;
    observer_.on_step(sim_.snapshot(), c);
  }

  /// Records a fault and its reaction; \return its index in summary_.faults.
  std::size_t react(const std::string& fault, const std::string& reaction,
                    std::optional<double> injected, std::optional<double> detected,
                    std::optional<double> resolved) {
    summary_.faults.push_back({fault, injected, detected, resolved, reaction});
    return summary_.faults.size() - 1;
  }

  /// Marks the faults in `open` resolved now.
  void resolve(std::vector<std::size_t>& open) {
    for (const std::size_t k : open) summary_.faults[k].resolved_t = sim_.time();
    open.clear();
  }

  void fireTask(const std::string& event) {
    if (!task_.fire(event)) {
      throw Error("task machine: no transition on '" + event + "' from '" + task_.current() + "'");
    }
  }

  void finish(RunStatus status, const std::string& detail) {
    for (const InjectedFault& f : pending_) {
      react(faultKindName(f.kind), "never acted: no command came from the ground station after it",
            f.at_s, std::nullopt, std::nullopt);
    }
    pending_.clear();
    summary_.status = status;
    mode_ = Mode::kDone;
    if (status == RunStatus::kCompleted || status == RunStatus::kReturned) {
      resolve(until_start_);  // the return these faults caused reached the start
      fireTask("job_done");
    }
    log("run_end", "", std::string(runStatusName(status)) + ": " + detail);
  }

  // ---- sub-tasks ------------------------------------------------------------------------------

  void startPlanSubtask(std::size_t index) {
    plan_index_ = index;
    const Subtask& s = summary_.plan[index];
    startSegment({s.behavior, true, false}, s.action + " -> disc " + std::to_string(s.disc) +
                                                " (plan " + std::to_string(index + 1) + "/" +
                                                std::to_string(summary_.plan.size()) + ")");
  }

  void startSegment(const Segment& segment, const std::string& detail,
                    const std::string& from_state = "") {
    segment_ = segment;
    ++subtask_;
    StateMachine& m = *machine();
    m.reset();
    if (!from_state.empty()) m.jumpTo(from_state);
    fireTask("next_" + segment.combined);
    log("subtask_start", "", detail);
    startBehavior(false);
  }

  /// The segment is over: its machine is back in a final state, or (on the way back) at a state
  /// with both clamps closed.
  void endSegment(bool abandoned = false) {
    StateMachine& m = *machine();
    const bool completed = !abandoned && m.inFinal() && m.steps() > 0;
    const Segment done = *segment_;
    if (completed) {
      ++summary_.subtasks_completed;
      if (done.counted && done.combined == "CB1") ++disc_;
      if (done.counted && done.combined == "CB3") --disc_;
      if (done.counted && done.combined == "CB2") ++summary_.discs_cleaned;
    }
    log("subtask_done", "",
        sensedText((completed ? "back in " : "stopped in ") + m.current(), m.current()));
    active_.reset();
    const std::string stopped_in = m.current();
    if (returning_) {
      if (!completed && !m.inFinal()) {
        // Half-way (e.g. CB1's q4): CB3 from this state undoes the half-done move.
        const CombinedBehavior* cb3 = model_.combinedBehavior("CB3");
        if (std::find(cb3->states.begin(), cb3->states.end(), stopped_in) == cb3->states.end()) {
          throw Error(model_.source + ": cannot return from state " + stopped_in +
                      ": it is not a state of CB3");
        }
        startSegment({"CB3", false, false},
                     "return: CB3 from " + stopped_in + " back to " + cb3->initial, stopped_in);
      } else if (disc_ > 0) {
        startSegment({"CB3", true, false},
                     "return: move up one disc (" + std::to_string(disc_) + " below the start)");
      } else {
        finish(endStatus(), "back at the start");
      }
      return;
    }
    if (return_after_disc_ && done.combined == "CB2") {
      startReturn("low battery: disc " + std::to_string(disc_) + " finished");
      return;
    }
    if (plan_index_ + 1 < summary_.plan.size()) {
      startPlanSubtask(plan_index_ + 1);
    } else {
      finish(endStatus(),
             "plan done, " + std::to_string(summary_.discs_cleaned) + " discs cleaned");
    }
  }

  // ---- behaviours -----------------------------------------------------------------------------

  /// Runs the behaviour of the current state (resume = the state is re-entered after a fault).
  void startBehavior(bool resume) {
    StateMachine& m = *machine();
    const std::string state = m.current();
    const CombinedBehavior& cb = *model_.combinedBehavior(segment_->combined);
    const Transition* t = cb.transitionFrom(state);
    if (!t) throw Error(model_.source + ": " + cb.name + ": no transition out of " + state);
    if (resume) {
      m.jumpTo(state);  // re-entry: the timeout starts again
      if (restorePose(state)) return;
    }
    const BehaviorRun run = resolveRun(model_, *t);
    runBehavior(run, false);
  }

  void runBehavior(const BehaviorRun& run, bool restore,
                   std::optional<std::string> reclose_to = std::nullopt) {
    Active a;
    a.behavior = run.behavior->name;
    a.event = run.target->ends_on;
    a.joint = simJointFromName(run.behavior->body.actuator);
    a.command = commandOf(run, a.joint, run.behavior->name);
    a.timeout = run.behavior->timeout_s;
    a.entered_at = sim_.time();
    a.restore = restore;
    a.reclose_to = std::move(reclose_to);
    if (a.event == "encoder_reached") {
      a.target_count = std::llround(a.command.value * countsPerUnit(a.joint));
    }
    if (a.event == "current_held") {
      const Parameter* i = run.behavior->parameter("I");
      const Parameter* hold = run.behavior->parameter("hold");
      if (!i || !hold) {
        throw Error(model_.source + ": " + a.behavior +
                    ": current_held needs parameters I and hold");
      }
      a.hold_current = i->unit == "mA" ? i->value / 1000.0 : i->value;
      a.hold_time = hold->unit == "ms" ? hold->value / 1000.0 : hold->value;
    }
    active_ = a;
    if (restore) {
      log("restore", a.behavior,
          "a fault stopped " + std::string(simJointName(a.joint)) + "; " + stateName() +
              " needs it: set again before resuming");
    }
    send(a.command, a.behavior);
  }

  double countsPerUnit(SimJoint joint) const {
    const RobotSimulatorConfig& c = sim_.config();
    switch (joint) {
      case SimJoint::kJ3:
        return c.j3.counts_per_unit;
      case SimJoint::kJ4:
        return c.j4.counts_per_unit;
      case SimJoint::kJ5:
        return c.j5.counts_per_unit;
      default:
        return 1.0;
    }
  }

  /// Before resuming `state`: a pose value that stopping every joint undid (a spinning brush)
  /// is set again first. \return whether a restoring behaviour was started.
  bool restorePose(const std::string& state) {
    const StatePose* pose = model_.poseOf(state);
    if (!pose) return false;
    for (std::size_t k = 0; k < model_.state_vector.components.size(); ++k) {
      const StateComponent& c = model_.state_vector.components[k];
      const std::string& value = c.values[pose->pose[k]];
      for (const BasicBehavior& b : model_.behaviors) {
        if (b.body.changes.size() != 1 || b.body.changes[0] != c.name) continue;
        const BehaviorTarget* target = b.body.target(value);
        if (!target || target->command != "spin") continue;
        const BehaviorRun run{&b, target, k, pose->pose[k], std::nullopt};
        const SimJoint joint = simJointFromName(b.body.actuator);
        const SimCommand spin = commandOf(run, joint, b.name);
        const SimJointState& j = sim_.snapshot().joint(joint);
        if (std::abs(j.velocity - spin.value) > 1e-9 * std::max(1.0, std::abs(spin.value))) {
          runBehavior(run, true);
          return true;
        }
      }
    }
    return false;
  }

  bool endingEventSeen(Active& a) {
    const SimSnapshot& s = sim_.snapshot();
    const SimJointState& j = s.joint(a.joint);
    if (a.event == "zero_switch") return j.zero_switch;
    if (a.event == "encoder_reached") return j.encoder == a.target_count;
    if (a.event == "encoder_zero") return j.encoder == 0;
    if (a.event == "speed_zero") return !j.moving && j.velocity == 0.0;
    if (a.event == "speed_reached") {
      return !j.moving && std::abs(j.velocity - a.command.value) <=
                              1e-9 * std::max(1.0, std::abs(a.command.value));
    }
    // current_held: at least I, without a break, for the hold time.
    if (j.current >= a.hold_current) {
      if (!a.held_since) a.held_since = s.time;
      return s.time - *a.held_since >= a.hold_time - 1e-9;
    }
    a.held_since.reset();
    return false;
  }

  /// A zero switch that reads pressed while its clamp's encoder says the jaw is more than half
  /// a degree open: a sensor fault, like a timeout (seed section 2.4 (2)). Checked on both
  /// clamps at every step, whatever runs: a switch stuck pressed on a closed jaw shows at once.
  /// \return the clamp and the text.
  std::optional<std::pair<SimJoint, std::string>> sensorMismatch() const {
    for (const SimJoint clamp : {kFixedClamp, kMovingClamp}) {
      const SimJointState& j = sim_.snapshot().joint(clamp);
      const SimClampConfig& c =
          clamp == kFixedClamp ? sim_.config().fixed_clamp : sim_.config().moving_clamp;
      if (!j.zero_switch || std::abs(static_cast<double>(j.encoder)) <= 0.5 * c.counts_per_deg) {
        continue;
      }
      return std::make_pair(clamp, std::string(simJointName(clamp)) +
                                       "'s zero switch reads pressed but its encoder reads " +
                                       number(static_cast<double>(j.encoder) / c.counts_per_deg) +
                                       " deg");
    }
    return std::nullopt;
  }

  /// The sensor check while the robot runs; \return false when it handed control to the
  /// operator. A disagreement already found while the robot stood still keeps its time.
  bool superviseSensors() {
    const auto mismatch = sensorMismatch();
    const std::optional<double> seen = std::exchange(mismatch_seen_at_, std::nullopt);
    mismatch_handed_over_ = mismatch.has_value();
    if (!mismatch) {
      if (seen) {  // found while stopped, gone before the robot ran again: the operator's repair
        react("sensor_mismatch", "found while the robot stood still; repaired before it ran again",
              std::nullopt, seen, sim_.time());
      }
      return true;
    }
    stopAll();
    if (!seen) log("sensor_mismatch", active_ ? active_->behavior : "", mismatch->second);
    handOver("sensor_mismatch", mismatch->second, sensorFaultAt(mismatch->first), seen);
    return false;
  }

  /// The sensor check while the robot stands still (waiting for the link, or in MANUAL): a
  /// disagreement is logged when it shows and handled when the robot runs again.
  void noteSensors() {
    if (mismatch_seen_at_ || mismatch_handed_over_) return;
    if (const auto mismatch = sensorMismatch()) {
      mismatch_seen_at_ = sim_.time();
      log("sensor_mismatch", active_ ? active_->behavior : "",
          mismatch->second + "; the robot stands still: handled when it runs again");
    }
  }

  /// When the fault file broke the sensor a behaviour on `joint` waits for [s], if it did.
  std::optional<double> sensorFaultAt(SimJoint joint) const {
    if (joint == kFixedClamp) return switch_fault_at_[0];
    if (joint == kMovingClamp) return switch_fault_at_[1];
    return std::nullopt;
  }

  void superviseBehavior() {
    if (!superviseSensors()) return;
    Active& a = *active_;
    if (endingEventSeen(a)) {
      if (a.command.kind == SimCommandKind::kClose || a.command.kind == SimCommandKind::kRelease) {
        sim_.command(SimCommand::stop(a.joint));  // the jaw holds: cut the motor
      }
      ++summary_.behaviors_run;
      if (a.restore) {
        log("restored", a.behavior, a.event);
        startBehavior(false);
        return;
      }
      if (a.reclose_to) {
        const std::string to = *a.reclose_to;
        active_.reset();
        log("reclosed", a.behavior, "both clamps grip: " + sensedText("in " + to, to));
        landOn(to, true);
        return;
      }
      StateMachine& m = *machine();
      const std::string from = m.current();
      const std::string behavior = a.behavior;
      if (!m.fire(a.event)) {
        throw Error(segment_->combined + ": no transition on '" + a.event + "' from " + from);
      }
      active_.reset();
      log(a.event, behavior, from + " -> " + m.current());
      if (m.inFinal() && m.steps() > 0) {
        endSegment();
      } else if (segment_->settling) {
        settle();
      } else {
        startBehavior(false);
      }
      return;
    }
    if (a.timeout && sim_.time() - a.entered_at >= *a.timeout - 1e-9) {
      stopAll();
      const std::string what =
          a.behavior + " did not end on " + a.event + " within " + number(*a.timeout) + " s";
      log("timeout", a.behavior, what);
      handOver("timeout", what, sensorFaultAt(a.joint));
    }
  }

  void stopAll() {
    for (std::size_t k = 0; k < kSimJointCount; ++k) {
      sim_.command(SimCommand::stop(static_cast<SimJoint>(k)));
    }
  }

  // ---- commands, the command check and the interference check ---------------------------------

  /// Sends a behaviour's command; \return false when it was refused (control handed over).
  bool send(const SimCommand& command, const std::string& behavior) {
    const bool ground = !returning_;  // on the way back the robot runs on its own
    if (ground && !sim_.snapshot().link_up) {
      log("command_not_sent", behavior, describe(command) + ": the link is down");
      return true;  // the link supervision stops everything and resends it
    }
    if (const auto both = opensBothClamps(command)) {
      violate("before sending " + describe(command) + ": " + *both);
      return false;
    }
    if (ground) {
      if (const auto corrupt = takeFault(FaultKind::kCorruptCommand)) {
        const std::uint64_t seq = ++seq_;
        const std::string what = "seq " + std::to_string(seq) + " (" + describe(command) +
                                 ") failed the robot's command check; its echo (seq " +
                                 std::to_string(seq - 1) + ", " + stateName() +
                                 ") did not match; resent";
        log("command_rejected", behavior, what, seq);
        react("corrupt_command", what, corrupt->at_s, sim_.time(), sim_.time());
      }
      if (command.kind != SimCommandKind::kStop) {
        if (auto f = takeFault(FaultKind::kWrongCommand)) {
          const std::uint64_t seq = ++seq_;
          log("command", behavior, "received " + describe(f->command) + " (wrong command)", seq);
          if (const auto reason = interference(f->command)) {
            log("refused", behavior, describe(f->command) + ": " + *reason, seq);
            react("wrong_command",
                  "refused " + describe(f->command) + " (" + *reason +
                      "); the behaviour's own command sent instead",
                  f->at_s, sim_.time(), sim_.time());
          } else {
            sim_.command(f->command);
            react("wrong_command",
                  describe(f->command) + " passed the interference check and was executed", f->at_s,
                  std::nullopt, std::nullopt);
            return true;
          }
        }
      }
    }
    const std::uint64_t seq = ++seq_;
    if (const auto reason = interference(command)) {
      log("refused", behavior, describe(command) + ": " + *reason, seq);
      safetyStop(command, behavior, *reason);
      return false;
    }
    sim_.command(command);
    log("command", behavior,
        describe(command) + (ground
                                 ? "; echo seq " + std::to_string(seq) + " " + stateName() +
                                       (sensorsFit(stateName())
                                            ? " matches"
                                            : ": " + sensedText("in " + stateName(), stateName()))
                                 : "; on board"),
        seq);
    return true;
  }

  /// Where the run is now, in `behavior`.
  RunPlace place(const std::string& behavior) const {
    const SimSnapshot& s = sim_.snapshot();
    return {s.step, s.time, subtask_, segment_ ? segment_->combined : "", stateName(), behavior};
  }

  /// A behaviour's own command was refused: every joint stops and the run ends there.
  void safetyStop(const SimCommand& command, const std::string& behavior,
                  const std::string& reason) {
    stopAll();
    SafetyStop stop;
    static_cast<RunPlace&>(stop) = place(behavior);
    stop.command = describe(command);
    stop.reason = reason;
    std::ostringstream text;
    text << "step " << stop.step << " (t = " << stop.t << " s): refused " << behavior
         << "'s own command " << stop.command << " in " << stop.combined << " " << stop.state
         << " (sub-task " << stop.subtask << "): " << reason;
    stop.message = text.str();
    summary_.safety_stop = stop;
    react("refused_own_command", "every joint stopped; the run ends (safety stop)", std::nullopt,
          sim_.time(), std::nullopt);
    finish(RunStatus::kSafetyStop, stop.message);
  }

  /// Why releasing a clamp would leave the robot hanging by neither (the other clamp does not
  /// grip, as its sensors say), or nothing.
  std::optional<std::string> opensBothClamps(const SimCommand& command) const {
    if (command.kind != SimCommandKind::kRelease) return std::nullopt;
    const SimJoint other = command.joint == kFixedClamp ? kMovingClamp : kFixedClamp;
    if (sim_.snapshot().joint(other).gripping) return std::nullopt;
    return std::string("it would open ") + simJointName(command.joint) + " while " +
           simJointName(other) + " does not grip: both clamps open";
  }

  /// The values a component may have: one per value index, true when possible.
  using ValueSet = std::vector<bool>;

  /// The values a positioned component (named positions, the robot's units) may have with its
  /// joint anywhere in [lo, hi]: every named position in the interval, and the nearest one on
  /// either side of each end that is not a named position (the joint is between them).
  static ValueSet valuesSpanned(const StateComponent& c, double lo, double hi) {
    constexpr double kSamePosition = 1e-9;  // [mm or deg] named positions are exact
    ValueSet set(c.values.size(), false);
    for (const double end : {lo, hi}) {
      int below = -1, above = -1;
      for (std::size_t v = 0; v < c.positions.size(); ++v) {
        const double p = c.positions[v];
        if (p <= end + kSamePosition && (below < 0 || p > c.positions[below]))
          below = static_cast<int>(v);
        if (p >= end - kSamePosition && (above < 0 || p < c.positions[above]))
          above = static_cast<int>(v);
      }
      if (below >= 0) set[below] = true;
      if (above >= 0) set[above] = true;
    }
    for (std::size_t v = 0; v < c.positions.size(); ++v) {
      if (c.positions[v] >= lo - kSamePosition && c.positions[v] <= hi + kSamePosition) {
        set[v] = true;
      }
    }
    return set;
  }

  /// The commands with which the model's behaviours set each value of component `k`.
  std::vector<std::vector<std::string>> commandsSetting(std::size_t k) const {
    const StateComponent& c = model_.state_vector.components[k];
    std::vector<std::vector<std::string>> commands(c.values.size());
    for (const BasicBehavior& b : model_.behaviors) {
      if (b.body.changes.size() != 1 || b.body.changes[0] != c.name) continue;
      for (const BehaviorTarget& target : b.body.targets) {
        const int v = c.indexOf(target.value);
        if (v >= 0) commands[v].push_back(target.command);
      }
    }
    return commands;
  }

  /// The pose the sensors read, per component the values it may have: a clamp's value is the
  /// one its close behaviour sets while it grips, its release's otherwise; a positioned joint's
  /// the named position its encoder reads, or the two it lies between; the brush's the value of
  /// its spin while it turns, of its stop at rest. A component the sensors cannot name may have
  /// any value.
  std::vector<ValueSet> sensedPose() const {
    const StateVectorSpec& spec = model_.state_vector;
    const SimSnapshot& s = sim_.snapshot();
    std::vector<ValueSet> pose;
    for (std::size_t k = 0; k < spec.components.size(); ++k) {
      const StateComponent& c = spec.components[k];
      ValueSet set(c.values.size(), false);
      SimJoint joint;
      try {
        joint = simJointFromName(c.actuator);
      } catch (const Error&) {
        pose.emplace_back(c.values.size(), true);
        continue;
      }
      const SimJointState& j = s.joint(joint);
      if (!c.positions.empty()) {
        const double at = static_cast<double>(j.encoder) / countsPerUnit(joint);
        set = valuesSpanned(c, at, at);
      } else {
        const auto commands = commandsSetting(k);
        const bool clamp = joint == kFixedClamp || joint == kMovingClamp;
        const bool turning = j.velocity != 0.0 || j.moving;
        for (std::size_t v = 0; v < c.values.size(); ++v) {
          for (const std::string& command : commands[v]) {
            if (clamp && (command == (j.gripping ? "close" : "release"))) set[v] = true;
            if (!clamp && command == (turning ? "spin" : "stop")) set[v] = true;
          }
        }
      }
      if (std::none_of(set.begin(), set.end(), [](bool b) { return b; }))
        set.assign(set.size(), true);
      pose.push_back(std::move(set));
    }
    return pose;
  }

  /// "fixed_clamp=closed moving_clamp=open j3=home|extended ...".
  std::string describePose(const std::vector<ValueSet>& pose) const {
    const StateVectorSpec& spec = model_.state_vector;
    std::string text;
    for (std::size_t k = 0; k < spec.components.size(); ++k) {
      text += (k ? " " : "") + spec.components[k].name + "=";
      bool first = true;
      for (std::size_t v = 0; v < pose[k].size(); ++v) {
        if (!pose[k][v]) continue;
        text += (first ? "" : "|") + spec.components[k].values[v];
        first = false;
      }
    }
    return text;
  }

  /// The first pose of the product of `pose`'s value sets that a rule forbids, with the rule.
  std::optional<std::pair<Pose, const PoseRule*>> forbiddenPose(
      const std::vector<ValueSet>& pose) const {
    const StateVectorSpec& spec = model_.state_vector;
    Pose p(pose.size(), 0);
    std::optional<std::pair<Pose, const PoseRule*>> found;
    std::function<void(std::size_t)> visit = [&](std::size_t k) {
      if (found) return;
      if (k == pose.size()) {
        if (const PoseRule* rule = spec.brokenRule(p)) found.emplace(p, rule);
        return;
      }
      for (std::size_t v = 0; v < pose[k].size(); ++v) {
        if (!pose[k][v]) continue;
        p[k] = static_cast<int>(v);
        visit(k + 1);
      }
    };
    visit(0);
    return found;
  }

  /// The FSM state whose pose the sensors read, when exactly one state's pose fits.
  std::optional<std::string> sensedState(const std::vector<ValueSet>& pose) const {
    std::optional<std::string> found;
    for (const StatePose& sp : model_.poses) {
      bool fits = true;
      for (std::size_t k = 0; k < pose.size() && fits; ++k) fits = pose[k][sp.pose[k]];
      if (!fits) continue;
      if (found) return std::nullopt;
      found = sp.state;
    }
    return found;
  }

  /// Whether the pose of `state` is one the sensors allow (a joint between two named positions
  /// allows either).
  bool sensorsFit(const std::string& state) const {
    const StatePose* sp = model_.poseOf(state);
    if (!sp) return false;
    const std::vector<ValueSet> pose = sensedPose();
    for (std::size_t k = 0; k < pose.size(); ++k) {
      if (!pose[k][sp->pose[k]]) return false;
    }
    return true;
  }

  /// For the log: `claim` (e.g. "back in q1") when the sensors fit the pose of `state`, else
  /// "the machine is back in q1, but the sensors read q6 (fixed_clamp=closed ...)".
  std::string sensedText(const std::string& claim, const std::string& state) const {
    if (sensorsFit(state)) return claim;
    const std::vector<ValueSet> pose = sensedPose();
    const std::optional<std::string> sensed = sensedState(pose);
    return "the machine is " + claim + ", but the sensors read " +
           (sensed ? *sensed + " (" : std::string("(")) + describePose(pose) + ")";
  }

  /// Why `command` must not be sent now, or nothing: the simulator's refuse() (joint limits,
  /// command kinds), a release while the other clamp does not grip, and the pose rules: every
  /// pose the robot may pass through while the command runs, from the pose the sensors read
  /// (not the machine's state) with the commanded component over the values between where it
  /// is and where the command takes it, must be allowed.
  std::optional<std::string> interference(const SimCommand& command) const {
    if (const auto reason = sim_.refuse(command)) return reason;
    if (const auto reason = opensBothClamps(command)) return reason;
    const StateVectorSpec& spec = model_.state_vector;
    const std::vector<ValueSet> sensed = sensedPose();
    for (std::size_t k = 0; k < spec.components.size(); ++k) {
      const StateComponent& c = spec.components[k];
      if (c.actuator != simJointName(command.joint)) continue;
      std::vector<ValueSet> pose = sensed;
      if (command.kind == SimCommandKind::kMoveTo && !c.positions.empty()) {
        const double at = static_cast<double>(sim_.snapshot().joint(command.joint).encoder) /
                          countsPerUnit(command.joint);
        pose[k] = valuesSpanned(c, std::min(at, command.value), std::max(at, command.value));
      } else {
        const auto commands = commandsSetting(k);
        for (std::size_t v = 0; v < c.values.size(); ++v) {
          for (const std::string& name : commands[v]) {
            if (name == commandKindName(command.kind)) pose[k][v] = true;
          }
        }
      }
      if (const auto bad = forbiddenPose(pose)) {
        return "from the pose the sensors read (" + describePose(sensed) +
               ") it would pass through " + spec.describe(bad->first) + ", which pose rule '" +
               bad->second->name + "' forbids";
      }
    }
    return std::nullopt;
  }

  std::optional<InjectedFault> takeFault(FaultKind kind) {
    for (auto it = pending_.begin(); it != pending_.end(); ++it) {
      if (it->kind == kind) {
        InjectedFault f = *it;
        pending_.erase(it);
        return f;
      }
    }
    return std::nullopt;
  }

  // ---- faults and exceptions ------------------------------------------------------------------

  void applyFaults() {
    const double t = sim_.time();
    while (next_fault_ < faults_.size() && faults_[next_fault_].at_s <= t + 1e-9) {
      const InjectedFault& f = faults_[next_fault_++];
      std::string detail = faultKindName(f.kind);
      switch (f.kind) {
        case FaultKind::kLinkDown:
          if (sim_.snapshot().link_up) outage_injected_at_ = t;  // an outage starts
          sim_.setLinkUp(false);
          if (f.duration_s) {
            link_back_at_.push_back(t + *f.duration_s);
          } else {
            link_down_for_good_ = true;
          }
          detail += f.duration_s ? " for " + number(*f.duration_s) + " s" : " for good";
          break;
        case FaultKind::kZeroSwitchStuck: {
          const bool fixed = f.clamp == kFixedClamp;
          const SimFault sf = fixed ? (f.reads_pressed ? SimFault::kFixedZeroSwitchAlwaysPressed
                                                       : SimFault::kFixedZeroSwitchNeverPressed)
                                    : (f.reads_pressed ? SimFault::kMovingZeroSwitchAlwaysPressed
                                                       : SimFault::kMovingZeroSwitchNeverPressed);
          sim_.setFault(sf);
          switch_fault_at_[fixed ? 0 : 1] = t;
          detail += std::string(": ") + simJointName(f.clamp) + " reads " +
                    (f.reads_pressed ? "pressed" : "not pressed");
          break;
        }
        case FaultKind::kBatteryDrain:
          drain_ += f.current_a;
          sim_.setFault(SimFault::kBatteryDrain, drain_);
          detail += ": +" + number(f.current_a) + " A";
          break;
        case FaultKind::kCorruptCommand:
        case FaultKind::kWrongCommand:
          pending_.push_back(f);
          detail += ": armed for the next command";
          break;
      }
      log("fault_injected", "", detail);
    }
    for (auto it = link_back_at_.begin(); it != link_back_at_.end();) {
      if (*it <= t + 1e-9) {
        it = link_back_at_.erase(it);
        if (link_back_at_.empty() && !link_down_for_good_) {
          sim_.setLinkUp(true);
          log("link_up", "", "the radio link is back");
          resolve(until_link_);
        }
      } else {
        ++it;
      }
    }
  }

  void superviseLink() {
    const bool up = sim_.snapshot().link_up;
    if (up) link_loss_noted_ = false;
    if (!up && !link_loss_noted_ && (returning_ || mode_ == Mode::kManual)) {
      link_loss_noted_ = true;
      const std::string what = returning_ ? "during the return: nothing changes, the robot "
                                            "returns on its own"
                                          : "in MANUAL: the robot stays stopped; the operator "
                                            "acts once the link is back";
      log("link_lost", active_ ? active_->behavior : "", what);
      until_link_.push_back(
          react("link_down", what, outage_injected_at_, sim_.time(), std::nullopt));
    }
    if (mode_ == Mode::kRunning && !returning_ && !up) {
      link_loss_noted_ = true;
      stopAll();
      link_lost_at_ = sim_.time();
      mode_ = Mode::kWaitingForLink;
      fireTask("link_lost");
      log("link_lost", active_ ? active_->behavior : "",
          "every joint stopped; waiting up to " + number(options_.faults.link_wait_s) +
              " s for the link");
      return;
    }
    if (mode_ != Mode::kWaitingForLink) return;
    if (up) {
      const double waited = sim_.time() - link_lost_at_;
      react("link_down", "stopped, link back after " + number(waited) + " s, resumed",
            outage_injected_at_, link_lost_at_, sim_.time());
      mode_ = Mode::kRunning;
      fireTask("resume_" + segment_->combined);  // back to the interrupted superstate
      log("link_restored", "", "resuming " + stateName());
      startBehavior(true);
    } else if (sim_.time() - link_lost_at_ >= options_.faults.link_wait_s - 1e-9) {
      until_start_.push_back(react("link_down",
                                   "stopped, no link after " + number(options_.faults.link_wait_s) +
                                       " s, returned to the start on its own",
                                   outage_injected_at_, link_lost_at_, std::nullopt));
      mode_ = Mode::kRunning;
      fireTask("resume_" + segment_->combined);  // back to the interrupted superstate
      startReturn("no link for " + number(options_.faults.link_wait_s) + " s");
    }
  }

  /// Control to the operator (MANUAL), with the next scripted response if there is one.
  /// \param detected when the fault was found [s]; now when not given.
  void handOver(const std::string& fault, const std::string& what, std::optional<double> injected,
                std::optional<double> detected = std::nullopt) {
    if (!detected) detected = sim_.time();
    mode_ = Mode::kManual;
    fireTask("hand_over");
    const auto& responses = options_.faults.operator_responses;
    if (next_response_ >= responses.size()) {
      react(fault, what + "; control to the operator; no scripted response: the run stops",
            injected, detected, std::nullopt);
      finish(RunStatus::kHaltedInManual, "waiting for the operator after: " + what);
      return;
    }
    response_ = responses[next_response_++];
    response_at_ = sim_.time() + response_->after_s;
    until_operator_.push_back(react(fault,
                                    what + "; control to the operator; scripted response " +
                                        operatorActionName(response_->action) + " after " +
                                        number(response_->after_s) + " s",
                                    injected, detected, std::nullopt));
    log("manual", "", "control to the operator: " + what);
  }

  void superviseOperator() {
    if (mode_ != Mode::kManual || sim_.time() < response_at_ - 1e-9) return;
    if (!returning_ && !sim_.snapshot().link_up) {  // the operator works from the ground
      if (link_back_at_.empty() || link_down_for_good_) {
        finish(RunStatus::kHaltedInManual,
               "the operator cannot reach the robot: the link is down for good");
      }
      return;
    }
    const OperatorAction action = response_->action;
    response_.reset();
    resolve(until_operator_);
    if (action == OperatorAction::kRepairAndResume) {
      for (const SimFault f :
           {SimFault::kFixedZeroSwitchNeverPressed, SimFault::kFixedZeroSwitchAlwaysPressed,
            SimFault::kMovingZeroSwitchNeverPressed, SimFault::kMovingZeroSwitchAlwaysPressed}) {
        sim_.setFault(f, 0.0);
      }
      switch_fault_at_ = {};
    }
    mode_ = Mode::kRunning;
    fireTask("resume_" + segment_->combined);  // back to the interrupted superstate
    log("operator", "", operatorActionName(action));
    if (action == OperatorAction::kReturn) {
      startReturn("the operator's order");
    } else {
      startBehavior(true);
    }
  }

  void superviseBattery() {
    if (battery_alarm_ || !sim_.snapshot().battery_low) return;
    battery_alarm_ = true;
    summary_.battery_alarm_t = sim_.time();
    const std::string voltage = number(sim_.snapshot().battery_voltage) + " V";
    log("battery_low", active_ ? active_->behavior : "", "alarm: battery at " + voltage);
    if (options_.faults.low_battery == LowBatteryPolicy::kAlarmOnly) {
      react("battery_low", "alarm at " + voltage + "; the job goes on (policy alarm_only)",
            std::nullopt, sim_.time(), sim_.time());
    } else if (returning_ || (segment_ && segment_->combined == "CB3")) {
      until_start_.push_back(react("battery_low",
                                   "alarm at " + voltage + "; already on the way back",
                                   std::nullopt, sim_.time(), std::nullopt));
    } else {
      return_after_disc_ = true;
      until_start_.push_back(react(
          "battery_low",
          "alarm at " + voltage + "; finishing disc " +
              std::to_string(disc_ + (segment_->combined == "CB1" ? 1 : 0)) + ", then returning",
          std::nullopt, sim_.time(), std::nullopt));
    }
  }

  /// Back to the start: the interrupted behaviour is finished first (it may have half moved a
  /// jaw: the state's pose is not what the robot has), then CB1 goes on to the next state with
  /// both clamps closed, CB2 and CB3 to their end; CB3 from a CB1 state other than q1 undoes
  /// the half-done move; then one CB3 per disc below the start.
  void startReturn(const std::string& why) {
    returning_ = true;
    const int climbs = disc_ + (returnCompletesCb1() ? 1 : 0);
    log("return_start", "",
        why + "; " + std::to_string(climbs) + " disc(s) to climb back to the start" +
            (climbs != disc_ ? " (the CB1 in hand goes on to its end first)" : ""));
    if (!active_) {  // between sub-tasks
      endSegmentForReturn();
      return;
    }
    if (segment_->combined == "CB2") {
      startBehavior(true);  // CB2 holds with both clamps throughout: on to its end
    } else {
      segment_->settling = true;
      settle();
    }
  }

  /// The joint value class of J3 its encoder reads exactly (home, extended), or -1 mid-travel.
  int j3Class() const {
    const StateVectorSpec& spec = model_.state_vector;
    for (std::size_t k = 0; k < spec.components.size(); ++k) {
      const StateComponent& c = spec.components[k];
      if (c.actuator != "J3") continue;
      const std::int64_t encoder = sim_.snapshot().joint(SimJoint::kJ3).encoder;
      for (std::size_t v = 0; v < c.positions.size(); ++v) {
        if (encoder == std::llround(c.positions[v] * countsPerUnit(SimJoint::kJ3))) {
          return static_cast<int>(v);
        }
      }
    }
    return -1;
  }

  /// What settle() does in a state: run the state's own behaviour; land in `to` at once (both
  /// clamps grip); or close the open clamp again with `closer` and land in `to`.
  struct SettleStep {
    enum Kind { kOwn, kLand, kReclose } kind{kOwn};
    std::string to;
    const BasicBehavior* closer{nullptr};
    SimJoint open{kFixedClamp};
  };

  /// settle()'s decision in `state` of the current CB1 or CB3, the clamps gripping as given and
  /// J3 in position class `j3` (-1: mid travel).
  SettleStep settleStep(const std::string& state, bool fixed, bool moving, int j3) const {
    const CombinedBehavior& cb = *model_.combinedBehavior(segment_->combined);
    const BehaviorRun own = resolveRun(model_, *cb.transitionFrom(state));
    const SimJoint open = fixed ? kMovingClamp : kFixedClamp;
    if (j3 < 0 || (!(fixed && moving) && own.behavior->body.actuator == simJointName(open) &&
                   own.target->command == "close")) {
      return {};  // J3 mid travel, or the state's own behaviour closes the clamp
    }
    // The state whose pose is the robot's once both clamps grip: the state's pose with both
    // clamps closed and J3 where its encoder says.
    const StateVectorSpec& spec = model_.state_vector;
    Pose pose = model_.poseOf(state)->pose;
    for (const int k : {fixed_component_, moving_component_}) {
      pose[k] = spec.components[k].indexOf("closed");
    }
    for (std::size_t k = 0; k < spec.components.size(); ++k) {
      if (spec.components[k].actuator == "J3") pose[k] = j3;
    }
    std::string to;
    for (const std::string& q : cb.states) {
      if (model_.poseOf(q)->pose == pose) to = q;
    }
    if (to.empty()) return {};  // the model has no such state: go on instead
    if (fixed && moving) return {SettleStep::kLand, to, nullptr, open};
    for (const BasicBehavior& b : model_.behaviors) {
      const BehaviorTarget* target = b.body.target("closed");
      if (b.body.actuator != simJointName(open) || !target || target->command != "close") continue;
      return {SettleStep::kReclose, to, &b, open};
    }
    return {};  // the model has no behaviour that closes this clamp
  }

  /// On the way back in CB1 or CB3: reach a state whose pose has both clamps closed by the
  /// shortest safe way. Both clamps gripping: the robot is there. One clamp open (or half
  /// released) with J3 at a named position, so that its platform sits at a disc: close it again
  /// (the clamp's close behaviour) unless the state's own behaviour is that very close; J3 mid
  /// travel: finish the state's own behaviour first, then settle again.
  void settle() {
    StateMachine& m = *machine();
    const std::string state = m.current();
    const SimSnapshot& s = sim_.snapshot();
    const SettleStep step =
        settleStep(state, s.joint(kFixedClamp).gripping, s.joint(kMovingClamp).gripping, j3Class());
    const CombinedBehavior& cb = *model_.combinedBehavior(segment_->combined);
    const Transition& own_transition = *cb.transitionFrom(state);
    if (step.kind == SettleStep::kOwn) {
      startBehavior(true);
      return;
    }
    if (step.kind == SettleStep::kLand) {  // the state's own close gripped before the stop
      landOn(step.to, step.to != own_transition.to);
      return;
    }
    const StateVectorSpec& spec = model_.state_vector;
    const int component = step.open == kFixedClamp ? fixed_component_ : moving_component_;
    m.jumpTo(state);
    const BehaviorRun run{step.closer, step.closer->body.target("closed"),
                          static_cast<std::size_t>(component),
                          spec.components[component].indexOf("closed"), std::nullopt};
    log("reclose", step.closer->name,
        std::string(simJointName(step.open)) + " closes again instead of " +
            own_transition.behavior + ": the shortest way to both clamps gripping, in " + step.to);
    runBehavior(run, false, step.to);
  }

  /// Whether a return starting now brings the CB1 in hand to its end (settle() runs its own
  /// behaviours until it is back in a final state), so that it counts one disc more to climb.
  /// Follows settle()'s decisions from the sensed clamps and J3, then from each state's pose.
  bool returnCompletesCb1() {
    if (!active_ || !segment_ || segment_->combined != "CB1") return false;
    const CombinedBehavior& cb = *model_.combinedBehavior("CB1");
    const StateMachine& m = *machine();
    const StateVectorSpec& spec = model_.state_vector;
    std::string state = m.current();
    std::size_t steps = m.steps();
    const SimSnapshot& s = sim_.snapshot();
    bool fixed = s.joint(kFixedClamp).gripping, moving = s.joint(kMovingClamp).gripping;
    int j3 = j3Class();
    for (std::size_t n = 0; n <= cb.transitions.size(); ++n) {
      const SettleStep step = settleStep(state, fixed, moving, j3);
      const std::string own_to = cb.transitionFrom(state)->to;
      if (step.kind != SettleStep::kOwn) {  // landOn(): complete only by its own transitions
        const bool reversal = step.kind == SettleStep::kReclose || step.to != own_to;
        return m.isFinal(step.to) && !reversal && steps > 0;
      }
      state = own_to;
      ++steps;
      if (m.isFinal(state)) return true;
      const Pose& pose = model_.poseOf(state)->pose;
      fixed = pose[fixed_component_] == spec.components[fixed_component_].indexOf("closed");
      moving = pose[moving_component_] == spec.components[moving_component_].indexOf("closed");
      for (std::size_t k = 0; k < spec.components.size(); ++k) {
        if (spec.components[k].actuator == "J3") j3 = pose[k];
      }
    }
    return false;
  }

  /// The robot holds the string with both clamps in state `to` of the current CB1 or CB3
  /// (`reversal`: reached by closing a clamp again, not by the machine's own transitions).
  void landOn(const std::string& to, bool reversal) {
    StateMachine& m = *machine();
    segment_->settling = false;
    if (to != m.current()) m.jumpTo(to);
    if (m.inFinal()) {
      // Back where the segment started (a reversal) or at its end (its last transition).
      endSegment(reversal || m.steps() == 0);
    } else if (segment_->combined == "CB1") {
      endSegment(true);  // CB3 from here undoes the half-done move
    } else {
      startBehavior(false);  // CB3: on up to its end
    }
  }

  void endSegmentForReturn() {
    if (disc_ > 0) {
      startSegment({"CB3", true, false},
                   "return: move up one disc (" + std::to_string(disc_) + " below the start)");
    } else {
      finish(endStatus(), "back at the start");
    }
  }

  /// Back at the start: completed when every disc was cleaned, returned otherwise.
  RunStatus endStatus() const {
    return summary_.discs_cleaned == options_.insulators && disc_ == 0 ? RunStatus::kCompleted
                                                                       : RunStatus::kReturned;
  }

  bool checkInvariant() {
    const SimSnapshot& s = sim_.snapshot();
    if (s.joint(kFixedClamp).gripping || s.joint(kMovingClamp).gripping) return true;
    violate("both clamps open");
    return false;
  }

  /// Stops the run on the safety invariant (never both clamps open): broken at this step, or
  /// about to be by a command.
  void violate(const std::string& what) {
    InvariantViolation v;
    static_cast<RunPlace&>(v) = place(active_ ? active_->behavior : "");
    std::ostringstream text;
    text << "step " << v.step << " (t = " << v.t << " s): " << what << ": sub-task " << v.subtask
         << " (" << v.combined << "), state " << v.state << ", behaviour "
         << (v.behavior.empty() ? "none" : v.behavior);
    v.message = text.str();
    summary_.violation = v;
    log("invariant_violated", v.behavior, v.message);
    stopAll();
    finish(RunStatus::kInvariantViolated, v.message);
  }

  void accountPhase() {
    if (!segment_) return;
    const double dt = sim_.config().dt;
    (segment_->combined == "CB2" ? summary_.phase_two_s : summary_.phase_one_s) += dt;
  }

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

}  // namespace

const char* runStatusName(RunStatus status) {
  switch (status) {
    case RunStatus::kCompleted:
      return "completed";
    case RunStatus::kReturned:
      return "returned";
    case RunStatus::kHaltedInManual:
      return "halted_in_manual";
    case RunStatus::kInvariantViolated:
      return "invariant_violated";
    case RunStatus::kTimeLimit:
      return "time_limit";
    case RunStatus::kBatteryEmpty:
      return "battery_empty";
    case RunStatus::kSafetyStop:
      return "safety_stop";
  }
  return "unknown";
}

RobotSimulatorConfig simulatorConfigFor(const BehaviorModel& model, int insulators) {
  RobotSimulatorConfig config;
  if (model.insulator.pitch_mm > 0.0) config.string.pitch = model.insulator.pitch_mm;
  config.string.home_gap = 2.0 * config.string.pitch;
  config.string.tolerance = std::min(config.string.tolerance, 0.25 * config.string.pitch);
  config.string.disc_count = std::max(insulators, 0) + 2;
  return config;
}

RunOptions RunOptions::forModel(const BehaviorModel& model, int insulators) {
  RunOptions options;
  options.insulators = insulators;
  options.simulator = simulatorConfigFor(model, insulators);
  return options;
}

StateMachine taskMachine() {
  StateMachine m("task");
  for (const char* s : {"idle", "CB1", "CB2", "CB3", "FAULT", "MANUAL", "done"}) m.addState(s);
  m.setStateLabel("CB1", "CB1\nmove down one disc");
  m.setStateLabel("CB2", "CB2\nclean the disc");
  m.setStateLabel("CB3", "CB3\nmove up one disc");
  m.setStateLabel("FAULT", "FAULT\nlink lost: stopped");
  m.setStateLabel("MANUAL", "MANUAL\noperator in control");
  m.addTransition("idle", "next_CB1", "CB1");
  m.addTransition("CB1", "next_CB2", "CB2");
  m.addTransition("CB2", "next_CB1", "CB1");
  // On to CB3 from any superstate: the plan's way back, or a return after a fault.
  for (const char* s : {"CB1", "CB2", "CB3"}) {
    m.addTransition(s, "next_CB3", "CB3");
    m.addTransition(s, "job_done", "done");
    m.addTransition(s, "link_lost", "FAULT");
    m.addTransition(s, "hand_over", "MANUAL");
    m.addTransition("FAULT", std::string("resume_") + s, s);
    m.addTransition("MANUAL", std::string("resume_") + s, s);
  }
  m.setInitial("idle");
  m.addFinal("done");
  return m;
}

RunSummary runCleaningJob(const BehaviorModel& model, const RunOptions& options,
                          const RunObserver& observer) {
  return CleaningRun(model, options, observer).run();
}

}  // namespace mcws
