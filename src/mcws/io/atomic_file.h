#pragma once
/// \file
/// \brief Output files that appear whole or not at all.

#include <cstdio>
#include <string>

namespace mcws::io {

/// \brief Checks that `path` can be created: its directory exists, is a directory and is
/// writable, and `path` itself is not a directory.
/// \throws mcws::Error naming the path and what is wrong.
void checkOutputPath(const std::string& path);

/// \brief A file written under a temporary name beside its target and renamed onto the target
/// by commit(). Destroyed without commit(), it removes the temporary file: a failed run leaves
/// no partial output. A run stopped by SIGINT, SIGTERM or SIGHUP removes its temporary files too
/// (a handler installed with the first AtomicFile, which then lets the signal end the process).
class AtomicFile {
 public:
  /// \throws mcws::Error when the target's directory is missing or not writable.
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// \brief The open temporary file.
  std::FILE* stream() { return file_; }
  /// \brief Writes `size` bytes. \throws mcws::Error on a write error (disk full, ...).
  void write(const void* data, std::size_t size);
  /// \brief Flushes, closes and renames onto the target. \throws mcws::Error on failure.
  void commit();
  /// \brief Target path.
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::string temp_path_;
  std::FILE* file_{nullptr};
  int signal_slot_{-1};
};

}  // namespace mcws::io
