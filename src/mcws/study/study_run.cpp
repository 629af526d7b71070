#include "mcws/study/study_run.h"

#include <cmath>
#include <filesystem>
#include <numeric>
#include <optional>
#include <sstream>

#include "mcws/collision/robot_bodies.h"
#include "mcws/core/decimal.h"
#include "mcws/core/error.h"
#include "mcws/core/length_unit.h"
#include "mcws/core/stopwatch.h"
#include "mcws/filters/orthant_boundary.h"
#include "mcws/io/cloud_io.h"
#include "mcws/reach/map_cache.h"
#include "mcws/reach/reach_report.h"
#include "mcws/sampling/sample_report.h"
#include "mcws/sampling/sampler.h"
#include "mcws/study/detail/study_stages.h"
#include "mcws/workspace/drawing.h"
#include "mcws/workspace/envelope_report.h"
#include "mcws/workspace/measure_report.h"
#include "mcws/workspace/refine.h"

namespace mcws {
namespace detail {

namespace {

std::string inDirectory(const StudyState& state, const std::string& name) {
  return (std::filesystem::path(state.directory) / name).string();
}

void report(const StudyState& state, const std::string& stage, std::size_t done,
            std::size_t total) {
  if (state.options.progress) state.options.progress(stage, done, total);
}

/// The progress callback of one stage.
std::function<void(std::size_t, std::size_t)> reporter(const StudyState& state,
                                                       const std::string& stage) {
  return
      [&state, stage](std::size_t done, std::size_t total) { report(state, stage, done, total); };
}

/// The ReachStudy options of the study (as mcws_reach and mcws_place read their flags).
ReachStudyOptions studyOptions(const StudyState& state) {
  const Study& study = *state.study;
  ReachStudyOptions options;
  options.approach_tolerance = study.reach.approach_tolerance;
  options.starts = study.reach.ik_starts;
  options.ik.seed = study.seed;
  options.threads = state.options.threads;
  options.quality = defaultQualityOptions(study.problem.robot);
  return options;
}

std::vector<ReachTarget> targetsOf(const Study& study) {
  std::vector<ReachTarget> targets;
  for (const StudyTarget& target : study.targets) targets.push_back(target.target);
  return targets;
}

/// The workspace samples as mcws_sample writes them, read back as mcws_measure reads them.
/// mcws_refine --input boundary.pcd --cloud samples.pcd --seed S: the cloud followed by new
/// samples near the boundary points' configurations, into refined.pcd and state.samples.
nlohmann::json refineWorkspace(StudyState& state, const pcl::PointCloud<WorkspacePoint>& parents,
                               const io::WorkspaceCloud& cloud) {
  const Study& study = *state.study;
  RefineOptions options;
  options.seed = study.seed;
  const RefineSampler refine(study.problem.robot, parents, options);
  io::WorkspaceCloud refined = cloud;
  const std::size_t kept = refined.size();
  refined.resize(kept + study.workspace.refine);
  generateInChunks(refine, study.workspace.refine, refined.data() + kept, state.options.threads,
                   reporter(state, "workspace refinement"));
  pcl::Indices all(refined.size());
  std::iota(all.begin(), all.end(), 0);
  io::CloudProvenance provenance = robotProvenance(study.problem.robot);
  provenance.sampling = io::SamplingRecord{"tool", false, {}};
  io::writeCloud(refined, all, inDirectory(state, "refined.pcd"), provenance);
  state.samples.clear();
  for (const WorkspacePoint& p : refined) state.samples.push_back(pcl::PointXYZ(p.x, p.y, p.z));
  return {{"file", "refined.pcd"},
          {"new_samples", study.workspace.refine},
          {"points", refined.size()},
          {"spread", options.spread},
          {"seed", options.seed},
          {"note",
           "as mcws_refine --input boundary.pcd --cloud samples.pcd; the volume and the "
           "envelope are the refined cloud's, without the edge correction"}};
}

nlohmann::json sampleWorkspace(StudyState& state) {
  const Study& study = *state.study;
  const Robot& robot = study.problem.robot;
  RobotSamplerOptions sampler_options;
  sampler_options.seed = study.seed;
  const RobotSampler sampler(robot, sampler_options);
  io::CloudProvenance provenance = robotProvenance(robot);
  provenance.sampling = io::SamplingRecord{"tool", false, {}};
  const std::string path = inDirectory(state, "samples.pcd");
  SampleSummary summary;
  {
    io::ScopedProvenance scoped(provenance);
    summary = writeSamples(sampler, study.workspace.samples, path, io::PcdFormat::kBinary,
                           state.options.threads, reporter(state, "workspace samples"));
  }
  const io::WorkspaceCloud::Ptr cloud = io::readCloud(path);
  state.samples.clear();
  for (const WorkspacePoint& p : *cloud) state.samples.push_back(pcl::PointXYZ(p.x, p.y, p.z));
  nlohmann::json out = {{"file", "samples.pcd"},
                        {"points", summary.points},
                        {"seed", study.seed},
                        {"length_unit", unitName(robot.length_unit)},
                        {"point", "tool"}};
  addRobotNames(out, robot);
  addBoundingBox(out, summary, unitName(robot.length_unit));

  OrthantBoundary<WorkspacePoint> filter(true);
  filter.setPlane(BoundaryPlane::k3D);
  filter.setNumberOfThreads(state.options.threads);
  filter.setGridSearch(true);
  filter.setInputCloud(cloud);
  pcl::Indices kept;
  filter.filter(kept);
  io::writeCloud(*cloud, kept, inDirectory(state, "boundary.pcd"), provenance);
  state.boundary.clear();
  pcl::PointCloud<WorkspacePoint> parents;
  for (const auto i : kept) {
    const WorkspacePoint& p = (*cloud)[static_cast<std::size_t>(i)];
    state.boundary.push_back(pcl::PointXYZ(p.x, p.y, p.z));
    parents.push_back(p);
  }
  nlohmann::json result = {
      {"samples", out},
      {"boundary", {{"file", "boundary.pcd"}, {"method", "orthant"}, {"points", kept.size()}}}};
  if (study.workspace.refine > 0) result["refine"] = refineWorkspace(state, parents, *cloud);
  return result;
}

}  // namespace

Eigen::Vector3d stopMove(const Study& study, double stop) {
  return stop * study.problem.sway.line_direction.normalized();
}

void runWorkspace(StudyState& state) {
  const Study& study = *state.study;
  const Robot& robot = study.problem.robot;
  nlohmann::json out = sampleWorkspace(state);
  report(state, "workspace envelope", 0, 1);
  MeasureOptions options;
  options.alpha_factor = study.workspace.alpha;
  options.edge_correction = study.workspace.refine == 0;  // refined samples lie on the edge
  options.threads = state.options.threads;
  state.envelope = workspaceEnvelope(state.samples, options);
  const ResultUnits units(robot.length_unit, std::nullopt);
  out["measure"] = regionMeasureJson(state.envelope.measure, options, 3, units);
  out["measure"]["method"] = "delaunay";
  const EnvelopeDrawing drawing =
      envelopeDrawing(state.envelope.mesh, state.samples, study.workspace.azimuth);
  out["envelope"] = envelopeSummary(state.envelope, options, drawing, units);
  out["envelope"]["file"] = "envelope.ply";
  out["envelope"]["drawing"]["file"] = "drawing.png";
  const std::string unit = unitName(robot.length_unit);
  saveSurface(state.envelope.mesh, inDirectory(state, "envelope.ply"),
              "robot '" + robot.name + "', study " + study.name, unit);
  state.drawing_png =
      renderEnvelopeDrawing(drawing, DrawingFormat::kPng, robot.name, unit, tipName(robot));
  io::writeWholeFile(inDirectory(state, "drawing.png"), state.drawing_png);
  report(state, "workspace envelope", 1, 1);
  state.report["workspace"] = out;
}

namespace {

/// The reach stage's map: from the map cache when it holds it (StudyRunOptions::map_cache), else
/// built and stored there.
ReachMap cachedMap(const StudyState& state, const ReachSampling& sampling,
                   const CollisionModel* self) {
  const Study& study = *state.study;
  const Robot& robot = study.problem.robot;
  std::ostringstream nowhere;
  std::ostream& log = state.options.log ? *state.options.log : nowhere;
  const ReachMapCache cache(state.options.map_cache, robot, study.reach.grid, sampling, self);
  CachedMapInfo info;
  if (std::optional<ReachMap> cached = cache.load(log, "mcws_study", &info)) {
    log << "mcws_study: reusing the cached map " << cache.path() << " (built " << info.built_utc
        << " from " << info.samples << " samples in " << info.build_seconds << " s)\n";
    return std::move(*cached);
  }
  if (cache.enabled())
    log << "mcws_study: building the reach map (will be cached at " << cache.path() << ")\n";
  const Stopwatch clock;
  ReachMap map =
      buildReachMap(robot, study.reach.grid, sampling, [&](std::uint64_t done, std::uint64_t all) {
        report(state, "reach map samples", static_cast<std::size_t>(done),
               static_cast<std::size_t>(all));
      });
  cache.store(map, clock.seconds(), log, "mcws_study");
  return map;
}

}  // namespace

void runReach(StudyState& state) {
  const Study& study = *state.study;
  const Robot& robot = study.problem.robot;
  ReachSampling sampling;
  sampling.samples = study.reach.samples;
  sampling.seed = study.seed;
  sampling.threads = state.options.threads;
  sampling.quality = defaultQualityOptions(robot);
  // The map counts samples free of self-collision, the line left to IK (as mcws_place's).
  const CollisionModel self_model = robotBodiesOnly(study.problem.collision);
  const CollisionChecker self(robot, self_model);
  sampling.collision = &self;
  state.map = cachedMap(state, sampling, hasGeometry(self_model) ? &self_model : nullptr);
  state.checker = std::make_unique<CollisionChecker>(robot, study.problem.collision);
  const ReachStudy reach(robot, state.checker.get(), studyOptions(state));
  state.at_origin = reach.evaluate(targetsOf(study), Eigen::Isometry3d::Identity(),
                                   reporter(state, "reach study targets"));
  nlohmann::json out;
  out["map"] = mapSummary(robot, study.reach.grid, sampling, sampling.samples, state.map, true);
  out["study"] = studySummary(robot, studyOptions(state), state.at_origin, true);
  out["study"]["stop"] = 0.0;
  out["study"]["note"] = "the robot at stop 0 (its base as the robot file places it)";
  state.report["reach"] = out;
}

namespace {

/// Per target: at which stops IK reaches it.
nlohmann::json reachTable(const StudyState& state) {
  const Study& study = *state.study;
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t t = 0; t < study.targets.size(); ++t) {
    nlohmann::json stops = nlohmann::json::array();
    for (std::size_t s = 0; s < study.stops.size(); ++s) {
      if (state.per_stop[s][t].reached) stops.push_back(study.stops[s]);
    }
    const TargetReach& best = state.per_stop[static_cast<std::size_t>(state.best)][t];
    rows.push_back(
        {{"target", study.targets[t].name},
         {"reached_at_chosen_stop", best.reached},
         {"manipulability", best.reached ? nlohmann::json(best.manipulability) : nlohmann::json()},
         {"clearance", best.reached && std::isfinite(best.clearance)
                           ? nlohmann::json(best.clearance)
                           : nlohmann::json()},
         {"stops_reaching", stops}});
  }
  return rows;
}

}  // namespace

void runPlacement(StudyState& state) {
  const Study& study = *state.study;
  const Robot& robot = study.problem.robot;
  const ReachStudyOptions options = studyOptions(state);
  const ReachStudy reach(robot, state.checker.get(), options);
  const std::vector<ReachTarget> targets = targetsOf(study);
  std::vector<Eigen::Vector3d> moves;
  for (double stop : study.stops) moves.push_back(stopMove(study, stop));
  PlacementOptions placement;
  placement.confirm = -1;  // every stop: the report says which stop reaches which target
  placement.approach_tolerance = options.approach_tolerance;
  state.candidates =
      placeBase(state.map, reach, targets, moves, placement, reporter(state, "placement stops"));
  state.best = bestCandidate(state.candidates);
  state.per_stop.clear();
  for (std::size_t s = 0; s < moves.size(); ++s) {
    Eigen::Isometry3d T_move = Eigen::Isometry3d::Identity();
    T_move.translation() = moves[s];
    state.per_stop.push_back(reach.evaluate(targets, T_move));
    report(state, "reach study per stop", s + 1, moves.size());
  }
  std::vector<std::string> unreached;
  std::string names;
  for (std::size_t t = 0; t < targets.size(); ++t) {
    bool any = false;
    for (const auto& stop : state.per_stop) any = any || stop[t].reached;
    if (!any) {
      unreached.push_back(study.targets[t].name);
      names += (names.empty() ? "" : ", ") + study.targets[t].name;
    }
  }
  if (unreached.size() == targets.size() || state.best < 0 ||
      state.candidates[static_cast<std::size_t>(state.best)].ik.reached == 0) {
    throw Error(study.source + ": stops: no stop from " + formatNumber(study.stops.front()) +
                " to " + formatNumber(study.stops.back()) + " " + unitName(robot.length_unit) +
                " reaches any target (targets " + names + ")");
  }
  const nlohmann::json map_about = {
      {"source", "built"}, {"samples", study.reach.samples}, {"self_collision", true}};
  nlohmann::json out = placementSummary(robot, targets.size(), state.map, map_about, options, true,
                                        state.candidates, state.best);
  addRobotNames(out, robot);
  out["confirmation"] = confirmationJson(placement, state.candidates);
  const BaseCandidate& best = state.candidates[static_cast<std::size_t>(state.best)];
  out["chosen_stop"] = {{"offset_along", study.stops[static_cast<std::size_t>(state.best)]},
                        {"targets_reached", best.ik.reached},
                        {"targets", targets.size()}};
  out["targets"] = reachTable(state);
  out["unreached_by_every_stop"] = unreached;
  out["units"]["chosen_stop.offset_along"] = unitName(robot.length_unit);
  out["units"]["targets.manipulability"] =
      state.report["reach"]["study"]["manipulability"]["manipulability_unit"];
  out["units"]["targets.clearance"] = unitName(robot.length_unit);
  out["units"]["targets.stops_reaching"] = unitName(robot.length_unit);
  state.report["placement"] = out;
}

}  // namespace detail

