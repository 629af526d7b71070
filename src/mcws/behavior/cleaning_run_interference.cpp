// CleaningRun (cleaning_run.h): the pose the sensors read and the interference check of a command
// against the pose rules.

#include "mcws/behavior/cleaning_run.h"

#include <algorithm>
#include <functional>
#include <utility>

#include "mcws/core/error.h"

namespace mcws {
namespace cleaning {

ValueSet CleaningRun::valuesSpanned(const StateComponent& c, double lo, double hi) {
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

std::vector<std::vector<std::string>> CleaningRun::commandsSetting(std::size_t k) const {
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

std::vector<ValueSet> CleaningRun::sensedPose() const {
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

std::string CleaningRun::describePose(const std::vector<ValueSet>& pose) const {
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

std::optional<std::pair<Pose, const PoseRule*>> CleaningRun::forbiddenPose(
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

std::optional<std::string> CleaningRun::sensedState(const std::vector<ValueSet>& pose) const {
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

bool CleaningRun::sensorsFit(const std::string& state) const {
  const StatePose* sp = model_.poseOf(state);
  if (!sp) return false;
  const std::vector<ValueSet> pose = sensedPose();
  for (std::size_t k = 0; k < pose.size(); ++k) {
    if (!pose[k][sp->pose[k]]) return false;
  }
  return true;
}

std::string CleaningRun::sensedText(const std::string& claim, const std::string& state) const {
  if (sensorsFit(state)) return claim;
  const std::vector<ValueSet> pose = sensedPose();
  const std::optional<std::string> sensed = sensedState(pose);
  return "the machine is " + claim + ", but the sensors read " +
         (sensed ? *sensed + " (" : std::string("(")) + describePose(pose) + ")";
}

std::optional<std::string> CleaningRun::interference(const SimCommand& command) const {
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

}  // namespace cleaning
}  // namespace mcws
