#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>

#include "mcws/behavior/behavior_executor.h"
#include "mcws/behavior/behavior_model.h"
#include "mcws/collision/shape_yaml.h"
#include "mcws/core/error.h"
#include "mcws/core/text_file.h"
#include "mcws/planning/scenario_sections.h"
#include "mcws/reach/targets_file.h"
#include "mcws/study/study.h"

namespace mcws {

namespace {

/// At most this many stops (as mcws_place's positions along one axis).
constexpr double kMaxStops = 1e5;
/// At most this many map samples: 2^53, the largest whole number a double (the reader's
/// numbers) holds exactly; mcws_place --samples takes up to 2^63 - 1.
constexpr std::size_t kMaxMapSamples = std::size_t{1} << 53;

class StudyReader : ScenarioSectionReader {
 public:
  explicit StudyReader(std::string source) : ScenarioSectionReader(std::move(source)) {}

  Study read(const YAML::Node& root) {
    if (!root.IsMap()) fail(root, "the document must be a map of study fields");
    checkKeys(root, "study",
              {"name", "robot", "seed", "line", "targets", "stops", "start", "joint_scale", "base",
               "sway", "planner", "validation", "workspace", "reach", "offsets", "behaviour"});
    Study study;
    study.source = source();
    study.name = text(require(root, "name", "study"), "name");
    study.distance_unit = readProblem(root, "study", study.robot_path, study.problem, false);
    if (const YAML::Node seed = root["seed"]) study.seed = seedOf(seed, "seed");
    study.inputs = {study.source, study.robot_path};
    readLine(require(root, "line", "study"), study);
    readTargets(require(root, "targets", "study"), study);
    readStops(require(root, "stops", "study"), study);
    if (const YAML::Node workspace = root["workspace"]) readWorkspace(workspace, study.workspace);
    readReach(require(root, "reach", "study"), study.reach);
    if (const YAML::Node offsets = root["offsets"]) readOffsets(offsets, study.offsets);
    if (const YAML::Node behaviour = root["behaviour"]) readBehaviour(behaviour, study);
    return study;
  }

 private:
  void readLine(const YAML::Node& node, Study& study) {
    checkKeys(node, "line", {"conductors", "fittings"});
    const YAML::Node conductors = require(node, "conductors", "line");
    if (!conductors.IsSequence() || conductors.size() == 0)
      fail(conductors, "line: conductors: must be a non-empty list");
    std::set<std::string> names;
    for (std::size_t i = 0; i < conductors.size(); ++i) {
      study.conductors.push_back(readConductor(conductors[i], i));
      checkName(conductors[i]["name"], "line: conductors", study.conductors.back().name, names);
    }
    if (const YAML::Node fittings = node["fittings"]) {
      if (!fittings.IsSequence()) fail(fittings, "line: fittings: must be a list of named shapes");
      ShapeYamlReader shapes(source());
      for (std::size_t i = 0; i < fittings.size(); ++i) {
        const YAML::Node item = fittings[i];
        const std::string where = "line: fitting " + std::to_string(i + 1);
        if (!item.IsMap() || !item["name"]) fail(item, where + ": must be a map with a 'name'");
        BodySpec body;
        body.name = text(item["name"], where + ": name");
        checkName(item["name"], "line: fittings", body.name, names);
        body.shapes.push_back(shapes.readShape(item, where + " '" + body.name + "'", true));
        study.fittings.push_back(std::move(body));
      }
    }
    // The robot file's scene goes, with the allowed pairs that name its objects.
    CollisionModel& model = study.problem.collision;
    std::set<std::string> replaced;
    for (const BodySpec& object : model.environment) replaced.insert(object.name);
    study.replaced_environment = replaced.size();
    model.allowed.erase(std::remove_if(model.allowed.begin(), model.allowed.end(),
                                       [&](const auto& pair) {
                                         return replaced.count(pair.first) ||
                                                replaced.count(pair.second);
                                       }),
                        model.allowed.end());
    model.environment = lineBodies(study);
  }

  void checkName(const YAML::Node& node, const std::string& where, const std::string& name,
                 std::set<std::string>& names) const {
    if (!names.insert(name).second) fail(node, where + ": name '" + name + "' is already used");
  }

  Conductor readConductor(const YAML::Node& node, std::size_t i) {
    const std::string where = "line: conductor " + std::to_string(i + 1);
    checkKeys(node, where, {"name", "radius", "points"});
    Conductor conductor;
    conductor.name = text(require(node, "name", where), where + ": name");
    conductor.radius = quantity(require(node, "radius", where), 'l', where + ": radius");
    if (!(conductor.radius > 0.0))
      fail(node["radius"], where + ": radius " + node["radius"].Scalar() + " must be > 0");
    const YAML::Node points = require(node, "points", where);
    if (!points.IsSequence() || points.size() < 2)
      fail(points, where + ": points: must list at least two points [x, y, z] with units");
    for (const YAML::Node& point : points)
      conductor.points.push_back(vector3(point, 'l', where + ": points"));
    return conductor;
  }

