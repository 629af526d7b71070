#pragma once
/// \file
/// \brief Output files that appear whole or not at all, and the outputs of a run that appear
/// together or not at all (OutputSet).

#include <sys/types.h>

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace mcws::io {

/// \brief Checks, before any work, that AtomicFile(path) can write `path` under the rules of
/// AtomicFile: symbolic links are followed; an existing device, FIFO or socket must be writable;
/// an existing regular file must have a write permission bit; otherwise the directory of the
/// final target must exist, be a directory and be writable, and the target not be a directory;
/// an existing file must not be one the run reads (requireInputFile()).
/// \throws mcws::UsageError when the path is one of the run's inputs; mcws::Error naming the path
///   and what else is wrong.
void checkOutputPath(const std::string& path);

/// \brief Whether writing `a` and writing `b` would write one file: the final targets of their
/// links, compared by device and inode where they exist and else by the canonical path of their
/// directory plus their name ("b.pcd", "./b.pcd", "/abs/b.pcd" and "linked-dir/b.pcd" are one new
/// file). Devices, FIFOs and sockets (and the descriptors of /dev/stdout, /dev/fd/N) are written
/// through, replace nothing and are never the same file as another output.
bool sameOutputFile(const std::string& a, const std::string& b);

/// \brief An output file that appears whole, on commit(), or not at all.
///
/// What is written depends on what the target path is when the AtomicFile is made:
/// - **A descriptor of this process** (`/dev/stdout`, `/dev/stderr`, `/dev/fd/N`,
///   `/proc/self/fd/N`, also through links): written through a duplicate of that descriptor, so
///   a shell's `>> log` appends and `> log` writes at its offset; nothing is truncated or renamed.
/// - **A symbolic link** (also a chain of links, also a dangling one) is followed to its final
///   target, and the rules below apply to that target in that target's directory: the link stays
///   a link and its target gets the new content.
/// - **An existing device, FIFO or socket** (`/dev/null`, a named pipe) is opened and written
///   straight through: no temporary file, no rename, so the device node stays what it is;
///   commit() flushes and closes. A FIFO is opened without waiting: with no reader the
///   constructor throws "no reader" instead of blocking. Bytes written through cannot be taken
///   back, so here a run that fails midway leaves what it wrote (but see OutputSet).
/// - **An existing regular file without any write permission bit** is refused ("is read-only"),
///   by its mode bits, so also for root (which access() would let through).
/// - **An existing file the run reads** (noted by requireInputFile(): a robot file, its meshes, a
///   scenario, a map, an input cloud) is refused with mcws::UsageError, when the AtomicFile is
///   made and again on commit(), for inputs read in between.
/// - **Otherwise** the bytes go to an unnamed file made with O_TMPFILE in the target's
///   directory. commit() flushes it, syncs it to the disk, gives it a short temporary name
///   (`.<start of the name>.mcws-<pid>-<n>`, within NAME_MAX however long the target's name) and
///   renames that onto the target. Until then the file has no name, so even SIGKILL leaves
///   nothing behind. Where the file system does not offer O_TMPFILE, the file is created under
///   that temporary name instead. New files get mode 0666 & ~umask.
///
/// Destroyed without commit(), it removes its file: a failed run leaves no partial output. A run
/// ended by a signal whose default action ends the process and that can be caught (SIGINT,
/// SIGTERM, SIGHUP, SIGPIPE, SIGQUIT, SIGXFSZ, SIGUSR1, SIGUSR2, SIGALRM, SIGVTALRM, SIGPROF)
/// removes the temporary names too: a handler installed with the first AtomicFile, for the
/// signals still at their default action (a signal ignored with nohup stays ignored), unlinks
/// them and lets the signal end the process as before.
///
/// While an OutputSet is alive on the thread, commit() only finishes the file and hands it to
/// the set, which gives every such file its name together (OutputSet::commit()).
class AtomicFile {
 public:
  /// \throws mcws::Error naming the path when it cannot be written (see checkOutputPath()).
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// \brief The open file (unnamed, temporary, the device itself, or a buffer for it).
  std::FILE* stream() { return file_; }
  /// \brief Writes `size` bytes. \throws mcws::Error on a write error (disk full, ...).
  void write(const void* data, std::size_t size);
  /// \brief Tells the file system the file will hold `size` bytes, so that it can give them their
  /// place on the disk now rather than while the bytes are being written (fallocate, keeping the
  /// file's size). A regular file only; does nothing where the file system cannot (the writes
  /// then report what is wrong, such as a full disk).
  void reserve(std::uint64_t size);
  /// \brief Whether writeAt() may be used: the bytes go to a file that can be written at offsets
  /// (a regular file, also the buffer of a device in an OutputSet), not straight to a device,
  /// FIFO or socket.
  bool positional() const { return file_ && (!write_through_ || device_ >= 0); }
  /// \brief Writes `size` bytes at byte `offset` of the file (pwrite), leaving what write()
  /// appends where it was. Safe to call from several threads at once (on distinct ranges) once
  /// the bytes write() takes are all written; write() must not be called after it.
  /// \pre positional(). \throws mcws::Error on a write error (disk full, ...).
  void writeAt(std::uint64_t offset, const void* data, std::size_t size);
  /// \brief Flushes, syncs, closes and gives the file the target's name, or, while an OutputSet
  /// is alive on this thread, hands it to that set. \throws mcws::Error on failure.
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
  friend class OutputSet;
  /// The file's state, moved into an OutputSet on commit().
  AtomicFile(AtomicFile&& other) noexcept;
  /// \brief Flushes the written bytes to the disk (regular files) and checks the target is still
  /// no input of the run; the file stays open and unnamed. \throws mcws::Error on failure.
  void finish();
  /// \brief A finished file's bytes buffered for a device: sent to it now. \throws on failure.
  void sendBuffered();
  /// \brief A finished regular file: gives it its temporary name. \throws mcws::Error.
  void link();
  /// \brief A linked file: renamed onto the target. \throws mcws::Error.
  void rename();
  /// \brief Names the unnamed file `temp_path_` (linkat through /proc/self/fd).
  void linkTempFile();
  /// \brief Closes the file and removes the temporary name, if any.
  void discard();
  /// \brief The bytes [begin, end) of the file to ask the disk to write now (sync_file_range,
  /// without waiting): the whole pages of its written start [0, `written`) not asked for yet, once
  /// they are 8 MiB or more. Empty for what is written through. Not thread-safe.
  std::pair<std::uint64_t, std::uint64_t> writebackRange(std::uint64_t written);

  /// The ranges writeAt() has written, to find the written start of the file.
  struct Written;

  std::string path_;                  ///< as given
  std::string target_;                ///< `path_` with its symbolic links followed
  std::string temp_path_;             ///< the temporary name; empty while the file has none
  std::FILE* file_{nullptr};          ///< open until commit() or destruction
  std::uint64_t appended_{0};         ///< bytes write() took
  std::uint64_t writeback_to_{0};     ///< the disk was asked to write bytes [0, writeback_to_)
  std::unique_ptr<Written> written_;  ///< what writeAt() has written (made with the file)
  int device_{-1};             ///< a device whose bytes are buffered in `file_` (in an OutputSet)
  bool write_through_{false};  ///< the target is a device, FIFO, socket or descriptor
  bool unnamed_{false};        ///< made with O_TMPFILE and not linked yet
  int signal_slot_{-1};        ///< where `temp_path_` is registered for the signal handler
};

/// \brief A directory of files being made (flat: files only), removed with its files if a signal
/// ends the process before unregisterTempDirectory() (the handler of AtomicFile's temporary
/// names, SIGINT, SIGTERM, ...). \return a slot for unregisterTempDirectory(); -1 when the table
/// (4 directories) is full or the path too long: that directory is then not removed on a signal.
int registerTempDirectory(const std::string& path);
/// \brief Forgets a registerTempDirectory() slot (-1: nothing).
void unregisterTempDirectory(int slot);

/// \brief Writes `bytes` to `path` through an AtomicFile and commits it (into the OutputSet alive
/// on this thread, if any). \throws mcws::Error as AtomicFile does.
void writeWholeFile(const std::string& path, const std::string& bytes);

/// \brief The outputs of one run, which appear together or not at all.
///
/// While the set is alive, every AtomicFile committed on its thread (directly, or by a writer
/// such as PcdStreamWriter) is flushed and synced to the disk but keeps no name: the set holds
/// it. commit() then gives them all their names; destroyed without commit(), the set removes
/// them, and nothing that lay at any output path has been touched. Outputs to a device, FIFO or
/// descriptor made while the set is alive are opened at once (a FIFO without a reader fails
/// before any work) but buffered in an unnamed temporary file and sent on commit(), before any
/// regular output is renamed, so that a failing send leaves the regular outputs unwritten too.
/// Two outputs that are one file (sameOutputFile()) are refused with mcws::UsageError.
///
/// A tool makes the set before it writes its first output and commits it once every output is
/// written:
/// \code
///   io::OutputSet outputs;
///   saveCloud(boundary, output);   // committed into the set
///   saveCloud(interior, interior_path);
///   outputs.commit();              // both appear, or (on an exception) neither
/// \endcode
class OutputSet {
 public:
  OutputSet();
  /// \brief Removes the outputs not given their names.
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  /// \brief Sends the buffered device outputs, then links every regular output under its
  /// temporary name, then renames them all onto their targets. \throws mcws::Error (nothing
  /// renamed) when a send or a link fails.
  void commit();
  /// \brief The set alive on this thread, or nullptr.
  static OutputSet* current();

 private:
  friend class AtomicFile;
  /// \brief Takes a finished file. \throws mcws::UsageError when it is the same file as one
  /// the set holds.
  void adopt(AtomicFile&& file);

  std::vector<std::unique_ptr<AtomicFile>> files_;
  OutputSet* previous_{nullptr};  ///< the set this one hides, restored on destruction
  bool committed_{false};
};

}  // namespace mcws::io
