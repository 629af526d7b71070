// mcws.reach_study and mcws.place: targets solved by inverse kinematics (the library's reach
// module, ReachStudy, as mcws_reach --targets solves them) and base placement (placeBase, as
// mcws_place), their per-target and per-position points and their summaries.
#include <pybind11/stl.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>

#include "bindings.h"
#include "loaded_robot.h"
#include "mcws/collision/collision_checker.h"
#include "mcws/collision/robot_bodies.h"
#include "mcws/core/decimal.h"
#include "mcws/core/stopwatch.h"
#include "mcws/io/atomic_file.h"
#include "mcws/io/pcd_stream_writer.h"
#include "mcws/reach/base_placement.h"
#include "mcws/reach/map_cache.h"
#include "mcws/reach/placement_map.h"
#include "mcws/reach/reach_report.h"
#include "mcws/reach/reach_study.h"
#include "mcws/reach/targets_file.h"
#include "mcws/sampling/sample_report.h"
#include "mcws/sampling/sampler.h"
#include "point_layout.h"
#include "reach_map_result.h"
#include "sample_array.h"

namespace mcws::python {

namespace {

/// The points of a study or a placement, the summary and the robot a saved file records.
template <typename PointT>
struct PointsResult {
  std::vector<PointT, Eigen::aligned_allocator<PointT>> points;
  std::string summary;  ///< compact JSON
  std::optional<io::CloudProvenance> provenance;
  std::function<std::string()> picture;  ///< the tool's --plot PNG (a placement's), or none

