#include "mcws/behavior/fault_script.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <utility>

#include "mcws/core/error.h"
#include "mcws/core/input_files.h"
#include "mcws/core/text_file.h"
#include "mcws/core/yaml_reader.h"

namespace mcws {
namespace {

/// Units of a time, and their size in seconds.
const std::map<std::string, double> kTimeUnits = {{"s", 1.0}, {"ms", 0.001}, {"min", 60.0}};
constexpr double kOneDay = 86400.0;  // [s]
/// Units of a current, and their size in amperes.
const std::map<std::string, double> kCurrentUnits = {{"A", 1.0}, {"mA", 0.001}};

const std::map<std::string, FaultKind> kFaultKinds = {
    {"link_down", FaultKind::kLinkDown},
    {"zero_switch_stuck", FaultKind::kZeroSwitchStuck},
    {"corrupt_command", FaultKind::kCorruptCommand},
    {"wrong_command", FaultKind::kWrongCommand},
    {"battery_drain", FaultKind::kBatteryDrain},
};

/// The keys a fault of each kind takes besides `at` and `type`.
const std::map<FaultKind, std::set<std::string>> kFaultKeys = {
    {FaultKind::kLinkDown, {"duration"}},
    {FaultKind::kZeroSwitchStuck, {"clamp", "reads"}},
    {FaultKind::kCorruptCommand, {}},
    {FaultKind::kWrongCommand, {"joint", "command", "value"}},
    {FaultKind::kBatteryDrain, {"current"}},
};

const std::map<std::string, OperatorAction> kOperatorActions = {
    {"repair_and_resume", OperatorAction::kRepairAndResume},
    {"resume", OperatorAction::kResume},
    {"return", OperatorAction::kReturn},
};

const std::map<std::string, LowBatteryPolicy> kLowBatteryPolicies = {
    {"alarm_only", LowBatteryPolicy::kAlarmOnly},
    {"finish_disc_and_return", LowBatteryPolicy::kFinishDiscAndReturn},
};

const std::map<std::string, SimJoint> kClamps = {{"fixed", kFixedClamp}, {"moving", kMovingClamp}};
const std::map<std::string, bool> kReadings = {{"pressed", true}, {"not_pressed", false}};

/// The names of a name -> value table, in order.
template <typename Value>
std::set<std::string> namesOf(const std::map<std::string, Value>& table) {
  std::set<std::string> names;
  for (const auto& item : table) names.insert(item.first);
  return names;
}

class FaultScriptReader : YamlReader {
 public:
  explicit FaultScriptReader(std::string source) : YamlReader(std::move(source)) {}

  FaultScript read(const YAML::Node& root) {
    script_.source = source();
    if (!root || root.IsNull()) return std::move(script_);  // empty, or comments only
    if (!root.IsMap()) {
      fail(root, "fault file: the document must be a map with keys faults, operator, policy");
    }
    checkKeys(root, "fault file", {"policy", "faults", "operator"});
    if (const YAML::Node policy = root["policy"]) readPolicy(policy);
    if (const YAML::Node faults = root["faults"]) readFaults(faults);
    if (const YAML::Node responses = root["operator"]) readOperator(responses);
    return std::move(script_);
  }

 private:
  /// The value of `key` in `map` (undefined when absent); a key with no value fails at the key's
  /// line (yaml-cpp marks an empty value at the token after it).
  YAML::Node field(const YAML::Node& map, const std::string& key, const std::string& where) const {
    for (const auto& item : map) {
      if (item.first.Scalar() != key) continue;
      if (item.second.IsNull()) fail(item.first, where + ": " + key + ": has no value");
      return item.second;
    }
    return map[key];
  }

  YAML::Node require(const YAML::Node& map, const std::string& key,
                     const std::string& where) const {
    const YAML::Node node = field(map, key, where);
    if (!node) fail(map, where + ": missing field '" + key + "'");
    return node;
  }

  /// YamlReader::text(), but "has no value" for a node with none.
  std::string text(const YAML::Node& node, const std::string& where) const {
    if (node.IsNull()) fail(node, where + ": has no value");
    return YamlReader::text(node, where);
  }

  /// The value called `text(node)` in `table`, or "where: unknown what 'name' (names)".
  template <typename Value>
  Value lookUp(const YAML::Node& node, const std::string& where, const std::string& key,
               const std::string& what, const std::map<std::string, Value>& table) const {
    const std::string name = text(node, where + ": " + key);
    const auto it = table.find(name);
    if (it == table.end()) {
      fail(node, where + ": unknown " + what + " '" + name + "' (" + joined(namesOf(table)) + ")");
    }
    return it->second;
  }

