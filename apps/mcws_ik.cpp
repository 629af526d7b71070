// mcws_ik: inverse kinematics of one tool pose: the joint vector, iterations and residual.
#include <cstdio>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/app.h"
#include "common/pose_args.h"
#include "mcws/kinematics/inverse_kinematics.h"
#include "mcws/kinematics/robot_yaml.h"

int main(int argc, char** argv) {
  using namespace mcws;
  return app::run("mcws_ik", [&] {
    app::CommandLine cli(
        "mcws_ik --robot FILE (--pose \"x y z roll pitch yaw\" | --matrix \"16 numbers\") "
        "[options]",
        "Finds joint values within the joint limits that put the tool frame at the given pose in\n"
        "the world frame (damped least squares with seeded random restarts). Lengths are in the\n"
        "robot file's length unit, angles in rad; roll pitch yaw are fixed-axis angles,\n"
        "R = Rz(yaw) Ry(pitch) Rx(roll). --matrix takes the 4x4 pose row by row; a rotation\n"
        "printed with few decimals (|R^T R - I| <= 1e-3) is replaced by the nearest rotation.\n"
        "Exits 1 when no solution is found within the tolerances.");
    cli.add()("robot", app::po::value<std::string>(), "robot description (.yaml)")(
        "pose", app::po::value<std::string>(), "target: x y z [length unit] roll pitch yaw [rad]")(
        "matrix", app::po::value<std::string>(), "target: 16 numbers of the 4x4 pose, row by row")(
        "q0", app::po::value<std::string>(),
        "first guess, one value per joint [rad | length unit] (default: middle of the limits)")(
        "position-only", "match the tool point only (arms with fewer than 6 joints)")(
        "tolerance", app::po::value<std::string>(), "position tolerance [length unit] (1e-6)")(
        "angle-tolerance", app::po::value<std::string>(), "orientation tolerance [rad] (1e-6)")(
        "restarts", app::po::value<std::string>(), "random restarts after the first guess (20)")(
        "seed", app::po::value<std::string>(), "seed of the restarts, a whole number >= 0 (1)")(
        "json", "print one JSON object on stdout");
    if (!cli.parse(argc, argv)) return app::kExitOk;

    if (cli.has("pose") == cli.has("matrix")) {
      throw app::UsageError(cli.has("pose") ? "--pose and --matrix exclude each other"
                                            : "missing --pose or --matrix");
    }
    const Eigen::Isometry3d T_target = cli.has("pose")
                                           ? app::parsePose(cli.required("pose"), "pose")
                                           : app::parseMatrix(cli.required("matrix"), "matrix");
    auto positive = [&](const std::string& flag) {
      const double value = app::parseNumber(cli.text(flag, "1e-6"), flag);
      if (value <= 0.0) throw app::UsageError("--" + flag + ": " + cli.text(flag, "") + " <= 0");
      return value;
    };
    IkOptions options;
    options.position_only = cli.has("position-only");
    options.position_tolerance = positive("tolerance");
    options.orientation_tolerance = positive("angle-tolerance");
    options.restarts =
        static_cast<int>(app::parseInteger(cli.text("restarts", "20"), "restarts", 0, 1000000));
    options.seed = static_cast<std::uint64_t>(app::parseInteger(
        cli.text("seed", "1"), "seed", 0, std::numeric_limits<std::int64_t>::max()));

    const std::string robot_path = cli.required("robot");
    Robot robot;
    try {
      robot = loadRobot(robot_path);
    } catch (const Error& e) {
      throw Error(std::string("--robot: ") + e.what());
    }
    Eigen::VectorXd q0 = 0.5 * (robot.lowerLimits() + robot.upperLimits());
    if (cli.has("q0")) {
      q0 = app::parseNumberList(cli.required("q0"), "q0");
      try {
        robot.checkSize(q0);
      } catch (const Error& e) {
        throw app::UsageError(std::string("--q0: ") + e.what());
      }
    }

    const IkResult result = solveIk(robot, T_target, q0, options);
    const char* unit = unitName(robot.length_unit);
    if (!result.converged()) {
      std::ostringstream msg;
      msg.precision(4);
      msg << "no solution (" << ikStatusName(result.status) << "): the best pose found is "
          << result.position_error << " " << unit << " and " << result.orientation_error
          << " rad away, after " << result.iterations << " iterations from " << result.attempts
          << " starts";
      if (robot.dof() < 6 && !options.position_only) {
        msg << "; the robot has " << robot.dof() << " joints, try --position-only";
      }
      throw Error(msg.str());
    }
    if (cli.has("json")) {
      nlohmann::json out;
      out["robot"] = robot.name;
      out["unit"] = unit;
      out["status"] = ikStatusName(result.status);
      out["q"] = std::vector<double>(result.q.data(), result.q.data() + result.q.size());
      out["iterations"] = result.iterations;
      out["attempts"] = result.attempts;
      out["position_error"] = result.position_error;
      out["orientation_error"] = result.orientation_error;
      std::cout << out.dump() << "\n";
    } else {
      std::printf("q:");
      for (int i = 0; i < robot.dof(); ++i) std::printf(" %.9f", result.q[i]);
      std::printf("\niterations: %d (%d start%s)\nposition error: %.3g %s\n", result.iterations,
                  result.attempts, result.attempts == 1 ? "" : "s", result.position_error, unit);
      if (!options.position_only) {
        std::printf("orientation error: %.3g rad\n", result.orientation_error);
      }
    }
    return app::kExitOk;
  });
}
