#include "mcws/behavior/cleaning_run.h"

#include <algorithm>

#include "mcws/core/decimal.h"
#include "mcws/core/error.h"

namespace mcws {
namespace cleaning {
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

}  // namespace

CleaningRun::CleaningRun(const BehaviorModel& model, const RunOptions& options,
                         const RunObserver& observer)
    : model_(model), options_(options), observer_(observer), sim_(options.simulator) {
  validateBehaviorModel(model_);
  if (options_.insulators < 1) {
    throw Error("insulators: " + std::to_string(options_.insulators) + " discs; must be >= 1");
  }
  if (!(options_.max_time_s > 0.0)) {
    throw Error("max_time: " + formatNumber(options_.max_time_s) + " s; must be > 0");
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

RunSummary CleaningRun::run() {
  log("run_start", "",
      std::to_string(options_.insulators) + " discs, " + std::to_string(summary_.plan.size()) +
          " sub-tasks");
  notifyStep();
  applyFaults();  // those at time 0 act on the first command
  startPlanSubtask(0);
  while (mode_ != Mode::kDone) {
    if (sim_.time() >= options_.max_time_s) {
      finish(RunStatus::kTimeLimit,
             "simulated time limit " + formatNumber(options_.max_time_s) + " s reached");
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

void CleaningRun::accountPhase() {
  if (!segment_) return;
  const double dt = sim_.config().dt;
  (segment_->combined == "CB2" ? summary_.phase_two_s : summary_.phase_one_s) += dt;
}

void CleaningRun::findClampComponents() {
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

void CleaningRun::checkRunnable() const {
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

SimCommand CleaningRun::commandOf(const BehaviorRun& run, SimJoint joint,
                                  const std::string& where) const {
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
        throw Error(where + ": parameter speed is in " + speed->unit + "; " + simJointName(joint) +
                    " needs " + unit);
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

double CleaningRun::countsPerUnit(SimJoint joint) const {
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

void CleaningRun::log(const std::string& event, const std::string& behavior,
                      const std::string& detail, std::optional<std::uint64_t> seq) {
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

void CleaningRun::notifyStep() {
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

std::size_t CleaningRun::react(const std::string& fault, const std::string& reaction,
                               std::optional<double> injected, std::optional<double> detected,
                               std::optional<double> resolved) {
  summary_.faults.push_back({fault, injected, detected, resolved, reaction});
  return summary_.faults.size() - 1;
}

void CleaningRun::resolve(std::vector<std::size_t>& open) {
  for (const std::size_t k : open) summary_.faults[k].resolved_t = sim_.time();
  open.clear();
}

void CleaningRun::fireTask(const std::string& event) {
  if (!task_.fire(event)) {
    throw Error("task machine: no transition on '" + event + "' from '" + task_.current() + "'");
  }
}

void CleaningRun::finish(RunStatus status, const std::string& detail) {
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

}  // namespace cleaning

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
  return cleaning::CleaningRun(model, options, observer).run();
}

}  // namespace mcws
