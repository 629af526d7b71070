// mcws_study: the whole power-line study in one command: where to stop the robot on the line,
// which arm path to take to each target, how likely it touches the line under sway, the working
// range and its accuracy; one report (JSON and a self-contained HTML page).
#include <omp.h>

#include <filesystem>
#include <iostream>
#include <map>

#include "common/app.h"
#include "common/flags.h"
#include "mcws/study/study.h"
#include "mcws/study/study_output.h"
#include "mcws/study/study_run.h"

namespace {

using namespace mcws;

constexpr char kUsage[] =
    "mcws_study --study STUDY.yaml --output DIR [--json] [--seed N] [--threads N] "
    "[--map-cache DIR|off]";

constexpr char kSummary[] =
    R"(Runs the study a STUDY.yaml describes (see studies/): (1) the workspace: samples, boundary,
volume with its accuracy, envelope mesh and datasheet drawing (as mcws_sample, mcws_boundary,
mcws_measure, mcws_envelope); (2) the reachability map and the reach study of the targets (as
mcws_reach); (3) the base placement over the stops along the line, every stop confirmed by IK
with the line as environment (as mcws_place); (4) at the chosen stop, for each reached target
the IK solution as goal, planning under base sway from the start with the validation against
the shortest and padded paths (as mcws_plan). The study's line replaces the robot file's own
environment. Writes DIR/report.json (every number with its unit), DIR/report.html (one
self-contained page that works offline) and the clouds, meshes and pictures made; DIR appears
whole at the end (its missing parent folders made then), and a failed run leaves what lay at DIR
untouched and makes no folder. DIR must be new, empty or a former output of mcws_study (its
report.json and the files a study writes, nothing else); --map-cache must lie outside it.
Progress on stderr. Exit 1 when no stop reaches any target (naming them), or the study file is
wrong (file:line: field); 2 for a bad command line. --seed replaces every seed of the study
(samples, map, IK, sway, roadmap); the report is the same for any --threads (apart from
seconds).)";

}  // namespace

int main(int argc, char** argv) {
  return app::run("mcws_study", [&] {
    app::CommandLine cli(kUsage, kSummary);
    cli.addValue("study", "study file (.yaml), see studies/");
    cli.addValue("output",
                 "output directory (made, with missing parent folders, or replaced as a whole)");
    cli.addSwitch("json", "print the report as one JSON object on stdout");
    cli.addValue("seed", "seed of every random draw of the study (default: the study's)");
    cli.addValue("threads", "worker threads, 0 = all cores (default 0)");
    cli.addValue("map-cache",
                 "folder of the reach-map cache (mcws_place's, e.g. ~/.cache/mcws/reach-maps): "
                 "the reach map is reused from it or stored there, or off (default: off)");
    if (!cli.parse(argc, argv)) return app::kExitOk;
    const std::string output = cli.required("output");
    const int threads = app::readThreads(cli);
    if (threads > 0) omp_set_num_threads(threads);
    Study study = loadStudy(cli.required("study"));
    if (cli.has("seed")) {
      study.seed = study.problem.seed = study.problem.roadmap.seed = app::readSeed(cli);
    }

    StudyRunOptions options;
    options.threads = threads;
    options.map_cache = cli.text("map-cache", "off");
    if (options.map_cache.empty()) throw app::UsageError("--map-cache: empty (a folder, or off)");
    if (options.map_cache == "off") options.map_cache.clear();
    StudyDirectory directory(output, study.inputs, options.map_cache);
    std::map<std::string, app::Progress> bars;
    options.log = &std::cerr;
    options.progress = [&](const std::string& stage, std::size_t done, std::size_t total) {
      bars.try_emplace(stage, "mcws_study", stage).first->second.update(done, total);
    };
    StudyRun run = runStudy(study, directory.path(), options);
    saveStudyReport(run, directory.path());
    directory.commit();
    if (cli.has("json")) {
      std::cout << run.report.dump() << "\n";
    } else {
      std::cerr << "mcws_study: report in "
                << (std::filesystem::path(output) / "report.html").string() << " and report.json\n";
    }
    return app::kExitOk;
  });
}
