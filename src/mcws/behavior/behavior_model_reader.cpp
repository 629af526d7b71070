#include "mcws/behavior/behavior_model.h"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <utility>

#include "mcws/core/error.h"
#include "mcws/core/input_files.h"
#include "mcws/core/text_file.h"
#include "mcws/core/yaml_reader.h"
#include "mcws/kinematics/robot_entry.h"
#include "mcws/kinematics/robot_yaml.h"

namespace mcws {
namespace {

/// Units a behaviour parameter may carry.
const std::set<std::string> kParameterUnits = {"A",   "mA",  "V",    "s",     "ms", "mm",
                                               "deg", "rpm", "mm/s", "deg/s", "N"};

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

  /// `robot: FILE`, or a map choosing a URDF's chain (readRobotEntry()).
  void readRobot(const YAML::Node& node) {
    const RobotEntry entry = readRobotEntry(*this, node);
    model_.robot_path = entry.path;
    model_.robot_line = lineOf(entry.file_node);
    try {
      model_.robot = loadRobot(entry.path, entry.chain);
      model_.robot->package_path = entry.package_path;
      model_.robot->srdf = entry.srdf;
    } catch (const UrdfChainError& e) {
      entry.failChain(*this, e);
    } catch (const Error& e) {
      fail(entry.file_node, std::string("robot: ") + e.what());
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

  /// One entry of a list of named entries (state-vector components, pose rules): its keys
  /// checked against `keys`, its line, its name, and the label messages give it after the name
  /// is known ("pose rule 'clamp'"; before: "pose rule 2").
  struct NamedRow {
    YAML::Node node;
    int line{0};
    std::string name, label;
  };
  NamedRow namedRow(const YAML::Node& row, const std::string& kind, std::size_t i,
                    const std::set<std::string>& keys) const {
    const std::string where = kind + " " + std::to_string(i + 1);
    checkKeys(row, where, keys);
    NamedRow named{row, lineOf(row), text(require(row, "name", where), where + ": name"), ""};
    named.label = kind + " '" + named.name + "'";
    return named;
  }

  void readStateVector(const YAML::Node& node) {
    if (!node.IsSequence() || node.size() == 0) {
      fail(node, "state_vector: must be a non-empty list of components");
    }
    StateVectorSpec& spec = model_.state_vector;
    spec.line = lineOf(node);
    for (std::size_t i = 0; i < node.size(); ++i) {
      const NamedRow named =
          namedRow(node[i], "state vector: component", i, {"name", "actuator", "values"});
      const YAML::Node& row = named.node;
      const std::string& label = named.label;
      StateComponent c;
      c.line = named.line;
      c.name = named.name;
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
      const NamedRow named = namedRow(node[i], "pose rule", i, {"name", "when", "require"});
      const YAML::Node& row = named.node;
      const std::string& label = named.label;
      PoseRule rule;
      rule.line = named.line;
      rule.name = named.name;
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

}  // namespace

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
  return parseBehaviorModel(readRest(in), path);
}

}  // namespace mcws
