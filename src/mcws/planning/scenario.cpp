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
    scenario.distance_unit =
        readProblem(root, "scenario", scenario.robot_path, scenario.problem, true);
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
