// mcws.plan's C++ part: arm planning under base sway (the library's planning module, SwayPlanner,
// as mcws_plan plans), its JSON report and the chosen path.
#include <omp.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>

#include "bindings.h"
#include "mcws/io/atomic_file.h"
#include "mcws/planning/plan_report.h"
#include "mcws/planning/scenario.h"
#include "mcws/planning/sway_planner.h"

namespace mcws::python {

namespace {

/// A plan's report and, when a path was accepted, the path and its CSV (mcws_plan --output).
struct PlanResult {
  std::string report;  ///< planJson(), compact
  std::optional<std::string> csv;
  std::string status;             ///< noPathStatus() when no path was accepted
  std::vector<double> waypoints;  ///< rows of dof joint values [rad | length unit]
  int dof{0};
  /// What the pictures are drawn from (mcws_plan --plot, --plot-offsets): the scenario, its
  /// planner and the accepted round (none when no path was accepted).
  std::unique_ptr<Scenario> scenario;
  std::unique_ptr<SwayPlanner> planner;
  std::optional<PlanningRound> round;
  int threads{0};
};

/// omp_set_num_threads(threads) for a call, as mcws_plan --threads, undone after it.
class PlanThreads {
 public:
  explicit PlanThreads(int threads) : before_(omp_get_max_threads()) {
    if (threads > 0) omp_set_num_threads(threads);
  }
  ~PlanThreads() { omp_set_num_threads(before_); }
  PlanThreads(const PlanThreads&) = delete;
  PlanThreads& operator=(const PlanThreads&) = delete;

 private:
  int before_;
};

std::unique_ptr<PlanResult> plan(const py::object& scenario_path,
                                 const std::optional<std::int64_t>& seed,
                                 const std::optional<std::int64_t>& validation_poses, int threads,
                                 const py::object& progress) {
  const std::string path = pathArgument(scenario_path);
  threads = threadCount(threads);
  if (validation_poses && (*validation_poses < 0 || *validation_poses > 100000000)) {
    throw UsageError("validation_poses: " + std::to_string(*validation_poses) +
                     " is not in 0 .. 100000000 (0 skips the validation)");
  }
  const std::uint64_t seed_value = seed ? nonNegative(*seed, "seed") : 0;
  Checkpoint checkpoint(progress, "mcws.plan", "steps");
  auto result = std::make_unique<PlanResult>();
  py::gil_scoped_release release;
  result->scenario = std::make_unique<Scenario>(loadScenario(path));
  const Scenario& scenario = *result->scenario;
  SwayPlanningProblem& problem = result->scenario->problem;
  if (seed) problem.seed = problem.roadmap.seed = seed_value;
  if (validation_poses && *validation_poses > 0) problem.validation_poses = *validation_poses;
  const PlanThreads set(threads);
  result->threads = threads;
  result->planner = std::make_unique<SwayPlanner>(problem);
  const SwayPlanner& planner = *result->planner;
  // The stages report on the calling thread between their steps; the segments' checks report
  // from inside a parallel loop, where Python is not called. Ctrl-C is looked for within the
  // roadmap's growth, the segments' checks and the validation too (the library's CancelCheck).
  const PlanningProgress report = [&](const std::string&, std::size_t done, std::size_t total) {
    if (!omp_in_parallel()) checkpoint(done, total);
  };
  const SwayPlanningResult planned =
      planner.plan(!validation_poses || *validation_poses > 0, report, signalCheck());
  result->report = planJson(scenario, planned).dump();
  result->dof = problem.robot.dof();
  if (!planned.accepted) {
    result->status = noPathStatus(scenario, planned);
    return result;
  }
  result->round = planned.rounds[*planned.accepted];
  const PathSafety& best = *planned.rounds[*planned.accepted].best;
  result->csv = pathCsv(scenario, best);
  for (const Eigen::VectorXd& q : best.waypoints) {
    result->waypoints.insert(result->waypoints.end(), q.data(), q.data() + q.size());
  }
  return result;
}

/// mcws_plan --plot (`offsets` false: the configuration space in `cells` cells per axis, a
/// two-joint robot's) or --plot-offsets (each offset's round planned again).
void savePicture(const PlanResult& r, const py::object& path_value, bool offsets, int cells) {
  const std::string path = pathArgument(path_value);
  if (!r.round) throw Error(path + ": no path to draw: " + r.status);
  if (cells < 4 || cells > 2000) {
    throw UsageError("cells: " + std::to_string(cells) + " is not in 4 .. 2000");
  }
  const Robot& robot = r.scenario->problem.robot;
  if (!offsets && robot.dof() != 2) {
    throw UsageError("save_plot: draws a two-joint configuration space; robot '" + robot.name +
                     "' has " + std::to_string(robot.dof()));
  }
  py::gil_scoped_release release;
  const PlanThreads set(r.threads);
  io::writeWholeFile(
      path, offsets ? renderOffsetsPng(*r.scenario, scanOffsets(*r.planner))
                    : renderConfigurationSpacePng(*r.scenario, *r.planner, *r.round, cells));
}

}  // namespace

void bindPlan(py::module_& m) {
  py::class_<PlanResult>(m, "_Plan", "mcws.plan's C++ part (see mcws.Plan).")
      .def("report", [](const PlanResult& r) { return r.report; })
      .def("path",
           [](const PlanResult& r) -> py::object {
             if (!r.csv) return py::none();
             return ownedDoubles(r.waypoints, {static_cast<py::ssize_t>(r.waypoints.size() / r.dof),
                                               static_cast<py::ssize_t>(r.dof)});
           })
      .def(
          "save",
          [](const PlanResult& r, const py::object& path_value) {
            const std::string path = pathArgument(path_value);
            if (!r.csv) throw Error(path + ": no path to write: " + r.status);
            io::writeWholeFile(path, *r.csv);
          },
          py::arg("path"))
      .def(
          "save_plot",
          [](const PlanResult& r, const py::object& path, int cells) {
            savePicture(r, path, false, cells);
          },
          py::arg("path"), py::arg("cells"))
      .def(
          "save_offsets_plot",
          [](const PlanResult& r, const py::object& path) { savePicture(r, path, true, 120); },
          py::arg("path"));
  m.def("_plan", &plan, "mcws.plan's C++ part.", py::arg("scenario"), py::arg("seed").none(true),
        py::arg("validation_poses").none(true), py::arg("threads"), py::arg("progress"));
}

}  // namespace mcws::python
