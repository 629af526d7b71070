#pragma once
/// \file
/// \brief What every mcws_* stage tool shares: flag parsing that tells a missing flag from a
/// malformed one, exit codes, one-line errors, progress on stderr.

#include <Eigen/Core>
#include <boost/program_options.hpp>
#include <chrono>
#include <cstdint>
#include <exception>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mcws/core/activity.h"
#include "mcws/core/error.h"

#include "mcws/distributed/processes.h"
#include "mcws/io/progress.h"

namespace mcws::app {

namespace po = boost::program_options;

constexpr int kExitOk = 0;       ///< success, or --help
constexpr int kExitFailure = 1;  ///< a failed load, save or computation
constexpr int kExitUsage = 2;    ///< a bad command line

/// \brief A bad command line (exit code 2).
using UsageError = mcws::UsageError;

/// \brief Runs a tool's body: mcws::app::UsageError and Boost.Program_options errors print
/// "program: message" and return 2, every other error prints it and returns 1. Running out of
/// memory (std::bad_alloc, which names nothing) is reported with the innermost Activity and the
/// flags given: "out of memory while reading --input 'a.pcd' (given: --input a.pcd --radius 2)".
/// Control bytes in a message are escaped (escapedControlBytes()), so it stays one line.
int run(const char* program, const std::function<int()>& body);

/// \brief run() for a tool that may run on several processes (mpirun): `body` calls
/// processes.setUpDone() once its command line and inputs are read. A failure before that point
/// (a bad flag, a bad file, on any process) is agreed on there: the first process that failed
/// prints its one line and every process returns the worst exit code. A failure after it is
/// printed by the process it happened on, which ends every process (Processes::abortAll()).
int run(const char* program, distributed::Processes& processes, const std::function<int()>& body);

using mcws::Activity;

/// \brief Flags of one tool (long options only, so "--q '-1 0.5'" reads as a value).
class CommandLine {
 public:
  /// \param usage first help line, e.g. "mcws_fk --robot FILE --q \"q1 q2 ...\" [options]".
  /// \param summary what the tool does, one paragraph.
  CommandLine(std::string usage, std::string summary);
  /// \brief Declares a flag that takes a value, read with required(), text() or has().
  void addValue(const char* flag, const char* help);
  /// \brief Declares a flag that may be given several times, read with all().
  void addValues(const char* flag, const char* help);
  /// \brief Declares a flag without a value, read with has().
  void addSwitch(const char* flag, const char* help);
  /// \brief Where flags are declared, Boost's way (prefer addValue() and its siblings: one flag
  /// a line).
  po::options_description_easy_init add() { return options_.add_options(); }
  /// \brief Parses argv. \return false when --help was given (help printed to stdout).
  /// \throws UsageError for unknown flags, stray arguments, missing values (a value that starts
  ///   with "--" is taken for a forgotten value) or repeated single flags.
  bool parse(int argc, char** argv);

  bool has(const std::string& flag) const { return values_.count(flag) > 0; }
  /// \brief The text of a flag that must be present. \throws UsageError when missing.
  std::string required(const std::string& flag) const;
  /// \brief The text of a flag, or `fallback`.
  std::string text(const std::string& flag, const std::string& fallback) const;
  /// \brief Every value of a repeatable flag.
  std::vector<std::string> all(const std::string& flag) const;

 private:
  std::string usage_, summary_;
  po::options_description options_;
  po::variables_map values_;
};

/// \brief A number in a short form for messages: 6 significant digits, no trailing zeros
/// (0.102375, 39, 1e+30).
std::string shortNumber(double value);
/// \brief A real number; "0.5x", "", "nan" are errors naming the flag.
double parseNumber(const std::string& text, const std::string& flag);
/// \brief A whole number in [minimum, maximum]; "10x", "-3", "1e3" are errors naming the flag.
std::int64_t parseInteger(const std::string& text, const std::string& flag, std::int64_t minimum,
                          std::int64_t maximum);
/// \brief Numbers separated by spaces or commas, e.g. "0.1 -2, 3".
Eigen::VectorXd parseNumberList(const std::string& text, const std::string& flag);
/// \brief "name=value" pairs separated by commas, e.g. "theta3=0,a2=30".
std::vector<std::pair<std::string, double>> parseAssignments(const std::string& text,
                                                             const std::string& flag);

/// \brief A file named on the command line: the flag (without "--") and the path, e.g.
/// {"input", "a.pcd"}. A path that comes from another file has a label that reads after "--",
/// e.g. {"scenario's robot", path}.
using FlagPath = std::pair<std::string, std::string>;

/// \brief Checks a tool's output files before anything is computed: each output with a non-empty
/// path must differ from the other outputs and from every input with a non-empty path, and
/// mcws::io::checkOutputPath() must accept it (directory exists and is writable, not read-only).
/// Two paths are the same file when they are equal, name the same existing file (std::filesystem
/// ::equivalent: through symbolic or hard links) or resolve to the same path (weakly_canonical:
/// "./a.pcd" is "a.pcd"). An existing device, FIFO or socket is written through, so it replaces
/// nothing and is never the same file as another.
/// \throws UsageError "--output: 'a.pcd' is the same file as --input" or "--plot: must differ
///   from --output"; mcws::Error (exit 1) for a directory that is missing or not writable or a
///   read-only file.
void checkOutputs(const std::vector<FlagPath>& outputs, const std::vector<FlagPath>& inputs);

using io::Progress;

}  // namespace mcws::app
