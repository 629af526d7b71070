// CleaningRun (cleaning_run.h): sub-tasks (a combined behaviour's FSM, run state by state) and
// basic behaviours (a command, then its ending event or its timeout).

#include "mcws/behavior/cleaning_run.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "mcws/core/decimal.h"
#include "mcws/core/error.h"

namespace mcws {
namespace cleaning {

void CleaningRun::startPlanSubtask(std::size_t index) {
  plan_index_ = index;
  const Subtask& s = summary_.plan[index];
  startSegment({s.behavior, true, false}, s.action + " -> disc " + std::to_string(s.disc) +
                                              " (plan " + std::to_string(index + 1) + "/" +
                                              std::to_string(summary_.plan.size()) + ")");
}

void CleaningRun::startSegment(const Segment& segment, const std::string& detail,
                               const std::string& from_state) {
  segment_ = segment;
  ++subtask_;
  StateMachine& m = *machine();
  m.reset();
  if (!from_state.empty()) m.jumpTo(from_state);
  fireTask("next_" + segment.combined);
  log("subtask_start", "", detail);
  startBehavior(false);
}

void CleaningRun::endSegment(bool abandoned) {
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
    finish(endStatus(), "plan done, " + std::to_string(summary_.discs_cleaned) + " discs cleaned");
  }
}

void CleaningRun::startBehavior(bool resume) {
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

void CleaningRun::runBehavior(const BehaviorRun& run, bool restore,
                              std::optional<std::string> reclose_to) {
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
      throw Error(model_.source + ": " + a.behavior + ": current_held needs parameters I and hold");
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

bool CleaningRun::restorePose(const std::string& state) {
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

bool CleaningRun::endingEventSeen(Active& a) {
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

void CleaningRun::superviseBehavior() {
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
        a.behavior + " did not end on " + a.event + " within " + formatNumber(*a.timeout) + " s";
    log("timeout", a.behavior, what);
    handOver("timeout", what, sensorFaultAt(a.joint));
  }
}

void CleaningRun::stopAll() {
  for (std::size_t k = 0; k < kSimJointCount; ++k) {
    sim_.command(SimCommand::stop(static_cast<SimJoint>(k)));
  }
}

}  // namespace cleaning
}  // namespace mcws
