// mcws_fk: forward kinematics of one joint vector: the 4x4 tool (or flange) pose.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "common/app.h"
#include "common/flags.h"
#include "common/units.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/sampling/sample_report.h"

namespace {

constexpr char kUsage[] = R"(mcws_fk --robot FILE --q "q1 q2 ..." [options])";

constexpr char kSummary[] =
    R"(Prints the homogeneous 4x4 pose of the tool frame (or the flange) in the world frame for one
joint vector. Joint values are in rad (revolute) and in the robot file's length unit (prismatic);
the pose's translation is in that length unit, or in --unit's (m for ROS conventions). The plain
output is the matrix under a '#' line naming the frame and the unit (numpy.loadtxt and gnuplot
skip it); --json gives "pose", "position" and "q" with "length_unit" and "units", and "robot"
and "tip" (the URDF tip link, or tool or flange), as every tool's --json names them.)";

void declareFlags(mcws::app::CommandLine& cli) {
  mcws::app::declareRobotFlags(cli, "robot description (.yaml or .urdf)");
  cli.addValue("q", "joint values, separated by spaces or commas");
  cli.addValue("frame", "tool | flange (default tool)");
  cli.addSwitch("ignore-limits", "accept joint values outside the joint limits");
  mcws::app::declareUnitFlag(cli);
  cli.addSwitch("json", "print one JSON object on stdout");
}

}  // namespace

int main(int argc, char** argv) {
  using namespace mcws;
  return app::run("mcws_fk", [&] {
    app::CommandLine cli(kUsage, kSummary);
    declareFlags(cli);
    if (!cli.parse(argc, argv)) return app::kExitOk;
    const std::string q_text = cli.required("q");
    const std::string frame =
        app::parseChoice(cli.text("frame", "tool"), "frame", {"tool", "flange"});
    const Eigen::VectorXd q = app::parseNumberList(q_text, "q");

    const Robot robot = app::readRobot(cli);
    app::checkJointValues(
        robot, q, "q",
        cli.has("ignore-limits") ? app::JointLimits::kIgnore : app::JointLimits::kCheck);
    const ChainPoses poses = chainPoses(robot, q);
    const ResultUnits units = app::readResultUnits(cli, robot.length_unit, robot.source);
    Eigen::Matrix4d T = (frame == "tool" ? poses.T_world_tool : poses.T_world_flange).matrix();
    T.topRightCorner<3, 1>() *= units.length(1.0);
    const std::string length = units.lengthName();
    if (cli.has("json")) {
      nlohmann::json out;
      addRobotNames(out, robot, frame == "tool" ? SamplePoint::kTool : SamplePoint::kFlange);
      out["length_unit"] = length;
      out["frame"] = frame;
      out["q"] = std::vector<double>(q.data(), q.data() + q.size());
      for (int r = 0; r < 4; ++r) out["pose"].push_back({T(r, 0), T(r, 1), T(r, 2), T(r, 3)});
      out["position"] = {T(0, 3), T(1, 3), T(2, 3)};
      out["units"] = {{"q", jointUnits(robot)},
                      {"pose", "1 (rotation), " + length + " (last column)"},
                      {"position", length}};
      std::cout << out.dump() << "\n";
    } else {
      std::printf("# %s frame in the world frame; translation (last column) in %s\n", frame.c_str(),
                  length.c_str());
      for (int r = 0; r < 4; ++r) {
        std::printf("%12.6f %12.6f %12.6f %14.6f\n", T(r, 0), T(r, 1), T(r, 2), T(r, 3));
      }
    }
    return app::kExitOk;
  });
}
