#include "mcws/behavior/rehearsal.h"

#include <functional>
#include <optional>
#include <sstream>
#include <utility>

#include "mcws/behavior/behavior_report.h"
#include "mcws/io/atomic_file.h"

namespace mcws {

namespace {

/// A text output, written under a temporary name; none for an empty path.
struct Output {
  std::optional<io::AtomicFile> file;
  explicit Output(const std::string& path) {
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

RunSummary rehearseCleaningJob(const BehaviorModel& model, const RunOptions& options,
                               int insulators, const RehearsalFiles& files) {
  Output log(files.log), timeline(files.timeline), plot(files.plot);
  log.write(logHeaderJson(files.model, insulators, files.faults) + "\n");
  TimelineRecorder recorder(files.period, options.simulator.dt);
  RunObserver observer;
  if (!files.log.empty())
    observer.on_log = [&](const LogRecord& r) { log.write(logRecordJson(r) + "\n"); };
  if (!files.timeline.empty() || !files.plot.empty()) observer.on_step = std::ref(recorder);
  const RunSummary summary = runCleaningJob(model, options, observer);
  if (!files.timeline.empty()) {
    std::ostringstream csv;
    writeTimelineCsv(csv, recorder.rows());
    timeline.write(csv.str());
  }
  if (!files.plot.empty()) {
    const auto window =
        files.plot_all ? std::make_pair(0.0, summary.duration_s) : firstDiscWindow(recorder.rows());
    plot.write(plotJointSpeeds(recorder.rows(), window.first, window.second,
                               model.name + ": " + std::to_string(insulators) + " disc(s), " +
                                   runStatusName(summary.status)));
  }
  log.commit();
  timeline.commit();
  plot.commit();
  return summary;
}

}  // namespace mcws
