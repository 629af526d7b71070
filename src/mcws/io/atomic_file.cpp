#include "mcws/io/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <utility>

#include "mcws/core/error.h"
#include "mcws/core/input_files.h"

namespace mcws::io {
namespace fs = std::filesystem;

namespace {

// Temporary names to remove if a signal ends the process. A fixed table: the handler may only
// call async-signal-safe functions (unlink, signal, raise) and read lock-free atomics.
constexpr std::size_t kMaxPath = 4096;

/// Paths the signal handler removes: fixed arrays (nothing to allocate in the handler), a flag per
/// slot that the handler reads, slots taken under a mutex.
template <int N>
class SignalPathTable {
 public:
  /// \return the slot holding `path`; -1 when the path is too long or every slot is taken (that
  /// path is then not removed on a signal).
  int add(const std::string& path) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (path.size() >= kMaxPath) return -1;
    for (int k = 0; k < N; ++k) {
      if (!used_[k].load()) {
        std::memcpy(paths_[k], path.c_str(), path.size() + 1);
        used_[k].store(true);
        return k;
      }
    }
    return -1;
  }
  /// Forgets a slot of add() (-1: nothing).
  void remove(int slot) {
    if (slot >= 0) used_[slot].store(false);
  }
  /// Calls `f` on each path held (async-signal-safe when `f` is).
  template <class F>
  void forEach(F f) const {
    for (int k = 0; k < N; ++k) {
      if (used_[k].load()) f(paths_[k]);
    }
  }

 private:
  std::mutex mutex_;
  char paths_[N][kMaxPath]{};
  std::atomic<bool> used_[N]{};
};

// Files being made by AtomicFile, unlinked on a signal.
SignalPathTable<32> g_temp_files;

/// Signals whose default action ends the process and that a handler can catch.
constexpr int kCleanedSignals[] = {SIGINT,  SIGTERM, SIGHUP,  SIGPIPE,   SIGQUIT, SIGXFSZ,
                                   SIGUSR1, SIGUSR2, SIGALRM, SIGVTALRM, SIGPROF};

/// Links followed before giving up, as the kernel's limit (MAXSYMLINKS).
constexpr int kMaxLinkHops = 40;
/// Bytes of the target's name kept in a temporary name: with the dot, ".mcws-", a pid and a
/// counter (at most 10 digits each) the name stays within NAME_MAX.
constexpr std::size_t kMaxNamePrefix = 200;
static_assert(1 + kMaxNamePrefix + 6 + 10 + 1 + 10 <= NAME_MAX);

// Directories of files being made (registerTempDirectory()), emptied and removed on a signal.
SignalPathTable<4> g_temp_dirs;

/// Removes the files of a flat directory and the directory, with system calls only (no
/// allocation: readdir's DIR is malloc'd, so the entries are read with getdents64).
void removeFlatDirectory(const char* path) {
  const int fd = ::open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd >= 0) {
    alignas(8) static char entries[8192];
    for (;;) {
      const long size = ::syscall(SYS_getdents64, fd, entries, sizeof entries);
      if (size <= 0) break;
      for (long at = 0; at < size;) {
        // struct linux_dirent64: d_ino (8), d_off (8), d_reclen (2), d_type (1), d_name.
        unsigned short length = 0;
        std::memcpy(&length, entries + at + 16, sizeof length);
        const char* name = entries + at + 19;
        if (std::strcmp(name, ".") != 0 && std::strcmp(name, "..") != 0) ::unlinkat(fd, name, 0);
        at += length;
      }
    }
    ::close(fd);
  }
  ::rmdir(path);
}

extern "C" void removeTempFilesAndReraise(int signal_number) {
  g_temp_files.forEach([](const char* path) { ::unlink(path); });
  g_temp_dirs.forEach(removeFlatDirectory);
  // The signal is blocked while its handler runs: raised again, it ends the process on return.
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

/// Installs the handler, once, for each signal of kCleanedSignals still at its default action.
void installSignalHandlers() {
  static const bool installed = [] {
    struct sigaction cleanup {};
    cleanup.sa_handler = removeTempFilesAndReraise;
    sigemptyset(&cleanup.sa_mask);
    for (int signal_number : kCleanedSignals) {
      struct sigaction current {};
      if (::sigaction(signal_number, nullptr, &current) == 0 && !(current.sa_flags & SA_SIGINFO) &&
          current.sa_handler == SIG_DFL) {
        ::sigaction(signal_number, &cleanup, nullptr);
      }
    }
    return true;
  }();
  (void)installed;
}

int registerTempFile(const std::string& path) { return g_temp_files.add(path); }

void unregisterTempFile(int slot) { g_temp_files.remove(slot); }

}  // namespace

