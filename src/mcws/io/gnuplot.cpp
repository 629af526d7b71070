#include "mcws/io/gnuplot.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "mcws/core/error.h"
#include "mcws/io/process.h"

namespace mcws::io {

namespace fs = std::filesystem;

ScratchDir::ScratchDir() {
  std::string pattern = (fs::temp_directory_path() / "mcws_plot_XXXXXX").string();
  if (!::mkdtemp(pattern.data())) {
    throw Error(std::string("cannot create a temporary directory: ") + std::strerror(errno));
  }
  path_ = pattern;
}

ScratchDir::~ScratchDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

std::string gnuplotQuoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') out += '\'';
    if (c != '\n') out += c;
  }
  return out + "'";
}

std::string runGnuplot(const ScratchDir& dir, const std::string& script,
                       const std::string& picture) {
  const std::string script_path = dir.file("plot.gp"), log = dir.file("gnuplot.log");
  std::ofstream(script_path, std::ios::binary) << script;
  int spawn_errno = 0;
  const int status = runProgram({"gnuplot", script_path}, log, spawn_errno);
  if (status < 0) {
    throw Error(std::string("cannot run gnuplot (package gnuplot-nox): ") +
                std::strerror(spawn_errno));
  }
  const std::string bytes = readFile(picture);
  const bool svg = picture.size() >= 4 && picture.compare(picture.size() - 4, 4, ".svg") == 0;
  const bool complete =
      svg ? bytes.find("</svg>") != std::string::npos : bytes.rfind("\x89PNG", 0) == 0;
  if (status != 0 || !complete) {
    // Lines of blanks and carets are gnuplot's pointers at the bad spot of the line before.
    const std::string message = lastLine(readFile(log), " \t^");
    throw Error("gnuplot failed (exit " + std::to_string(status) + ")" +
                (message.empty() ? "" : ": " + message));
  }
  return bytes;
}

}  // namespace mcws::io
