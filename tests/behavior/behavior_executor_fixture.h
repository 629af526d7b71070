#pragma once
// The executor tests' model, one recorded run and an injected fault (behavior_executor_test.cpp
// and behavior_executor_faults_test.cpp).

#include <string>
#include <utility>
#include <vector>

#include "mcws/behavior/behavior_executor.h"
#include "test_support.h"

namespace mcws::test {

inline const BehaviorModel& model() {
  static const BehaviorModel m = loadBehaviorModel(robotPath("insulator_cleaner_behaviors"));
  return m;
}

/// Everything a run reported.
struct Recorded {
  std::vector<LogRecord> log;
  std::vector<SimSnapshot> steps;
  std::vector<StepContext> contexts;
  RunSummary summary;
  /// Steps at which neither clamp gripped, counted independently of the executor.
  int unsafe_steps{0};

  /// The log records of one event, in order.
  std::vector<LogRecord> events(const std::string& event) const {
    std::vector<LogRecord> out;
    for (const LogRecord& r : log) {
      if (r.event == event) out.push_back(r);
    }
    return out;
  }
  /// The records of sub-task k.
  std::vector<LogRecord> subtask(int k) const {
    std::vector<LogRecord> out;
    for (const LogRecord& r : log) {
      if (r.subtask == k) out.push_back(r);
    }
    return out;
  }
};

inline Recorded runJob(const BehaviorModel& m, int discs, const FaultScript& faults = {}) {
  RunOptions options = RunOptions::forModel(m, discs);
  options.faults = faults;
  Recorded rec;
  RunObserver observer;
  observer.on_log = [&](const LogRecord& r) { rec.log.push_back(r); };
  observer.on_step = [&](const SimSnapshot& s, const StepContext& c) {
    rec.steps.push_back(s);
    rec.contexts.push_back(c);
    if (!s.joint(kFixedClamp).gripping && !s.joint(kMovingClamp).gripping) ++rec.unsafe_steps;
  };
  rec.summary = runCleaningJob(m, options, observer);
  return rec;
}

inline InjectedFault fault(FaultKind kind, double at) {
  InjectedFault f;
  f.kind = kind;
  f.at_s = at;
  return f;
}

/// A fault of `kind` at `at` [s] that lasts `duration` [s] (a link outage that ends).
inline InjectedFault fault(FaultKind kind, double at, double duration) {
  InjectedFault f = fault(kind, at);
  f.duration_s = duration;
  return f;
}

/// The faults `faults`, the link waited for `link_wait` [s] before the robot returns.
inline FaultScript faultScript(double link_wait, std::vector<InjectedFault> faults) {
  FaultScript script;
  script.link_wait_s = link_wait;
  script.faults = std::move(faults);
  return script;
}

/// The faults `faults`, answered by the operator's `action` `after` [s] from the hand-over.
inline FaultScript answeredFaults(std::vector<InjectedFault> faults, double after,
                                  OperatorAction action) {
  FaultScript script;
  script.faults = std::move(faults);
  script.operator_responses = {{after, action, 0}};
  return script;
}

}  // namespace mcws::test
