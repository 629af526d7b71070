#include "common/app.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <new>
#include <sstream>

#include "mcws/core/control_bytes.h"
#include "mcws/core/decimal.h"
#include "mcws/core/input_files.h"
#include "mcws/core/length_text.h"
#include "mcws/io/atomic_file.h"

namespace mcws::app {

namespace {

/// The flags of the command line, as given, for the out-of-memory message ("" before parsing).
std::string& givenFlags() {
  static std::string given;
  return given;
}

/// run()'s body with the error line returned in `message` (with its newline) instead of printed.
int runCapturing(const char* program, const std::function<int()>& body, std::string& message) {
  const RunInputs inputs;  // the files the run reads, which none of its outputs may replace
  try {
    return body();
  } catch (const distributed::OtherProcessFailed& e) {
    return e.code;  // reported by the process that failed
  } catch (const std::bad_alloc&) {
    const std::string activity = Activity::takeFailed();
    message = std::string(program) + ": out of memory" +
              (activity.empty() ? std::string() : " while " + activity) +
              (givenFlags().empty() ? std::string() : " (given: " + givenFlags() + ")") +
              ": a file or flag asks for more than this machine has\n";
    return kExitFailure;
  } catch (const UsageError& e) {
    message = std::string(program) + ": " + escapedControlBytes(e.what()) + " (see --help)\n";
    return kExitUsage;
  } catch (const po::error& e) {
    message = std::string(program) + ": " + escapedControlBytes(e.what()) + " (see --help)\n";
    return kExitUsage;
  } catch (const std::exception& e) {
    message = std::string(program) + ": " + escapedControlBytes(e.what()) + "\n";
    return kExitFailure;
  }
}

}  // namespace

int run(const char* program, const std::function<int()>& body) {
  std::string message;
  const int code = runCapturing(program, body, message);
  std::cerr << message;
  return code;
}

int run(const char* program, distributed::Processes& processes, const std::function<int()>& body) {
  std::string message;
  const int code = runCapturing(
      program,
      [&] {
        processes.require();
        return body();
      },
      message);
  if (!processes.distributed()) {
    std::cerr << message;
    return code;
  }
  if (!processes.setUpAgreed()) {
    if (code == kExitOk) return code;  // --help: no process went further
    // Failed in its set-up: the others agree on it at the end of theirs, and the first process
    // that failed reports.
    const distributed::Agreement agreement = processes.agreeOnSetUp(code);
    if (processes.rank() == agreement.first_failed) std::cerr << message;
    processes.barrier();  // the launcher ends the run at the first exit: report first
    return agreement.code;
  }
  if (processes.setUpFailed()) {  // found at the agreement: the process it names reports
    if (processes.rank() == processes.setUpFirstFailed()) std::cerr << message;
    processes.barrier();
    return code;
  }
  // Failed on its own after the set-up: it reports, and ends every process.
  std::cerr << message;
  if (code != kExitOk) processes.abortAll(code);
  return code;
}

CommandLine::CommandLine(std::string usage, std::string summary)
    : usage_(std::move(usage)), summary_(std::move(summary)), options_("Options") {
  options_.add_options()("help", "print this help and exit");
}

void CommandLine::addValue(const char* flag, const char* help) {
  options_.add_options()(flag, po::value<std::string>(), help);
}

void CommandLine::addValues(const char* flag, const char* help) {
  options_.add_options()(flag, po::value<std::vector<std::string>>(), help);
}

void CommandLine::addSwitch(const char* flag, const char* help) {
  options_.add_options()(flag, help);
}

bool CommandLine::parse(int argc, char** argv) {
  const auto style = po::command_line_style::allow_long |
                     po::command_line_style::long_allow_adjacent |
                     po::command_line_style::long_allow_next;
  const po::positional_options_description no_positionals;
  po::store(po::command_line_parser(argc, argv)
                .options(options_)
                .positional(no_positionals)
                .style(style)
                .run(),
            values_);
  if (values_.count("help")) {
    std::cout << "Usage: " << usage_ << "\n\n" << summary_ << "\n\n" << options_ << "\n";
    return false;
  }
  po::notify(values_);
  std::string& given = givenFlags();
  given.clear();
  for (int k = 1; k < argc; ++k) {
    std::string word = escapedControlBytes(argv[k]);
    if (word.size() > 60) word = word.substr(0, 60) + "...";
    given += (k > 1 ? " " : "") + word;
  }
  if (given.size() > 300) given = given.substr(0, 300) + "...";
  for (const auto& [flag, value] : values_) {
    const auto* text = boost::any_cast<std::string>(&value.value());
    if (text && text->rfind("--", 0) == 0) {
      throw UsageError("--" + flag + " has no value (next comes '" + *text + "')");
    }
    // An empty value ("--output ''", an unset shell variable) names nothing: never a default.
    const bool takes_value = options_.find(flag, false).semantic()->max_tokens() > 0;
    if (takes_value && text && text->empty()) {
      throw UsageError("--" + flag + ": the value is empty");
    }
    if (const auto* texts = boost::any_cast<std::vector<std::string>>(&value.value())) {
      for (const std::string& t : *texts) {
        if (t.rfind("--", 0) == 0)
          throw UsageError("--" + flag + " has no value (next comes '" + t + "')");
        if (t.empty()) throw UsageError("--" + flag + ": a value is empty");
      }
    }
  }
  return true;
}

std::string CommandLine::required(const std::string& flag) const {
  if (!has(flag)) throw UsageError("missing --" + flag);
  return values_[flag].as<std::string>();
}

std::string CommandLine::text(const std::string& flag, const std::string& fallback) const {
  return has(flag) ? values_[flag].as<std::string>() : fallback;
}

std::vector<std::string> CommandLine::all(const std::string& flag) const {
  return has(flag) ? values_[flag].as<std::vector<std::string>>() : std::vector<std::string>{};
}

std::string shortNumber(double value) { return formatNumber(value); }

double parseNumber(const std::string& text, const std::string& flag) {
  return mcws::decimalFromText(text, "--" + flag);
}

std::int64_t parseInteger(const std::string& text, const std::string& flag, std::int64_t minimum,
                          std::int64_t maximum) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(begin, &end, 10);
  const bool digits =
      !text.empty() &&
      text.find_first_not_of("0123456789", text[0] == '-' || text[0] == '+') == std::string::npos &&
      text.size() > (text[0] == '-' || text[0] == '+' ? 1u : 0u);
  if (!digits || end != begin + text.size()) {
    throw UsageError("--" + flag + ": '" + text + "' is not a whole number");
  }
  if (errno == ERANGE) {  // a whole number all the same, beyond what any flag takes
    throw UsageError("--" + flag + ": " + text + " is " +
                     (text[0] == '-' ? "less than " + std::to_string(minimum)
                                     : "more than " + std::to_string(maximum)));
  }
  if (value < minimum) {
    throw UsageError("--" + flag + ": " + text + " is less than " + std::to_string(minimum));
  }
  if (value > maximum) {
    throw UsageError("--" + flag + ": " + text + " is more than " + std::to_string(maximum));
  }
  return value;
}

