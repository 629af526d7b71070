#pragma once
/// \file
/// \brief The files a run reads: checked to be regular files before a reader opens them, and
/// noted, so that no output of the same run replaces one of them (io::AtomicFile asks
/// inputFileOf() before it writes).
///
/// Header-only, so that the loaders' fuzz build links without the io module.

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mcws/core/error.h"

namespace mcws {

namespace detail {

/// An input as the file system knows it: device and inode, so that any spelling of the path,
/// a symbolic or a hard link, is the same input.
struct InputFile {
  dev_t device;
  ino_t inode;
  std::string path;  ///< as the reader was given it
  std::string kind;  ///< what it is, for messages ("collision mesh")
};

inline std::mutex& inputFilesMutex() {
  static std::mutex mutex;
  return mutex;
}

inline std::vector<InputFile>& inputFileList() {
  static std::vector<InputFile> files;
  return files;
}

/// RunInputs alive (nested ones count).
inline int& runInputsDepth() {
  static int depth = 0;
  return depth;
}

/// What a non-regular file is, for messages.
inline const char* fileTypeName(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "a special file";
}

}  // namespace detail

/// \brief Checks that `path` names an existing regular file (symbolic links followed). Call it
/// before a reader opens the file: a FIFO nobody writes would block the open for ever, and a
/// device may never end.
/// \param path the file, as given.
/// \param kind what the file is, for messages ("robot file", "collision mesh").
/// \return the file's status.
/// \throws mcws::Error "kind name is empty", "path: kind does not exist", "path: kind is not a
///   regular file (a FIFO)" (a directory, a device, a socket likewise) or "path: cannot read kind:
///   reason".
inline struct stat requireRegularFile(const std::string& path, const std::string& kind) {
  if (path.empty()) throw Error(kind + " name is empty");
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) {
    if (errno == ENOENT) throw Error(path + ": " + kind + " does not exist");
    throw Error(path + ": cannot read " + kind + ": " + std::strerror(errno));
  }
  if (!S_ISREG(status.st_mode)) {
    throw Error(path + ": " + kind + " is not a regular file (" +
                detail::fileTypeName(status.st_mode) + ")");
  }
  return status;
}

/// \brief One run: while it lives, the files requireInputFile() checks are noted as the run's
/// inputs, which no output of the run may replace (io::AtomicFile refuses them); they are
/// forgotten when it ends. The tools make one for their whole run (app::run()); a program that
/// runs many stages (a test, a script through the Python API) makes one per stage, so that a file
/// read by one stage may be written by the next.
class RunInputs {
 public:
  RunInputs() {
    const std::lock_guard<std::mutex> lock(detail::inputFilesMutex());
    if (detail::runInputsDepth()++ == 0) detail::inputFileList().clear();
  }
  ~RunInputs() {
    const std::lock_guard<std::mutex> lock(detail::inputFilesMutex());
    if (--detail::runInputsDepth() == 0) detail::inputFileList().clear();
  }
  RunInputs(const RunInputs&) = delete;
  RunInputs& operator=(const RunInputs&) = delete;
};

/// \brief requireRegularFile(), and, while a RunInputs lives, notes the file as one of the run's
/// inputs.
inline void requireInputFile(const std::string& path, const std::string& kind) {
  const struct stat status = requireRegularFile(path, kind);
  const std::lock_guard<std::mutex> lock(detail::inputFilesMutex());
  if (detail::runInputsDepth() == 0) return;
  for (const detail::InputFile& file : detail::inputFileList()) {
    if (file.device == status.st_dev && file.inode == status.st_ino) return;
  }
  detail::inputFileList().push_back({status.st_dev, status.st_ino, path, kind});
}

/// \brief The input (its path and kind) that is the same file as the existing file of `status`,
/// if the run has read one.
inline std::optional<std::pair<std::string, std::string>> inputFileOf(const struct stat& status) {
  const std::lock_guard<std::mutex> lock(detail::inputFilesMutex());
  for (const detail::InputFile& file : detail::inputFileList()) {
    if (file.device == status.st_dev && file.inode == status.st_ino) {
      return std::make_pair(file.path, file.kind);
    }
  }
  return std::nullopt;
}

}  // namespace mcws
