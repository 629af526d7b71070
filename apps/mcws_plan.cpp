// mcws_plan: the maintenance-arm patent's arm planning for a robot whose base sways on the line
// (steps s10-s70), with the chosen path validated on fresh base poses against the shortest and
// padded paths.
#include <omp.h>

#include <iostream>
#include <map>
#include <optional>

#include "common/app.h"
#include "common/flags.h"
#include "mcws/io/atomic_file.h"
#include "mcws/planning/plan_report.h"

namespace {

using namespace mcws;

constexpr char kUsage[] = "mcws_plan --scenario S.yaml --output path.csv [options]";

constexpr char kSummary[] =
    R"(Plans the arm of a robot whose base sways (the maintenance-arm patent): m candidate paths through a roadmap for
the measured base pose, their segments checked exactly for n base poses drawn from the scenario's
sway, the dominant path taken at every shared node. The best path is accepted when the upper end
of the 95 % Wilson interval of its whole-path collision rate over the n poses is at most
max_collision_probability (acceptance: whole_path, the default; patent_p: the patent's P >=
threshold); otherwise the base is shifted along the line within the range, which moves the tool's
end away from the target (reported as goal_displacement). Writes the chosen path (CSV: D then one
column per joint, units in the names) and prints a report ending in a status line. Exit 0 with an
accepted path; 1 when no path is accepted within the base range, the start collides at the
measured base pose, the goal does (unless allow_goal_shift), or the roadmap cannot connect them;
2 for a bad command line.)";

void declareFlags(app::CommandLine& cli) {
  cli.addValue("scenario", "scenario file (.yaml), see scenarios/");
  cli.addValue("output", "chosen path (CSV)");
  cli.addSwitch("json", "print the report as one JSON object on stdout");
  cli.addValue("plot", "PNG of the configuration space (two-joint robots), paths and shared nodes");
  cli.addValue("plot-offsets",
               "PNG of the best path's P against the base offset, every step within the range");
  cli.addValue("cells", "cells per axis of --plot (default 120)");
  cli.addValue("seed", "seed of the base poses and the roadmap");
  cli.addValue("validation-poses",
               "fresh base poses of the validation (default: the scenario's, 10000); 0 skips it");
  cli.addValue("threads", "threads (default: all cores)");
}

}  // namespace

int main(int argc, char** argv) {
  return app::run("mcws_plan", [&] {
    app::CommandLine cli(kUsage, kSummary);
    declareFlags(cli);
    if (!cli.parse(argc, argv)) return app::kExitOk;
    const std::string output = cli.required("output");
    const std::string plot = cli.text("plot", ""), plot_offsets = cli.text("plot-offsets", "");
    const int cells =
        static_cast<int>(app::parseInteger(cli.text("cells", "120"), "cells", 4, 2000));
    if (cli.has("threads")) omp_set_num_threads(app::readThreads(cli, 1));
    std::optional<std::uint64_t> seed;
    std::optional<std::int64_t> validation_poses;
    if (cli.has("seed")) seed = app::readSeed(cli);
    if (cli.has("validation-poses"))
      validation_poses =
          app::parseInteger(cli.required("validation-poses"), "validation-poses", 0, 100000000);

    const std::string scenario_path = cli.required("scenario");
    Scenario scenario = loadScenario(scenario_path);
    SwayPlanningProblem& problem = scenario.problem;
    if (seed) problem.seed = problem.roadmap.seed = *seed;
    if (validation_poses && *validation_poses > 0) problem.validation_poses = *validation_poses;
    if (!plot.empty() && problem.robot.dof() != 2)
      throw app::UsageError("--plot: draws a two-joint configuration space; robot '" +
                            problem.robot.name + "' has " + std::to_string(problem.robot.dof()));
    app::checkOutputs({{"output", output}, {"plot", plot}, {"plot-offsets", plot_offsets}},
                      {{"scenario", scenario_path}, {"scenario's robot", scenario.robot_path}});

    const SwayPlanner planner(problem);
    std::map<std::string, app::Progress> bars;
    const PlanningProgress progress = [&](const std::string& stage, std::size_t done,
                                          std::size_t total) {
      bars.try_emplace(stage, "mcws_plan", stage).first->second.update(done, total);
    };
    const SwayPlanningResult result =
        planner.plan(!validation_poses || *validation_poses > 0, progress);
    std::cout << (cli.has("json") ? planJson(scenario, result).dump() + "\n"
                                  : planReport(scenario, result));
    if (!result.accepted) {
      std::cerr << "mcws_plan: no path: " << noPathStatus(scenario, result)
                << "; nothing written\n";
      return app::kExitFailure;
    }
    const PlanningRound& round = result.rounds[*result.accepted];
    io::OutputSet outputs;
    io::writeWholeFile(output, pathCsv(scenario, *round.best));
    if (!plot.empty()) {
      io::writeWholeFile(plot, renderConfigurationSpacePng(scenario, planner, round, cells));
    }
    if (!plot_offsets.empty()) {
      io::writeWholeFile(plot_offsets, renderOffsetsPng(scenario, scanOffsets(planner, progress)));
    }
    outputs.commit();
    return app::kExitOk;
  });
}