  /// A number and a unit of `units` ("1.5 min"), converted with the unit's factor.
  double quantity(const YAML::Node& node, const std::string& where,
                  const std::map<std::string, double>& units, const std::string& example) const {
    const std::string value = text(node, where);
    const Quantity q = YamlReader::quantity(node, where, value, namesOf(units), example);
    const double converted = q.value * units.at(q.unit) + 0.0;  // + 0.0: no -0
    if (!std::isfinite(converted)) fail(node, where + ": '" + value + "' is out of range");
    return converted;
  }

  double nonNegative(const YAML::Node& node, const std::string& where,
                     const std::map<std::string, double>& units, const std::string& example) const {
    const double value = quantity(node, where, units, example);
    if (value < 0.0) fail(node, where + ": '" + node.Scalar() + "' must be >= 0");
    return value;
  }

  double positive(const YAML::Node& node, const std::string& where,
                  const std::map<std::string, double>& units, const std::string& example) const {
    const double value = quantity(node, where, units, example);
    if (!(value > 0.0)) fail(node, where + ": '" + node.Scalar() + "' must be > 0");
    return value;
  }

  /// A waiting time the run must sit through: at most one day (a longer wait is a typing
  /// mistake, and the run would step through it 0.01 s at a time).
  double withinADay(const YAML::Node& node, const std::string& where, double seconds) const {
    if (seconds > kOneDay) {
      fail(node, where + ": '" + node.Scalar() + "' is more than a day (86400 s)");
    }
    return seconds;
  }

  /// A list, or nothing (`faults:` with no entries).
  bool isList(const YAML::Node& node, const std::string& where, const std::string& what) const {
    if (node.IsNull()) return false;
    if (!node.IsSequence()) fail(node, where + ": must be a list of " + what);
    return true;
  }

  void readPolicy(const YAML::Node& node) {
    if (node.IsNull()) return;
    checkKeys(node, "policy", {"link_wait", "low_battery"});
    if (const YAML::Node wait = field(node, "link_wait", "policy")) {
      script_.link_wait_s = withinADay(wait, "policy: link_wait",
                                       positive(wait, "policy: link_wait", kTimeUnits, "30 s"));
    }
    if (const YAML::Node low = field(node, "low_battery", "policy")) {
      script_.low_battery =
          lookUp(low, "policy", "low_battery", "low_battery policy", kLowBatteryPolicies);
    }
  }

  void readFaults(const YAML::Node& node) {
    if (!isList(node, "faults", "faults")) return;
    std::set<std::string> all_keys = {"at", "type"};
    for (const auto& kind : kFaultKeys) all_keys.insert(kind.second.begin(), kind.second.end());
    for (std::size_t i = 0; i < node.size(); ++i) {
      const YAML::Node row = node[i];
      const std::string where = "faults[" + std::to_string(i + 1) + "]";
      checkKeys(row, where, all_keys);
      InjectedFault fault;
      fault.line = lineOf(row);
      fault.kind = lookUp(require(row, "type", where), where, "type", "type", kFaultKinds);
      const std::string type = faultKindName(fault.kind);
      std::set<std::string> allowed = kFaultKeys.at(fault.kind);
      allowed.insert({"at", "type"});
      for (const auto& item : row) {
        const std::string key = item.first.Scalar();
        if (!allowed.count(key)) {
          fail(item.first, where + ": key '" + key + "' does not belong to a " + type +
                               " fault (allowed: " + joined(allowed) + ")");
        }
      }
      fault.at_s = nonNegative(require(row, "at", where), where + ": at", kTimeUnits, "12 s");
      switch (fault.kind) {
        case FaultKind::kLinkDown:
          if (const YAML::Node duration = field(row, "duration", where)) {
            fault.duration_s = positive(duration, where + ": duration", kTimeUnits, "40 s");
          }
          break;
        case FaultKind::kZeroSwitchStuck:
          fault.clamp = lookUp(require(row, "clamp", where), where, "clamp", "clamp", kClamps);
          fault.reads_pressed =
              lookUp(require(row, "reads", where), where, "reads", "reading", kReadings);
          break;
        case FaultKind::kCorruptCommand:
          break;
        case FaultKind::kWrongCommand:
          fault.command = readCommand(row, where);
          break;
        case FaultKind::kBatteryDrain:
          fault.current_a =
              positive(require(row, "current", where), where + ": current", kCurrentUnits, "8 A");
          break;
      }
      script_.faults.push_back(fault);
    }
    std::stable_sort(
        script_.faults.begin(), script_.faults.end(),
        [](const InjectedFault& a, const InjectedFault& b) { return a.at_s < b.at_s; });
  }

