#include "mcws/io/gnuplot.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "mcws/core/error.h"

extern char** environ;

namespace mcws::io {

namespace fs = std::filesystem;

namespace {

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Runs `gnuplot script`, stdout and stderr into `log`. \return exit status, or -1 on spawn error.
int spawnGnuplot(const std::string& script, const std::string& log, int& spawn_errno) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  std::string program = "gnuplot", argument = script;
  char* argv[] = {program.data(), argument.data(), nullptr};
  pid_t pid = 0;
  spawn_errno = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawn_errno != 0) return -1;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace

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

std::string runGnuplot(const ScratchDir& dir, const std::string& script, const std::string& png) {
  const std::string script_path = dir.file("plot.gp"), log = dir.file("gnuplot.log");
  std::ofstream(script_path, std::ios::binary) << script;
  int spawn_errno = 0;
  const int status = spawnGnuplot(script_path, log, spawn_errno);
  if (status < 0) {
    throw Error(std::string("cannot run gnuplot (package gnuplot-nox): ") +
                std::strerror(spawn_errno ? spawn_errno : errno));
  }
  const std::string bytes = readAll(png);
  if (status != 0 || bytes.rfind("\x89PNG", 0) != 0) {
    const std::string text = readAll(log);
    std::istringstream lines(text);
    std::string line, message;
    while (std::getline(lines, line)) {
      if (!line.empty() && line.find_first_not_of(" \t^") != std::string::npos) message = line;
    }
    throw Error("gnuplot failed (exit " + std::to_string(status) + ")" +
                (message.empty() ? "" : ": " + message));
  }
  return bytes;
}

}  // namespace mcws::io
