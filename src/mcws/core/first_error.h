#pragma once
/// \file
/// \brief The first error of a parallel loop, kept so it can be thrown after the loop: an
/// exception that leaves an OpenMP region ends the process (std::terminate).

#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <string>

#include "mcws/core/error.h"

namespace mcws {

/// \brief The error of the lowest-numbered failing item of a parallel loop, rethrown after it.
/// Thread-safe.
///
/// Once an item has failed, run() skips the items not yet started (an item under way runs to
/// its end), so the error reported is that of the lowest-numbered item among those that ran and
/// failed: with one failing item, that item's, whatever the thread count or schedule.
///
///     FirstError error;
///     #pragma omp parallel for
///     for (std::size_t i = 0; i < n; ++i) error.run(i, [&] { work(i); });
///     error.rethrow();  // mcws::Error with the message of the lowest item that threw
class FirstError {
 public:
  /// \brief Whether any item failed.
  bool failed() const { return failed_.load(std::memory_order_relaxed); }

  /// \brief Records item's failure; the lowest item's message is kept.
  void record(std::size_t item, const std::string& message) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!failed_ || item < item_) {
      item_ = item;
      message_ = message;
    }
    failed_ = true;
  }

  /// \brief Calls body() for item unless an item has failed already, recording what it throws
  /// (the what() of a std::exception; "unknown exception" for anything else).
  template <typename Body>
  void run(std::size_t item, Body&& body) {
    if (failed()) return;
    try {
      body();
    } catch (const std::exception& e) {
      record(item, e.what());
    } catch (...) {
      record(item, "unknown exception");
    }
  }

  /// \brief Throws mcws::Error with the lowest failing item's message, if any item failed.
  /// Call it after the loop, outside the parallel region.
  void rethrow() const {
    if (failed_) throw Error(message_);
  }

 private:
  std::atomic<bool> failed_{false};
  std::mutex mutex_;
  std::size_t item_{0};
  std::string message_;
};

}  // namespace mcws