  void readTargets(const YAML::Node& node, Study& study) {
    if (!node.IsSequence() || node.size() == 0)
      fail(node, "targets: must be a non-empty list of files ({file, name}) or poses");
    for (std::size_t i = 0; i < node.size(); ++i) {
      const YAML::Node item = node[i];
      const std::string where = "targets[" + std::to_string(i + 1) + "]";
      if (item.IsMap() && item["file"]) {
        checkKeys(item, where, {"file", "name", "standoff"});
        readTargetsFile(item, where, study);
      } else {
        checkKeys(item, where, {"name", "point", "normal", "standoff"});
        const Eigen::Vector3d point =
            vector3(require(item, "point", where), 'l', where + ": point");
        const Eigen::Vector3d normal =
            vector3(require(item, "normal", where), 'n', where + ": normal");
        StudyTarget target;
        target.name = text(require(item, "name", where), where + ": name");
        try {
          target.target = targetFromNormal(point, normal);
        } catch (const Error& e) {
          fail(item["normal"], where + ": " + e.what());
        }
        std::vector<ReachTarget> one{target.target};
        applyStandoff(one, standoff(item, where));
        target.target = one.front();
        study.targets.push_back(std::move(target));
      }
    }
    std::set<std::string> names;
    for (std::size_t i = 0; i < study.targets.size(); ++i) {
      if (!names.insert(study.targets[i].name).second)
        fail(node, "targets: name '" + study.targets[i].name + "' is used twice");
    }
  }

  /// The distance of the tool point from the target's surface, along its normal (0 when absent).
  double standoff(const YAML::Node& item, const std::string& where) const {
    if (!item["standoff"]) return 0.0;
    const double value = quantity(item["standoff"], 'l', where + ": standoff");
    if (value < 0.0)
      fail(item["standoff"], where + ": standoff " + item["standoff"].Scalar() + " must be >= 0");
    return value;
  }

  void readTargetsFile(const YAML::Node& item, const std::string& where, Study& study) {
    std::filesystem::path file = text(item["file"], where + ": file");
    if (file.is_relative()) file = std::filesystem::path(source()).parent_path() / file;
    const std::string name =
        item["name"] ? text(item["name"], where + ": name") : file.stem().string();
    study.inputs.push_back(file.string());
    std::vector<ReachTarget> targets;
    try {
      targets = loadTargets(file.string());
    } catch (const Error& e) {
      fail(item["file"], where + ": file: " + e.what());
    }
    applyStandoff(targets, standoff(item, where));
    for (std::size_t k = 0; k < targets.size(); ++k)
      study.targets.push_back({name + "_" + std::to_string(k + 1), targets[k]});
  }

  void readStops(const YAML::Node& node, Study& study) {
    checkKeys(node, "stops", {"from", "to", "step"});
    const double from = quantity(require(node, "from", "stops"), 'l', "stops: from");
    const double to = quantity(require(node, "to", "stops"), 'l', "stops: to");
    const double step = quantity(require(node, "step", "stops"), 'l', "stops: step");
    if (!(step > 0.0)) fail(node["step"], "stops: step " + node["step"].Scalar() + " must be > 0");
    if (to < from) {
      fail(node["to"], "stops: the range is empty: to " + node["to"].Scalar() + " is below from " +
                           node["from"].Scalar());
    }
    const double count = std::floor((to - from) / step + 1e-9) + 1.0;
    if (!(count <= kMaxStops)) fail(node["step"], "stops: more than 100000 stops");
    for (int k = 0; k < static_cast<int>(count); ++k) study.stops.push_back(from + k * step);
  }

  void readWorkspace(const YAML::Node& node, StudyWorkspace& workspace) {
    checkKeys(node, "workspace", {"samples", "refine", "alpha", "azimuth"});
    if (node["samples"]) workspace.samples = count(node["samples"], "workspace: samples");
    if (node["refine"]) workspace.refine = count(node["refine"], "workspace: refine", 0);
    if (node["alpha"]) {
      workspace.alpha = number(node["alpha"], "workspace: alpha");
      if (!(workspace.alpha >= 1.0 && workspace.alpha <= 1000.0))
        fail(node["alpha"], "workspace: alpha " + node["alpha"].Scalar() +
                                " is outside [1, 1000] (local spacings)");
    }
    if (node["azimuth"]) workspace.azimuth = quantity(node["azimuth"], 'a', "workspace: azimuth");
  }

