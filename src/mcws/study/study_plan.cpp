// Stage (4) of the study: planning under sway at the chosen stop.
#include <filesystem>

#include "mcws/core/error.h"
#include "mcws/io/atomic_file.h"
#include "mcws/planning/plan_report.h"
#include "mcws/study/detail/study_stages.h"

namespace mcws::detail {

namespace {

/// The scenario of one target at the chosen stop: the study's planning problem with the robot's
/// base and the sway's pivot moved by the stop, the IK solution as the goal.
Scenario stopScenario(const Study& study, double stop, const StudyTarget& target,
                      const Eigen::VectorXd& goal) {
  Scenario scenario;
  scenario.name = study.name + ": " + target.name;
  scenario.source = study.source;
  scenario.robot_path = study.robot_path;
  scenario.distance_unit = study.distance_unit;
  scenario.problem = study.problem;
  const Eigen::Vector3d move = stopMove(study, stop);
  scenario.problem.robot.T_world_base.pretranslate(move);
  scenario.problem.sway.pivot += move;
  scenario.problem.goal = goal;
  return scenario;
}

/// The best path of each round of a scan of the base offset (scanOffsets()).
nlohmann::json offsetsJson(const std::vector<PlanningRound>& rounds) {
  nlohmann::json rows = nlohmann::json::array();
  for (const PlanningRound& round : rounds) {
    nlohmann::json row = {{"base_offset", round.base_offset},
                          {"roadmap", roadmapStatusName(round.status)}};
    if (round.best) {
      row["P"] = round.best->probability;
      row["whole_path_free_fraction"] = round.best->free_fraction;
      row["free_interval_95"] = {round.best->free_interval.low, round.best->free_interval.high};
    }
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

void runPlanning(StudyState& state) {
  const Study& study = *state.study;
  const auto best = static_cast<std::size_t>(state.best);
  const double stop = study.stops[best];
  nlohmann::json targets = nlohmann::json::array();
  state.planned.clear();
  const std::size_t limit =
      study.reach.plan_targets == 0 ? study.targets.size() : study.reach.plan_targets;
  for (std::size_t t = 0; t < study.targets.size() && state.planned.size() < limit; ++t) {
    const TargetReach& reach = state.per_stop[best][t];
    if (!reach.reached) continue;
    PlannedTarget planned;
    planned.target = t;
    planned.scenario = stopScenario(study, stop, study.targets[t], reach.q);
    const std::string stage = "planning " + study.targets[t].name;
    const PlanningProgress progress = [&](const std::string& what, std::size_t done,
                                          std::size_t total) {
      if (state.options.progress) state.options.progress(stage + ": " + what, done, total);
    };
    const SwayPlanner planner(planned.scenario.problem);
    planned.result = planner.plan(true, progress);
    nlohmann::json goal = nlohmann::json::array();
    for (int j = 0; j < reach.q.size(); ++j) goal.push_back(reach.q[j]);
    nlohmann::json item = {{"target", study.targets[t].name},
                           {"stop", stop},
                           {"goal", goal},
                           {"plan", planJson(planned.scenario, planned.result)}};
    if (study.offsets.range > 0.0) {  // P against the base offset, as mcws_plan --plot-offsets
      SwayPlanningProblem scan = planned.scenario.problem;
      scan.base_step = study.offsets.step;
      scan.base_range = study.offsets.range;
      const SwayPlanner scanner(scan);
      item["offsets"] = offsetsJson(scanOffsets(scanner, progress));
    }
    if (planned.result.accepted) {
      const PlanningRound& round = planned.result.rounds[*planned.result.accepted];
      const std::string file = "path_" + study.targets[t].name + ".csv";
      io::writeWholeFile((std::filesystem::path(state.directory) / file).string(),
                         pathCsv(planned.scenario, *round.best));
      item["path_file"] = file;
    }
    targets.push_back(item);
    state.planned.push_back(std::move(planned));
  }
  state.report["planning"] = {
      {"stop", stop},
      {"targets", targets},
      {"distance_unit", study.distance_unit},
      {"note",
       "each reached target at the chosen stop (up to reach: plan_targets), its IK "
       "solution (collision-free with the line) the goal, planned from start as "
       "mcws_plan plans a scenario"}};
  state.report["planning"]["units"] = {
      {"stop", unitName(study.problem.robot.length_unit)},
      {"targets.goal", "per joint as plan.units.configuration (rad, or the length unit)"},
      {"targets.offsets.base_offset", unitName(study.problem.robot.length_unit)},
      {"targets.offsets.P", "fraction"},
      {"targets.offsets.whole_path_free_fraction", "fraction"}};
}

}  // namespace mcws::detail
