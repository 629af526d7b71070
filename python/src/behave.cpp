// mcws.behave's C++ part: the cleaning job rehearsed on the simulated insulator-cleaning robot
// (the library's behavior module, rehearseCleaningJob, as mcws_behave runs it), its summary and
// its log and timeline files.
#include <pybind11/stl.h>

#include <cmath>
#include <optional>

#include "bindings.h"
#include "mcws/behavior/behavior_report.h"
#include "mcws/behavior/rehearsal.h"

namespace mcws::python {

namespace {

/// The run: the summary (summaryJson()), why it failed (runFailure(), empty when it did not) and
/// the model's pose findings (checkPoseConsistency()'s messages, which mcws_behave prints).
std::tuple<std::string, std::string, std::vector<std::string>> behave(
    const std::string& model_path, int insulators, const std::optional<std::string>& faults,
    const std::optional<std::string>& log, const std::optional<std::string>& timeline,
    double period) {
  if (insulators < 1 || insulators > 200) {
    throw UsageError("insulators: " + std::to_string(insulators) + " is not in 1 .. 200");
  }
  if (!(period > 0.0 && std::isfinite(period))) {
    throw UsageError("timeline_period: " + py::str(py::float_(period)).cast<std::string>() +
                     " is not a finite time > 0 [s]");
  }
  try {
    TimelineRecorder(period, RobotSimulatorConfig().dt);
  } catch (const Error& e) {
    std::string what = e.what();
    if (what.rfind("timeline: ", 0) == 0) what.erase(0, 10);
    throw UsageError("timeline_period: " + what);
  }
  py::gil_scoped_release release;
  const BehaviorModel model = loadBehaviorModel(model_path);
  validateBehaviorModel(model);
  std::vector<std::string> findings;
  for (const PoseFinding& f : checkPoseConsistency(model)) findings.push_back(f.message);
  RunOptions options = RunOptions::forModel(model, insulators);
  if (faults) options.faults = loadFaultScript(*faults);
  const RunSummary summary = rehearseCleaningJob(model, options, insulators,
                                                 {model_path, faults.value_or(""), log.value_or(""),
                                                  timeline.value_or(""), "", period, false});
  return {summaryJson(summary).dump(), runFailure(summary), findings};
}

}  // namespace

void bindBehave(py::module_& m) {
  m.def("_behave", &behave, "mcws.behave's C++ part.", py::arg("model"), py::arg("insulators"),
        py::arg("faults").none(true), py::arg("log").none(true), py::arg("timeline").none(true),
        py::arg("timeline_period"));
}

}  // namespace mcws::python
