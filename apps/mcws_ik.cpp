// mcws_ik: inverse kinematics of one tool pose: the joint vector, iterations and residual.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "common/app.h"
#include "common/flags.h"
#include "common/pose_args.h"
#include "common/units.h"
#include "mcws/kinematics/inverse_kinematics.h"
#include "mcws/sampling/sample_report.h"

namespace {

using namespace mcws;

constexpr char kUsage[] =
    R"(mcws_ik --robot FILE (--pose "x y z roll pitch yaw" | --matrix "16 numbers") [options])";

constexpr char kSummary[] =
    R"(Finds joint values within the joint limits that put the tool frame at the given pose in the
world frame (damped least squares with seeded random restarts). Lengths are in the robot file's
length unit, angles in rad; roll pitch yaw are fixed-axis angles, R = Rz(yaw) Ry(pitch) Rx(roll).
--matrix takes the 4x4 pose row by row; a rotation printed with few decimals
(|R^T R - I| <= 1e-3) is replaced by the nearest rotation. With --free-roll only the tool point
and the direction of the tool's z axis count (orientation_error is then the angle between the
tool's z axis and the target's). The plain output is the joint values under a '#' line naming
their units, then the iterations and the errors with theirs. Exits 1 when no solution is found
within the tolerances.)";

void declareFlags(app::CommandLine& cli) {
  app::declareRobotFlags(cli, "robot description (.yaml or .urdf)");
  cli.addValue("pose", "target: x y z [length unit] roll pitch yaw [rad]");
  cli.addValue("matrix", "target: 16 numbers of the 4x4 pose, row by row");
  cli.addValue(
      "q0",
      R"(first guess, one value per joint [rad | length unit] (default: middle of the limits))");
  cli.addSwitch("position-only", "match the tool point only (arms with fewer than 6 joints)");
  cli.addSwitch("free-roll",
                "match the tool point and the direction of the tool's z axis, the roll about it "
                "free (a point and an approach direction; arms with 5 joints)");
  cli.addValue("tolerance", "position tolerance [length unit] (1e-6)");
  cli.addValue("angle-tolerance", "orientation tolerance [rad] (1e-6)");
  cli.addValue("restarts", "random restarts after the first guess (20)");
  cli.addValue("seed", "seed of the restarts, a whole number >= 0 (1)");
  cli.addSwitch("json", "print one JSON object on stdout");
}

/// The target pose from --pose or --matrix (exactly one of them).
Eigen::Isometry3d readTarget(const app::CommandLine& cli) {
  if (cli.has("pose") == cli.has("matrix")) {
    throw app::UsageError(cli.has("pose") ? "--pose and --matrix exclude each other"
                                          : "missing --pose or --matrix");
  }
  return cli.has("pose") ? app::parsePose(cli.required("pose"), "pose")
                         : app::parseMatrix(cli.required("matrix"), "matrix");
}

IkOptions readOptions(const app::CommandLine& cli) {
  IkOptions options;
  options.position_only = cli.has("position-only");
  options.free_roll = cli.has("free-roll");
  if (options.position_only && options.free_roll) {
    throw app::UsageError("--position-only and --free-roll exclude each other");
  }
  options.position_tolerance = app::parsePositive(cli.text("tolerance", "1e-6"), "tolerance");
  options.orientation_tolerance =
      app::parsePositive(cli.text("angle-tolerance", "1e-6"), "angle-tolerance");
  options.restarts =
      static_cast<int>(app::parseInteger(cli.text("restarts", "20"), "restarts", 0, 1000000));
  options.seed = app::readSeed(cli);
  return options;
}

/// The error for a pose without a solution: how close the best attempt came.
Error noSolution(const Robot& robot, const IkResult& result, const IkOptions& options) {
  std::string msg = describeIkFailure(robot, result);
  if (robot.dof() < 6 && !options.position_only) {
    msg += "; the robot has " + std::to_string(robot.dof()) + " joints, try --position-only" +
           (options.free_roll ? "" : " or --free-roll");
  }
  return Error(msg);
}

void printSolution(const Robot& robot, const IkResult& result, const IkOptions& options) {
  const char* unit = unitName(robot.length_unit);
  std::printf("# joint values q in %s\n", jointUnitsText(robot).c_str());
  std::printf("q:");
  for (int i = 0; i < robot.dof(); ++i) std::printf(" %.9f", result.q[i]);
  std::printf("\niterations: %d (%d start%s)\nposition error: %.3g %s\n", result.iterations,
              result.attempts, result.attempts == 1 ? "" : "s", result.position_error, unit);
  if (!options.position_only) {
    std::printf("%s error: %.3g rad\n", options.free_roll ? "approach (z axis)" : "orientation",
                result.orientation_error);
  }
}

}  // namespace

int main(int argc, char** argv) {
  return app::run("mcws_ik", [&] {
    app::CommandLine cli(kUsage, kSummary);
    declareFlags(cli);
    if (!cli.parse(argc, argv)) return app::kExitOk;
    const Eigen::Isometry3d T_target = readTarget(cli);
    const IkOptions options = readOptions(cli);

    const Robot robot = app::readRobot(cli);
    const Eigen::VectorXd q0 =
        cli.has("q0")
            ? app::parseJointValues(robot, cli.required("q0"), "q0", app::JointLimits::kIgnore)
            : Eigen::VectorXd(0.5 * (robot.lowerLimits() + robot.upperLimits()));

    const IkResult result = solveIk(robot, T_target, q0, options);
    if (!result.converged()) throw noSolution(robot, result, options);
    if (cli.has("json")) {
      nlohmann::json out;
      addRobotNames(out, robot);
      out["length_unit"] = unitName(robot.length_unit);
      out["status"] = ikStatusName(result.status);
      out["q"] = std::vector<double>(result.q.data(), result.q.data() + result.q.size());
      out["iterations"] = result.iterations;
      out["attempts"] = result.attempts;
      out["position_error"] = result.position_error;
      out["orientation_error"] = result.orientation_error;
      out["units"] = {{"q", jointUnits(robot)},
                      {"position_error", unitName(robot.length_unit)},
                      {"orientation_error", "rad"}};
      std::cout << out.dump() << "\n";
    } else {
      printSolution(robot, result, options);
    }
    return app::kExitOk;
  });
}
