#pragma once
/// \file
/// \brief Progress of a long run on stderr.

#include <chrono>
#include <cstddef>
#include <string>

#include "mcws/core/stopwatch.h"

namespace mcws::io {

/// \brief Progress lines "program: 45% (4500000/10000000 samples)" on stderr, only for runs longer
/// than about a second and at most twice a second.
class Progress {
 public:
  /// \param program the tool's name, first on each line; \param what what is counted.
  Progress(std::string program, std::string what);
  void update(std::size_t done, std::size_t total);
  /// \brief Seconds since construction [s].
  double seconds() const { return clock_.seconds(); }

 private:
  std::string program_, what_;
  Stopwatch clock_;
  std::chrono::steady_clock::time_point last_;
  bool shown_{false};
};

}  // namespace mcws::io