  /// The joint, command and value of a wrong_command fault. Whether the joint takes the command
  /// and the value lies within its limits is left to RobotSimulator::refuse() at run time.
  SimCommand readCommand(const YAML::Node& row, const std::string& where) const {
    SimCommand command;
    const YAML::Node joint = require(row, "joint", where);
    const std::string joint_name = text(joint, where + ": joint");
    try {
      command.joint = simJointFromName(joint_name);
    } catch (const Error& e) {
      fail(joint, where + ": " + e.what());
    }
    const YAML::Node kind = require(row, "command", where);
    const std::string kind_name = text(kind, where + ": command");
    try {
      command.kind = commandKindFromName(kind_name);
    } catch (const Error& e) {
      fail(kind, where + ": " + e.what());
    }
    const std::string name = commandKindName(command.kind);
    const YAML::Node value = field(row, "value", where);
    if (command.kind == SimCommandKind::kMoveTo || command.kind == SimCommandKind::kSpin) {
      // move_to: the joint's position unit (J3, J4 travel in mm, the others turn in deg).
      const bool travel = command.joint == SimJoint::kJ3 || command.joint == SimJoint::kJ4;
      const std::string unit =
          command.kind == SimCommandKind::kSpin ? "rpm" : (travel ? "mm" : "deg");
      if (!value) {
        fail(row, where + ": missing field 'value' (" + name + " on " +
                      simJointName(command.joint) + " needs one, in " + unit + ")");
      }
      command.value = quantity(value, where + ": value", {{unit, 1.0}}, "100 " + unit);
    } else if (value) {
      fail(value, where + ": a " + name + " command takes no value (got '" +
                      (value.IsScalar() ? value.Scalar() : std::string("...")) + "')");
    }
    return command;
  }

  void readOperator(const YAML::Node& node) {
    if (!isList(node, "operator", "responses")) return;
    for (std::size_t i = 0; i < node.size(); ++i) {
      const YAML::Node row = node[i];
      const std::string where = "operator[" + std::to_string(i + 1) + "]";
      checkKeys(row, where, {"after", "action"});
      OperatorResponse response;
      response.line = lineOf(row);
      const YAML::Node after = require(row, "after", where);
      response.after_s = withinADay(after, where + ": after",
                                    nonNegative(after, where + ": after", kTimeUnits, "30 s"));
      response.action =
          lookUp(require(row, "action", where), where, "action", "action", kOperatorActions);
      script_.operator_responses.push_back(response);
    }
  }

  FaultScript script_;
};

}  // namespace

const char* faultKindName(FaultKind kind) {
  switch (kind) {
    case FaultKind::kLinkDown:
      return "link_down";
    case FaultKind::kZeroSwitchStuck:
      return "zero_switch_stuck";
    case FaultKind::kCorruptCommand:
      return "corrupt_command";
    case FaultKind::kWrongCommand:
      return "wrong_command";
    case FaultKind::kBatteryDrain:
      return "battery_drain";
  }
  return "?";
}

const char* operatorActionName(OperatorAction action) {
  switch (action) {
    case OperatorAction::kRepairAndResume:
      return "repair_and_resume";
    case OperatorAction::kResume:
      return "resume";
    case OperatorAction::kReturn:
      return "return";
  }
  return "?";
}

const char* lowBatteryPolicyName(LowBatteryPolicy policy) {
  switch (policy) {
    case LowBatteryPolicy::kAlarmOnly:
      return "alarm_only";
    case LowBatteryPolicy::kFinishDiscAndReturn:
      return "finish_disc_and_return";
  }
  return "?";
}

FaultScript parseFaultScript(const std::string& text, const std::string& source) {
  return FaultScriptReader(source).read(loadYamlDocument(text, source, "a fault file"));
}

FaultScript loadFaultScript(const std::string& path) {
  std::error_code ec;
  std::ifstream in;
  if (std::filesystem::is_regular_file(path, ec)) {
    requireInputFile(path, "fault file");  // noted: no output of the run replaces it
    in.open(path, std::ios::binary);
  }
  if (!in.is_open() || !in) throw Error(path + ": cannot read");
  const std::string text = readRest(in);
  if (in.bad()) throw Error(path + ": cannot read");
  return parseFaultScript(text, path);
}

}  // namespace mcws
