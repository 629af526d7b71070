// mcws_traj: a joint-space trajectory (the quintic blend of Liu, Han, Xu & Li 2021, the cubic, or a
// cubic spline through via points), sampled at a rate and written as CSV, with an optional PNG.
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "common/app.h"
#include "common/flags.h"
#include "common/pose_args.h"
#include "common/units.h"
#include "mcws/io/atomic_file.h"
#include "mcws/sampling/sample_report.h"
#include "mcws/trajectory/cartesian_line.h"
#include "mcws/trajectory/joint_trajectory.h"
#include "mcws/trajectory/tool_path.h"
#include "mcws/trajectory/trajectory_io.h"
#include "mcws/trajectory/trajectory_report.h"

namespace {

using namespace mcws;

constexpr char kUsage[] =
    R"(mcws_traj --robot FILE --from "q..." --to "q..." --duration S --rate HZ --output CSV [options])";

constexpr char kSummary[] =
    R"(Plans a joint-space move from --from to --to: the quintic blend of Liu, Han, Xu & Li 2021 (zero velocity and
acceleration at both ends) or the cubic (zero end velocity); with --via, a cubic spline through
the via points, reached at equal intervals, at rest at both ends. Writes CSV, each column named
with its unit: t_s, joint positions (j1_rad, or a prismatic joint's in the robot's length unit),
velocities (j1_rad_per_s), accelerations (j1_rad_per_s2), tool x_mm y_mm z_mm (the robot's
length unit). Joint values in rad and the robot's length unit, time in s. The whole move is
checked against the joint limits (and --max-velocity). With
--to-pose instead of --to, the tool moves on a straight line (orientation by slerp, timed by the
profile) from its pose at --from to that pose, each sample solved by IK seeded with the previous
one; a sample without a solution, or a joint jump (another IK branch), stops it with an error
naming the time. --duration lies in [0.001, 1000000] s, --rate in (0, 1000000] Hz, and a run
writes at most 1000000 samples (about 300 MB of CSV), with progress on stderr when it is long.)";

/// --duration [s]: below a millisecond a move is a jump; the upper end only keeps the arithmetic
/// of the profiles well inside a double.
constexpr double kDurationRange[2] = {1e-3, 1e6};
constexpr double kMaxRate = 1e6;  ///< --rate [Hz]
/// Samples one run writes: a million (1000 s at 1 kHz) is about 300 MB of CSV and 0.2 GB of
/// memory; beyond, the file is more than a spreadsheet or a plot can take.
constexpr double kMaxSamples = 1e6;

void declareFlags(app::CommandLine& cli) {
  app::declareRobotFlags(cli, "robot description (.yaml or .urdf)");
  cli.addValue("from", "start joint values");
  cli.addValue("to", "goal joint values");
  cli.addValue("to-pose",
               "goal tool pose \"x y z roll pitch yaw\" [length unit, rad]: a straight-line move");
  cli.addValues("via", "via joint values (repeatable)");
  cli.addValue("duration", "duration of the move [s]");
  cli.addValue("rate", "samples per second [Hz]");
  cli.addValue("profile", "quintic | cubic (default quintic; with --via only cubic)");
  cli.addValue("max-velocity", "velocity limit [per s], one value for all joints or one per joint");
  cli.addValue("output", "CSV file to write");
  cli.addValue("plot", "PNG of joint curves and tool path (gnuplot)");
  cli.addSwitch("json", "print a JSON summary on stdout");
}

/// The move the command line asks for, before the robot is loaded.
struct Move {
  double duration{0.0}, rate{0.0};
  std::string profile;            ///< quintic | cubic
  std::vector<std::string> vias;  ///< joint values of the via points, as typed
  bool line{false};               ///< --to-pose: a straight tool line
  std::string from, to;           ///< --from and --to (or --to-pose), as typed
  std::string output, plot;       ///< plot empty: none
  std::string duration_text;      ///< as typed, for the plot's title
};

Move readMove(const app::CommandLine& cli) {
  Move m;
  m.duration_text = cli.required("duration");
  m.duration = app::parsePositive(m.duration_text, "duration", "s");
  if (m.duration < kDurationRange[0] || m.duration > kDurationRange[1]) {
    throw app::UsageError("--duration: " + m.duration_text +
                          " is not in [0.001, 1000000] s (a millisecond to 11.6 days)");
  }
  m.rate = app::parsePositive(cli.required("rate"), "rate", "Hz");
  if (m.rate > kMaxRate) {
    throw app::UsageError("--rate: " + cli.required("rate") + " is not in (0, 1000000] Hz");
  }
  // Both in range, the count fits a double exactly; the library's own limit is far above ours.
  if (std::floor(m.duration * m.rate) + 2.0 > kMaxSamples) {
    throw app::UsageError(
        "--duration " + m.duration_text + " s at --rate " + cli.required("rate") +
        " Hz: " + std::to_string(static_cast<long long>(m.duration * m.rate) + 1) +
        " samples, more than the 1000000 mcws_traj writes (a CSV of about 300 "
        "MB); lower --rate or split the move");
  }
  m.vias = cli.all("via");
  m.profile = app::parseChoice(cli.text("profile", m.vias.empty() ? "quintic" : "cubic"), "profile",
                               {"quintic", "cubic"});
  if (!m.vias.empty() && m.profile == "quintic") {
    throw app::UsageError(
        "--profile: quintic blends one move; through --via the path is a cubic spline (use "
        "--profile cubic)");
  }
  m.output = cli.required("output");
  m.plot = cli.text("plot", "");
  if (m.plot == m.output) throw app::UsageError("--plot: must differ from --output");
  m.line = cli.has("to-pose");
  if (m.line == cli.has("to")) throw app::UsageError("give one of --to and --to-pose");
  if (m.line && !m.vias.empty()) throw app::UsageError("--via does not apply to --to-pose");
  if (m.line && cli.has("max-velocity"))
    throw app::UsageError("--max-velocity does not apply to --to-pose");
  m.from = cli.required("from");
  m.to = cli.required(m.line ? "to-pose" : "to");
  return m;
}

