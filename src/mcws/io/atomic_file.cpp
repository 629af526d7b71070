#include "mcws/io/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <mutex>

#include "mcws/core/error.h"

namespace mcws::io {
namespace fs = std::filesystem;

namespace {

// Temporary files to remove if a signal ends the process. A fixed table: the handler may only
// call async-signal-safe functions (unlink, signal, raise) and read lock-free atomics.
constexpr int kMaxOpenFiles = 32;
constexpr std::size_t kMaxPath = 4096;
char g_temp_paths[kMaxOpenFiles][kMaxPath];
std::atomic<bool> g_temp_used[kMaxOpenFiles];

extern "C" void removeTempFilesAndReraise(int signal_number) {
  for (int k = 0; k < kMaxOpenFiles; ++k) {
    if (g_temp_used[k].load()) ::unlink(g_temp_paths[k]);
  }
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

int registerTempFile(const std::string& path) {
  static const bool installed = [] {
    for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
      std::signal(signal_number, removeTempFilesAndReraise);
    }
    return true;
  }();
  (void)installed;
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

}  // namespace

void checkOutputPath(const std::string& path) {
  if (path.empty()) throw Error("output path is empty");
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::exists(dir, ec)) {
    throw Error("cannot write '" + path + "': directory '" + dir.string() + "' does not exist");
  }
  if (!fs::is_directory(dir, ec)) {
    throw Error("cannot write '" + path + "': '" + dir.string() + "' is not a directory");
  }
  if (::access(dir.c_str(), W_OK | X_OK) != 0) {
    throw Error("cannot write '" + path + "': directory '" + dir.string() + "' is not writable");
  }
  if (fs::is_directory(target, ec)) {
    throw Error("cannot write '" + path + "': it is a directory");
  }
}

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  checkOutputPath(path_);
  temp_path_ = path_ + ".tmp." + std::to_string(::getpid());
  file_ = std::fopen(temp_path_.c_str(), "wb");
  if (!file_) {
    throw Error("cannot write '" + path_ + "': " + std::strerror(errno));
  }
  signal_slot_ = registerTempFile(temp_path_);
}

AtomicFile::~AtomicFile() {
  if (file_) {
    std::fclose(file_);
    std::remove(temp_path_.c_str());
  }
  unregisterTempFile(signal_slot_);
}

void AtomicFile::write(const void* data, std::size_t size) {
  if (size > 0 && std::fwrite(data, 1, size, file_) != size) {
    throw Error("cannot write '" + path_ + "': " + std::strerror(errno));
  }
}

void AtomicFile::commit() {
  std::FILE* file = file_;
  file_ = nullptr;
  const bool ok = std::fflush(file) == 0 && std::ferror(file) == 0;
  const int saved_errno = errno;
  if (std::fclose(file) != 0 || !ok) {
    std::remove(temp_path_.c_str());
    throw Error("cannot write '" + path_ + "': " + std::strerror(ok ? errno : saved_errno));
  }
  if (std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    const int rename_errno = errno;
    std::remove(temp_path_.c_str());
    throw Error("cannot write '" + path_ + "': " + std::strerror(rename_errno));
  }
  unregisterTempFile(signal_slot_);
  signal_slot_ = -1;
}

}  // namespace mcws::io
