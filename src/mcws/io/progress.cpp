#include "mcws/io/progress.h"

#include <iostream>
#include <utility>

namespace mcws::io {

Progress::Progress(std::string program, std::string what)
    : program_(std::move(program)),
      what_(std::move(what)),
      last_(std::chrono::steady_clock::now()) {}

void Progress::update(std::size_t done, std::size_t total) {
  const auto now = std::chrono::steady_clock::now();
  const bool finished = done >= total;
  if (clock_.seconds() < 1.0 && !shown_) return;
  if (!finished && std::chrono::duration<double>(now - last_).count() < 0.5) return;
  last_ = now;
  shown_ = true;
  const int percent = total ? static_cast<int>(100.0 * static_cast<double>(done) / total) : 100;
  std::cerr << program_ << ": " << percent << "% (" << done << "/" << total << " " << what_
            << ")\n";
}

}  // namespace mcws::io