  void save(const py::object& path_value) const {
    const std::string path = pathArgument(path_value);
    py::gil_scoped_release release;
    io::PcdStreamWriter<PointT> cloud(path, points.size(), io::PcdFormat::kBinary, provenance);
    cloud.write(points.data(), points.size());
    cloud.commit();
  }
};
using StudyResult = PointsResult<ReachTargetPoint>;
using PlaceResult = PointsResult<BasePoint>;

/// The targets of a file (a path), of points (N, 3) with normals (N, 3), or of poses (N, 4, 4),
/// moved `standoff` off their surface.
std::vector<ReachTarget> targetsOf(const py::handle& value, const py::handle& normals_value,
                                   double standoff) {
  std::vector<ReachTarget> targets;
  if (py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value) ||
      py::hasattr(value, "__fspath__")) {
    if (!normals_value.is_none()) throw UsageError("normals: a targets file holds its own");
    targets = loadTargets(pathArgument(value, "targets"));
  } else {
    const DoubleArray array = doubleArray(value, "targets");
    const bool poses = array.ndim() == 3 && array.shape(1) == 4 && array.shape(2) == 4;
    if (!poses && !(array.ndim() == 2 && array.shape(1) == 3)) {
      throw UsageError("targets: shape " + shapeText(array) +
                       " is neither (N, 3) points (with normals) nor (N, 4, 4) poses");
    }
    const py::ssize_t n = array.shape(0);
    if (poses != normals_value.is_none()) {
      throw UsageError(poses ? "normals: poses (N, 4, 4) hold their orientation"
                             : "normals: give the (N, 3) surface normals of the points");
    }
    std::optional<DoubleArray> normals;
    if (!poses) {
      normals = doubleArray(normals_value, "normals");
      if (normals->ndim() != 2 || normals->shape(0) != n || normals->shape(1) != 3) {
        throw UsageError("normals: shape " + shapeText(*normals) + " is not (" + std::to_string(n) +
                         ", 3)");
      }
    }
    for (py::ssize_t i = 0; i < n; ++i) {
      const std::string row = "targets: row " + std::to_string(i);
      if (poses) {
        ReachTarget target;
        target.pose = checkedPose(
            Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(array.data() + 16 * i),
            "targets[" + std::to_string(i) + "]");
        target.free_roll = false;
        targets.push_back(target);
        continue;
      }
      const double* p = array.data() + 3 * i;
      const double* d = normals->data() + 3 * i;
      targets.push_back(asUsageError(row, [&] {
        return targetFromNormal(Eigen::Vector3d(p[0], p[1], p[2]),
                                Eigen::Vector3d(d[0], d[1], d[2]));
      }));
    }
    if (targets.empty()) throw UsageError("targets: none given");
  }
  const std::string standoff_text = py::str(py::float_(standoff));
  if (!std::isfinite(standoff)) throw UsageError("standoff: " + standoff_text + " is not finite");
  if (standoff < 0.0) throw UsageError("standoff: " + standoff_text + " is less than 0");
  if (standoff != 0.0) applyStandoff(targets, standoff);
  return targets;
}

/// How targets are solved, as mcws_reach --targets' flags.
struct StudyArguments {
  double standoff, approach_tolerance_deg;
  int ik_starts;
  std::int64_t seed;
  int threads;
  bool collision;
  std::optional<std::string> quality_task;
  std::optional<double> length;
  py::object progress;  ///< the call's progress argument (Checkpoint)
};

ReachStudyOptions studyOptions(const Robot& robot, const StudyArguments& a) {
  ReachStudyOptions options;
  if (!(a.approach_tolerance_deg >= 0.0 && a.approach_tolerance_deg <= 180.0)) {
    throw UsageError(
        "approach_tolerance: " + py::str(py::float_(a.approach_tolerance_deg)).cast<std::string>() +
        " is not in [0, 180] deg");
  }
  options.approach_tolerance = a.approach_tolerance_deg * M_PI / 180.0;
  if (a.ik_starts < 1 || a.ik_starts > 1000) {
    throw UsageError("ik_starts: " + std::to_string(a.ik_starts) + " is not in 1 .. 1000");
  }
  options.starts = a.ik_starts;
  options.ik.seed = nonNegative(a.seed, "seed");
  options.threads = threadCount(a.threads);
  options.quality = qualityOptions(robot, a.quality_task, a.length);
  return options;
}

std::unique_ptr<StudyResult> reachStudy(const LoadedRobot& loaded, const py::handle& targets_value,
                                        const py::handle& normals, const StudyArguments& a) {
  const Robot& robot = loaded.robot;
  const ReachStudyOptions options = studyOptions(robot, a);
  const std::vector<ReachTarget> targets = targetsOf(targets_value, normals, a.standoff);
  const std::unique_ptr<CollisionChecker> checker =
      a.collision ? collisionCheckerIfModelled(loaded, true) : nullptr;
  Checkpoint checkpoint(a.progress, "mcws.reach_study", "targets");
  auto result = std::make_unique<StudyResult>();
  result->provenance = robotProvenance(robot);
  std::vector<TargetReach> reaches;
  {
    py::gil_scoped_release release;
    const ReachStudy study(robot, checker.get(), options);
    // From OpenMP's thread 0, the calling thread.
    reaches = study.evaluate(targets, Eigen::Isometry3d::Identity(), std::ref(checkpoint));
  }
  for (std::size_t i = 0; i < targets.size(); ++i) {
    result->points.push_back(reachTargetPoint(targets[i], reaches[i]));
  }
  nlohmann::json summary = studySummary(robot, options, reaches, checker != nullptr);
  addRobotNames(summary, robot);  // "robot" and "tip", as mcws_reach --targets --json
  result->summary = summary.dump();
  return result;
}

/// The map a placement scores from, as mcws_place's: a given ReachMap (its header checked as
/// --map's) or one built here (`build` set), whose samples count when free of self-collision,
/// taken from and stored in the map cache `cache` (a folder; empty: none) as mcws_place does.
struct PlaceMap {
  py::object given;  ///< a _ReachMap, or None
  std::optional<MapArguments> build;
  std::string cache;
};

/// What the cache wrote on its log (an entry it ignored, one it could not store), as a Python
/// RuntimeWarning; call with the GIL held.
void warnOf(const std::ostringstream& log) {
  std::istringstream lines(log.str());
  for (std::string line; std::getline(lines, line);) {
    if (PyErr_WarnEx(PyExc_RuntimeWarning, line.c_str(), 1) != 0) throw py::error_already_set();
  }
}

/// A map built here for `source`, from the map cache when it holds it (else stored there);
/// `cache_json` receives what the cache did (as mcws_place --json's "map_cache").
const ReachMap& builtMap(const LoadedRobot& loaded, const PlaceMap& source, const StudyArguments& a,
                         std::unique_ptr<MapResult>& built, nlohmann::json& about,
                         nlohmann::json& cache_json) {
  const Robot& robot = loaded.robot;
  // The self-collision model (the links and the tool, not the environment): part of the key.
  std::optional<CollisionModel> self;
  if (a.collision) {
    self = robotBodiesOnly(loadCollisionModel(robot, loaded.path));
    if (!hasGeometry(*self)) self.reset();
  }
  const std::unique_ptr<CollisionChecker> checker =
      self ? std::make_unique<CollisionChecker>(robot, *self) : nullptr;
  const ReachMapCache cache(source.cache, robot, mapGrid(*source.build),
                            mapSampling(robot, *source.build, checker.get()),
                            self ? &*self : nullptr);
  std::ostringstream log;
  if (cache.enabled()) {
    cache_json = {{"directory", cache.directory()},
                  {"path", cache.path()},
                  {"reused", false},
                  {"stored", false}};
    CachedMapInfo info;
    std::optional<ReachMap> cached;
    {
      py::gil_scoped_release release;
      cached = cache.load(log, "mcws.place", &info);
    }
    warnOf(log);
    if (cached) {
      cache_json["reused"] = true;
      about = {{"source", "cache"},
               {"samples", info.samples},
               {"self_collision", info.self_collision},
               {"built_utc", info.built_utc}};
      built = std::make_unique<MapResult>();
      built->map = std::move(*cached);
      return built->map;
    }
  }
  Checkpoint checkpoint(a.progress, "mcws.place", "map samples");
  const Stopwatch clock;
  built = buildMap(loaded, *source.build, checker.get(), checkpoint);
  if (cache.enabled()) {
    {
      py::gil_scoped_release release;
      cache_json["stored"] = cache.store(built->map, clock.seconds(), log, "mcws.place");
    }
    warnOf(log);
  }
  about = {{"source", "built"},
           {"samples", static_cast<std::uint64_t>(source.build->samples)},
           {"self_collision", checker != nullptr}};
  return built->map;
}

/// The map of `source`, held in `built` when built here; its "about" for the summary.
const ReachMap& placementMap(const LoadedRobot& loaded, const PlaceMap& source,
                             const StudyArguments& a, const ReachStudyOptions& options,
                             std::unique_ptr<MapResult>& built, nlohmann::json& about,
                             nlohmann::json& cache_json) {
  const Robot& robot = loaded.robot;
  if (!source.given.is_none()) {
    if (source.build) throw UsageError("resolution is for a map built here, not with map");
    if (!source.cache.empty()) throw UsageError("map_cache is for a map built here, not with map");
    if (!py::isinstance<MapResult>(source.given)) {
      throw UsageError("map: " + std::string(py::str(py::type::of(source.given).attr("__name__"))) +
                       " is not an mcws.ReachMap");
    }
    const auto& given = source.given.cast<const MapResult&>();
    std::uint64_t samples = 0;
    asUsageError("map", [&] {
      checkPlacementMap(given.header, given.source, robot, loaded.path,
                        qualitySummary(options.quality, robot).dump(), samples);
    });
    about = {{"source", given.source}, {"samples", samples}};
    return given.map;
  }
  if (!source.build) throw UsageError("give map (an mcws.ReachMap) or resolution and samples");
  return builtMap(loaded, source, a, built, about, cache_json);
}

std::vector<Eigen::Vector3d> offsetsOf(const std::vector<double>& xs, const std::vector<double>& ys,
                                       const std::vector<double>& zs) {
  for (const auto& [name, values] : {std::pair{"line", &xs}, {"across", &ys}, {"up", &zs}}) {
    if (values->empty()) throw UsageError(std::string(name) + ": no offsets given");
    for (const double v : *values) {
      if (!std::isfinite(v)) throw UsageError(std::string(name) + ": an offset is not finite");
    }
  }
  if (xs.size() * ys.size() * zs.size() > 1000000) {
    throw UsageError("line x across x up: more than 1000000 base positions");
  }
  return offsetGrid(xs, ys, zs);
}

std::unique_ptr<PlaceResult> place(const LoadedRobot& loaded, const py::handle& targets_value,
                                   const py::handle& normals, const std::vector<double>& xs,
                                   const std::vector<double>& ys, const std::vector<double>& zs,
                                   int confirm, double confirm_margin, const PlaceMap& source,
                                   const StudyArguments& a) {
  const Robot& robot = loaded.robot;
  const ReachStudyOptions options = studyOptions(robot, a);
  const std::vector<ReachTarget> targets = targetsOf(targets_value, normals, a.standoff);
  const std::vector<Eigen::Vector3d> moves = offsetsOf(xs, ys, zs);
  if (confirm < -1 || confirm > 1000000) {
    throw UsageError("confirm: " + std::to_string(confirm) + " is not in 0 .. 1000000 (-1: all)");
  }
  if (!(confirm_margin == -1.0 || (confirm_margin >= 0.0 && confirm_margin <= 1.0))) {
    throw UsageError("confirm_margin: " + formatNumber(confirm_margin) +
                     " is not a share of the targets in 0 .. 1 (None: no margin)");
  }
  PlacementOptions placement;
  placement.confirm = confirm;
  placement.confirm_margin = confirm_margin;
  placement.approach_tolerance = options.approach_tolerance;
  nlohmann::json about, cache_json;
  std::unique_ptr<MapResult> built;
  const ReachMap& map = placementMap(loaded, source, a, options, built, about, cache_json);
  const std::unique_ptr<CollisionChecker> checker =
      a.collision ? collisionCheckerIfModelled(loaded, true) : nullptr;
  Checkpoint checkpoint(a.progress, "mcws.place", "positions confirmed");
  std::vector<BaseCandidate> candidates;
  {
    py::gil_scoped_release release;
    const ReachStudy study(robot, checker.get(), options);
    candidates = placeBase(map, study, targets, moves, placement, std::ref(checkpoint));
  }
  auto result = std::make_unique<PlaceResult>();
  result->provenance = robotProvenance(robot);  // as mcws_place --output records it
  for (const BasePoint& p : basePoints(candidates, robot.T_world_base)) result->points.push_back(p);
  nlohmann::json summary =
      placementSummary(robot, targets.size(), map, about, options, checker != nullptr, candidates,
                       bestCandidate(candidates));
  summary["confirmation"] = confirmationJson(placement, candidates);
  if (!cache_json.is_null()) summary["map_cache"] = cache_json;  // as mcws_place --map-cache
  addRobotNames(summary, robot);  // "robot" and "tip", as mcws_place --json
  result->summary = summary.dump();
  result->picture = [candidates, name = robot.name, unit = unitName(robot.length_unit)] {
    return renderPlacementPng(candidates, name, unit);  // mcws_place --plot
  };
  return result;
}

/// The points of `result` as a structured array viewing them (kept alive by `owner`).
template <typename PointT>
py::array pointArray(const PointsResult<PointT>& result, const py::object& owner, int joints) {
  return py::array(pointDtype<PointT>(joints), {static_cast<py::ssize_t>(result.points.size())},
                   {static_cast<py::ssize_t>(sizeof(PointT))}, result.points.data(), owner);
}

template <typename PointT>
void bindPointsResult(py::module_& m, const char* name) {
  py::class_<PointsResult<PointT>>(m, name)
      .def("summary", [](const PointsResult<PointT>& r) { return r.summary; })
      .def("save", &PointsResult<PointT>::save, py::arg("path"))
      .def(
          "save_plot",
          [](const PointsResult<PointT>& r, const py::object& path_value) {
            const std::string path = pathArgument(path_value);
            if (!r.picture) throw UsageError("save_plot: this result has no picture");
            py::gil_scoped_release release;
            io::writeWholeFile(path, r.picture());
          },
          py::arg("path"))
      .def(
          "points",
          [](const py::object& self, int joints) {
            return pointArray(self.cast<const PointsResult<PointT>&>(), self, joints);
          },
          py::arg("joints"));
}

}  // namespace

