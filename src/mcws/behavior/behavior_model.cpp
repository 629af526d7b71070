#include "mcws/behavior/behavior_model.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "mcws/core/error.h"
#include "mcws/core/input_files.h"
#include "mcws/core/yaml_reader.h"
#include "mcws/kinematics/robot_yaml.h"

namespace mcws {
namespace {

/// Units a behaviour parameter may carry.
const std::set<std::string> kParameterUnits = {"A",   "mA",  "V",    "s",     "ms", "mm",
                                               "deg", "rpm", "mm/s", "deg/s", "N"};
/// Commands a basic behaviour may give its actuator.
const std::set<std::string> kCommands = {"close", "release", "move_to", "spin", "stop"};

class BehaviorModelReader : YamlReader {
 public:
  explicit BehaviorModelReader(std::string source) : YamlReader(std::move(source)) {}

  BehaviorModel read(const YAML::Node& root) {
    if (!root.IsMap()) fail(root, "the document must be a map of behaviour model fields");
    checkKeys(root, "model",
              {"name", "robot", "insulator", "events", "state_vector", "pose_rules",
               "basic_behaviors", "poses", "combined_behaviors"});
    model_.source = source();
    model_.name = text(require(root, "name", "model"), "name");
    if (const YAML::Node robot = root["robot"]) readRobot(robot);
    if (const YAML::Node insulator = root["insulator"]) readInsulator(insulator);
    readEvents(require(root, "events", "model"));
    readStateVector(require(root, "state_vector", "model"));
    if (const YAML::Node rules = root["pose_rules"]) readRules(rules);
    readBehaviors(require(root, "basic_behaviors", "model"));
    readPoses(require(root, "poses", "model"));
    readCombined(require(root, "combined_behaviors", "model"));
    return std::move(model_);
  }

 private:
  Quantity quantity(const YAML::Node& node, const std::string& where,
                    const std::set<std::string>& units) const {
    return YamlReader::quantity(node, where, text(node, where), units, "155 mm");
  }

  double positive(const YAML::Node& node, const std::string& where,
                  const std::set<std::string>& units) const {
    const Quantity q = quantity(node, where, units);
    if (!(q.value > 0.0)) fail(node, where + ": " + node.Scalar() + " must be > 0");
    return q.value;
  }

  void readRobot(const YAML::Node& node) {
    const std::string file = text(node, "robot");
    std::filesystem::path path(file);
    if (path.is_relative()) path = std::filesystem::path(source()).parent_path() / path;
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {
      fail(node, "robot: '" + file + "' does not exist (looked for " + path.string() + ")");
    }
    model_.robot_path = path.string();
    model_.robot_line = lineOf(node);
    try {
      model_.robot = loadRobot(model_.robot_path);
    } catch (const Error& e) {
      fail(node, std::string("robot: ") + e.what());
    }
  }

  void readInsulator(const YAML::Node& node) {
    checkKeys(node, "insulator", {"type", "pitch", "upper_shed_diameter", "lower_shed_diameter"});
    InsulatorSpec& spec = model_.insulator;
    spec.line = lineOf(node);
    spec.type = text(require(node, "type", "insulator"), "insulator: type");
    spec.pitch_mm = positive(require(node, "pitch", "insulator"), "insulator: pitch", {"mm"});
    spec.upper_shed_diameter_mm = positive(require(node, "upper_shed_diameter", "insulator"),
                                           "insulator: upper_shed_diameter", {"mm"});
    spec.lower_shed_diameter_mm = positive(require(node, "lower_shed_diameter", "insulator"),
                                           "insulator: lower_shed_diameter", {"mm"});
  }

  void readEvents(const YAML::Node& node) {
    checkNames(node, "events");
    for (const auto& item : node) {
      const std::string name = item.first.Scalar();
      model_.events.push_back({name, text(item.second, "events: " + name), lineOf(item.first)});
    }
    if (model_.events.empty()) fail(node, "events: Sigma must not be empty");
  }

