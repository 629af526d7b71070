#include "mcws/core/first_error.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <new>
#include <stdexcept>
#include <string>

namespace mcws {
namespace {

/// The message FirstError::rethrow() throws ("unknown exception" for what is not a
/// std::exception), or "" when it throws nothing.
std::string rethrown(const FirstError& error) {
  try {
    error.rethrow();
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
    return "unknown exception";
  }
  return "";
}

TEST(FirstError, ThrowsNothingWhenNoItemFailed) {
  FirstError error;
  int ran = 0;
  for (std::size_t i = 0; i < 5; ++i) error.run(i, [&] { ++ran; });
  EXPECT_FALSE(error.failed());
  EXPECT_EQ(ran, 5);
  EXPECT_NO_THROW(error.rethrow());
}

TEST(FirstError, KeepsTheLowestItemWhateverTheOrderOfRecording) {
  FirstError error;
  error.record(7, "item 7");
  error.record(3, "item 3");
  error.record(5, "item 5");
  EXPECT_TRUE(error.failed());
  EXPECT_EQ(rethrown(error), "item 3");
}

TEST(FirstError, RunSkipsItemsOnceOneHasFailed) {
  FirstError error;
  error.run(4, [] { throw std::runtime_error("item 4"); });
  bool ran = false;
  error.run(1, [&] { ran = true; });
  EXPECT_FALSE(ran);
  EXPECT_EQ(rethrown(error), "item 4");
}

TEST(FirstError, CatchesWhatIsNotAStdException) {
  FirstError error;
  error.run(2, [] { throw 42; });
  EXPECT_EQ(rethrown(error), "unknown exception");
  EXPECT_THROW(error.rethrow(), int);
}

// The exception comes back as it was thrown: running out of memory stays std::bad_alloc (the
// tools name what they were doing), a bad command line stays a UsageError (exit code 2).
TEST(FirstError, RethrowsTheExceptionItself) {
  FirstError memory;
  memory.run(0, [] { throw std::bad_alloc(); });
  EXPECT_THROW(memory.rethrow(), std::bad_alloc);
  FirstError usage;
  usage.run(0, [] { throw UsageError("--threads: bad"); });
  EXPECT_THROW(usage.rethrow(), UsageError);
  FirstError recorded;
  recorded.record(1, "item 1");
  EXPECT_THROW(recorded.rethrow(), Error);
}

// A parallel loop of 1000 items on 4 threads in which item 613 throws: the exception stays
// inside the region (an exception leaving it would end this test with std::terminate) and the
// loop's error is item 613's.
TEST(FirstError, GuardsAParallelLoopAndRethrowsTheFailingItemsError) {
  constexpr std::size_t kItems = 1000, kFailing = 613;
  FirstError error;
#pragma omp parallel for schedule(dynamic) num_threads(4)
  for (std::size_t i = 0; i < kItems; ++i) {
    error.run(i, [&] {
      if (i == kFailing) throw std::runtime_error("item " + std::to_string(i) + " failed");
    });
  }
  EXPECT_TRUE(error.failed());
  EXPECT_EQ(rethrown(error), "item 613 failed");
}

// Every item records from its own thread (no skipping): items 13, 110, 207, ... (i % 97 == 13)
// fail, and the error kept is the lowest one's, item 13, whichever thread got there first.
TEST(FirstError, TheLowestItemWinsAcrossThreads) {
  FirstError error;
#pragma omp parallel for schedule(static, 1) num_threads(4)
  for (int i = 999; i >= 0; --i) {
    if (i % 97 == 13) error.record(static_cast<std::size_t>(i), "item " + std::to_string(i));
  }
  EXPECT_EQ(rethrown(error), "item 13");
}

}  // namespace
}  // namespace mcws
