#include "common/flags.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <utility>

#include "mcws/core/length_text.h"
#include "mcws/kinematics/robot_urdf.h"
#include "mcws/kinematics/robot_yaml.h"

namespace mcws::app {

double parsePositive(const std::string& text, const std::string& flag, const std::string& unit) {
  const double value = parseNumber(text, flag);
  if (!(value > 0.0)) {
    throw UsageError("--" + flag + ": " + text + (unit.empty() ? "" : " " + unit) +
                     " is not a positive number");
  }
  return value;
}

double parseNonNegative(const std::string& text, const std::string& flag) {
  const double value = parseNumber(text, flag);
  if (value < 0.0) throw UsageError("--" + flag + ": " + text + " is less than 0");
  return value;
}

std::string parseChoice(const std::string& text, const std::string& flag,
                        std::initializer_list<const char*> choices) {
  std::string wanted;
  std::size_t k = 0;
  for (const char* choice : choices) {
    if (text == choice) return text;
    wanted += (k == 0 ? "" : k + 1 == choices.size() ? " or " : ", ") + std::string(choice);
    ++k;
  }
  throw UsageError("--" + flag + ": '" + text + "' is not " + wanted);
}

std::uint64_t readSeed(const CommandLine& cli, std::uint64_t fallback) {
  return static_cast<std::uint64_t>(parseInteger(cli.text("seed", std::to_string(fallback)), "seed",
                                                 0, std::numeric_limits<std::int64_t>::max()));
}

int readThreads(const CommandLine& cli, int minimum) {
  return static_cast<int>(parseInteger(cli.text("threads", "0"), "threads", minimum, kMaxThreads));
}

SamplePoint readPoint(const CommandLine& cli) {
  return parseChoice(cli.text("point", "tool"), "point", {"tool", "flange"}) == "tool"
             ? SamplePoint::kTool
             : SamplePoint::kFlange;
}

double parseLength(const std::string& text, const std::string& flag, LengthUnit unit,
                   bool allow_zero) {
  return mcws::lengthFromText(text, "--" + flag, unit, allow_zero);
}

double parseAngle(const std::string& text, const std::string& flag) {
  for (const auto& [suffix, radians] : {std::pair{"deg", M_PI / 180.0}, {"rad", 1.0}}) {
    const std::string s = suffix;
    if (text.size() > s.size() && text.compare(text.size() - s.size(), s.size(), s) == 0) {
      return parseNonNegative(text.substr(0, text.size() - s.size()), flag) * radians;
    }
  }
  if (parseNonNegative(text, flag) == 0.0) return 0.0;
  throw UsageError("--" + flag + ": " + text + " has no unit (write 5deg or 0.087rad)");
}

void declareQualityFlags(CommandLine& cli) {
  cli.addValue("quality-task",
               "position | full: the Jacobian rows manipulability measures (default full for 6 "
               "or more joints, position for fewer)");
  cli.addValue("length",
               "characteristic length L of --quality-task full: a length with unit (50cm) or a "
               "number in the robot's unit (default the chain's length)");
}

QualityOptions readQualityOptions(const CommandLine& cli, const Robot& robot) {
  QualityOptions quality = defaultQualityOptions(robot);
  if (cli.has("quality-task")) {
    quality.task = parseQualityTask(
        parseChoice(cli.required("quality-task"), "quality-task", {"position", "full"}));
  }
  if (cli.has("length")) {
    quality.characteristic_length =
        parseLength(cli.required("length"), "length", robot.length_unit);
  }
  return quality;
}

BoundaryPlane readPlane(const CommandLine& cli) {
  if (!cli.has("plane")) return BoundaryPlane::k3D;
  return asUsageError("plane", [&] { return parseBoundaryPlane(cli.required("plane")); });
}

void declareRobotFlags(CommandLine& cli, const char* help) {
  cli.addValue("robot", help);
  cli.addValue("base",
               "URDF: first link of the chain, whose frame is the base frame (default the "
               "root link)");
  cli.addValue("tip",
               "URDF: last link of the chain, whose frame is the tool frame: any link "
               "below --base, e.g. a fixed tool0 or TCP frame (default the one leaf)");
  cli.addValues("package-path",
                "URDF: folder holding ROS packages for package:// mesh URIs, searched before "
                "ROS_PACKAGE_PATH and the folders above the URDF (repeatable)");
  cli.addValue("srdf", "SRDF file whose <disable_collisions> link pairs the collision checks skip");
}

Robot readRobot(const CommandLine& cli) {
  const std::string path = cli.required("robot");
  const UrdfChainOptions chain{cli.text("base", ""), cli.text("tip", "")};
  if (!(chain.base_link.empty() && chain.tip_link.empty()) &&
      std::filesystem::path(path).extension() != ".urdf") {
    throw UsageError("--base and --tip need a .urdf robot");
  }
  const std::vector<std::string> packages = cli.all("package-path");
  if (!packages.empty() && std::filesystem::path(path).extension() != ".urdf") {
    throw UsageError("--package-path needs a .urdf robot");
  }
  for (const std::string& folder : packages) {
    std::error_code ec;
    if (!std::filesystem::is_directory(folder, ec)) {
      throw UsageError("--package-path: '" + folder + "' is not a folder");
    }
  }
  const std::string srdf = cli.text("srdf", "");
  std::error_code no_throw;
  if (cli.has("srdf") && !std::filesystem::is_regular_file(srdf, no_throw)) {
    throw UsageError("--srdf: '" + srdf + "' is not a file");
  }
  const Activity reading("reading --robot '" + path + "'");
  try {
    Robot robot = loadRobot(path, chain);
    robot.package_path = packages;
    robot.srdf = srdf;
    return robot;
  } catch (const UrdfChainError& e) {
    const bool leaves = e.problem() == UrdfChainError::Problem::kSeveralLeaves;
    throw UsageError((leaves ? "--robot: " : "") + e.describe("--base", "--tip", "--tip"));
  } catch (const Error& e) {
    throw Error(std::string("--robot: ") + e.what());
  }
}

void checkJointValues(const Robot& robot, const Eigen::VectorXd& q, const std::string& flag,
                      JointLimits limits) {
  asUsageError(flag, [&] {
    if (limits == JointLimits::kCheck) {
      robot.checkJointVector(q);
    } else {
      robot.checkSize(q);
    }
  });
}

Eigen::VectorXd parseJointValues(const Robot& robot, const std::string& text,
                                 const std::string& flag, JointLimits limits) {
  const Eigen::VectorXd q = parseNumberList(text, flag);
  checkJointValues(robot, q, flag, limits);
  return q;
}

void declareRegionFlags(CommandLine& cli, const std::string& prefix) {
  // The descriptions are copied (boost::program_options keeps a std::string).
  const std::string alpha =
      prefix + "simplex size limit, local spacings (default 3; 5 with --correction none)";
  const std::string correction = prefix + "efron | none (default efron; none for refined clouds)";
  const std::string threads =
      prefix + "worker threads, 0 = all cores (default 0; the result is the same for any)";
  cli.addValue("alpha", alpha.c_str());
  cli.addValue("correction", correction.c_str());
  cli.addValue("threads", threads.c_str());
}

MeasureOptions readRegionOptions(const CommandLine& cli) {
  // --alpha [local spacings]: at 1 a uniform cloud's own triangles already fail the limit (18 %
  // of them); 1000 spacings span a 2-D cloud of 10^6 points, so a wider limit keeps the hull.
  constexpr double kAlphaRange[2] = {1.0, 1000.0};
  MeasureOptions options;
  options.edge_correction =
      parseChoice(cli.text("correction", "efron"), "correction", {"efron", "none"}) == "efron";
  // A refined cloud packs samples onto the joint-limit surfaces, where the k-th neighbour
  // measures the surface's density and understates the spacing just inside: alpha 5 keeps the
  // simplices there (de-icing arm, 10^6 samples: volume -0.19 % at 3, -0.02 % at 5).
  options.alpha_factor =
      parsePositive(cli.text("alpha", options.edge_correction ? "3" : "5"), "alpha");
  if (!(options.alpha_factor >= kAlphaRange[0] && options.alpha_factor <= kAlphaRange[1])) {
    throw UsageError("--alpha: " + cli.required("alpha") + " is not in [1, 1000] local spacings");
  }
  options.threads = readThreads(cli);
  return options;
}

}  // namespace mcws::app
