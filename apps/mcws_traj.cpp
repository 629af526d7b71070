// mcws_traj: a joint-space trajectory (seed 003's quintic blend, the cubic, or a cubic spline
// through via points), sampled at a rate and written as CSV, with an optional PNG.
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "common/app.h"
#include "common/pose_args.h"
#include "mcws/io/atomic_file.h"
#include "mcws/kinematics/inverse_kinematics.h"
#include "mcws/kinematics/robot_urdf.h"
#include "mcws/kinematics/robot_yaml.h"
#include "mcws/trajectory/cartesian_line.h"
#include "mcws/trajectory/joint_trajectory.h"
#include "mcws/trajectory/trajectory_io.h"

namespace {

using namespace mcws;

/// A joint vector flag: dof() finite values inside the joint limits, or a usage error.
Eigen::VectorXd jointVector(const Robot& robot, const std::string& text, const std::string& flag) {
  const Eigen::VectorXd q = app::parseNumberList(text, flag);
  try {
    robot.checkJointVector(q);
  } catch (const Error& e) {
    throw app::UsageError("--" + flag + ": " + e.what());
  }
  return q;
}

double positive(const app::CommandLine& cli, const std::string& flag, const char* unit) {
  const double value = app::parseNumber(cli.required(flag), flag);
  if (value <= 0.0) {
    throw app::UsageError("--" + flag + ": " + cli.required(flag) + " " + unit +
                          " is not a positive number");
  }
  return value;
}

Robot loadTrajectoryRobot(const app::CommandLine& cli) {
  const std::string path = cli.required("robot");
  if (!cli.has("root") && !cli.has("tip")) return loadRobot(path);
  if (std::filesystem::path(path).extension() != ".urdf") {
    throw app::UsageError("--root and --tip need a .urdf robot");
  }
  return loadRobotUrdf(path, {cli.text("root", ""), cli.text("tip", "")});
}

}  // namespace

