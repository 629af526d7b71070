#pragma once
/// \file
/// \brief What a run is doing, for the message when memory runs out (std::bad_alloc names
/// nothing).

#include <exception>
#include <string>
#include <utility>
#include <vector>

namespace mcws {

/// \brief Names what a tool is doing while the object lives, e.g. "reading --input 'a.pcd'", for
/// the message of app::run() when memory runs out. Activities nest; header-only so that the
/// loaders' fuzz build, which has no app.cpp, links.
class Activity {
 public:
  explicit Activity(std::string what) : unwinding_(std::uncaught_exceptions()) {
    failed().clear();  // an exception that left an earlier one was handled
    stack().push_back(std::move(what));
  }
  /// Left by an exception: remembered as the activity that failed (the innermost one).
  ~Activity() {
    if (std::uncaught_exceptions() > unwinding_ && failed().empty()) failed() = stack().back();
    stack().pop_back();
  }
  Activity(const Activity&) = delete;
  Activity& operator=(const Activity&) = delete;
  /// \brief The activity an exception left last (then forgotten), else the innermost one alive,
  /// "" when none.
  static std::string takeFailed() {
    std::string what = failed().empty() && !stack().empty() ? stack().back() : failed();
    failed().clear();
    return what;
  }

 private:
  static std::vector<std::string>& stack() {
    static std::vector<std::string> activities;  // the tools' main thread only
    return activities;
  }
  static std::string& failed() {
    static std::string what;
    return what;
  }
  int unwinding_;  ///< exceptions in flight when the activity began
};

}  // namespace mcws
