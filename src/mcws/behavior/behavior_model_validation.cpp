#include "mcws/behavior/behavior_model.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <utility>

#include "mcws/core/error.h"
#include "mcws/core/yaml_reader.h"

namespace mcws {
namespace {

/// Commands a basic behaviour may give its actuator.
const std::set<std::string> kCommands = {"close", "release", "move_to", "spin", "stop"};

/// Throws at the first problem of a model; each check names the item and its line.
class Validator {
 public:
  explicit Validator(const BehaviorModel& model) : model_(model) {}

  ValidationReport run() {
    checkStateVector();
    checkBehaviors();
    checkPoses();
    for (const CombinedBehavior& cb : model_.combined) checkCombined(cb);
    return report();
  }

 private:
  [[noreturn]] void fail(int line, const std::string& message) const {
    throw Error(atLine(model_.source, line) + ": " + message);
  }

  void checkStateVector() const {
    if (!model_.robot) return;
    const Robot& robot = *model_.robot;
    for (const StateComponent& c : model_.state_vector.components) {
      const std::string label = "state vector: component '" + c.name + "'";
      const auto joint = std::find_if(robot.joints.begin(), robot.joints.end(),
                                      [&](const Joint& j) { return j.name == c.actuator; });
      if (joint == robot.joints.end()) {
        std::vector<std::string> names;
        for (const Joint& j : robot.joints) names.push_back(j.name);
        fail(c.line, label + ": actuator '" + c.actuator + "' is not a joint of robot '" +
                         robot.name + "' (" + joined(names) + ")");
      }
      if (c.positions.empty()) continue;
      const bool revolute = joint->type == JointType::kRevolute;
      const std::string unit = revolute ? "deg" : "mm";
      if (c.position_unit != unit) {
        fail(c.line, label + ": positions are in " + c.position_unit + "; joint '" + joint->name +
                         "' is " + jointTypeName(joint->type) + " (" + unit + ")");
      }
      const double scale = revolute ? M_PI / 180.0 : 0.001 / unitInMetres(robot.length_unit);
      for (std::size_t v = 0; v < c.values.size(); ++v) {
        const double q = c.positions[v] * scale;
        const double slack = 1e-9 * (1.0 + std::abs(q));
        if (q < joint->lower - slack || q > joint->upper + slack) {
          std::ostringstream value;
          value << c.positions[v];
          fail(c.line, label + ": position '" + c.values[v] + "' = " + value.str() + " " + unit +
                           " is outside joint '" + joint->name + "' limits " +
                           describeLimits(*joint, robot.length_unit));
        }
      }
    }
  }

  void checkBehaviors() const {
    const StateVectorSpec& spec = model_.state_vector;
    for (const BasicBehavior& b : model_.behaviors) {
      const std::string label = "basic behaviour '" + b.name + "'";
      const int line = b.body.changes_line;
      if (b.body.changes.size() != 1) {
        fail(line, label + ": changes " +
                       (b.body.changes.empty()
                            ? std::string("no state-vector component")
                            : std::to_string(b.body.changes.size()) + " state-vector components (" +
                                  joined(b.body.changes) + ")") +
                       "; a basic behaviour changes exactly one");
      }
      const int k = spec.componentIndex(b.body.changes.front());
      if (k < 0) {
        fail(line, label + ": changes '" + b.body.changes.front() +
                       "', which is not a state-vector component");
      }
      const StateComponent& c = spec.components[k];
      if (c.actuator != b.body.actuator) {
        fail(b.body.line, label + ": commands " + b.body.actuator + " but changes " + c.name +
                              ", which " + c.actuator + " drives");
      }
      if (b.body.targets.empty()) fail(b.body.line, label + ": has no targets");
      for (const BehaviorTarget& t : b.body.targets) {
        const std::string tw = label + ": target '" + t.value + "'";
        if (c.indexOf(t.value) < 0) {
          fail(t.line, tw + ": not a value of " + c.name + " (" + joined(c.values) + ")");
        }
        if (!kCommands.count(t.command)) {
          fail(t.line, tw + ": unknown command '" + t.command + "' (" + joined(kCommands) + ")");
        }
        if (t.command == "move_to" && c.positions.empty()) {
          fail(t.line, tw + ": move_to needs named positions; " + c.name + " has none");
        }
        if (!model_.event(t.ends_on)) {
          fail(t.line, tw + ": ends on unknown event '" + t.ends_on + "' (" + eventNames() + ")");
        }
      }
    }
  }

  void checkPoses() const {
    for (const StatePose& p : model_.poses) {
      if (const PoseRule* rule = model_.state_vector.brokenRule(p.pose)) {
        fail(p.line, "poses: state '" + p.state + "': pose " +
                         model_.state_vector.describe(p.pose) + " is forbidden by rule '" +
                         rule->name + "' (line " + std::to_string(rule->line) + ")");
      }
    }
  }