void bindReachStudy(py::module_& m) {
  bindPointsResult<ReachTargetPoint>(m, "_ReachStudy");
  bindPointsResult<BasePoint>(m, "_Placement");
  m.def(
      "_reach_study",
      [](const LoadedRobot& robot, const py::handle& targets, const py::handle& normals,
         double standoff, double approach_tolerance, int ik_starts, std::int64_t seed, int threads,
         bool collision, const std::optional<std::string>& quality_task,
         const std::optional<double>& length, const py::object& progress) {
        return reachStudy(robot, targets, normals,
                          {standoff, approach_tolerance, ik_starts, seed, threads, collision,
                           quality_task, length, progress});
      },
      "mcws.reach_study's C++ part.", py::arg("robot"), py::arg("targets"),
      py::arg("normals").none(true), py::arg("standoff"), py::arg("approach_tolerance"),
      py::arg("ik_starts"), py::arg("seed"), py::arg("threads"), py::arg("collision"),
      py::arg("quality_task").none(true), py::arg("length").none(true), py::arg("progress"));
  m.def(
      "_default_map_cache", &defaultMapCacheDirectory,
      "mcws_place's default map cache folder (\"\" when neither XDG_CACHE_HOME nor HOME is set).");
  m.def(
      "_place",
      [](const LoadedRobot& robot, const py::handle& targets, const py::handle& normals,
         const std::vector<double>& line, const std::vector<double>& across,
         const std::vector<double>& up, int confirm, std::optional<double> confirm_margin,
         const py::object& map, std::optional<double> resolution, std::int64_t samples,
         int orientations, int rolls, bool manipulability, double standoff,
         double approach_tolerance, int ik_starts, std::int64_t seed, int threads, bool collision,
         const std::optional<std::string>& quality_task, const std::optional<double>& length,
         const std::string& map_cache, const py::object& progress) {
        PlaceMap source{map, std::nullopt, map_cache};
        if (resolution) {
          source.build =
              MapArguments{*resolution, samples,        seed,         threads, orientations,
                           rolls,       manipulability, quality_task, length};
        }
        return place(robot, targets, normals, line, across, up, confirm,
                     confirm_margin.value_or(-1.0), source,
                     {standoff, approach_tolerance, ik_starts, seed, threads, collision,
                      quality_task, length, progress});
      },
      "mcws.place's C++ part.", py::arg("robot"), py::arg("targets"), py::arg("normals").none(true),
      py::arg("line"), py::arg("across"), py::arg("up"), py::arg("confirm"),
      py::arg("confirm_margin").none(true), py::arg("map").none(true),
      py::arg("resolution").none(true), py::arg("samples"), py::arg("orientations"),
      py::arg("rolls"), py::arg("manipulability"), py::arg("standoff"),
      py::arg("approach_tolerance"), py::arg("ik_starts"), py::arg("seed"), py::arg("threads"),
      py::arg("collision"), py::arg("quality_task").none(true), py::arg("length").none(true),
      py::arg("map_cache"), py::arg("progress"));
}

}  // namespace mcws::python
