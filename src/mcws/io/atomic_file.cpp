#include "mcws/io/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <mutex>

#include "mcws/core/error.h"

namespace mcws::io {
namespace fs = std::filesystem;

namespace {

// Temporary names to remove if a signal ends the process. A fixed table: the handler may only
// call async-signal-safe functions (unlink, signal, raise) and read lock-free atomics.
constexpr int kMaxOpenFiles = 32;
constexpr std::size_t kMaxPath = 4096;
char g_temp_paths[kMaxOpenFiles][kMaxPath];
std::atomic<bool> g_temp_used[kMaxOpenFiles];

/// Signals whose default action ends the process and that a handler can catch.
constexpr int kCleanedSignals[] = {SIGINT,  SIGTERM, SIGHUP,  SIGPIPE,   SIGQUIT, SIGXFSZ,
                                   SIGUSR1, SIGUSR2, SIGALRM, SIGVTALRM, SIGPROF};

/// Links followed before giving up, as the kernel's limit (MAXSYMLINKS).
constexpr int kMaxLinkHops = 40;
/// Bytes of the target's name kept in a temporary name: with the dot, ".mcws-", a pid and a
/// counter (at most 10 digits each) the name stays within NAME_MAX.
constexpr std::size_t kMaxNamePrefix = 200;
static_assert(1 + kMaxNamePrefix + 6 + 10 + 1 + 10 <= NAME_MAX);

extern "C" void removeTempFilesAndReraise(int signal_number) {
  for (int k = 0; k < kMaxOpenFiles; ++k) {
    if (g_temp_used[k].load()) ::unlink(g_temp_paths[k]);
  }
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

int registerTempFile(const std::string& path) {
  static std::mutex mutex;
  const std::lock_guard<std::mutex> lock(mutex);
  if (path.size() >= kMaxPath) return -1;
  for (int k = 0; k < kMaxOpenFiles; ++k) {
    if (!g_temp_used[k].load()) {
      std::memcpy(g_temp_paths[k], path.c_str(), path.size() + 1);
      g_temp_used[k].store(true);
      return k;
    }
  }
  return -1;  // more files open than the table holds: those are not cleaned up on a signal
}

void unregisterTempFile(int slot) {
  if (slot >= 0) g_temp_used[slot].store(false);
}

/// `path` with its symbolic links followed to the end of the chain; for a dangling link, the
/// path the last link names.
std::string followLinks(const std::string& path) {
  fs::path current(path);
  for (int hop = 0; hop < kMaxLinkHops; ++hop) {
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(current, ec))) return current.string();
    const fs::path next = fs::read_symlink(current, ec);
    if (ec) throw Error("cannot write '" + path + "': " + ec.message());
    current = next.is_absolute() ? next : current.parent_path() / next;
  }
  throw Error("cannot write '" + path + "': too many levels of symbolic links");
}

/// The directory a file lands in: its parent, or "." for a bare name.
fs::path directoryOf(const fs::path& file) {
  return file.has_parent_path() ? file.parent_path() : fs::path(".");
}

/// Where AtomicFile writes a path, checked.
struct Destination {
  std::string file;           ///< the path with its links followed
  bool write_through{false};  ///< an existing device, FIFO or socket
};

Destination checkDestination(const std::string& path) {
  if (path.empty()) throw Error("output path is empty");
  // A device reached through a link (/dev/stdout -> /proc/self/fd/1 -> pipe:[...]) is opened by
  // the kernel, which knows where such links lead: the path is kept as given.
  struct stat status {};
  if (::stat(path.c_str(), &status) == 0 && !S_ISREG(status.st_mode) && !S_ISDIR(status.st_mode)) {
    if (::access(path.c_str(), W_OK) != 0) {
      throw Error("cannot write '" + path + "': " + std::strerror(errno));
    }
    return {path, true};
  }
  const std::string file = followLinks(path);
  const std::string what =
      "cannot write '" + path + "'" + (file == path ? "" : " (a link to '" + file + "')") + ": ";
  if (::stat(file.c_str(), &status) == 0) {
    if (S_ISDIR(status.st_mode)) throw Error(what + "it is a directory");
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
  return {file, false};
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

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  const Destination destination = checkDestination(path_);
  target_ = destination.file;
  write_through_ = destination.write_through;
  installSignalHandlers();
  int fd = -1;
  if (write_through_) {
    // Without O_NONBLOCK, opening a FIFO nobody reads would wait for a reader forever.
    fd = ::open(target_.c_str(), O_WRONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0 && errno == ENXIO) throw Error("cannot write '" + path_ + "': no reader");
    if (fd >= 0) ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
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

AtomicFile::~AtomicFile() { discard(); }

void AtomicFile::discard() {
  if (file_) std::fclose(file_);
  file_ = nullptr;
  if (!temp_path_.empty()) ::unlink(temp_path_.c_str());
  temp_path_.clear();
  unregisterTempFile(signal_slot_);
  signal_slot_ = -1;
}

void AtomicFile::write(const void* data, std::size_t size) {
  if (size > 0 && std::fwrite(data, 1, size, file_) != size) {
    throw Error("cannot write '" + path_ + "': " + std::strerror(errno));
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

void AtomicFile::commit() {
  const bool flushed = std::fflush(file_) == 0 && std::ferror(file_) == 0;
  if (!flushed) {
    const int flush_errno = errno;
    discard();
    throw Error("cannot write '" + path_ + "': " + std::strerror(flush_errno));
  }
  if (unnamed_) linkTempFile();
  std::FILE* file = file_;
  file_ = nullptr;
  if (std::fclose(file) != 0) {
    const int close_errno = errno;
    discard();
    throw Error("cannot write '" + path_ + "': " + std::strerror(close_errno));
  }
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

}  // namespace mcws::io
