#include "mcws/io/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "mcws/core/error.h"

namespace mcws::io {
namespace fs = std::filesystem;

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
}

AtomicFile::~AtomicFile() {
  if (file_) {
    std::fclose(file_);
    std::remove(temp_path_.c_str());
  }
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
}

}  // namespace mcws::io