/// --max-velocity: one positive value per joint (one value: the same for all), or empty.
Eigen::VectorXd readMaxVelocity(const app::CommandLine& cli, const Robot& robot) {
  if (!cli.has("max-velocity")) return {};
  Eigen::VectorXd v = app::parseNumberList(cli.required("max-velocity"), "max-velocity");
  if (v.size() == 1) v = Eigen::VectorXd::Constant(robot.dof(), v[0]);
  if (v.size() != robot.dof() || (v.array() <= 0).any()) {
    throw app::UsageError("--max-velocity: give one positive value or " +
                          std::to_string(robot.dof()) + " (one per joint)");
  }
  return v;
}

/// What the move is, for the plot's title and --json.
std::string moveShape(const Move& move) {
  if (move.line) return "straight tool line, " + move.profile + " timing";
  if (move.vias.empty()) return move.profile + " move";
  return "cubic spline through " + std::to_string(move.vias.size()) +
         (move.vias.size() == 1 ? " via point" : " via points");
}

/// The CSV and, with --plot, the PNG: both written or neither.
/// The CSV is written in pieces, with progress on stderr for a long one.
void saveMove(const Robot& robot, const Move& move, const SampledTrajectory& samples) {
  io::OutputSet outputs;
  io::AtomicFile csv_file(move.output);
  app::Progress progress("mcws_traj", "samples written");
  writeTrajectoryCsv(robot, samples, [&](const std::string& piece, std::size_t done) {
    csv_file.write(piece.data(), piece.size());
    progress.update(done, static_cast<std::size_t>(samples.size()));
  });
  csv_file.commit();
  if (!move.plot.empty()) {
    io::writeWholeFile(move.plot, renderTrajectoryPng(robot, samples,
                                                      robot.name + ": " + moveShape(move) + ", " +
                                                          move.duration_text + " s"));
  }
  outputs.commit();
}

/// The --json summary: the move as asked, and what its samples do (trajectorySummary()).
nlohmann::json summaryJson(const Robot& robot, const Move& move, const SampledTrajectory& samples,
                           const Eigen::MatrixXd& xyz) {
  nlohmann::json out = trajectorySummary(robot, samples, xyz);
  addRobotNames(out, robot);
  out["profile"] = move.line           ? "line, " + move.profile
                   : move.vias.empty() ? move.profile
                                       : "cubic spline";
  out["duration"] = move.duration;
  out["rate"] = move.rate;
  out["output"] = move.output;
  if (!move.plot.empty()) out["plot"] = move.plot;
  out["units"]["duration"] = "s";
  out["units"]["rate"] = "Hz";
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  return app::run("mcws_traj", [&] {
    app::CommandLine cli(kUsage, kSummary);
    declareFlags(cli);
    if (!cli.parse(argc, argv)) return app::kExitOk;
    const Move move = readMove(cli);

    const Robot robot = app::readRobot(cli);
    std::vector<Eigen::VectorXd> points{app::parseJointValues(robot, move.from, "from")};
    for (std::size_t k = 0; k < move.vias.size(); ++k)
      points.push_back(app::parseJointValues(robot, move.vias[k], "via " + std::to_string(k + 1)));
    const Eigen::Isometry3d T_goal =
        move.line ? app::parsePose(move.to, "to-pose") : Eigen::Isometry3d();
    if (!move.line) points.push_back(app::parseJointValues(robot, move.to, "to"));
    const Eigen::VectorXd max_velocity = readMaxVelocity(cli, robot);
    app::checkOutputs({{"output", move.output}, {"plot", move.plot}},
                      {{"robot", cli.required("robot")}});

    SampledTrajectory samples;
    if (move.line) {
      CartesianLineOptions line;
      line.duration = move.duration;
      line.rate = move.rate;
      line.profile = profileFromName(move.profile);
      samples = ikToolLine(robot, points.front(), T_goal, line);
    } else {
      const JointTrajectory trajectory =
          move.vias.empty() ? pointToPoint(points.front(), points.back(), move.duration,
                                           profileFromName(move.profile))
                            : cubicSpline(points, evenTimes(points.size(), move.duration));
      checkTrajectoryLimits(robot, trajectory, max_velocity);
      samples = sampleTrajectory(trajectory, move.rate);
    }
    saveMove(robot, move, samples);

    const Eigen::MatrixXd xyz = toolPositions(robot, samples);
    if (cli.has("json")) {
      std::cout << summaryJson(robot, move, samples, xyz).dump() << "\n";
    } else {
      std::cerr << "[done : " << samples.size() << " samples, tool path " << pathLength(xyz) << " "
                << unitName(robot.length_unit) << "] -> " << move.output
                << (move.plot.empty() ? "" : ", " + move.plot) << "\n";
    }
    return app::kExitOk;
  });
}
