#include "mcws/collision/package_uri.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>
#include <utility>

#include "mcws/core/error.h"

namespace mcws {
namespace {

namespace fs = std::filesystem;

/// Deepest folder below a search folder that the crawl enters (rospack has no limit; a limit
/// keeps a search folder such as / from taking for ever).
constexpr int kMaxCrawlDepth = 16;

bool isDirectory(const fs::path& path) {
  std::error_code ec;
  return fs::is_directory(path, ec);
}

bool isPackage(const fs::path& folder) {
  std::error_code ec;
  return fs::is_regular_file(folder / "package.xml", ec);
}

/// The package folder called `name` at or below `root`, or an empty path.
fs::path crawl(const fs::path& root, const std::string& name) {
  if (!isDirectory(root)) return {};
  if (root.filename() == name && isPackage(root)) return root;
  if (isPackage(root)) return {};  // rospack does not look inside a package
  std::error_code ec;
  fs::recursive_directory_iterator it(root, fs::directory_options::skip_permission_denied, ec);
  for (const fs::recursive_directory_iterator end; !ec && it != end; it.increment(ec)) {
    const fs::path& folder = it->path();
    const std::string leaf = folder.filename().string();
    if (!it->is_directory(ec) || ec) {
      ec.clear();
      continue;
    }
    if ((!leaf.empty() && leaf[0] == '.') || it.depth() >= kMaxCrawlDepth) {
      it.disable_recursion_pending();
      continue;
    }
    if (!isPackage(folder)) continue;
    if (leaf == name) return folder;
    it.disable_recursion_pending();
  }
  return {};
}

/// The folders of a ':'-separated list, empty entries left out.
std::vector<std::string> splitPath(const std::string& list) {
  std::vector<std::string> folders;
  std::string::size_type from = 0;
  while (from <= list.size()) {
    const auto to = std::min(list.find(':', from), list.size());
    if (to > from) folders.push_back(list.substr(from, to - from));
    from = to + 1;
  }
  return folders;
}

std::string joined(const std::vector<std::string>& folders) {
  std::string text;
  for (const std::string& folder : folders) text += (text.empty() ? "" : ", ") + folder;
  return text;
}

}  // namespace

PackageSearch packageSearchFromEnvironment(std::vector<std::string> package_path) {
  PackageSearch search;
  search.package_path = std::move(package_path);
  if (const char* value = std::getenv("ROS_PACKAGE_PATH")) search.ros_package_path = value;
  return search;
}

std::string resolvePackageUri(const std::string& uri, const std::string& robot_file,
                              const PackageSearch& search) {
  const std::string prefix = "package://";
  const std::string rest = uri.substr(prefix.size());
  const fs::path robot_folder = fs::absolute(fs::path(robot_file)).parent_path();
  const auto slash = rest.find('/');
  if (slash == std::string::npos) {
    if (rest.empty()) throw Error("mesh '" + uri + "': no package name or file after package://");
    return (robot_folder / rest).string();
  }
  const std::string name = rest.substr(0, slash), inside = rest.substr(slash + 1);
  if (name.empty() || name == "." || name == "..") {
    throw Error("mesh '" + uri + "': '" + name + "' is not a package name");
  }
  const std::vector<std::string> ros = splitPath(search.ros_package_path);
  for (const auto* folders : {&search.package_path, &ros}) {
    for (const std::string& folder : *folders) {
      const fs::path found = crawl(folder, name);
      if (!found.empty()) return (found / inside).string();
    }
  }
  for (fs::path folder = robot_folder;; folder = folder.parent_path()) {
    if (isDirectory(folder / name)) return (folder / name / inside).string();
    if (folder == folder.parent_path()) break;
  }
  const std::vector<std::string>& given = search.package_path;
  throw Error("mesh '" + uri + "': package '" + name + "' not found; looked in --package-path " +
              (given.empty() ? "(none)" : joined(given)) + "; ROS_PACKAGE_PATH " +
              (ros.empty() ? "(unset)" : joined(ros)) + "; and for a folder '" + name + "' in " +
              robot_folder.string() + " and each folder above it");
}

}  // namespace mcws
