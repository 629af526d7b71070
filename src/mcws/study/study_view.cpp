// The report's "view" (docs: /work/wt/notes/study_contract.md): the answers at the top and the
// sections the page shows, every number taken from the report itself.
#include "mcws/core/decimal.h"
#include "mcws/core/length_unit.h"
#include "mcws/study/detail/study_stages.h"

namespace mcws::detail {

namespace {

using Json = nlohmann::json;

Json column(const std::string& name, const std::string& unit) {
  return {{"name", name}, {"unit", unit}};
}

/// The answer of one planned target: the chosen path's whole-path collision probability on the
/// validation poses, against the shortest and the padded path.
Json pathAnswer(const StudyState& state, std::size_t i) {
  const Study& study = *state.study;
  const std::string name = study.targets[state.planned[i].target].name;
  const std::string at = "/planning/targets/" + std::to_string(i) + "/plan/validation";
  const Json& validation = state.report.at(Json::json_pointer(at));
  Json answer = {{"label", "Path to " + name + ": whole-path collision probability"},
                 {"unit", "fraction"},
                 {"value", validation.at("chosen_collision_probability")},
                 {"source", at + "/chosen_collision_probability"},
                 {"interval", validation.at("chosen_interval_95")},
                 {"interval_source", at + "/chosen_interval_95"}};
  std::string note;
  for (const char* other : {"shortest", "padded"}) {
    const std::string key = std::string(other) + "_collision_probability";
    if (!validation.contains(key)) continue;
    const Json& interval = validation.at(std::string(other) + "_interval_95");
    note += std::string(note.empty() ? "" : "; ") + other + " path " +
            formatNumber(validation.at(key).get<double>()) + " [" +
            formatNumber(interval[0].get<double>()) + ", " +
            formatNumber(interval[1].get<double>()) + "]";
  }
  // Whether the planner accepted the path: a refused one is shown, never recommended.
  const Json& plan =
      state.report.at(Json::json_pointer("/planning/targets/" + std::to_string(i) + "/plan"));
  const std::string status = plan.at("status").get<std::string>();
  const std::string verdict =
      status == "ok"
          ? "accepted: the upper end of its 95 % interval on the planning poses is at most " +
                formatNumber(plan.at("max_collision_probability").get<double>())
          : "REFUSED (" + status +
                "): no path to this target keeps the collision "
                "probability within " +
                formatNumber(plan.at("max_collision_probability").get<double>()) +
                "; do not use it without a smaller sway or another stop";
  answer["note"] = verdict + "; " + note + " (95 % intervals, " +
                   std::to_string(validation.at("poses").get<std::size_t>()) + " fresh base poses)";
  if (status != "ok")
    answer["label"] = "Best path to " + name + " (refused): whole-path collision probability";
  return answer;
}

Json answers(const StudyState& state) {
  const Study& study = *state.study;
  const std::string unit = unitName(study.problem.robot.length_unit);
  const Json& chosen = state.report.at("placement").at("chosen_stop");
  Json out = Json::array();
  out.push_back({{"label", "Stop the robot at (along the line)"},
                 {"value", chosen.at("offset_along")},
                 {"unit", unit},
                 {"source", "/placement/chosen_stop/offset_along"},
                 {"note", std::to_string(chosen.at("targets_reached").get<std::size_t>()) + " of " +
                              std::to_string(study.targets.size()) +
                              " targets reached (IK with the line as environment)"}});
  for (std::size_t i = 0; i < state.planned.size(); ++i) {
    if (state.report.at("planning").at("targets").at(i).at("plan").contains("validation"))
      out.push_back(pathAnswer(state, i));
  }
  out.push_back({{"label", "Workspace volume"},
                 {"value", state.report.at("workspace").at("measure").at("volume")},
                 {"unit", unit + "^3"},
                 {"source", "/workspace/measure/volume"},
                 {"note", state.report.at("workspace").contains("refine")
                              ? "the region the samples and their refinement near the boundary "
                                "cover, Delaunay alpha measure without edge correction (the "
                                "de-icing arm's refined 1e6-point cloud: within 0.03 % of the "
                                "closed form, BENCHMARKS.md)"
                              : "the region the samples cover, Delaunay alpha measure with "
                                "Efron's edge correction (0.04 % for 1e5 uniform samples of a "
                                "ball; a joint-sampled cloud stops short of the true edge by up "
                                "to a few per cent: BENCHMARKS.md)"}});
  out.push_back(
      {{"label", "Maximum reach from the first joint's axis"},
       {"value", state.report.at("workspace").at("envelope").at("drawing").at("max_reach")},
       {"unit", unit},
       {"source", "/workspace/envelope/drawing/max_reach"},
       {"note",
        "from the envelope mesh and the samples' top view (as the datasheet "
        "drawing)"}});
  return out;
}

/// The placement's shares against the stop, and each planned target's rounds.
Json offsetsChart(const StudyState& state) {
  const Study& study = *state.study;
  Json map_share = {
      {"name", "targets the map marks reached"}, {"x", Json::array()}, {"y", Json::array()}};
  Json ik_share = {{"name", "targets reached (IK)"}, {"x", Json::array()}, {"y", Json::array()}};
  for (std::size_t s = 0; s < state.candidates.size(); ++s) {
    map_share["x"].push_back(study.stops[s]);
    map_share["y"].push_back(state.candidates[s].map_share);
    ik_share["x"].push_back(study.stops[s]);
    ik_share["y"].push_back(state.candidates[s].ik.share_reached);
  }
  return {{"kind", "chart"},
          {"title", "Targets reached against the stop along the line"},
          {"x",
           {{"label", "stop (base offset along the line)"},
            {"unit", unitName(study.problem.robot.length_unit)}}},
          {"y", {{"label", "share of the targets"}, {"unit", "fraction"}}},
          {"series", {ik_share, map_share}}};
}

/// P and the whole-path free fraction (with its 95 % interval) of each planned target's best
/// path against the base offset from the chosen stop (the study's `offsets:` scan).
Json pAgainstOffsetChart(const StudyState& state) {
  const Study& study = *state.study;
  Json series = Json::array();
  const Json& targets = state.report.at("planning").at("targets");
  for (const Json& target : targets) {
    if (!target.contains("offsets")) continue;
    const std::string name = target.at("target").get<std::string>();
    Json p = {{"name", name + ": P (patent)"}, {"x", Json::array()}, {"y", Json::array()}};
    Json free = {{"name", name + ": whole-path free fraction, 95 % interval"},
                 {"x", Json::array()},
                 {"y", Json::array()},
                 {"lo", Json::array()},
                 {"hi", Json::array()}};
    for (const Json& row : target.at("offsets")) {
      if (!row.contains("P")) continue;
      p["x"].push_back(row.at("base_offset"));
      p["y"].push_back(row.at("P"));
      free["x"].push_back(row.at("base_offset"));
      free["y"].push_back(row.at("whole_path_free_fraction"));
      free["lo"].push_back(row.at("free_interval_95")[0]);
      free["hi"].push_back(row.at("free_interval_95")[1]);
    }
    series.push_back(p);
    series.push_back(free);
  }
  if (series.empty()) return Json();
  return {{"kind", "chart"},
          {"title", "P against the base offset from the chosen stop"},
          {"x",
           {{"label", "base offset along the line from the stop"},
            {"unit", unitName(study.problem.robot.length_unit)}}},
          {"y", {{"label", "probability"}, {"unit", "fraction"}}},
          {"series", series}};
}

Json candidatesTable(const StudyState& state) {
  Json rows = Json::array();
  for (const PlannedTarget& planned : state.planned) {
    const std::string name = state.study->targets[planned.target].name;
    if (!planned.result.validated) continue;
    const PlanningRound& round = planned.result.rounds[*planned.result.validated];
    for (std::size_t k = 0; k < round.candidates.size(); ++k) {
      const PathSafety& path = round.candidates[k];
      rows.push_back({name, k + 1, path.length, path.probability, path.collision_rate,
                      path.collision_interval.low, path.collision_interval.high});
    }
  }
  return {{"kind", "table"},
          {"title", "Candidate paths (planning poses)"},
          {"columns",
           {column("target", ""), column("candidate", ""), column("length D", "scaled joint"),
            column("P (patent)", "fraction"), column("whole-path collision rate", "fraction"),
            column("95 % low", "fraction"), column("95 % high", "fraction")}},
          {"rows", rows},
          {"note", "D = " + state.study->distance_unit}};
}

Json validationTable(const StudyState& state) {
  Json rows = Json::array();
  for (const PlannedTarget& planned : state.planned) {
    const std::string name = state.study->targets[planned.target].name;
    for (const ValidationRow& row : planned.result.validation) {
      if (!row.planned) {
        rows.push_back({name, row.name, "no path", nullptr, nullptr, nullptr});
        continue;
      }
      rows.push_back({name, row.name, row.length, row.collision_probability, row.interval.low,
                      row.interval.high});
    }
  }
  return {{"kind", "table"},
          {"title", "Validation on fresh base poses: chosen, shortest and padded paths"},
          {"columns",
           {column("target", ""), column("path", ""), column("length D", "scaled joint"),
            column("whole-path collision probability", "fraction"), column("95 % low", "fraction"),
            column("95 % high", "fraction")}},
          {"rows", rows}};
}

/// The unit of the reach study's manipulability (qualitySummary()'s "manipulability_unit").
std::string manipulabilityUnit(const StudyState& state) {
  const Json& study = state.report.at("reach").at("study");
  const Json* quality = study.contains("manipulability") ? &study.at("manipulability") : nullptr;
  if (quality && quality->contains("manipulability_unit") &&
      quality->at("manipulability_unit").is_string())
    return quality->at("manipulability_unit").get<std::string>();
  return "";
}

Json reachTableView(const StudyState& state) {
  const Study& study = *state.study;
  const std::string unit = unitName(study.problem.robot.length_unit);
  Json rows = Json::array();
  for (const Json& target : state.report.at("placement").at("targets")) {
    std::string stops;
    for (const Json& stop : target.at("stops_reaching"))
      stops += (stops.empty() ? "" : ", ") + formatNumber(stop.get<double>());
    rows.push_back({target.at("target"), target.at("reached_at_chosen_stop").get<bool>() ? 1 : 0,
                    target.at("manipulability"), target.at("clearance"),
                    stops.empty() ? "none" : stops});
  }
  return {{"kind", "table"},
          {"title", "Reach study of the targets"},
          {"columns",
           {column("target", ""), column("reached at the chosen stop", "1 yes, 0 no"),
            column("manipulability", manipulabilityUnit(state)), column("clearance", unit),
            column("stops reaching it", unit)}},
          {"rows", rows}};
}

Json stagesTable(const StudyState& state) {
  Json rows = Json::array();
  for (const Json& stage : state.report.at("stages"))
    rows.push_back({stage.at("stage"), stage.at("seconds")});
  return {{"kind", "table"},
          {"title", "Time of each stage"},
          {"columns", {column("stage", ""), column("time", "s")}},
          {"rows", rows}};
}

}  // namespace

Json studyView(const StudyState& state) {
  Json sections = Json::array();
  sections.push_back({{"kind", "image"},
                      {"title", "Working range (datasheet drawing)"},
                      {"png_base64", base64(state.drawing_png)},
                      {"alt", "side and top view of the workspace envelope with dimensions"}});
  sections.push_back(offsetsChart(state));
  if (Json chart = pAgainstOffsetChart(state); !chart.is_null()) sections.push_back(chart);
  sections.push_back(candidatesTable(state));
  sections.push_back(validationTable(state));
  sections.push_back(reachTableView(state));
  if (!state.behaviour_timeline.is_null()) sections.push_back(state.behaviour_timeline);
  sections.push_back(stagesTable(state));
  sections.push_back(
      {{"kind", "text"},
       {"title", "The line"},
       {"text", state.report.at("line").at("note").get<std::string>() +
                    "; conductors are capsules along their polylines, fittings the shapes given. "
                    "The workspace, boundary and reach map are drawn at the chosen stop."}});
  return {{"title", state.study->name}, {"answers", answers(state)}, {"sections", sections}};
}

}  // namespace mcws::detail