  std::string eventNames() const {
    std::vector<std::string> names;
    for (const EventSpec& e : model_.events) names.push_back(e.name);
    return joined(names);
  }

  void checkCombined(const CombinedBehavior& cb) const {
    const std::set<std::string> q = checkStates(cb);
    std::map<std::pair<std::string, std::string>, int> delta;  // (from, event) -> line
    std::map<std::string, const Transition*> runs;             // from -> first transition
    std::map<std::string, std::vector<std::string>> next, previous;
    for (const Transition& t : cb.transitions) {
      const std::string tw = cb.name + ": transition " + t.from + " -> " + t.to;
      checkTransition(t, tw, q);
      checkOneRunPerState(t, tw, delta, runs);
      next[t.from].push_back(t.to);
      previous[t.to].push_back(t.from);
    }
    checkReachable(cb, next, previous);
  }

  /// Q, the initial state and the final states of `cb`; \return Q.
  std::set<std::string> checkStates(const CombinedBehavior& cb) const {
    const std::string& name = cb.name;
    if (cb.states.empty()) fail(cb.states_line, name + ": Q (states) is empty");
    std::set<std::string> q;
    for (const std::string& s : cb.states) {
      if (!q.insert(s).second) fail(cb.states_line, name + ": state '" + s + "' listed twice");
      if (!model_.poseOf(s)) {
        fail(cb.states_line, name + ": state '" + s + "' has no pose (poses:)");
      }
    }
    if (cb.initial.empty()) fail(cb.line, name + ": no initial state (initial: q0)");
    if (!q.count(cb.initial)) {
      fail(cb.initial_line, name + ": initial state '" + cb.initial + "' is not in its states");
    }
    if (cb.finals.empty())
      fail(cb.final_line ? cb.final_line : cb.line, name + ": no final state (final: F)");
    for (const std::string& f : cb.finals) {
      if (!q.count(f)) fail(cb.final_line, name + ": final state '" + f + "' is not in its states");
    }
    return q;
  }

  /// Transition `t` (named `tw` in messages) joins states of Q with a known behaviour, one of
  /// its targets and that target's ending event.
  void checkTransition(const Transition& t, const std::string& tw,
                       const std::set<std::string>& q) const {
    for (const std::string* s : {&t.from, &t.to}) {
      if (!q.count(*s)) fail(t.line, tw + ": '" + *s + "' is not in its states");
    }
    const BasicBehavior* b = model_.behavior(t.behavior);
    if (!b) fail(t.line, tw + ": unknown behaviour '" + t.behavior + "'");
    std::vector<std::string> values;
    for (const BehaviorTarget& target : b->body.targets) values.push_back(target.value);
    const BehaviorTarget* target = nullptr;
    if (t.target.empty()) {
      if (b->body.targets.size() != 1) {
        fail(t.line, tw + ": " + b->name + " needs a target (" + joined(values) + ")");
      }
      target = &b->body.targets.front();
    } else {
      target = b->body.target(t.target);
      if (!target) {
        fail(t.line,
             tw + ": " + b->name + " cannot set '" + t.target + "' (" + joined(values) + ")");
      }
    }
    if (!model_.event(t.event)) {
      fail(t.line, tw + ": unknown event '" + t.event + "' (" + eventNames() + ")");
    }
    if (t.event != target->ends_on) {
      fail(t.line, tw + ": event '" + t.event + "' is not the ending event of " + b->name +
                       (t.target.empty() ? "" : " " + t.target) + " (" + target->ends_on + ")");
    }
  }

  /// A state has one transition per event (`delta`: (from, event) -> line) and runs one
  /// behaviour (`runs`: from -> its first transition), counting `t` in.
  void checkOneRunPerState(const Transition& t, const std::string& tw,
                           std::map<std::pair<std::string, std::string>, int>& delta,
                           std::map<std::string, const Transition*>& runs) const {
    const auto key = std::make_pair(t.from, t.event);
    if (const auto it = delta.find(key); it != delta.end()) {
      fail(t.line, tw + ": " + t.from + " already has a transition on " + t.event + " (line " +
                       std::to_string(it->second) + ")");
    }
    delta[key] = t.line;
    if (const auto it = runs.find(t.from); it != runs.end()) {
      const Transition& first = *it->second;
      if (first.behavior != t.behavior || first.target != t.target) {
        fail(t.line, tw + ": " + t.from + " already runs " + first.behavior +
                         (first.target.empty() ? "" : " " + first.target) + " (line " +
                         std::to_string(first.line) + "); a state runs one behaviour");
      }
    } else {
      runs[t.from] = &t;
    }
  }

