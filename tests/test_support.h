#pragma once
// Helpers shared by the tests: paths, temporary directories, running a tool.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "mcws/core/error.h"

namespace mcws::test {

// The sanitizer build (MCWS_SANITIZE) runs the same code 3 to 80 times slower. The few tests whose
// size serves an exhaustive or statistical claim divide it by this there: the sanitizers look for
// memory errors and undefined behaviour, which a smaller case through the same code shows as well,
// while the release suite runs the full size (docs/testing.md).
#if defined(__SANITIZE_ADDRESS__)  // GCC
#define MCWS_TEST_ASAN 1
#elif defined(__has_feature)  // clang
#if __has_feature(address_sanitizer)
#define MCWS_TEST_ASAN 1
#endif
#endif
#if defined(MCWS_TEST_ASAN)
inline constexpr int kSanitizerShrink = 8;
#else
inline constexpr int kSanitizerShrink = 1;
#endif

/// The robot files of robots/ that every loader test reads.
inline const char* const kShippedRobots[] = {"deicing", "ta1400", "inspection6", "maintenance4",
                                             "insulator_cleaner"};

inline std::string robotPath(const std::string& name) {
  return std::string(MCWS_ROBOTS_DIR) + "/" + name + ".yaml";
}

inline std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// \brief A numeric CSV file with a header line, as the tools write trajectories and paths.
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  /// The last row; throws (a failed test rather than a crash) when there is none.
  const std::vector<double>& last() const {
    if (rows.empty()) throw std::runtime_error("the CSV has no rows");
    return rows.back();
  }
  /// The index of a named column (a failure and 0 when there is none).
  int column(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i) {
      if (header[i] == name) return static_cast<int>(i);
    }
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
  /// The largest value (or absolute value) of a column.
  double max(const std::string& name, bool absolute) const {
    const int c = column(name);
    double best = -1e300;
    for (const auto& row : rows) best = std::max(best, absolute ? std::abs(row[c]) : row[c]);
    return best;
  }
};

/// \brief Parses CSV text; a row with another cell count than the header throws.
inline Csv parseCsv(const std::string& text) {
  Csv csv;
  std::istringstream lines(text);
  std::string line;
  std::getline(lines, line);
  std::istringstream head(line);
  for (std::string cell; std::getline(head, cell, ',');) csv.header.push_back(cell);
  while (std::getline(lines, line)) {
    std::vector<double> row;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
    if (row.size() != csv.header.size()) {  // a failed test, not a read past the row's end
      throw std::runtime_error("CSV row '" + line + "' has " + std::to_string(row.size()) +
                               " cells, the header " + std::to_string(csv.header.size()));
    }
    csv.rows.push_back(row);
  }
  return csv;
}

inline void writeFile(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

/// A fresh directory under the system temp dir, removed with its contents at scope exit.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "mcws_test_XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  /// Names of the files in the directory (to check that nothing partial was left).
  std::size_t fileCount() const {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(path_)) ++n;
    return n;
  }

 private:
  std::filesystem::path path_;
};

/// Result of running a command through the shell.
struct RunResult {
  int exit_code{-1};
  std::string out, err;
};

/// Runs `command` (a shell command line) with stdout and stderr captured.
inline RunResult run(const std::string& command) {
  TempDir dir;
  const std::string out = dir.file("stdout"), err = dir.file("stderr");
  const int status = std::system((command + " >" + out + " 2>" + err + " </dev/null").c_str());
  RunResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = readFile(out);
  result.err = readFile(err);
  return result;
}

/// The message of the mcws::Error that `call` throws ("" and a failure when it throws none).
template <typename Call>
std::string errorOf(Call&& call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no mcws::Error thrown";
  return "";
}

/// `text` with the first `from` replaced by `to` (a failure when `from` is not in it).
inline std::string replaceOnce(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

/// Replaces every `from` in `text` by `to`.
inline void replaceAll(std::string& text, const std::string& from, const std::string& to) {
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
}

/// Number of lines in a text.
inline int lineCount(const std::string& text) {
  int lines = 0;
  for (char c : text) lines += c == '\n';
  return lines;
}

/// Runs a stage tool that must fail: its exit code, one line on stderr "tool: ...message...",
/// nothing on stdout, and nothing written into `output_dir`.
inline void expectToolFailure(const std::string& tool, const std::string& args, int exit_code,
                              const std::string& message, const TempDir& output_dir) {
  const RunResult r = run(tool + " " + args);
  const std::string name = std::filesystem::path(tool).filename().string();
  EXPECT_EQ(r.exit_code, exit_code) << args << "\n" << r.err;
  EXPECT_EQ(r.err.rfind(name + ": ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(message), std::string::npos)
      << args << "\nwanted: " << message << "\ngot: " << r.err;
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_EQ(output_dir.fileCount(), 0u) << args;
}

}  // namespace mcws::test