int main(int argc, char** argv) {
  return app::run("mcws_traj", [&] {
    app::CommandLine cli(
        "mcws_traj --robot FILE --from \"q...\" --to \"q...\" --duration S --rate HZ --output "
        "CSV [options]",
        "Plans a joint-space move from --from to --to: seed 003's quintic blend (zero velocity "
        "and\n"
        "acceleration at both ends) or the cubic (zero end velocity); with --via, a cubic spline\n"
        "through the via points, reached at equal intervals, at rest at both ends. Writes CSV:\n"
        "t, joint positions, velocities (_vel), accelerations (_acc), tool x y z. Joint values\n"
        "in rad and the robot's length unit, time in s. The whole move is checked against the\n"
        "joint limits (and --max-velocity). With --to-pose instead of --to, the tool moves on a\n"
        "straight line (orientation by slerp, timed by the profile) from its pose at --from to\n"
        "that pose, each sample solved by IK seeded with the previous one; a sample without a\n"
        "solution, or a joint jump (another IK branch), stops it with an error naming the time.");
    cli.add()("robot", app::po::value<std::string>(), "robot description (.yaml or .urdf)")(
        "root", app::po::value<std::string>(), "URDF: first link of the chain (default: root)")(
        "tip", app::po::value<std::string>(), "URDF: last link of the chain (default: the leaf)")(
        "from", app::po::value<std::string>(), "start joint values")(
        "to", app::po::value<std::string>(), "goal joint values")(
        "to-pose", app::po::value<std::string>(),
        "goal tool pose \"x y z roll pitch yaw\" [length unit, rad]: a straight-line move")(
        "via", app::po::value<std::vector<std::string>>(), "via joint values (repeatable)")(
        "duration", app::po::value<std::string>(), "duration of the move [s]")(
        "rate", app::po::value<std::string>(), "samples per second [Hz]")(
        "profile", app::po::value<std::string>(),
        "quintic | cubic (default quintic; with --via only cubic)")(
        "max-velocity", app::po::value<std::string>(),
        "velocity limit [per s], one value for all joints or one per joint")(
        "output", app::po::value<std::string>(), "CSV file to write")(
        "plot", app::po::value<std::string>(), "PNG of joint curves and tool path (gnuplot)")(
        "json", "print a JSON summary on stdout");
    if (!cli.parse(argc, argv)) return app::kExitOk;

    const double duration = positive(cli, "duration", "s");
    const double rate = positive(cli, "rate", "Hz");
    try {
      sampleCount(duration, rate);
    } catch (const Error& e) {
      throw app::UsageError(std::string("--rate: ") + e.what());
    }
    const std::vector<std::string> vias = cli.all("via");
    const std::string profile_name = cli.text("profile", vias.empty() ? "quintic" : "cubic");
    if (profile_name != "quintic" && profile_name != "cubic") {
      throw app::UsageError("--profile: '" + profile_name + "' is not quintic or cubic");
    }
    if (!vias.empty() && profile_name == "quintic") {
      throw app::UsageError(
          "--profile: quintic blends one move; through --via the path is a "
          "cubic spline (use --profile cubic)");
    }
    const std::string output = cli.required("output"), plot = cli.text("plot", "");
    if (plot == output) throw app::UsageError("--plot: must differ from --output");
    const bool line = cli.has("to-pose");
    if (line == cli.has("to")) throw app::UsageError("give one of --to and --to-pose");
    if (line && !vias.empty()) throw app::UsageError("--via does not apply to --to-pose");
    if (line && cli.has("max-velocity"))
      throw app::UsageError("--max-velocity does not apply to --to-pose");
    const std::string from_text = cli.required("from"),
                      to_text = cli.required(line ? "to-pose" : "to");

    const Robot robot = loadTrajectoryRobot(cli);
    std::vector<Eigen::VectorXd> points{jointVector(robot, from_text, "from")};
    for (std::size_t k = 0; k < vias.size(); ++k) {
      points.push_back(jointVector(robot, vias[k], "via " + std::to_string(k + 1)));
    }
    const Eigen::Isometry3d goal = line ? app::parsePose(to_text, "to-pose") : Eigen::Isometry3d();
    if (!line) points.push_back(jointVector(robot, to_text, "to"));
    Eigen::VectorXd max_velocity;
    if (cli.has("max-velocity")) {
      max_velocity = app::parseNumberList(cli.required("max-velocity"), "max-velocity");
      if (max_velocity.size() == 1)
        max_velocity = Eigen::VectorXd::Constant(robot.dof(), max_velocity[0]);
      if (max_velocity.size() != robot.dof() || (max_velocity.array() <= 0).any()) {
        throw app::UsageError("--max-velocity: give one positive value or " +
                              std::to_string(robot.dof()) + " (one per joint)");
      }
    }
    io::checkOutputPath(output);
    if (!plot.empty()) io::checkOutputPath(plot);

    const TimeProfile profile = profileFromName(profile_name);
    SampledTrajectory samples;
    if (line) {
      IkOptions ik_options;
      ik_options.restarts = 2;  // seeded with the previous sample: a restart means a new branch
      const IkFunction ik = [&](const Eigen::Isometry3d& T, const Eigen::VectorXd& seed) {
        const IkResult r = solveIk(robot, T, seed, ik_options);
        return r.converged() ? std::optional<Eigen::VectorXd>(r.q) : std::nullopt;
      };
      CartesianLineOptions options;
      options.duration = duration;
      options.rate = rate;
      options.profile = profile;
      CartesianLineResult result = cartesianLine(robot, points.front(), goal, ik, options);
      if (result.status != CartesianLineStatus::kSuccess) throw Error(result.message);
      samples = std::move(result.trajectory);
    } else {
      const JointTrajectory trajectory =
          vias.empty() ? pointToPoint(points.front(), points.back(), duration, profile)
                       : cubicSpline(points, evenTimes(points.size(), duration));
      checkTrajectoryLimits(robot, trajectory, max_velocity);
      samples = sampleTrajectory(trajectory, rate);
    }

    const std::string csv = trajectoryCsv(robot, samples);
    io::AtomicFile csv_file(output);
    csv_file.write(csv.data(), csv.size());
    std::optional<io::AtomicFile> png_file;
    if (!plot.empty()) {
      const std::string shape = line ? "straight tool line, " + profile_name + " timing"
                                : vias.empty()
                                    ? profile_name + " move"
                                    : "cubic spline through " + std::to_string(vias.size()) +
                                          (vias.size() == 1 ? " via point" : " via points");
      const std::string png = renderTrajectoryPng(
          robot, samples, robot.name + ": " + shape + ", " + cli.required("duration") + " s");
      png_file.emplace(plot);
      png_file->write(png.data(), png.size());
    }
    csv_file.commit();
    if (png_file) png_file->commit();

    const Eigen::MatrixXd xyz = toolPositions(robot, samples);
    double path_length = 0.0;
    for (Eigen::Index i = 1; i < xyz.rows(); ++i)
      path_length += (xyz.row(i) - xyz.row(i - 1)).norm();
    if (cli.has("json")) {
      nlohmann::json out;
      out["robot"] = robot.name;
      out["unit"] = unitName(robot.length_unit);
      out["profile"] = line           ? "line, " + profile_name
                       : vias.empty() ? profile_name
                                      : "cubic spline";
      out["duration"] = duration;
      out["rate"] = rate;
      out["samples"] = samples.size();
      out["output"] = output;
      if (!plot.empty()) out["plot"] = plot;
      for (int j = 0; j < robot.dof(); ++j) {
        out["joints"].push_back(robot.joints[j].name);
        out["peak_velocity"].push_back(samples.qd.col(j).cwiseAbs().maxCoeff());
        out["peak_acceleration"].push_back(samples.qdd.col(j).cwiseAbs().maxCoeff());
      }
      out["tool_start"] = {xyz(0, 0), xyz(0, 1), xyz(0, 2)};
      const Eigen::Index last = xyz.rows() - 1;
      out["tool_end"] = {xyz(last, 0), xyz(last, 1), xyz(last, 2)};
      out["tool_path_length"] = path_length;
      std::cout << out.dump() << "\n";
    } else {
      std::cerr << "[done : " << samples.size() << " samples, tool path " << path_length << " "
                << unitName(robot.length_unit) << "] -> " << output
                << (plot.empty() ? "" : ", " + plot) << "\n";
    }
    return app::kExitOk;
  });
}