  /// The behaviour model, loaded and checked here so that a bad one fails before any stage
  /// runs: read (loadBehaviorModel()), validated (validateBehaviorModel(), as mcws_behave
  /// --check) and its job set up for the study's discs by a run stopped after its first step
  /// (the task plan's combined behaviours, the clamp's components, a sensor behind every event:
  /// what runCleaningJob() checks before it runs). Any mistake: "behaviour: model: <why>".
  void readBehaviour(const YAML::Node& node, Study& study) {
    checkKeys(node, "behaviour", {"model", "insulators"});
    const YAML::Node model = require(node, "model", "behaviour");
    std::filesystem::path file = text(model, "behaviour: model");
    if (file.is_relative()) file = std::filesystem::path(source()).parent_path() / file;
    study.behaviour.model = file.string();
    study.inputs.push_back(file.string());
    const std::size_t discs =
        count(require(node, "insulators", "behaviour"), "behaviour: insulators");
    if (discs > 200)
      fail(node["insulators"], "behaviour: insulators " + node["insulators"].Scalar() +
                                   " is more than 200 (as mcws_behave --insulators)");
    study.behaviour.insulators = static_cast<int>(discs);
    try {
      study.behaviour.loaded = loadBehaviorModel(study.behaviour.model);
      validateBehaviorModel(*study.behaviour.loaded);
      RunOptions start = RunOptions::forModel(*study.behaviour.loaded, study.behaviour.insulators);
      start.max_time_s = std::numeric_limits<double>::min();  // one step, then the time limit
      runCleaningJob(*study.behaviour.loaded, start);
    } catch (const Error& e) {
      fail(model, std::string("behaviour: model: ") + e.what());
    }
    if (!study.behaviour.loaded->robot_path.empty())
      study.inputs.push_back(study.behaviour.loaded->robot_path);
  }

  void readOffsets(const YAML::Node& node, StudyOffsets& offsets) {
    checkKeys(node, "offsets", {"range", "step"});
    offsets.range = quantity(require(node, "range", "offsets"), 'l', "offsets: range");
    offsets.step = quantity(require(node, "step", "offsets"), 'l', "offsets: step");
    if (!(offsets.step > 0.0) || !(offsets.range >= 0.0) || offsets.range > 50 * offsets.step)
      fail(node, "offsets: step must be > 0 and range from 0 to 50 steps");
  }

  void readReach(const YAML::Node& node, StudyReach& reach) {
    checkKeys(node, "reach",
              {"resolution", "samples", "orientations", "rolls", "approach_tolerance", "ik_starts",
               "plan_targets"});
    reach.grid.resolution =
        quantity(require(node, "resolution", "reach"), 'l', "reach: resolution");
    if (node["samples"])
      reach.samples = count(node["samples"], "reach: samples", 1, kMaxMapSamples);
    if (node["orientations"])
      reach.grid.directions = static_cast<int>(count(node["orientations"], "reach: orientations"));
    if (node["rolls"]) reach.grid.rolls = static_cast<int>(count(node["rolls"], "reach: rolls"));
    try {
      reach.grid.check();
    } catch (const Error& e) {
      fail(node, std::string("reach: ") + e.what());
    }
    if (node["approach_tolerance"]) {
      reach.approach_tolerance =
          quantity(node["approach_tolerance"], 'a', "reach: approach_tolerance");
      if (reach.approach_tolerance < 0.0 || reach.approach_tolerance > M_PI)
        fail(node["approach_tolerance"], "reach: approach_tolerance is outside [0, 180] deg");
    }
    if (node["ik_starts"])
      reach.ik_starts = static_cast<int>(count(node["ik_starts"], "reach: ik_starts", 1, 1000));
    if (node["plan_targets"]) {
      reach.plan_targets = node["plan_targets"].IsScalar() && node["plan_targets"].Scalar() == "all"
                               ? 0
                               : count(node["plan_targets"], "reach: plan_targets");
    }
  }
};

}  // namespace

std::vector<BodySpec> lineBodies(const Study& study) {
  std::vector<BodySpec> bodies;
  for (const Conductor& conductor : study.conductors) {
    BodySpec body;
    body.name = conductor.name;
    for (std::size_t k = 0; k + 1 < conductor.points.size(); ++k) {
      ShapeSpec capsule;
      capsule.type = ShapeType::kCapsule;
      capsule.p_from = conductor.points[k];
      capsule.p_to = conductor.points[k + 1];
      capsule.radius = conductor.radius;
      capsule.source = study.source + ": line: " + conductor.name;
      body.shapes.push_back(capsule);
    }
    bodies.push_back(std::move(body));
  }
  bodies.insert(bodies.end(), study.fittings.begin(), study.fittings.end());
  return bodies;
}

Study parseStudy(const std::string& text, const std::string& source) {
  return StudyReader(source).read(loadYamlDocument(text, source, "a study file"));
}

Study loadStudy(const std::string& path) {
  return parseStudy(readTextFile(path, "study file"), path);
}

}  // namespace mcws