int registerTempDirectory(const std::string& path) {
  installSignalHandlers();
  return g_temp_dirs.add(path);
}

void unregisterTempDirectory(int slot) { g_temp_dirs.remove(slot); }

namespace {

/// The descriptor N that `path` names when it is `/proc/self/fd/N`, `/proc/thread-self/fd/N`,
/// `/proc/<this process>/fd/N` or `/dev/fd/N` (lexically).
std::optional<int> descriptorOf(const fs::path& path) {
  const std::string text = path.lexically_normal().string();
  for (const std::string& prefix :
       {std::string("/proc/self/fd/"), std::string("/proc/thread-self/fd/"),
        "/proc/" + std::to_string(::getpid()) + "/fd/", std::string("/dev/fd/")}) {
    if (text.size() <= prefix.size() || text.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string digits = text.substr(prefix.size());
    if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) {
      return std::nullopt;
    }
    return std::stoi(digits);
  }
  return std::nullopt;
}

/// Where a path leads: its final target after the links, or a descriptor of this process met on
/// the way (/dev/stdout -> /proc/self/fd/1), which the kernel resolves to what the descriptor
/// holds (a pipe, a terminal, a file opened with O_APPEND), not to a path to replace.
struct Resolved {
  std::string file;               ///< the path with its links followed (or where they stopped)
  std::optional<int> descriptor;  ///< the descriptor the chain reached, if any
};

/// `path` with its symbolic links followed to the end of the chain; for a dangling link, the
/// path the last link names.
Resolved followLinks(const std::string& path) {
  fs::path current(path);
  for (int hop = 0; hop < kMaxLinkHops; ++hop) {
    if (const std::optional<int> descriptor = descriptorOf(current)) {
      return {current.string(), descriptor};
    }
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(current, ec))) return {current.string(), std::nullopt};
    const fs::path next = fs::read_symlink(current, ec);
    if (ec) throw Error("cannot write '" + path + "': " + ec.message());
    current = next.is_absolute() ? next : current.parent_path() / next;
  }
  throw Error("cannot write '" + path + "': too many levels of symbolic links");
}

/// Refuses to write over a file this run reads (requireInputFile() noted it).
void refuseInput(const std::string& path, const struct stat& status) {
  if (const auto input = inputFileOf(status)) {
    throw UsageError("cannot write '" + path + "': it is the " + input->second + " '" +
                     input->first + "' this run reads");
  }
}

/// The directory a file lands in: its parent, or "." for a bare name.
fs::path directoryOf(const fs::path& file) {
  return file.has_parent_path() ? file.parent_path() : fs::path(".");
}

/// Where AtomicFile writes a path, checked.
struct Destination {
  std::string file;               ///< the path with its links followed
  bool write_through{false};      ///< an existing device, FIFO or socket, or a descriptor
  std::optional<int> descriptor;  ///< a descriptor of this process to write through
};

