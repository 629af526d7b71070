#pragma once
/// \file
/// \brief Child processes (gnuplot, Graphviz dot) run to completion, and reading what they left.

#include <string>
#include <vector>

namespace mcws::io {

/// \brief Runs `argv` (argv[0] the program) and waits for it: stdin from /dev/null, stdout and
/// stderr into the file `log_path` (created or truncated, mode 0600). A program name without a
/// slash is looked up on PATH (posix_spawnp); a path with one is run as given (posix_spawn).
/// \param spawn_errno set to the errno of the failure when the program cannot be started or
/// waited for.
/// \return the exit status, 128 + the signal number when a signal ended it, or -1 when it could
/// not be started or waited for.
int runProgram(const std::vector<std::string>& argv, const std::string& log_path, int& spawn_errno);

/// \brief The executable regular file `name` in a directory of PATH (an empty entry meaning
/// "."), "dir/name"; "" when there is none or PATH is unset.
std::string findOnPath(const std::string& name);

/// \brief The bytes of the file at `path`; "" when it cannot be read.
std::string readFile(const std::string& path);

/// \brief The last line of `text` holding a character not in `blank` ("" when none): a
/// program's last message in its log.
std::string lastLine(const std::string& text, const std::string& blank);

}  // namespace mcws::io