  void readStateVector(const YAML::Node& node) {
    if (!node.IsSequence() || node.size() == 0) {
      fail(node, "state_vector: must be a non-empty list of components");
    }
    StateVectorSpec& spec = model_.state_vector;
    spec.line = lineOf(node);
    for (std::size_t i = 0; i < node.size(); ++i) {
      const YAML::Node row = node[i];
      const std::string where = "state vector: component " + std::to_string(i + 1);
      checkKeys(row, where, {"name", "actuator", "values"});
      StateComponent c;
      c.line = lineOf(row);
      c.name = text(require(row, "name", where), where + ": name");
      const std::string label = "state vector: component '" + c.name + "'";
      if (spec.componentIndex(c.name) >= 0) fail(row["name"], label + ": given twice");
      c.actuator = text(require(row, "actuator", label), label + ": actuator");
      const YAML::Node values = require(row, "values", label);
      if (values.IsMap()) {  // named positions
        checkNames(values, label + ": values");
        for (const auto& item : values) {
          const Quantity q =
              quantity(item.second, label + ": " + item.first.Scalar(), {"mm", "deg"});
          if (!c.position_unit.empty() && q.unit != c.position_unit) {
            fail(item.second, label + ": position '" + item.first.Scalar() + "' is in " + q.unit +
                                  ", the others in " + c.position_unit);
          }
          c.position_unit = q.unit;
          c.values.push_back(item.first.Scalar());
          c.positions.push_back(q.value);
        }
      } else if (values.IsSequence()) {
        for (const YAML::Node& value : values) {
          const std::string name = text(value, label + ": values");
          if (c.indexOf(name) >= 0) fail(value, label + ": value '" + name + "' given twice");
          c.values.push_back(name);
        }
      } else {
        fail(values, label + ": values must be a list, or a map of named positions");
      }
      if (c.values.size() < 2) {
        fail(values, label + ": has " + std::to_string(c.values.size()) +
                         " value(s); a component needs at least two");
      }
      spec.components.push_back(c);
    }
  }

  /// `{component: value or [values], ...}` of a pose rule.
  std::vector<PoseCondition> conditions(const YAML::Node& node, const std::string& where) const {
    checkNames(node, where);
    std::vector<PoseCondition> out;
    for (const auto& item : node) {
      const std::string name = item.first.Scalar();
      const int k = model_.state_vector.componentIndex(name);
      if (k < 0) fail(item.first, where + ": '" + name + "' is not a state-vector component");
      const StateComponent& component = model_.state_vector.components[k];
      PoseCondition condition;
      condition.component = static_cast<std::size_t>(k);
      for (const std::string& value : texts(item.second, where + ": " + name)) {
        const int v = component.indexOf(value);
        if (v < 0) {
          fail(item.second, where + ": '" + value + "' is not a value of " + name + " (" +
                                joined(component.values) + ")");
        }
        condition.values.push_back(v);
      }
      out.push_back(condition);
    }
    return out;
  }

  void readRules(const YAML::Node& node) {
    if (!node.IsSequence()) fail(node, "pose_rules: must be a list of rules");
    for (std::size_t i = 0; i < node.size(); ++i) {
      const YAML::Node row = node[i];
      const std::string where = "pose rule " + std::to_string(i + 1);
      checkKeys(row, where, {"name", "when", "require"});
      PoseRule rule;
      rule.line = lineOf(row);
      rule.name = text(require(row, "name", where), where + ": name");
      const std::string label = "pose rule '" + rule.name + "'";
      if (row["when"]) rule.when = conditions(row["when"], label + ": when");
      rule.require = conditions(require(row, "require", label), label + ": require");
      model_.state_vector.rules.push_back(rule);
    }
  }

  std::vector<Port> ports(const YAML::Node& node, const std::string& where) const {
    checkNames(node, where);
    std::vector<Port> out;
    for (const auto& item : node) {
      out.push_back({item.first.Scalar(), text(item.second, where + ": " + item.first.Scalar()),
                     lineOf(item.first)});
    }
    return out;
  }