Destination checkDestination(const std::string& path) {
  if (path.empty()) throw Error("output path is empty");
  const Resolved resolved = followLinks(path);
  struct stat status {};
  if (resolved.descriptor) {
    if (::fstat(*resolved.descriptor, &status) != 0) {
      throw Error("cannot write '" + path + "': descriptor " +
                  std::to_string(*resolved.descriptor) + " is not open");
    }
    refuseInput(path, status);
    return {path, true, resolved.descriptor};
  }
  // A device reached through a link is opened by the kernel, which knows where such links lead:
  // the path is kept as given.
  if (::stat(path.c_str(), &status) == 0 && !S_ISREG(status.st_mode) && !S_ISDIR(status.st_mode)) {
    if (::access(path.c_str(), W_OK) != 0) {
      throw Error("cannot write '" + path + "': " + std::strerror(errno));
    }
    return {path, true, std::nullopt};
  }
  const std::string& file = resolved.file;
  const std::string what =
      "cannot write '" + path + "'" + (file == path ? "" : " (a link to '" + file + "')") + ": ";
  if (::stat(file.c_str(), &status) == 0) {
    if (S_ISDIR(status.st_mode)) throw Error(what + "it is a directory");
    refuseInput(path, status);
    // The mode bits, not access(): root may write anything, but a file marked read-only is
    // meant to stay as it is.
    if ((status.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0) {
      throw Error(what + "it is read-only");
    }
  }
  const fs::path dir = directoryOf(file);
  std::error_code ec;
  if (!fs::exists(dir, ec)) {
    throw Error(what + "directory '" + dir.string() + "' does not exist");
  }
  if (!fs::is_directory(dir, ec)) {
    throw Error(what + "'" + dir.string() + "' is not a directory");
  }
  if (::access(dir.c_str(), W_OK | X_OK) != 0) {
    throw Error(what + "directory '" + dir.string() + "' is not writable");
  }
  return {file, false, std::nullopt};
}

/// What identifies an output's file: "dev:inode" when it exists, else the canonical path of its
/// directory plus its name; nullopt for what is written through (replaces nothing).
std::optional<std::string> outputIdentity(const std::string& path) {
  Resolved resolved;
  try {
    resolved = followLinks(path);
  } catch (const Error&) {
    return std::nullopt;  // a loop of links: refused when written
  }
  if (resolved.descriptor) return std::nullopt;
  struct stat status {};
  if (::stat(resolved.file.c_str(), &status) == 0) {
    if (!S_ISREG(status.st_mode)) return std::nullopt;
    return std::to_string(status.st_dev) + ":" + std::to_string(status.st_ino);
  }
  const fs::path file(resolved.file);
  std::error_code ec;
  const fs::path dir = fs::weakly_canonical(fs::absolute(directoryOf(file), ec), ec);
  return "path:" + (dir / file.filename()).lexically_normal().string();
}

/// A fresh temporary name beside `file`: ".<start of its name>.mcws-<pid>-<n>".
std::string temporaryName(const std::string& file) {
  static std::atomic<unsigned> counter{0};
  const fs::path target(file);
  const std::string name = "." + target.filename().string().substr(0, kMaxNamePrefix) + ".mcws-" +
                           std::to_string(::getpid()) + "-" + std::to_string(counter++);
  return (directoryOf(target) / name).string();
}

}  // namespace

void checkOutputPath(const std::string& path) { checkDestination(path); }

bool sameOutputFile(const std::string& a, const std::string& b) {
  const std::optional<std::string> first = outputIdentity(a);
  return first && first == outputIdentity(b);
}

namespace {
thread_local OutputSet* g_current_set = nullptr;

/// Opens an existing device, FIFO or socket to write through, or duplicates the descriptor.
int openWriteThrough(const std::string& path, const std::string& target,
                     const std::optional<int>& descriptor) {
  if (descriptor) {
    const int fd = ::fcntl(*descriptor, F_DUPFD_CLOEXEC, 3);
    if (fd < 0) throw Error("cannot write '" + path + "': " + std::strerror(errno));
    return fd;
  }
  // Without O_NONBLOCK, opening a FIFO nobody reads would wait for a reader forever.
  const int fd = ::open(target.c_str(), O_WRONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0 && errno == ENXIO) throw Error("cannot write '" + path + "': no reader");
  if (fd < 0) throw Error("cannot write '" + path + "': " + std::strerror(errno));
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  return fd;
}

/// Writes all of `size` bytes to `fd`. \return false on an error (errno set).
bool writeAll(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t written = ::write(fd, data, size);
    if (written < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data += written;
    size -= static_cast<std::size_t>(written);
  }
  return true;
}
}  // namespace

/// The ranges of a file writeAt() has written: its start [0, contiguous), all written, and the
/// ranges written beyond it (a few: the threads write nearly in order).
struct AtomicFile::Written {
  std::mutex mutex;
  bool stream_flushed{false};  ///< `file_`'s buffer (what write() took) has been flushed
  std::uint64_t contiguous{0};
  std::map<std::uint64_t, std::uint64_t> ahead;  ///< begin -> end

