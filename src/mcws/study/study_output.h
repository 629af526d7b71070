#pragma once
/// \file
/// \brief The output directory of a study, appearing whole or not at all, and the report files.

#include <string>
#include <vector>

#include "mcws/study/study_run.h"

namespace mcws {

/// \brief A directory of outputs made beside its target, renamed onto it by commit().
///
/// The files are written into a new directory `.<name>.mcws-study-<pid>` beside `target`;
/// commit() moves what lies at `target` aside, renames the new directory to `target` and removes
/// the old one. Destroyed without commit() (a failed run), it removes the new directory, and
/// what lay at `target` is untouched.
class StudyDirectory {
 public:
  /// \param inputs the files the run reads: none may lie inside `target`.
  /// \throws mcws::UsageError when `target` holds one of `inputs`, or is a directory neither
  ///   empty nor a former output (it has no report.json: `--output ~` must not replace a home);
  ///   mcws::Error when `target` is an existing file (not a directory), when its parent
  ///   directory does not exist, or when the new directory cannot be made.
  StudyDirectory(std::string target, const std::vector<std::string>& inputs);
  ~StudyDirectory();
  StudyDirectory(const StudyDirectory&) = delete;
  StudyDirectory& operator=(const StudyDirectory&) = delete;

  /// \brief Where the files go until commit().
  const std::string& path() const { return temporary_; }
  /// \brief Renames the directory onto the target. \throws mcws::Error when it cannot.
  void commit();

 private:
  std::string target_, temporary_;
  bool committed_{false};
  int signal_slot_{-1};  ///< `temporary_` registered for removal if a signal ends the run
};

/// \brief Writes `run.report` as `directory`/report.json (2-space indented) and the page
/// report::reportHtml() makes of it and the scene as `directory`/report.html.
/// \throws mcws::Error when a file cannot be written or the page cannot be made.
void saveStudyReport(const StudyRun& run, const std::string& directory);

}  // namespace mcws
