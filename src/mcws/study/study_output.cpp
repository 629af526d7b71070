#include "mcws/study/study_output.h"

#include <unistd.h>

#include <algorithm>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <system_error>

#include "mcws/core/error.h"
#include "mcws/io/atomic_file.h"
#include "mcws/io/process.h"
#include "mcws/report/report_page.h"

namespace mcws {

namespace fs = std::filesystem;

namespace {

/// The files a study writes into its directory (saveStudyReport(), study_run.cpp's stages),
/// apart from the accepted paths path_<target>.csv (study_plan.cpp), which its report.json names
/// under planning.targets[].path_file.
constexpr const char* kStudyOutputFiles[] = {"report.json",  "report.html", "samples.pcd",
                                             "boundary.pcd", "refined.pcd", "envelope.ply",
                                             "drawing.png"};

/// `target` as an absolute path without trailing separators ("out/" -> "<cwd>/out").
fs::path studyOutputPath(const std::string& target) {
  if (target.empty()) throw UsageError("--output: empty (a directory)");
  fs::path path = fs::absolute(target).lexically_normal();
  while (path.has_relative_path() && path.filename().empty()) path = path.parent_path();
  if (!path.has_relative_path())
    throw UsageError("--output " + target + ": names no directory a study can make or replace");
  return path;
}

/// `path` absolute with its links followed (as far as it exists).
fs::path resolvedPath(const fs::path& path) {
  std::error_code error;
  const fs::path absolute = fs::absolute(path).lexically_normal();
  fs::path resolved = fs::weakly_canonical(absolute, error);
  return error ? absolute : resolved;
}

/// Whether `path` is `directory` or lies inside it, their links followed.
bool liesInside(const fs::path& path, const fs::path& directory) {
  const fs::path outer = resolvedPath(directory), inner = resolvedPath(path);
  auto outer_end = outer.end(), inner_end = inner.end();
  if (outer_end != outer.begin() && std::prev(outer_end)->empty()) --outer_end;  // "dir/"
  return std::mismatch(outer.begin(), outer_end, inner.begin(), inner_end).first == outer_end;
}

/// `path`'s entries, sorted by name.
std::vector<std::string> sortedEntries(const fs::path& path) {
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(path))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// Whether `report` is a study report of the builds before the "format" member: no "format", and
/// every top-level member a study report has (so that a run of this build replaces the output
/// of an earlier one, as scripts/run_main.sh does; the files beside it are checked as for a
/// marked one).
bool isUnmarkedStudyReport(const nlohmann::json& report) {
  if (report.contains("format")) return false;
  for (const char* name : {"study", "source", "robot", "length_unit", "seed", "stages", "units",
                           "view", "workspace", "reach", "placement", "planning"}) {
    if (!report.contains(name)) return false;
  }
  return report.at("stages").is_array() && report.at("study").is_string();
}

/// \throws UsageError unless `directory` is empty or a former study output: a report.json marked
/// kStudyReportFormat (or an earlier build's, isUnmarkedStudyReport()), and regular files only,
/// each a name a study writes.
void refuseUnlessFormerOutput(const fs::path& directory, const std::string& target) {
  const std::vector<std::string> names = sortedEntries(directory);
  if (names.empty()) return;
  const std::string refused =
      "--output " + target + ": neither empty nor a former study's output (";
  const std::string whole = "); it would be replaced as a whole";
  const fs::path report_file = directory / "report.json";
  std::error_code error;
  if (!fs::is_regular_file(fs::symlink_status(report_file, error)))
    throw UsageError(refused + "no report.json" + whole);
  const nlohmann::json report =
      nlohmann::json::parse(io::readFile(report_file.string()), nullptr, false);
  if (!report.is_object() || (report.value("format", nlohmann::json()) != kStudyReportFormat &&
                              !isUnmarkedStudyReport(report)))
    throw UsageError(refused + "its report.json has no \"format\": \"" + kStudyReportFormat + "\"" +
                     whole);
  std::set<std::string> written(std::begin(kStudyOutputFiles), std::end(kStudyOutputFiles));
  const auto member = [](const nlohmann::json& object, const char* name) {
    return object.is_object() && object.contains(name) ? object.at(name) : nlohmann::json();
  };
  const nlohmann::json planned = member(member(report, "planning"), "targets");
  for (const nlohmann::json& item : planned.is_array() ? planned : nlohmann::json::array()) {
    const nlohmann::json file = member(item, "path_file");  // path_<target>.csv
    const std::string name = file.is_string() ? file.get<std::string>() : "";
    if (name.size() > 9 && name.compare(0, 5, "path_") == 0 &&
        name.compare(name.size() - 4, 4, ".csv") == 0)
      written.insert(name);
  }
  for (const std::string& name : names) {
    if (!written.count(name) || !fs::is_regular_file(fs::symlink_status(directory / name, error)))
      throw UsageError(refused + "it holds " + name + ", which a study does not write" + whole);
  }
}

/// The nearest existing ancestor of `path`. \throws Error when it is not a directory.
fs::path nearestExistingAncestor(const fs::path& path, const std::string& target) {
  std::error_code error;
  fs::path at = path.parent_path();
  while (!fs::exists(fs::symlink_status(at, error)) && at.has_relative_path())
    at = at.parent_path();
  if (!fs::is_directory(at, error))
    throw Error("--output " + target + ": " + at.string() + " is not a directory");
  return at;
}

/// `path`'s missing parent folders, the deepest first.
std::vector<fs::path> missingParents(const fs::path& path) {
  std::vector<fs::path> missing;
  std::error_code error;
  for (fs::path at = path.parent_path();
       at.has_relative_path() && !fs::exists(fs::symlink_status(at, error)); at = at.parent_path())
    missing.push_back(at);
  return missing;
}

/// Removes the folders `missingParents()` listed and commit() made (empty ones only).
void removeMadeFolders(const std::vector<fs::path>& made) {
  std::error_code ignored;
  for (const fs::path& folder : made) fs::remove(folder, ignored);
}

/// `path` beside itself, named ".<path's name>.<tag>-<pid>".
fs::path besideStudyOutput(const fs::path& path, const std::string& tag) {
  return path.parent_path() /
         ("." + path.filename().string() + "." + tag + "-" + std::to_string(::getpid()));
}

}  // namespace

StudyDirectory::StudyDirectory(std::string target, const std::vector<std::string>& inputs,
                               const std::string& map_cache)
    : target_(std::move(target)), path_(studyOutputPath(target_)) {
  std::error_code error;
  const fs::file_status status = fs::status(path_, error);
  if (fs::exists(status) && !fs::is_directory(status))
    throw Error("--output " + target_ + ": exists and is not a directory");
  if (!map_cache.empty() && liesInside(map_cache, path_))
    throw UsageError("--map-cache " + map_cache + ": the folder is --output " + target_ +
                     " or inside it (replaced as a whole: the cache would go with it)");
  if (fs::is_directory(status)) {
    for (const std::string& input : inputs) {
      if (liesInside(input, path_))
        throw UsageError("--output " + target_ + ": holds " + input +
                         ", an input of the run (the directory is replaced as a whole)");
    }
    refuseUnlessFormerOutput(path_, target_);
  }
  // In the nearest existing folder: a failed run makes no parent folder.
  const fs::path ancestor = nearestExistingAncestor(path_, target_);
  temporary_ = besideStudyOutput(ancestor / path_.filename(), "mcws-study").string();
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
  std::error_code error;
  const std::vector<fs::path> made = missingParents(path_);
  for (auto folder = made.rbegin(); folder != made.rend(); ++folder) {
    if (!fs::create_directory(*folder, error) && error) {
      removeMadeFolders(made);
      throw Error("--output " + target_ + ": cannot make " + folder->string() + ": " +
                  error.message());
    }
  }
  fs::path old;
  if (fs::exists(fs::symlink_status(path_, error))) {
    old = besideStudyOutput(path_, "mcws-study-old");
    fs::remove_all(old, error);
    fs::rename(path_, old, error);
    if (error) throw Error("--output " + target_ + ": cannot move it aside: " + error.message());
  }
  fs::rename(temporary_, path_, error);
  if (error) {
    std::error_code ignored;
    if (!old.empty()) fs::rename(old, path_, ignored);  // put it back
    removeMadeFolders(made);
    throw Error("--output " + target_ + ": cannot rename " + temporary_ +
                " onto it: " + error.message());
  }
  committed_ = true;
  io::unregisterTempDirectory(signal_slot_);
  signal_slot_ = -1;
  if (!old.empty()) fs::remove_all(old, error);
}

void saveStudyReport(StudyRun& run, const std::string& directory) {
  run.report["format"] = kStudyReportFormat;
  io::writeWholeFile((fs::path(directory) / "report.json").string(), run.report.dump(2) + "\n");
  report::PageOptions options;
  options.title = run.report.value("study", std::string("mcws study"));
  io::writeWholeFile((fs::path(directory) / "report.html").string(),
                     report::reportHtml(run.report, run.scene, options));
}

}  // namespace mcws
