// mcws_collide: checks one joint vector of a robot against its collision model (Fu, Hu, Chen & Pan
// 2016 section 2) and names the colliding pairs with their penetration, or the nearest pair.
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "common/app.h"
#include "common/flags.h"
#include "mcws/collision/collision_checker.h"
#include "mcws/collision/collision_report.h"

namespace {

using namespace mcws;

constexpr char kUsage[] = R"(mcws_collide --robot FILE --q "q1 q2 ..." [options])";

constexpr char kSummary[] =
    R"(Checks one joint vector against the robot file's collision model: link-link pairs (label 1),
the tool against the links it is not mounted on (2), links and tool against the environment (3).
Prints the label (the lowest code of any colliding pair, 0 when free) and each colliding pair with
its penetration depth, or, when free, the pair with the least clearance. Joint values in rad
(revolute) and the robot's length unit (prismatic); distances in that length unit.)";

void declareFlags(app::CommandLine& cli) {
  app::declareRobotFlags(
      cli, "robot description (.yaml with collision:, or .urdf with <collision> elements)");
  cli.addValue("q", "joint values, separated by spaces or commas");
  cli.addSwitch("all", "list every checked pair with its distance");
  cli.addSwitch("ignore-limits", "accept joint values outside the joint limits");
  cli.addSwitch("json", "print one JSON object on stdout");
}

void printReport(const Robot& robot, std::uint32_t label, std::size_t checked,
                 const std::vector<PairReport>& shown) {
  std::cout << "label " << label << " (" << labelName(label) << "), " << checked
            << " pairs checked\n";
  for (const PairReport& pair : shown) {
    std::cout << std::setw(12) << pair.body_a << " - " << std::setw(12) << std::left << pair.body_b
              << std::right << " " << std::setw(11) << labelName(pair.label);
    if (!pair.depth_known) {
      std::cout << "  colliding (mesh contact: no depth)\n";
    } else if (pair.colliding) {
      std::cout << "  colliding, penetration " << -pair.distance << " "
                << unitName(robot.length_unit) << "\n";
    } else {
      std::cout << "  clearance " << pair.distance << " " << unitName(robot.length_unit) << "\n";
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  return app::run("mcws_collide", [&] {
    app::CommandLine cli(kUsage, kSummary);
    declareFlags(cli);
    if (!cli.parse(argc, argv)) return app::kExitOk;
    const std::string path = cli.required("robot");
    const Eigen::VectorXd q = app::parseNumberList(cli.required("q"), "q");

    const Robot robot = app::readRobot(cli);
    app::checkJointValues(
        robot, q, "q",
        cli.has("ignore-limits") ? app::JointLimits::kIgnore : app::JointLimits::kCheck);
    const CollisionChecker checker(robot, loadRequiredCollisionModel(robot, path));

    const std::vector<PairReport> pairs = checker.report(q);
    const std::uint32_t label = reportedLabel(pairs);
    const std::vector<PairReport> shown = pairsToShow(pairs, cli.has("all"));
    if (cli.has("json")) {
      std::cout << collisionReportJson(robot, label, pairs.size(), shown).dump() << "\n";
    } else {
      printReport(robot, label, pairs.size(), shown);
    }
    return app::kExitOk;
  });
}