  /// Every state of `cb` is reachable from the initial state and has a way back to a final one.
  void checkReachable(const CombinedBehavior& cb,
                      std::map<std::string, std::vector<std::string>>& next,
                      std::map<std::string, std::vector<std::string>>& previous) const {
    const std::string& name = cb.name;
    const std::set<std::string> reached = closure({cb.initial}, next);
    for (const std::string& s : cb.states) {
      if (!reached.count(s)) {
        fail(cb.states_line,
             name + ": state '" + s + "' is unreachable from the initial state " + cb.initial);
      }
    }
    const std::set<std::string> back = closure(cb.finals, previous);
    for (const std::string& s : cb.states) {
      if (!back.count(s)) {
        fail(cb.states_line, name + ": state '" + s + "' has no way back to a final state (" +
                                 joined(cb.finals) + ")");
      }
    }
  }

  static std::set<std::string> closure(const std::vector<std::string>& start,
                                       std::map<std::string, std::vector<std::string>>& edges) {
    std::set<std::string> seen(start.begin(), start.end());
    std::vector<std::string> stack(start.begin(), start.end());
    while (!stack.empty()) {
      const std::string s = stack.back();
      stack.pop_back();
      for (const std::string& n : edges[s]) {
        if (seen.insert(n).second) stack.push_back(n);
      }
    }
    return seen;
  }

  ValidationReport report() const {
    ValidationReport r;
    const StateVectorSpec& spec = model_.state_vector;
    r.combinations = spec.combinations();
    r.allowed_poses = spec.allowedPoses().size();
    r.forbidden_poses = r.combinations - r.allowed_poses;
    r.states = model_.poses.size();
    std::set<Pose> used;
    for (const StatePose& p : model_.poses) used.insert(p.pose);
    r.poses_used = used.size();
    r.behaviors = model_.behaviors.size();
    r.events = model_.events.size();
    for (const CombinedBehavior& cb : model_.combined) {
      r.combined.push_back({cb.name, cb.states.size(), cb.transitions.size(), cb.events().size()});
    }
    return r;
  }

  const BehaviorModel& model_;
};

}  // namespace

ValidationReport validateBehaviorModel(const BehaviorModel& model) {
  return Validator(model).run();
}

std::string ValidationReport::summary() const {
  std::ostringstream out;
  out << "state vector: " << combinations << " combinations, " << allowed_poses << " allowed, "
      << forbidden_poses << " forbidden\n"
      << "FSM states: " << states << " (" << poses_used << " distinct poses)\n"
      << "basic behaviours: " << behaviors << "\n"
      << "events: " << events << "\n";
  for (const CombinedBehaviorCounts& cb : combined) {
    out << cb.name << ": " << cb.states << " states, " << cb.transitions << " transitions, "
        << cb.events << " events\n";
  }
  return out.str();
}

std::vector<PoseFinding> checkPoseConsistency(const BehaviorModel& model) {
  std::vector<PoseFinding> findings;
  const StateVectorSpec& spec = model.state_vector;
  for (const CombinedBehavior& cb : model.combined) {
    for (const Transition& t : cb.transitions) {
      const StatePose* from = model.poseOf(t.from);
      const StatePose* to = model.poseOf(t.to);
      if (!from || !to) {
        throw Error(atLine(model.source, t.line) + ": " + cb.name + ": transition " + t.from +
                    " -> " + t.to + ": a state without a pose");
      }
      const BehaviorRun run = resolveRun(model, t);
      const Pose reached = applyRun(run, from->pose);
      if (reached == to->pose) continue;
      const StateComponent& c = spec.components[run.component];
      std::string message = atLine(model.source, t.line) + ": " + cb.name + ": " + t.from + " -> " +
                            t.to + ": " + t.behavior + " sets " + c.name + " to " +
                            c.values[run.value];
      if (reached == from->pose) {
        message += ", which it already is in " + t.from;
      }
      std::string differences;
      for (std::size_t k = 0; k < spec.components.size(); ++k) {
        if (reached[k] == to->pose[k]) continue;
        differences += (differences.empty() ? "" : ", ") + spec.components[k].name + "=" +
                       spec.components[k].values[reached[k]] + " where " + t.to + " has " +
                       spec.components[k].name + "=" + spec.components[k].values[to->pose[k]];
      }
      message += "; it leaves " + differences;
      if (const PoseRule* rule = spec.brokenRule(reached)) {
        message += "; the pose reached is forbidden by rule '" + rule->name + "'";
      }
      findings.push_back({cb.name, t, reached, message});
    }
  }
  return findings;
}

}  // namespace mcws
