// mcws_plan: seed 001's arm planning for a robot whose base sways on the line (steps s10-s70),
// with the chosen path validated on fresh base poses against the shortest and padded paths.
#include <omp.h>

#include <iostream>
#include <map>
#include <optional>

#include "common/app.h"
#include "mcws/io/atomic_file.h"
#include "mcws/planning/plan_report.h"

namespace {

void save(mcws::io::AtomicFile& file, const std::string& bytes) {
  file.write(bytes.data(), bytes.size());
}

}  // namespace

int main(int argc, char** argv) {
  using namespace mcws;
  return app::run("mcws_plan", [&] {
    app::CommandLine cli(
        "mcws_plan --scenario S.yaml --output path.csv [options]",
        "Plans the arm of a robot whose base sways (seed 001): m candidate paths through a\n"
        "roadmap for the measured base pose, their segments checked exactly for n base poses\n"
        "drawn from the scenario's sway, the dominant path taken at every shared node; the base\n"
        "is shifted along the line while the best path's P is below the threshold. Writes the\n"
        "chosen path (CSV: D then one column per joint, units in the names) and prints a report.\n"
        "Exit 0 with a path, 1 when no path meets the threshold within the base range or start\n"
        "or goal collide or the roadmap cannot connect them, 2 for a bad command line.");
    cli.add()("scenario", app::po::value<std::string>(), "scenario file (.yaml), see scenarios/")(
        "output", app::po::value<std::string>(), "chosen path (CSV)")(
        "json", "print the report as one JSON object on stdout")(
        "plot", app::po::value<std::string>(),
        "PNG of the configuration space (two-joint robots), paths and shared nodes")(
        "plot-offsets", app::po::value<std::string>(),
        "PNG of the best path's P against the base offset, every step within the range")(
        "cells", app::po::value<std::string>(), "cells per axis of --plot (default 120)")(
        "seed", app::po::value<std::string>(), "seed of the base poses and the roadmap")(
        "validation-poses", app::po::value<std::string>(),
        "fresh base poses of the validation (default: the scenario's, 10000); 0 skips it")(
        "threads", app::po::value<std::string>(), "threads (default: all cores)");
    if (!cli.parse(argc, argv)) return app::kExitOk;
    const std::string output = cli.required("output");
    const std::string plot = cli.text("plot", ""), plot_offsets = cli.text("plot-offsets", "");
    const int cells =
        static_cast<int>(app::parseInteger(cli.text("cells", "120"), "cells", 4, 2000));
    if (cli.has("threads"))
      omp_set_num_threads(
          static_cast<int>(app::parseInteger(cli.required("threads"), "threads", 1, 1024)));
    std::optional<std::int64_t> seed, validation_poses;
    if (cli.has("seed")) seed = app::parseInteger(cli.required("seed"), "seed", 0, INT64_MAX);
    if (cli.has("validation-poses"))
      validation_poses =
          app::parseInteger(cli.required("validation-poses"), "validation-poses", 0, 100000000);
    const std::string scenario_path = cli.required("scenario");
    Scenario scenario = loadScenario(scenario_path);
    SwayPlanningProblem& problem = scenario.problem;
    if (seed) problem.seed = problem.roadmap.seed = static_cast<std::uint64_t>(*seed);
    if (validation_poses && *validation_poses > 0) problem.validation_poses = *validation_poses;
    if (!plot.empty() && problem.robot.dof() != 2)
      throw app::UsageError("--plot: draws a two-joint configuration space; robot '" +
                            problem.robot.name + "' has " + std::to_string(problem.robot.dof()));
    app::checkOutputs({{"output", output}, {"plot", plot}, {"plot-offsets", plot_offsets}},
                      {scenario_path, scenario.robot_path});

    const SwayPlanner planner(problem);
    std::map<std::string, app::Progress> bars;
    const PlanningProgress progress = [&](const std::string& stage, std::size_t done,
                                          std::size_t total) {
      bars.try_emplace(stage, "mcws_plan", stage).first->second.update(done, total);
    };
    const SwayPlanningResult result =
        planner.plan(!validation_poses || *validation_poses > 0, progress);
    if (cli.has("json")) {
      std::cout << planJson(scenario, result).dump() << "\n";
    } else {
      std::cout << planReport(scenario, result);
    }
    if (!result.accepted) {
      std::cerr << "mcws_plan: no path: " << noPathStatus(scenario, result)
                << "; nothing written\n";
      return app::kExitFailure;
    }
    const PlanningRound& round = result.rounds[*result.accepted];
    io::AtomicFile csv(output);
    save(csv, pathCsv(scenario, *round.best));
    std::optional<io::AtomicFile> cspace, offsets;
    if (!plot.empty()) {
      cspace.emplace(plot);
      save(*cspace, renderConfigurationSpacePng(scenario, planner, round, cells));
    }
    if (!plot_offsets.empty()) {
      offsets.emplace(plot_offsets);
      save(*offsets, renderOffsetsPng(scenario, scanOffsets(planner)));
    }
    csv.commit();
    if (cspace) cspace->commit();
    if (offsets) offsets->commit();
    return app::kExitOk;
  });
}