  void readBehaviors(const YAML::Node& node) {
    if (!node.IsSequence() || node.size() == 0) {
      fail(node, "basic_behaviors: must be a non-empty list of behaviours");
    }
    std::map<std::string, int> first_line;
    for (std::size_t i = 0; i < node.size(); ++i) {
      const YAML::Node row = node[i];
      const std::string where = "basic behaviour " + std::to_string(i + 1);
      checkKeys(row, where,
                {"name", "input_ports", "output_ports", "parameters", "timeout", "body"});
      BasicBehavior b;
      b.line = lineOf(row);
      b.name = text(require(row, "name", where), where + ": name");
      const std::string label = "basic behaviour '" + b.name + "'";
      if (const auto it = first_line.find(b.name); it != first_line.end()) {
        fail(row["name"],
             label + ": defined twice (first at line " + std::to_string(it->second) + ")");
      }
      first_line[b.name] = b.line;
      if (row["input_ports"]) b.input_ports = ports(row["input_ports"], label + ": input_ports");
      if (row["output_ports"])
        b.output_ports = ports(row["output_ports"], label + ": output_ports");
      if (const YAML::Node parameters = row["parameters"]) {
        checkNames(parameters, label + ": parameters");
        for (const auto& item : parameters) {
          const std::string name = item.first.Scalar();
          const Quantity q = quantity(item.second, label + ": parameter " + name, kParameterUnits);
          b.parameters.push_back({name, q.value, q.unit, lineOf(item.first)});
        }
      }
      if (const YAML::Node timeout = row["timeout"]) {
        b.timeout_s = positive(timeout, label + ": timeout", {"s"});
      }
      const YAML::Node body = require(row, "body", label);
      checkKeys(body, label + ": body", {"actuator", "changes", "targets"});
      b.body.line = lineOf(body);
      b.body.actuator = text(require(body, "actuator", label + ": body"), label + ": actuator");
      const YAML::Node changes = require(body, "changes", label + ": body");
      b.body.changes_line = lineOf(changes);
      if (!(changes.IsSequence() && changes.size() == 0)) {
        b.body.changes = texts(changes, label + ": changes");
      }
      const YAML::Node targets = require(body, "targets", label + ": body");
      checkNames(targets, label + ": targets");
      for (const auto& item : targets) {
        const std::string value = item.first.Scalar();
        const std::string tw = label + ": target '" + value + "'";
        checkKeys(item.second, tw, {"command", "ends_on"});
        b.body.targets.push_back(
            {value, text(require(item.second, "command", tw), tw + ": command"),
             text(require(item.second, "ends_on", tw), tw + ": ends_on"), lineOf(item.first)});
      }
      model_.behaviors.push_back(b);
    }
  }

  void readPoses(const YAML::Node& node) {
    checkNames(node, "poses");
    const StateVectorSpec& spec = model_.state_vector;
    for (const auto& item : node) {
      StatePose pose;
      pose.state = item.first.Scalar();
      pose.line = lineOf(item.first);
      const std::string where = "poses: state '" + pose.state + "'";
      checkNames(item.second, where);
      pose.pose.assign(spec.components.size(), -1);
      for (const auto& entry : item.second) {
        const std::string name = entry.first.Scalar();
        const int k = spec.componentIndex(name);
        if (k < 0) fail(entry.first, where + ": '" + name + "' is not a state-vector component");
        const std::string value = text(entry.second, where + ": " + name);
        const int v = spec.components[k].indexOf(value);
        if (v < 0) {
          fail(entry.second, where + ": '" + value + "' is not a value of " + name + " (" +
                                 joined(spec.components[k].values) + ")");
        }
        pose.pose[k] = v;
      }
      for (std::size_t k = 0; k < spec.components.size(); ++k) {
        if (pose.pose[k] < 0) {
          fail(item.first, where + ": no value for component '" + spec.components[k].name + "'");
        }
      }
      model_.poses.push_back(pose);
    }
  }