  /// Adds [begin, end); returns the new `contiguous`.
  std::uint64_t add(std::uint64_t begin, std::uint64_t end) {
    if (begin > contiguous) {
      std::uint64_t& known = ahead[begin];
      known = std::max(known, end);
      return contiguous;
    }
    contiguous = std::max(contiguous, end);
    for (auto next = ahead.begin(); next != ahead.end() && next->first <= contiguous;) {
      contiguous = std::max(contiguous, next->second);
      next = ahead.erase(next);
    }
    return contiguous;
  }
};

AtomicFile::AtomicFile(std::string path)
    : path_(std::move(path)), written_(std::make_unique<Written>()) {
  const Destination destination = checkDestination(path_);
  target_ = destination.file;
  write_through_ = destination.write_through;
  installSignalHandlers();
  int fd = -1;
  if (write_through_) {
    fd = openWriteThrough(path_, target_, destination.descriptor);
    struct stat opened {};
    const bool null_device = ::fstat(fd, &opened) == 0 && S_ISCHR(opened.st_mode) &&
                             major(opened.st_rdev) == 1 && minor(opened.st_rdev) == 3;
    if (g_current_set && !null_device) {
      // Part of a set: the bytes wait in an unnamed buffer until the set is committed (but for
      // /dev/null, which takes everything and keeps nothing).
      device_ = fd;
      file_ = std::tmpfile();
      if (!file_) {
        const int tmpfile_errno = errno;
        discard();
        throw Error("cannot write '" + path_ +
                    "': no temporary buffer: " + std::strerror(tmpfile_errno));
      }
      return;
    }
  } else {
    fd = ::open(directoryOf(target_).c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
    unnamed_ = fd >= 0;
    if (fd < 0 && (errno == EOPNOTSUPP || errno == EISDIR || errno == EINVAL)) {
      // No O_TMPFILE on this file system: a named temporary file, removed on a signal.
      do {
        unregisterTempFile(signal_slot_);
        temp_path_ = temporaryName(target_);
        signal_slot_ = registerTempFile(temp_path_);
        fd = ::open(temp_path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
      } while (fd < 0 && errno == EEXIST);
      if (fd < 0) {
        const int open_errno = errno;
        unregisterTempFile(signal_slot_);
        signal_slot_ = -1;
        temp_path_.clear();
        errno = open_errno;
      }
    }
  }
  if (fd < 0) throw Error("cannot write '" + path_ + "': " + std::strerror(errno));
  file_ = ::fdopen(fd, "wb");
  if (!file_) {
    const int fdopen_errno = errno;
    ::close(fd);
    discard();
    throw Error("cannot write '" + path_ + "': " + std::strerror(fdopen_errno));
  }
}

AtomicFile::AtomicFile(AtomicFile&& other) noexcept
    : path_(std::move(other.path_)),
      target_(std::move(other.target_)),
      temp_path_(std::move(other.temp_path_)),
      file_(std::exchange(other.file_, nullptr)),
      appended_(other.appended_),
      writeback_to_(other.writeback_to_),
      written_(std::move(other.written_)),
      device_(std::exchange(other.device_, -1)),
      write_through_(other.write_through_),
      unnamed_(other.unnamed_),
      signal_slot_(std::exchange(other.signal_slot_, -1)) {
  other.temp_path_.clear();
}

AtomicFile::~AtomicFile() { discard(); }

void AtomicFile::discard() {
  if (file_) std::fclose(file_);
  file_ = nullptr;
  if (device_ >= 0) ::close(device_);
  device_ = -1;
  if (!temp_path_.empty()) ::unlink(temp_path_.c_str());
  temp_path_.clear();
  unregisterTempFile(signal_slot_);
  signal_slot_ = -1;
}

void AtomicFile::write(const void* data, std::size_t size) {
  if (!file_) throw Error("cannot write '" + path_ + "': it is closed");
  if (size > 0 && std::fwrite(data, 1, size, file_) != size) {
    throw Error("cannot write '" + path_ + "': " + std::strerror(errno));
  }
  // Every 8 MiB, the disk is asked to start writing what the file holds so far, without waiting
  // for it: the fdatasync() of finish() then finds a large file mostly written while the run was
  // computing, instead of writing all of it at the end. A failure here shows again, and is
  // reported, at finish().
  appended_ += size;
  const auto [begin, end] = writebackRange(appended_);
  if (end > begin && std::fflush(file_) == 0) {
    ::sync_file_range(::fileno(file_), static_cast<off_t>(begin), static_cast<off_t>(end - begin),
                      SYNC_FILE_RANGE_WRITE);
  }
}

std::pair<std::uint64_t, std::uint64_t> AtomicFile::writebackRange(std::uint64_t written) {
  constexpr std::uint64_t kWritebackBytes = std::uint64_t{8} << 20;
  // Whole pages only: a page still being filled, written now, would be written again, and the
  // write that fills it would wait for the disk.
  constexpr std::uint64_t kPage = 4096;
  const std::uint64_t end = written / kPage * kPage;
  // A regular file only (not a FIFO or a device written through, nor its buffer).
  if (write_through_ || end < writeback_to_ + kWritebackBytes) return {0, 0};
  return {std::exchange(writeback_to_, end), end};
}

void AtomicFile::reserve(std::uint64_t size) {
  if (!file_ || write_through_ || size == 0) return;
  ::fallocate(::fileno(file_), FALLOC_FL_KEEP_SIZE, 0, static_cast<off_t>(size));
}

void AtomicFile::writeAt(std::uint64_t offset, const void* data, std::size_t size) {
  if (!file_) throw Error("cannot write '" + path_ + "': it is closed");
  if (!positional()) {
    throw Error("cannot write '" + path_ + "' at an offset: it is not a regular file");
  }
  // What write() left in the stream's buffer goes first (the header of a PcdStreamWriter);
  // flushed once, it stays empty. Under the lock, so that no thread reads the stream (its
  // descriptor) while another flushes it.
  int fd = -1;
  {
    const std::lock_guard<std::mutex> lock(written_->mutex);
    if (!written_->stream_flushed) {
      if (std::fflush(file_) != 0) {
        throw Error("cannot write '" + path_ + "': " + std::strerror(errno));
      }
      written_->stream_flushed = true;
    }
    fd = ::fileno(file_);
  }
  const char* bytes = static_cast<const char*>(data);
  for (std::size_t left = size; left > 0;) {
    const ssize_t written =
        ::pwrite(fd, bytes + (size - left), left, static_cast<off_t>(offset + (size - left)));
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) {
      throw Error("cannot write '" + path_ +
                  "': " + (written < 0 ? std::strerror(errno) : "nothing written"));
    }
    left -= static_cast<std::size_t>(written);
  }
  // The writeback of write(), over the start of the file written in full: the ranges beyond it
  // wait for the threads still writing below them.
  std::pair<std::uint64_t, std::uint64_t> range;
  {
    const std::lock_guard<std::mutex> lock(written_->mutex);
    written_->contiguous = std::max(written_->contiguous, appended_);  // what write() took
    range = writebackRange(written_->add(offset, offset + size));
  }
  if (range.second > range.first) {
    ::sync_file_range(fd, static_cast<off_t>(range.first),
                      static_cast<off_t>(range.second - range.first), SYNC_FILE_RANGE_WRITE);
  }
}

void AtomicFile::linkTempFile() {
  const std::string fd_path = "/proc/self/fd/" + std::to_string(::fileno(file_));
  int linked = -1;
  do {
    unregisterTempFile(signal_slot_);
    temp_path_ = temporaryName(target_);
    signal_slot_ = registerTempFile(temp_path_);
    linked = ::linkat(AT_FDCWD, fd_path.c_str(), AT_FDCWD, temp_path_.c_str(), AT_SYMLINK_FOLLOW);
  } while (linked != 0 && errno == EEXIST);
  if (linked != 0) {
    const int link_errno = errno;
    temp_path_.clear();  // not linked: no name to remove
    discard();
    throw Error("cannot write '" + path_ + "': " + std::strerror(link_errno));
  }
  unnamed_ = false;
}

const std::string& AtomicFile::temporaryPath() {
  if (write_through_) {
    throw Error("cannot write '" + path_ + "' from several processes: it is not a regular file");
  }
  if (unnamed_) linkTempFile();
  return temp_path_;
}

void AtomicFile::finish() {
  if (!file_) throw Error("cannot write '" + path_ + "': it is closed");
  // The bytes on the disk before any name points at them: a crash after the rename never leaves
  // a target that is empty or short.
  const bool flushed = std::fflush(file_) == 0 && std::ferror(file_) == 0 &&
                       (write_through_ || ::fdatasync(::fileno(file_)) == 0);
  if (!flushed) {
    const int flush_errno = errno;
    discard();
    throw Error("cannot write '" + path_ + "': " + std::strerror(flush_errno));
  }
  if (!write_through_) {
    // An input the run opened after this output was made (a mesh of the robot file, ...).
    struct stat status {};
    if (::stat(target_.c_str(), &status) == 0) {
      try {
        refuseInput(path_, status);
      } catch (...) {
        discard();
        throw;
      }
    }
  }
}

void AtomicFile::sendBuffered() {
  if (device_ < 0) return;
  std::rewind(file_);
  char buffer[1 << 16];
  bool sent = true;
  int send_errno = 0;
  for (std::size_t got; (got = std::fread(buffer, 1, sizeof buffer, file_)) > 0;) {
    if (!writeAll(device_, buffer, got)) {
      sent = false;
      send_errno = errno;
      break;
    }
  }
  if (sent && std::ferror(file_)) {
    sent = false;
    send_errno = EIO;
  }
  const int device = std::exchange(device_, -1);
  if (::close(device) != 0 && sent && errno != EINTR) {
    sent = false;
    send_errno = errno;
  }
  if (!sent) {
    discard();
    throw Error("cannot write '" + path_ + "': " + std::strerror(send_errno));
  }
  std::fclose(std::exchange(file_, nullptr));
}

void AtomicFile::link() {
  if (write_through_) {
    if (!file_) return;  // a buffer already sent
    if (std::fclose(std::exchange(file_, nullptr)) != 0) {
      const int close_errno = errno;
      discard();
      throw Error("cannot write '" + path_ + "': " + std::strerror(close_errno));
    }
    return;
  }
  if (unnamed_) linkTempFile();
  if (std::fclose(std::exchange(file_, nullptr)) != 0) {
    const int close_errno = errno;
    discard();
    throw Error("cannot write '" + path_ + "': " + std::strerror(close_errno));
  }
}

void AtomicFile::rename() {
  if (write_through_) return;
  if (std::rename(temp_path_.c_str(), target_.c_str()) != 0) {
    const int rename_errno = errno;
    discard();
    throw Error("cannot write '" + path_ + "': " + std::strerror(rename_errno));
  }
  temp_path_.clear();  // the name is the target's now
  unregisterTempFile(signal_slot_);
  signal_slot_ = -1;
}

void AtomicFile::commit() {
  finish();
  if (g_current_set) {
    g_current_set->adopt(std::move(*this));
    return;
  }
  sendBuffered();
  link();
  rename();
}

void writeWholeFile(const std::string& path, const std::string& bytes) {
  AtomicFile file(path);
  file.write(bytes.data(), bytes.size());
  file.commit();
}

OutputSet::OutputSet() : previous_(g_current_set) { g_current_set = this; }

OutputSet::~OutputSet() {
  g_current_set = previous_;
  files_.clear();  // each AtomicFile removes what it has not renamed
}

OutputSet* OutputSet::current() { return g_current_set; }

void OutputSet::adopt(AtomicFile&& file) {
  if (committed_) throw Error("cannot write '" + file.path_ + "': its output set was committed");
  auto held = std::unique_ptr<AtomicFile>(new AtomicFile(std::move(file)));
  for (const auto& other : files_) {
    if (sameOutputFile(held->path_, other->path_)) {
      throw UsageError("'" + held->path_ + "' and '" + other->path_ +
                       "' are the same file: two outputs of one run must differ");
    }
  }
  files_.push_back(std::move(held));
}

void OutputSet::commit() {
  committed_ = true;
  g_current_set = previous_;
  for (auto& file : files_) file->sendBuffered();
  for (auto& file : files_) file->link();
  for (auto& file : files_) file->rename();
  files_.clear();
}

}  // namespace mcws::io
