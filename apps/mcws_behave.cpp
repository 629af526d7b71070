// mcws_behave: the behaviour planning of Wang et al. 2018 rehearsed on a simulated
// insulator-cleaning robot: the task plan for N discs run by the task machine, the combined
// behaviours' state machines and the basic behaviours on a time-stepped robot, with faults injected
// and the safety invariant checked at every step.
#include <algorithm>
#include <iostream>

#include "common/app.h"
#include "common/flags.h"
#include "mcws/behavior/behavior_report.h"
#include "mcws/behavior/rehearsal.h"
#include "mcws/io/atomic_file.h"

namespace {

using namespace mcws;

constexpr char kUsage[] = "mcws_behave --model M.yaml (--check | --insulators N) [options]";

constexpr char kSummary[] =
    R"(Rehearses the cleaning job of Wang et al. 2018 on a simulated insulator-cleaning robot: the plan for N
discs ((CB1, CB2) per disc down the string, then CB3 per disc back up) is echoed on stderr, then
run by the task machine (CB1, CB2, CB3, FAULT, MANUAL), each combined behaviour's state machine
and each basic behaviour on a time-stepped robot (dt 0.01 s), with the faults of --faults
injected and the safety invariant (at least one clamp grips) checked after every step and before
every command. Prints a summary (--json: one JSON object). Log events: run_start, subtask_start,
command, <ending event> (zero_switch, encoder_reached, ...), subtask_done, fault_injected,
command_rejected, command_not_sent, refused, link_lost, link_up, link_restored, return_start,
reclose, reclosed, timeout, sensor_mismatch, manual, operator, restore, restored, battery_low,
invariant_violated, run_end. The outputs are written also when the invariant fails.
Every command, the behaviours' own included, passes the interference check (joint limits, the
model's pose rules on the pose the sensors read) before it is sent; a refused own command stops
the run (status safety_stop).
Exit 0 when the run ends back at the start or in MANUAL; 1 when the invariant is violated, an own
command is refused, the battery runs empty, the time limit is reached, or an input is bad
(--check: the model has a pose finding); 2 for a bad command line.)";

void declareFlags(app::CommandLine& cli) {
  cli.addValue("model", "behaviour model (.yaml), see robots/");
  cli.addValue("insulators", "discs to clean, as the worker counted them on the string (1-200)");
  cli.addSwitch("check", "validate the model and print its counts; run nothing");
  cli.addValue("faults",
               "fault file (.yaml): faults, operator responses, policies; see scenarios/faults/");
  cli.addValue("log", "event log: one JSON object per line (.jsonl)");
  cli.addValue("timeline",
               "joints, speeds, currents, switches, battery over time (.csv, units in the header)");
  cli.addValue("timeline-period",
               "time between timeline rows [s]: a whole multiple of the simulator's step 0.01 s "
               "(default 0.1)");
  cli.addValue("plot",
               "PNG of the joint speeds like Figure 10 of Wang et al. 2018 (first disc's cycle)");
  cli.addSwitch("plot-all", "draw the whole run in --plot, not the first disc's cycle");
  cli.addValue(
      "dot",
      R"(directory for Graphviz DOT of CB1-CB3 and the task machine (PNG too if `dot` exists))");
  cli.addSwitch("json", "print the summary (or --check's counts) as one JSON object on stdout");
}

/// The command line, checked.
struct Settings {
  std::string model, faults, log, timeline, plot, dot;  ///< paths; empty: not given
  double period{0.1};                                   ///< between timeline rows [s]
  bool check{false};                                    ///< --check instead of a run
  int insulators{0};                                    ///< 0 with --check
};

Settings readSettings(const app::CommandLine& cli) {
  Settings s;
  s.model = cli.required("model");
  s.check = cli.has("check");
  if (s.check == cli.has("insulators"))
    throw app::UsageError("give either --check or --insulators N");
  s.faults = cli.text("faults", "");
  s.log = cli.text("log", "");
  s.timeline = cli.text("timeline", "");
  s.plot = cli.text("plot", "");
  s.dot = cli.text("dot", "");
  s.period = app::parsePositive(cli.text("timeline-period", "0.1"), "timeline-period", "s");
  try {
    TimelineRecorder(s.period, RobotSimulatorConfig().dt);
  } catch (const Error& e) {
    std::string what = e.what();
    if (what.rfind("timeline: ", 0) == 0) what.erase(0, 10);
    throw app::UsageError("--timeline-period: " + what);
  }
  if (s.check) {
    for (const char* flag : {"faults", "log", "timeline", "plot", "plot-all", "timeline-period"}) {
      if (cli.has(flag))
        throw app::UsageError(std::string("--") + flag + ": needs a run, not --check");
    }
  }
  if (!s.check)
    s.insulators =
        static_cast<int>(app::parseInteger(cli.required("insulators"), "insulators", 1, 200));
  app::checkOutputs({{"log", s.log}, {"timeline", s.timeline}, {"plot", s.plot}},
                    {{"model", s.model}, {"faults", s.faults}});
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  return app::run("mcws_behave", [&] {
    app::CommandLine cli(kUsage, kSummary);
    declareFlags(cli);
    if (!cli.parse(argc, argv)) return app::kExitOk;
    const Settings settings = readSettings(cli);

    const BehaviorModel model = loadBehaviorModel(settings.model);
    const ValidationReport report = validateBehaviorModel(model);
    const std::vector<PoseFinding> findings = checkPoseConsistency(model);
    for (const PoseFinding& f : findings) {
      std::cerr << "mcws_behave: pose check: " << f.message << "\n";
    }
    RunOptions options = RunOptions::forModel(model, std::max(settings.insulators, 1));
    if (!settings.faults.empty()) options.faults = loadFaultScript(settings.faults);
    // The diagrams, log, timeline and plot appear together when the run ends (whatever its
    // status), or, when the tool fails, none of them.
    io::OutputSet outputs;
    std::vector<std::string> diagrams;
    if (!settings.dot.empty()) diagrams = writeStateMachineDots(model, settings.dot);
    const auto commitOutputs = [&] {
      outputs.commit();
      for (const std::string& file : diagrams) std::cerr << "mcws_behave: wrote " << file << "\n";
    };
    if (settings.check) {
      commitOutputs();
      if (cli.has("json")) {
        std::cout << checkJson(report, findings).dump() << "\n";
      } else {
        std::cout << report.summary()
                  << (findings.empty() ? "valid\n"
                                       : std::to_string(findings.size()) + " pose finding(s)\n");
      }
      return findings.empty() ? app::kExitOk : app::kExitFailure;
    }
    std::cerr << "mcws_behave: plan for " << settings.insulators << " disc(s):\n"
              << describePlan(planCleaningTask(settings.insulators));

    const RunSummary summary =
        rehearseCleaningJob(model, options, settings.insulators,
                            {settings.model, settings.faults, settings.log, settings.timeline,
                             settings.plot, settings.period, cli.has("plot-all")});
    commitOutputs();
    std::cout << (cli.has("json") ? summaryJson(summary).dump() + "\n" : summaryText(summary));
    const std::string failure = runFailure(summary);
    if (failure.empty()) return app::kExitOk;
    std::cerr << "mcws_behave: " << failure << "\n";
    return app::kExitFailure;
  });
}
