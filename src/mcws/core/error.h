#pragma once
/// \file
/// \brief The one exception type of mcws.

#include <stdexcept>
#include <string>

namespace mcws {

/// \brief A configuration or programmer error: a bad robot file, flag or argument.
///
/// The message is one line and names the file, row, joint or flag and the bad value.
/// Expected outcomes (no IK solution, a collision, a planner timeout) are never thrown;
/// they come back as a status or std::optional.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

/// \brief An error of the command line or of what it names together (a flag's bad value, two
/// outputs that are one file, an output that is one of the run's inputs): the tools exit with
/// code 2 for it, 1 for every other Error.
class UsageError : public Error {
 public:
  using Error::Error;
};

/// \brief Runs `call`, turning an mcws::Error it throws (a bad value found by a library
/// function) into a UsageError "`what`: message", `what` naming what the caller passed: a flag
/// ("--fix") or an argument ("q"). A UsageError passes unchanged.
template <typename Call>
auto asUsageError(const std::string& what, Call&& call) -> decltype(call()) {
  try {
    return call();
  } catch (const UsageError&) {
    throw;
  } catch (const Error& e) {
    throw UsageError(what + ": " + e.what());
  }
}

}  // namespace mcws
