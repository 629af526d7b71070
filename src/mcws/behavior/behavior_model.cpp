#include "mcws/behavior/behavior_model.h"

#include <algorithm>

#include "mcws/core/error.h"
#include "mcws/core/yaml_reader.h"

namespace mcws {

// ---- items -------------------------------------------------------------------------------------

const BehaviorTarget* BehaviorBody::target(const std::string& value) const {
  for (const BehaviorTarget& t : targets) {
    if (t.value == value) return &t;
  }
  return nullptr;
}

const Parameter* BasicBehavior::parameter(const std::string& parameter_name) const {
  for (const Parameter& p : parameters) {
    if (p.name == parameter_name) return &p;
  }
  return nullptr;
}

std::vector<std::string> CombinedBehavior::events() const {
  std::vector<std::string> out;
  for (const Transition& t : transitions) {
    if (std::find(out.begin(), out.end(), t.event) == out.end()) out.push_back(t.event);
  }
  return out;
}

const Transition* CombinedBehavior::transitionFrom(const std::string& state) const {
  for (const Transition& t : transitions) {
    if (t.from == state) return &t;
  }
  return nullptr;
}

int StateComponent::indexOf(const std::string& value) const {
  const auto it = std::find(values.begin(), values.end(), value);
  return it == values.end() ? -1 : static_cast<int>(it - values.begin());
}

bool PoseCondition::matches(const Pose& pose) const {
  return std::find(values.begin(), values.end(), pose[component]) != values.end();
}

bool PoseRule::brokenBy(const Pose& pose) const {
  for (const PoseCondition& c : when) {
    if (!c.matches(pose)) return false;
  }
  for (const PoseCondition& c : require) {
    if (!c.matches(pose)) return true;
  }
  return false;
}

std::size_t StateVectorSpec::combinations() const {
  std::size_t n = 1;
  for (const StateComponent& c : components) n *= c.values.size();
  return n;
}

const PoseRule* StateVectorSpec::brokenRule(const Pose& pose) const {
  for (const PoseRule& rule : rules) {
    if (rule.brokenBy(pose)) return &rule;
  }
  return nullptr;
}

std::vector<Pose> StateVectorSpec::allowedPoses() const {
  std::vector<Pose> out;
  if (components.empty()) return out;
  Pose pose(components.size(), 0);
  while (true) {
    if (allowed(pose)) out.push_back(pose);
    // Odometer order: the last component varies fastest.
    std::size_t k = components.size();
    while (k > 0) {
      --k;
      if (++pose[k] < static_cast<int>(components[k].values.size())) break;
      pose[k] = 0;
      if (k == 0) return out;
    }
  }
}

int StateVectorSpec::componentIndex(const std::string& component_name) const {
  for (std::size_t k = 0; k < components.size(); ++k) {
    if (components[k].name == component_name) return static_cast<int>(k);
  }
  return -1;
}

std::string StateVectorSpec::describe(const Pose& pose) const {
  std::string out;
  for (std::size_t k = 0; k < components.size() && k < pose.size(); ++k) {
    out += (k ? " " : "") + components[k].name + "=" + components[k].values[pose[k]];
  }
  return out;
}

const BasicBehavior* BehaviorModel::behavior(const std::string& behavior_name) const {
  for (const BasicBehavior& b : behaviors) {
    if (b.name == behavior_name) return &b;
  }
  return nullptr;
}

const CombinedBehavior* BehaviorModel::combinedBehavior(const std::string& cb_name) const {
  for (const CombinedBehavior& cb : combined) {
    if (cb.name == cb_name) return &cb;
  }
  return nullptr;
}

const EventSpec* BehaviorModel::event(const std::string& event_name) const {
  for (const EventSpec& e : events) {
    if (e.name == event_name) return &e;
  }
  return nullptr;
}

const StatePose* BehaviorModel::poseOf(const std::string& state) const {
  for (const StatePose& p : poses) {
    if (p.state == state) return &p;
  }
  return nullptr;
}

BehaviorRun resolveRun(const BehaviorModel& model, const Transition& transition) {
  const std::string where = atLine(model.source, transition.line) + ": transition " +
                            transition.from + " -> " + transition.to + ": ";
  BehaviorRun run;
  run.behavior = model.behavior(transition.behavior);
  if (!run.behavior) throw Error(where + "unknown behaviour '" + transition.behavior + "'");
  const BehaviorBody& body = run.behavior->body;
  run.target = transition.target.empty()
                   ? (body.targets.size() == 1 ? &body.targets.front() : nullptr)
                   : body.target(transition.target);
  if (!run.target) {
    throw Error(where + transition.behavior + " has no target '" + transition.target + "'");
  }
  const int k =
      body.changes.size() == 1 ? model.state_vector.componentIndex(body.changes.front()) : -1;
  if (k < 0) throw Error(where + transition.behavior + " does not change one known component");
  const StateComponent& c = model.state_vector.components[k];
  run.component = static_cast<std::size_t>(k);
  run.value = c.indexOf(run.target->value);
  if (run.value < 0) {
    throw Error(where + "'" + run.target->value + "' is not a value of " + c.name);
  }
  if (run.target->command == "move_to" && !c.positions.empty()) {
    run.position = c.positions[run.value];
  }
  return run;
}

Pose applyRun(const BehaviorRun& run, Pose pose) {
  pose.at(run.component) = run.value;
  return pose;
}

std::optional<std::string> fileStemProblem(const std::string& name) {
  if (name.empty()) return std::string("must not be empty");
  if (name.size() > 200) {
    return "has " + std::to_string(name.size()) + " bytes, more than 200";
  }
  if (name.front() == '.') return std::string("must not start with '.'");
  for (const char c : name) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '/' || c == '\\') return std::string("must not contain '/' or '\\'");
    if (byte < 0x20 || byte == 0x7f) return std::string("must not contain a control byte");
  }
  return std::nullopt;
}

std::string quotedName(const std::string& name) {
  static const char kHex[] = "0123456789abcdef";
  std::string out = "'";
  for (const char c : name) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte >= 0x7f || c == '\\' || c == '\'') {
      out += "\\x";
      out += kHex[byte >> 4];
      out += kHex[byte & 0xf];
    } else {
      out += c;
    }
  }
  return out + "'";
}

StateMachine stateMachineOf(const CombinedBehavior& combined) {
  StateMachine machine(combined.name);
  for (const std::string& s : combined.states) machine.addState(s);
  for (const Transition& t : combined.transitions) {
    machine.addTransition(t.from, t.event, t.to,
                          t.behavior + (t.target.empty() ? "" : " " + t.target) + "\n" + t.event);
  }
  if (!combined.initial.empty()) machine.setInitial(combined.initial);
  for (const std::string& f : combined.finals) machine.addFinal(f);
  return machine;
}

}  // namespace mcws