  void readCombined(const YAML::Node& node) {
    if (!node.IsSequence() || node.size() == 0) {
      fail(node, "combined_behaviors: must be a non-empty list of combined behaviours");
    }
    for (std::size_t i = 0; i < node.size(); ++i) {
      const YAML::Node row = node[i];
      const std::string where = "combined behaviour " + std::to_string(i + 1);
      checkKeys(row, where, {"name", "description", "states", "initial", "final", "transitions"});
      CombinedBehavior cb;
      cb.line = lineOf(row);
      cb.name = text(require(row, "name", where), where + ": name");
      if (model_.combinedBehavior(cb.name)) fail(row["name"], cb.name + ": defined twice");
      checkFileStem(row["name"], where, cb.name);
      if (row["description"]) cb.description = text(row["description"], cb.name + ": description");
      const YAML::Node states = require(row, "states", cb.name);
      cb.states_line = lineOf(states);
      if (!(states.IsSequence() && states.size() == 0))
        cb.states = texts(states, cb.name + ": states");
      if (const YAML::Node initial = row["initial"]) {
        cb.initial = text(initial, cb.name + ": initial");
        cb.initial_line = lineOf(initial);
      }
      if (const YAML::Node finals = row["final"]) {
        cb.final_line = lineOf(finals);
        if (!(finals.IsSequence() && finals.size() == 0))
          cb.finals = texts(finals, cb.name + ": final");
      }
      const YAML::Node transitions = require(row, "transitions", cb.name);
      if (!transitions.IsSequence()) fail(transitions, cb.name + ": transitions must be a list");
      for (std::size_t t = 0; t < transitions.size(); ++t) {
        const YAML::Node tr = transitions[t];
        const std::string tw = cb.name + ": transition " + std::to_string(t + 1);
        checkKeys(tr, tw, {"from", "to", "run", "target", "event"});
        Transition transition;
        transition.line = lineOf(tr);
        transition.from = text(require(tr, "from", tw), tw + ": from");
        transition.to = text(require(tr, "to", tw), tw + ": to");
        transition.behavior = text(require(tr, "run", tw), tw + ": run");
        if (tr["target"]) transition.target = text(tr["target"], tw + ": target");
        transition.event = text(require(tr, "event", tw), tw + ": event");
        cb.transitions.push_back(transition);
      }
      model_.combined.push_back(cb);
    }
  }

  /// A combined behaviour's name is the stem of its diagram's file (mcws_behave --dot): it must
  /// be a plain file name, and differ from the task diagram's and from every other combined
  /// behaviour's name, ignoring ASCII case.
  void checkFileStem(const YAML::Node& node, const std::string& where,
                     const std::string& name) const {
    const std::string label = where + ": name " + quotedName(name);
    if (const auto problem = fileStemProblem(name)) {
      fail(node, label + ": it names the file of its diagram and " + *problem);
    }
    const std::string folded = asciiLower(name);
    if (folded == asciiLower(kTaskDiagramName)) {
      fail(node, label + ": the task machine's diagram has that file name (" +
                     std::string(kTaskDiagramName) + ".dot)");
    }
    for (const CombinedBehavior& other : model_.combined) {
      if (asciiLower(other.name) == folded) {
        fail(node, label + ": differs from combined behaviour " + quotedName(other.name) +
                       " (line " + std::to_string(other.line) +
                       ") only in case: their diagrams would share a file name");
      }
    }
  }

  static std::string asciiLower(std::string text) {
    for (char& c : text) {
      if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    }
    return text;
  }

  BehaviorModel model_;
};

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

    std::map<std::pair<std::string, std::string>, int> delta;  // (from, event) -> line
    std::map<std::string, const Transition*> runs;             // from -> first transition
    std::map<std::string, std::vector<std::string>> next, previous;
    for (const Transition& t : cb.transitions) {
      const std::string tw = name + ": transition " + t.from + " -> " + t.to;
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
      next[t.from].push_back(t.to);
      previous[t.to].push_back(t.from);
    }

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

// ---- reading -----------------------------------------------------------------------------------

BehaviorModel parseBehaviorModel(const std::string& text, const std::string& source) {
  return BehaviorModelReader(source).read(loadYamlDocument(text, source, "a behaviour model"));
}

BehaviorModel loadBehaviorModel(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw Error(path + ": behaviour model file does not exist or is not a regular file");
  }
  requireInputFile(path, "behaviour model file");  // noted: no output of the run replaces it
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot read the behaviour model file");
  std::ostringstream text;
  text << in.rdbuf();
  return parseBehaviorModel(text.str(), path);
}

// ---- checks ------------------------------------------------------------------------------------

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
