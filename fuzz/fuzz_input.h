#pragma once
/// \file
/// \brief What the libFuzzer targets of fuzz/ share: the input as text, the only exception a
/// loader may throw, and a per-process file for loaders that read a path.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "mcws/core/error.h"

namespace mcws::fuzz {

/// \brief The fuzzer's bytes as a string (embedded NULs and invalid UTF-8 kept).
inline std::string text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// \brief Runs `load`, accepting only mcws::Error: the loaders document no other exception, so
/// any other escapes, ends the process and libFuzzer reports it as a crash (as it does a
/// sanitizer report, a leak or a timeout).
template <typename Load>
void expectOnlyMcwsErrors(Load&& load) {
  try {
    load();
  } catch (const Error&) {
    // a refused input: the expected outcome for almost every mutation
  }
}

/// \brief A file of this process under a directory made once in /tmp (removed at exit), for a
/// loader that takes a path. Each call overwrites the file with `bytes`.
/// \param name the file's name, whose extension the loader may look at (e.g. "input.pcd").
/// \return the file's path.
inline std::string writeInputFile(const std::string& bytes, const std::string& name) {
  static const std::filesystem::path dir = [] {
    char pattern[] = "/tmp/mcws_fuzz.XXXXXX";
    if (!mkdtemp(pattern)) {
      std::perror("mkdtemp");
      std::abort();
    }
    static std::filesystem::path made;
    made = pattern;
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(made, ec);
    });
    return made;
  }();
  const std::filesystem::path path = dir / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) {
    std::perror(path.c_str());
    std::abort();
  }
  return path.string();
}

}  // namespace mcws::fuzz
