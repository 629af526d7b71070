#include "mcws/planning/scenario.h"

#include <yaml-cpp/yaml.h>

#include "mcws/core/text_file.h"
#include "mcws/core/yaml_reader.h"
#include "mcws/planning/scenario_sections.h"

namespace mcws {

namespace {

class ScenarioReader : ScenarioSectionReader {
 public:
  explicit ScenarioReader(std::string source) : ScenarioSectionReader(std::move(source)) {}

  Scenario read(const YAML::Node& root) {
    if (!root.IsMap()) fail(root, "the document must be a map of scenario fields");
    checkKeys(
        root, "scenario",
        {"name", "robot", "start", "goal", "joint_scale", "base", "sway", "planner", "validation"});
    Scenario scenario;
    scenario.source = source();
    scenario.name = scalar(require(root, "name", "scenario"), "name");
    SwayPlanningProblem& problem = scenario.problem;

    readRobot(require(root, "robot", "scenario"), scenario.robot_path, problem);
    if (const YAML::Node base = root["base"]) problem.robot.T_world_base = pose(base, "base");

    problem.start = joints(require(root, "start", "scenario"), "start", problem.robot);
    problem.goal = joints(require(root, "goal", "scenario"), "goal", problem.robot);
    scenario.distance_unit = readJointScale(root["joint_scale"], problem);

    readSway(require(root, "sway", "scenario"), problem);
    if (const YAML::Node planner = root["planner"]) readPlanner(planner, problem);
    if (const YAML::Node validation = root["validation"]) readValidation(validation, problem);
    return scenario;
  }
};

}  // namespace

Scenario parseScenario(const std::string& text, const std::string& source) {
  return ScenarioReader(source).read(loadYamlDocument(text, source, "a scenario file"));
}

Scenario loadScenario(const std::string& path) {
  // Regular files only (a FIFO nobody writes would block), noted as an input of the run.
  return parseScenario(readTextFile(path, "scenario file"), path);
}

}  // namespace mcws
