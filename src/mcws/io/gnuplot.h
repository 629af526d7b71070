#pragma once
/// \file
/// \brief PNG and SVG pictures drawn by gnuplot (Debian package gnuplot-nox), run as a child
/// process.

#include <filesystem>
#include <string>

namespace mcws::io {

/// \brief A directory under the system's temporary directory, removed with its contents at
/// scope exit (data and script files for gnuplot).
class ScratchDir {
 public:
  /// \throws mcws::Error when the directory cannot be created.
  ScratchDir();
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  /// \brief Path of a file in the directory.
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

/// \brief A string as a gnuplot single-quoted literal (newlines dropped).
std::string gnuplotQuoted(const std::string& text);

/// \brief Runs gnuplot on `script`, which must write a PNG, or an SVG when the name ends in
/// ".svg", to `picture` (e.g. with `set terminal pngcairo` and `set output`), both files in `dir`.
/// \return the picture file's bytes.
/// \throws mcws::Error when gnuplot is missing or fails (with its last message line).
std::string runGnuplot(const ScratchDir& dir, const std::string& script,
                       const std::string& picture);

}  // namespace mcws::io
