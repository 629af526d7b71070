// Stage (5) of the study: the behaviour rehearsal of the cleaning job (as mcws_behave --json),
// and its timeline from the run's log.
#include "mcws/behavior/behavior_executor.h"
#include "mcws/behavior/behavior_model.h"
#include "mcws/behavior/behavior_report.h"
#include "mcws/study/detail/study_stages.h"

namespace mcws::detail {

namespace {

/// Intervals of equal `value` in the log's records: one event each, on `lane`.
void addIntervals(const std::vector<LogRecord>& records, double end, const std::string& lane,
                  std::string LogRecord::*value, nlohmann::json& events) {
  std::size_t first = 0;
  for (std::size_t k = 1; k <= records.size(); ++k) {
    if (k < records.size() && records[k].*value == records[first].*value) continue;
    const std::string label = records[first].*value;
    const double to = k < records.size() ? records[k].t : end;
    if (!label.empty() && to > records[first].t)
      events.push_back(
          {{"lane", lane}, {"start", records[first].t}, {"end", to}, {"label", label}});
    first = k;
  }
}

}  // namespace

void runBehaviour(StudyState& state) {
  const StudyBehaviour& settings = state.study->behaviour;
  if (settings.model.empty()) {
    state.report["behaviour"] = {{"run", false}, {"note", "the study names no behaviour model"}};
    return;
  }
  // Read and checked with the study (a bad model fails before any stage runs); a Study built
  // by hand may leave it to this stage.
  const BehaviorModel model =
      settings.loaded ? *settings.loaded : loadBehaviorModel(settings.model);
  std::vector<LogRecord> records;
  RunObserver observer;
  observer.on_log = [&](const LogRecord& record) { records.push_back(record); };
  const RunSummary summary =
      runCleaningJob(model, RunOptions::forModel(model, settings.insulators), observer);
  nlohmann::json out = nlohmann::json::parse(summaryJson(summary).dump());
  out["run"] = true;
  out["model"] = settings.model;
  out["failure"] = runFailure(summary);
  nlohmann::json events = nlohmann::json::array();
  addIntervals(records, summary.duration_s, "task", &LogRecord::task_state, events);
  addIntervals(records, summary.duration_s, "behaviour", &LogRecord::behavior, events);
  state.behaviour_timeline = {{"kind", "timeline"},
                              {"title", "Behaviour rehearsal: the cleaning job of " +
                                            std::to_string(settings.insulators) + " discs"},
                              {"unit", "s"},
                              {"lanes", {"task", "behaviour"}},
                              {"events", events}};
  state.report["behaviour"] = out;
}

}  // namespace mcws::detail
