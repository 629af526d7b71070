#include "mcws/study/study_output.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <system_error>

#include "mcws/core/error.h"
#include "mcws/io/atomic_file.h"
#include "mcws/report/report_page.h"

namespace mcws {

namespace fs = std::filesystem;

namespace {

/// `path` beside `target` named ".<target's name>.<tag>-<pid>".
std::string besideTarget(const std::string& target, const std::string& tag) {
  const fs::path path(target);
  fs::path name = path.filename();
  if (name.empty()) name = path.parent_path().filename();  // "out/"
  const fs::path parent = fs::path(target).lexically_normal().parent_path();
  return ((parent.empty() ? fs::path(".") : parent) /
          ("." + name.string() + "." + tag + "-" + std::to_string(::getpid())))
      .string();
}

}  // namespace

StudyDirectory::StudyDirectory(std::string target, const std::vector<std::string>& inputs)
    : target_(std::move(target)) {
  std::error_code error;
  const fs::path path = fs::path(target_).lexically_normal();
  if (fs::exists(path, error) && !fs::is_directory(path, error))
    throw Error("--output " + target_ + ": exists and is not a directory");
  if (fs::is_directory(path, error)) {
    const fs::path inside = fs::weakly_canonical(path, error);
    for (const std::string& input : inputs) {
      const fs::path file = fs::weakly_canonical(input, error);
      const auto [end, rest] =
          std::mismatch(inside.begin(), inside.end(), file.begin(), file.end());
      if (end == inside.end())
        throw UsageError("--output " + target_ + ": holds " + input +
                         ", an input of the run (the directory is replaced as a whole)");
    }
    if (!fs::is_empty(path, error) && !fs::exists(path / "report.json", error))
      throw UsageError("--output " + target_ +
                       ": a directory that is neither empty nor a former study's output (no "
                       "report.json); it would be replaced as a whole");
  }
  const fs::path parent = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  if (!fs::is_directory(parent, error))
    throw Error("--output " + target_ + ": directory " + parent.string() + " does not exist");
  temporary_ = besideTarget(target_, "mcws-study");
  fs::remove_all(temporary_, error);
  if (!fs::create_directory(temporary_, error))
    throw Error("--output " + target_ + ": cannot make " + temporary_ + ": " + error.message());
  signal_slot_ = io::registerTempDirectory(temporary_);  // Ctrl-C leaves nothing beside DIR
}

StudyDirectory::~StudyDirectory() {
  io::unregisterTempDirectory(signal_slot_);
  if (committed_) return;
  std::error_code ignored;
  fs::remove_all(temporary_, ignored);
}

void StudyDirectory::commit() {
  const fs::path target = fs::path(target_).lexically_normal();
  std::error_code error;
  std::string old;
  if (fs::exists(target, error)) {
    old = besideTarget(target_, "mcws-study-old");
    fs::remove_all(old, error);
    fs::rename(target, old, error);
    if (error) throw Error("--output " + target_ + ": cannot move it aside: " + error.message());
  }
  fs::rename(temporary_, target, error);
  if (error) {
    std::error_code ignored;
    if (!old.empty()) fs::rename(old, target, ignored);  // put it back
    throw Error("--output " + target_ + ": cannot rename " + temporary_ +
                " onto it: " + error.message());
  }
  committed_ = true;
  io::unregisterTempDirectory(signal_slot_);
  signal_slot_ = -1;
  if (!old.empty()) fs::remove_all(old, error);
}

void saveStudyReport(const StudyRun& run, const std::string& directory) {
  io::writeWholeFile((fs::path(directory) / "report.json").string(), run.report.dump(2) + "\n");
  report::PageOptions options;
  options.title = run.report.value("study", std::string("mcws study"));
  io::writeWholeFile((fs::path(directory) / "report.html").string(),
                     report::reportHtml(run.report, run.scene, options));
}

}  // namespace mcws