std::string base64(const std::string& bytes) {
  static const char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t k = 0; k < bytes.size(); k += 3) {
    const auto byte = [&](std::size_t i) {
      return i < bytes.size() ? static_cast<unsigned>(static_cast<unsigned char>(bytes[i])) : 0u;
    };
    const unsigned triple = byte(k) << 16 | byte(k + 1) << 8 | byte(k + 2);
    out += kAlphabet[(triple >> 18) & 63];
    out += kAlphabet[(triple >> 12) & 63];
    out += k + 1 < bytes.size() ? kAlphabet[(triple >> 6) & 63] : '=';
    out += k + 2 < bytes.size() ? kAlphabet[triple & 63] : '=';
  }
  return out;
}

StudyRun runStudy(const Study& study, const std::string& directory,
                  const StudyRunOptions& options) {
  detail::StudyState state;
  state.study = &study;
  state.directory = directory;
  state.options = options;
  nlohmann::json& report = state.report;
  report["study"] = study.name;
  report["source"] = study.source;
  report["robot"] = study.robot_path;
  report["length_unit"] = unitName(study.problem.robot.length_unit);
  report["seed"] = study.seed;
  report["stops"] = study.stops;
  report["units"]["stops"] = unitName(study.problem.robot.length_unit);
  nlohmann::json conductors = nlohmann::json::array(), fittings = nlohmann::json::array();
  for (const Conductor& c : study.conductors)
    conductors.push_back({{"name", c.name}, {"radius", c.radius}, {"points", c.points.size()}});
  for (const BodySpec& f : study.fittings)
    fittings.push_back({{"name", f.name}, {"type", shapeTypeName(f.shapes.front().type)}});
  report["line"] = {
      {"conductors", conductors},
      {"fittings", fittings},
      {"robot_environment_replaced", study.replaced_environment},
      {"note", "the robot file's own environment (" + std::to_string(study.replaced_environment) +
                   " objects) is replaced by the study's line"}};
  report["units"]["line.conductors.radius"] = unitName(study.problem.robot.length_unit);
  nlohmann::json stages = nlohmann::json::array();
  const std::pair<const char*, void (*)(detail::StudyState&)> steps[] = {
      {"workspace", detail::runWorkspace},
      {"reach", detail::runReach},
      {"placement", detail::runPlacement},
      {"planning", detail::runPlanning},
      {"behaviour", detail::runBehaviour}};
  for (const auto& [name, step] : steps) {
    const Stopwatch clock;
    step(state);
    stages.push_back({{"stage", name}, {"seconds", clock.seconds()}});
  }
  report["stages"] = stages;
  report["units"]["stages.seconds"] = "s";
  report["view"] = detail::studyView(state);
  return {report, detail::studyScene(state)};
}

}  // namespace mcws
