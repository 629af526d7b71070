// mcws_behave: seed 004's behaviour planning rehearsed on a simulated insulator-cleaning robot:
// the task plan for N discs run by the task machine, the combined behaviours' state machines and
// the basic behaviours on a time-stepped robot, with faults injected and the safety invariant
// checked at every step.
#include <algorithm>
#include <iostream>
#include <optional>
#include <sstream>

#include "common/app.h"
#include "mcws/behavior/behavior_report.h"
#include "mcws/io/atomic_file.h"

namespace {

using namespace mcws;

/// A text output: written under a temporary name, renamed when the run is over.
struct Output {
  std::optional<io::AtomicFile> file;
  void open(const std::string& path) {
    if (!path.empty()) file.emplace(path);
  }
  void write(const std::string& bytes) {
    if (file) file->write(bytes.data(), bytes.size());
  }
  void commit() {
    if (file) file->commit();
  }
};

}  // namespace

int main(int argc, char** argv) {
  return app::run("mcws_behave", [&] {
    app::CommandLine cli(
        "mcws_behave --model M.yaml (--check | --insulators N) [options]",
        "Rehearses seed 004's cleaning job on a simulated insulator-cleaning robot: the plan for\n"
        "N discs ((CB1, CB2) per disc down the string, then CB3 per disc back up) is echoed on\n"
        "stderr, then run by the task machine (CB1, CB2, CB3, FAULT, MANUAL), each combined\n"
        "behaviour's state machine and each basic behaviour on a time-stepped robot (dt 0.01 s),\n"
        "with the faults of --faults injected and the safety invariant (at least one clamp grips)\n"
        "checked after every step and before every command. Prints a summary (--json: one\n"
        "JSON object). Log events: run_start, subtask_start, command, <ending event>\n"
        "(zero_switch, encoder_reached, ...), subtask_done, fault_injected, command_rejected,\n"
        "command_not_sent, refused, link_lost, link_up, link_restored, return_start, reclose,\n"
        "reclosed, timeout, sensor_mismatch, manual, operator, restore, restored, battery_low,\n"
        "invariant_violated, run_end. The outputs are written also when the invariant fails.\n"
        "Exit 0 when the run ends back at the start or in MANUAL; 1 when the invariant is\n"
        "violated, the battery runs empty, the time limit is reached, or an input is bad\n"
        "(--check: the model has a pose finding); "
        "2 for a bad command line.");
    cli.add()("model", app::po::value<std::string>(), "behaviour model (.yaml), see robots/")(
        "insulators", app::po::value<std::string>(),
        "discs to clean, as the worker counted them on the string (1-200)")(
        "check", "validate the model and print its counts; run nothing")(
        "faults", app::po::value<std::string>(),
        "fault file (.yaml): faults, operator responses, policies; see scenarios/faults/")(
        "log", app::po::value<std::string>(), "event log: one JSON object per line (.jsonl)")(
        "timeline", app::po::value<std::string>(),
        "joints, speeds, currents, switches, battery over time (.csv, units in the header)")(
        "timeline-period", app::po::value<std::string>(),
        "time between timeline rows [s] (default 0.1; the step is 0.01)")(
        "plot", app::po::value<std::string>(),
        "PNG of the joint speeds like the seed's Figure 10 (first disc's cycle)")(
        "plot-all", "draw the whole run in --plot, not the first disc's cycle")(
        "dot", app::po::value<std::string>(),
        "directory for Graphviz DOT of CB1-CB3 and the task machine (PNG too if `dot` exists)")(
        "json", "print the summary (or --check's counts) as one JSON object on stdout");
    if (!cli.parse(argc, argv)) return app::kExitOk;
    const std::string model_path = cli.required("model");
    const bool check = cli.has("check");
    if (check == cli.has("insulators")) {
      throw app::UsageError("give either --check or --insulators N");
    }
    const std::string faults_path = cli.text("faults", "");
    const std::string log_path = cli.text("log", ""), timeline_path = cli.text("timeline", "");
    const std::string plot_path = cli.text("plot", ""), dot_dir = cli.text("dot", "");
    const double period = app::parseNumber(cli.text("timeline-period", "0.1"), "timeline-period");
    if (!(period > 0.0)) {
      throw app::UsageError("--timeline-period: " + cli.text("timeline-period", "") +
                            " s; must be > 0");
    }
    if (check) {
      for (const char* flag :
           {"faults", "log", "timeline", "plot", "plot-all", "timeline-period"}) {
        if (cli.has(flag))
          throw app::UsageError(std::string("--") + flag + ": needs a run, not --check");
      }
    }
    const int insulators =
        check
            ? 0
            : static_cast<int>(app::parseInteger(cli.required("insulators"), "insulators", 1, 200));
    app::checkOutputs({{"log", log_path}, {"timeline", timeline_path}, {"plot", plot_path}},
                      {model_path, faults_path});

    const BehaviorModel model = loadBehaviorModel(model_path);
    const ValidationReport report = validateBehaviorModel(model);
    const std::vector<PoseFinding> findings = checkPoseConsistency(model);
    for (const PoseFinding& f : findings) {
      std::cerr << "mcws_behave: pose check: " << f.message << "\n";
    }
    RunOptions options = RunOptions::forModel(model, std::max(insulators, 1));
    if (!faults_path.empty()) options.faults = loadFaultScript(faults_path);
    if (!dot_dir.empty()) {
      for (const std::string& file : writeStateMachineDots(model, dot_dir)) {
        std::cerr << "mcws_behave: wrote " << file << "\n";
      }
    }
    if (check) {
      std::cout << (cli.has("json")
                        ? checkJson(report, findings).dump() + "\n"
                        : report.summary() + (findings.empty() ? "valid\n"
                                                               : std::to_string(findings.size()) +
                                                                     " pose finding(s)\n"));
      return findings.empty() ? app::kExitOk : app::kExitFailure;
    }
    std::cerr << "mcws_behave: plan for " << insulators << " disc(s):\n"
              << describePlan(planCleaningTask(insulators));

    Output log, timeline, plot;
    log.open(log_path);
    timeline.open(timeline_path);
    plot.open(plot_path);
    log.write(logHeaderJson(model_path, insulators, faults_path) + "\n");
    TimelineRecorder recorder(period, options.simulator.dt);
    RunObserver observer;
    if (!log_path.empty()) {
      observer.on_log = [&](const LogRecord& r) { log.write(logRecordJson(r) + "\n"); };
    }
    if (!timeline_path.empty() || !plot_path.empty()) observer.on_step = std::ref(recorder);
    const RunSummary summary = runCleaningJob(model, options, observer);

    if (!timeline_path.empty()) {
      std::ostringstream csv;
      writeTimelineCsv(csv, recorder.rows());
      timeline.write(csv.str());
    }
    if (!plot_path.empty()) {
      const auto window = cli.has("plot-all") ? std::make_pair(0.0, summary.duration_s)
                                              : firstDiscWindow(recorder.rows());
      plot.write(plotJointSpeeds(recorder.rows(), window.first, window.second,
                                 model.name + ": " + std::to_string(insulators) + " disc(s), " +
                                     runStatusName(summary.status)));
    }
    log.commit();
    timeline.commit();
    plot.commit();
    std::cout << (cli.has("json") ? summaryJson(summary).dump() + "\n" : summaryText(summary));
    if (summary.status == RunStatus::kInvariantViolated) {
      std::cerr << "mcws_behave: safety invariant violated at " << summary.violation->message
                << "\n";
      return app::kExitFailure;
    }
    if (summary.status == RunStatus::kBatteryEmpty) {
      std::cerr << "mcws_behave: the battery ran empty; the robot is stranded on the string\n";
      return app::kExitFailure;
    }
    if (summary.status == RunStatus::kTimeLimit) {
      std::cerr << "mcws_behave: the simulated time limit was reached\n";
      return app::kExitFailure;
    }
    return app::kExitOk;
  });
}
