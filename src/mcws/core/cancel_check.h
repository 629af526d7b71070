#pragma once
/// \file
/// \brief How a long library call can be stopped from outside: a check it calls now and then.

#include <functional>

namespace mcws {

/// \brief Called by a long computation now and then (every few milliseconds of work) on the
/// thread that called it, between pieces of work: what it throws ends the computation, which
/// then returns nothing (no partial result). An empty one is never called, and calling it
/// changes no result. The Python bindings raise KeyboardInterrupt from it after Ctrl-C, as
/// OMPL's planners stop on a PlannerTerminationCondition.
using CancelCheck = std::function<void()>;

/// \brief Calls `check` (when set) once every `stride` calls of step(): the pieces of a loop.
class CancelPacer {
 public:
  CancelPacer(const CancelCheck& check, unsigned stride) : check_(check), stride_(stride) {}
  void step() {
    if (check_ && ++steps_ == stride_) {
      steps_ = 0;
      check_();
    }
  }

 private:
  const CancelCheck& check_;
  unsigned stride_;
  unsigned steps_{0};
};

}  // namespace mcws
