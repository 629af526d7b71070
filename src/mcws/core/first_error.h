#pragma once
/// \file
/// \brief The first error of a parallel loop, kept so it can be thrown after the loop: an
/// exception that leaves an OpenMP region ends the process (std::terminate).

#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <string>
#include <utility>

#include "mcws/core/error.h"

namespace mcws {

/// \brief The exception of the lowest-numbered failing item of a parallel loop, rethrown after it
/// as it was thrown (a std::bad_alloc stays one, so a tool still reports running out of memory).
/// Thread-safe.
///
/// Once an item has failed, run() skips the items not yet started (an item under way runs to
/// its end), so the error reported is that of the lowest-numbered item among those that ran and
/// failed: with one failing item, that item's, whatever the thread count or schedule.
///
///     FirstError error;
///     #pragma omp parallel for
///     for (std::size_t i = 0; i < n; ++i) error.run(i, [&] { work(i); });
///     error.rethrow();  // the exception of the lowest item that threw
class FirstError {
 public:
  /// \brief Whether any item failed.
  bool failed() const { return failed_.load(std::memory_order_relaxed); }

  /// \brief Whether an item below `item` failed (the one rethrow() would report comes first).
  bool failedBefore(std::size_t item) const {
    if (!failed()) return false;
    const std::lock_guard<std::mutex> lock(mutex_);
    return item_ < item;
  }

  /// \brief Records item's failure as mcws::Error(message); the lowest item's is kept.
  void record(std::size_t item, const std::string& message) {
    record(item, std::make_exception_ptr(Error(message)));
  }

  /// \brief Records item's failure, the exception `thrown`; the lowest item's is kept.
  void record(std::size_t item, std::exception_ptr thrown) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!failed_ || item < item_) {
      item_ = item;
      thrown_ = std::move(thrown);
    }
    failed_ = true;
  }

  /// \brief Calls body() for item unless an item has failed already, recording what it throws
  /// (anything: a std::exception or not).
  template <typename Body>
  void run(std::size_t item, Body&& body) {
    if (failed()) return;
    try {
      body();
    } catch (...) {
      record(item, std::current_exception());
    }
  }

  /// \brief Rethrows the lowest failing item's exception, if any item failed. Call it after the
  /// loop, outside the parallel region.
  void rethrow() const {
    if (failed_) std::rethrow_exception(thrown_);
  }

 private:
  std::atomic<bool> failed_{false};
  mutable std::mutex mutex_;
  std::size_t item_{0};
  std::exception_ptr thrown_;
};

}  // namespace mcws
