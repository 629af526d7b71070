#pragma once
/// \file
/// \brief The output directory of a study, appearing whole or not at all, and the report files.

#include <filesystem>
#include <string>
#include <vector>

#include "mcws/study/study_run.h"

namespace mcws {

/// \brief The "format" member saveStudyReport() adds to a study's report: what marks a
/// report.json as written by mcws_study, so that StudyDirectory knows a former output.
inline constexpr char kStudyReportFormat[] = "mcws_study report";

/// \brief A directory of outputs made beside its target, renamed onto it by commit().
///
/// `target` is taken without its trailing separators ("out/" is "out"). The files are written
/// into a new directory `.<name>.mcws-study-<pid>` in the nearest existing ancestor of
/// `target`'s parent (the parent itself when it exists: the same filesystem, so that a rename
/// moves it); commit() makes the missing parent folders, moves what lies at `target` aside,
/// renames the new directory to `target` and removes the old one. Destroyed without commit()
/// (a failed run), or ended by a signal before it, it removes the new directory: what lay at
/// `target` is untouched and no folder has been made.
class StudyDirectory {
 public:
  /// \param inputs the files the run reads: none may lie inside `target`.
  /// \param map_cache the folder of the run's reach-map cache ("": none): neither `target` nor
  ///   inside it.
  /// \throws mcws::UsageError when `target` names no folder (empty, "/"), holds one of
  ///   `inputs` or `map_cache`, or is a directory neither empty nor a former output (a
  ///   report.json whose "format" is kStudyReportFormat, or an earlier build's report without
  ///   it (every top-level member of a study report), and nothing a study does not write:
  ///   `--output ~` must not replace a home); mcws::Error when `target` is an existing file (not
  ///   a directory), when an ancestor of it is a file, or when the new directory cannot be made.
  StudyDirectory(std::string target, const std::vector<std::string>& inputs,
                 const std::string& map_cache = "");
  ~StudyDirectory();
  StudyDirectory(const StudyDirectory&) = delete;
  StudyDirectory& operator=(const StudyDirectory&) = delete;

  /// \brief Where the files go until commit().
  const std::string& path() const { return temporary_; }
  /// \brief Makes the target's missing parent folders and renames the directory onto the
  /// target. \throws mcws::Error when it cannot (the folders it made are removed again).
  void commit();

 private:
  std::string target_;          ///< as the user spelt it, for the messages
  std::filesystem::path path_;  ///< absolute, without trailing separators
  std::string temporary_;
  bool committed_{false};
  int signal_slot_{-1};  ///< `temporary_` registered for removal if a signal ends the run
};

/// \brief Adds `"format": kStudyReportFormat` to `run.report`, then writes the report as
/// `directory`/report.json (2-space indented) and the page report::reportHtml() makes of it and
/// the scene as `directory`/report.html.
/// \throws mcws::Error when a file cannot be written or the page cannot be made.
void saveStudyReport(StudyRun& run, const std::string& directory);

}  // namespace mcws
