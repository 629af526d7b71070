// CleaningRun (cleaning_run.h): the return to the start: settle where both clamps grip, then one
// CB3 per disc below the start.

#include "mcws/behavior/cleaning_run.h"

#include <cmath>

namespace mcws {
namespace cleaning {

void CleaningRun::startReturn(const std::string& why) {
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

int CleaningRun::j3Class() const {
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

SettleStep CleaningRun::settleStep(const std::string& state, bool fixed, bool moving,
                                   int j3) const {
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

void CleaningRun::settle() {
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
      std::string(simJointName(step.open)) + " closes again instead of " + own_transition.behavior +
          ": the shortest way to both clamps gripping, in " + step.to);
  runBehavior(run, false, step.to);
}

bool CleaningRun::returnCompletesCb1() {
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

void CleaningRun::landOn(const std::string& to, bool reversal) {
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

void CleaningRun::endSegmentForReturn() {
  if (disc_ > 0) {
    startSegment({"CB3", true, false},
                 "return: move up one disc (" + std::to_string(disc_) + " below the start)");
  } else {
    finish(endStatus(), "back at the start");
  }
}

RunStatus CleaningRun::endStatus() const {
  return summary_.discs_cleaned == options_.insulators && disc_ == 0 ? RunStatus::kCompleted
                                                                     : RunStatus::kReturned;
}

}  // namespace cleaning
}  // namespace mcws