Eigen::VectorXd parseNumberList(const std::string& text, const std::string& flag) {
  std::vector<double> values;
  std::istringstream items(text);
  for (std::string item; std::getline(items, item, ',');) {
    std::istringstream in(item);
    std::size_t before = values.size();
    for (std::string word; in >> word;) values.push_back(parseNumber(word, flag));
    if (values.size() == before && text.find(',') != std::string::npos) {
      throw UsageError("--" + flag + ": no number between commas in '" + text + "'");
    }
  }
  if (!text.empty() && text.back() == ',') {
    throw UsageError("--" + flag + ": no number after the last comma in '" + text + "'");
  }
  if (values.empty()) throw UsageError("--" + flag + ": no numbers in '" + text + "'");
  return Eigen::Map<Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

std::vector<std::pair<std::string, double>> parseAssignments(const std::string& text,
                                                             const std::string& flag) {
  std::vector<std::pair<std::string, double>> pairs;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    const auto equals = item.find('=');
    if (equals == std::string::npos || equals == 0) {
      throw UsageError("--" + flag + ": '" + item + "' is not name=value");
    }
    pairs.emplace_back(item.substr(0, equals), parseNumber(item.substr(equals + 1), flag));
  }
  if (pairs.empty()) throw UsageError("--" + flag + ": nothing in '" + text + "'");
  return pairs;
}

void checkOutputs(const std::vector<FlagPath>& outputs, const std::vector<FlagPath>& inputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const auto& [flag, path] = outputs[i];
    if (path.empty()) continue;
    for (std::size_t j = 0; j < i; ++j) {
      if (!outputs[j].second.empty() && io::sameOutputFile(path, outputs[j].second))
        throw UsageError("--" + flag + ": must differ from --" + outputs[j].first);
    }
    for (const auto& [input_flag, input] : inputs) {
      if (!input.empty() && io::sameOutputFile(path, input))
        throw UsageError("--" + flag + ": '" + path + "' is the same file as --" + input_flag);
    }
    io::checkOutputPath(path);  // a missing or read-only directory or file: a failed run (exit 1)
  }
}

}  // namespace mcws::app
