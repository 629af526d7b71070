#pragma once
/// \file
/// \brief Output files that appear whole or not at all.

#include <cstdio>
#include <string>

namespace mcws::io {

/// \brief Checks, before any work, that AtomicFile(path) can write `path` under the rules of
/// AtomicFile: symbolic links are followed; an existing device, FIFO or socket must be writable;
/// an existing regular file must have a write permission bit; otherwise the directory of the
/// final target must exist, be a directory and be writable, and the target not be a directory.
/// \throws mcws::Error naming the path and what is wrong.
void checkOutputPath(const std::string& path);

/// \brief An output file that appears whole, on commit(), or not at all.
///
/// What is written depends on what the target path is when the AtomicFile is made:
/// - **A symbolic link** (also a chain of links, also a dangling one) is followed to its final
///   target, and the rules below apply to that target in that target's directory: the link stays
///   a link and its target gets the new content.
/// - **An existing device, FIFO or socket** (`/dev/null`, `/dev/stdout`, a named pipe) is opened
///   and written straight through: no temporary file, no rename, so the device node stays what it
///   is; commit() flushes and closes. A FIFO is opened without waiting: with no reader the
///   constructor throws "no reader" instead of blocking. Bytes written through cannot be taken
///   back, so here a run that fails midway leaves what it wrote.
/// - **An existing regular file without any write permission bit** is refused ("is read-only"),
///   by its mode bits, so also for root (which access() would let through).
/// - **Otherwise** the bytes go to an unnamed file made with O_TMPFILE in the target's
///   directory. commit() gives it a short temporary name (`.<start of the name>.mcws-<pid>-<n>`,
///   within NAME_MAX however long the target's name) and renames that onto the target. Until
///   commit() the file has no name, so even SIGKILL leaves nothing behind. Where the file system
///   does not offer O_TMPFILE, the file is created under that temporary name instead. New files
///   get mode 0666 & ~umask.
///
/// Destroyed without commit(), it removes its file: a failed run leaves no partial output. A run
/// ended by a signal whose default action ends the process and that can be caught (SIGINT,
/// SIGTERM, SIGHUP, SIGPIPE, SIGQUIT, SIGXFSZ, SIGUSR1, SIGUSR2, SIGALRM, SIGVTALRM, SIGPROF)
/// removes the temporary names too: a handler installed with the first AtomicFile, for the
/// signals still at their default action (a signal ignored with nohup stays ignored), unlinks
/// them and lets the signal end the process as before.
class AtomicFile {
 public:
  /// \throws mcws::Error naming the path when it cannot be written (see checkOutputPath()).
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// \brief The open file (unnamed, temporary, or the device itself).
  std::FILE* stream() { return file_; }
  /// \brief Writes `size` bytes. \throws mcws::Error on a write error (disk full, ...).
  void write(const void* data, std::size_t size);
  /// \brief Flushes, closes and gives the file the target's name. \throws mcws::Error on failure.
  void commit();
  /// \brief Gives the file its temporary name now (if it has none yet) and returns it, so that
  /// other processes (the MPI ranks of mcws/distributed) can open and write it before commit().
  /// The name is removed as any temporary name is: on destruction without commit() and on the
  /// signals above. \throws mcws::Error for a device, FIFO or socket (no name to share) or when
  /// the name cannot be made.
  const std::string& temporaryPath();
  /// \brief Target path, as given.
  const std::string& path() const { return path_; }

 private:
  /// \brief Names the unnamed file `temp_path_` (linkat through /proc/self/fd).
  void linkTempFile();
  /// \brief Closes the file and removes the temporary name, if any.
  void discard();

  std::string path_;           ///< as given
  std::string target_;         ///< `path_` with its symbolic links followed
  std::string temp_path_;      ///< the temporary name; empty while the file has none
  std::FILE* file_{nullptr};   ///< open until commit() or destruction
  bool write_through_{false};  ///< the target is a device, FIFO or socket
  bool unnamed_{false};        ///< made with O_TMPFILE and not linked yet
  int signal_slot_{-1};        ///< where `temp_path_` is registered for the signal handler
};

}  // namespace mcws::io
