#pragma once
/// \file
/// \brief Wall time of a stage, for the seconds a report gives.

#include <chrono>

namespace mcws {

/// \brief Wall-clock seconds since construction (or the last restart()), from a steady clock.
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  /// \brief Seconds since construction or the last restart() [s].
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  void restart() { start_ = std::chrono::steady_clock::now(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace mcws
