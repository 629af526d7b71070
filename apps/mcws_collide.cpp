// mcws_collide: checks one joint vector of a robot against its collision model (Fu, Hu, Chen & Pan
// 2016 section 2) and names the colliding pairs with their penetration, or the nearest pair.
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>

#include "common/app.h"
#include "common/flags.h"
#include "mcws/collision/allowed_pairs.h"
#include "mcws/collision/collision_checker.h"
#include "mcws/collision/collision_report.h"
#include "mcws/io/atomic_file.h"
#include "mcws/sampling/sample_report.h"

namespace {

using namespace mcws;

constexpr char kUsage[] = R"(mcws_collide --robot FILE --q "q1 q2 ..." [options]
       mcws_collide --robot FILE --find-allowed-pairs N --output robot.srdf [--seed S])";

constexpr char kSummary[] =
    R"(Checks one joint vector against the robot file's collision model: link-link pairs (label 1),
the tool against the links it is not mounted on (2), links and tool against the environment (3).
Prints the label (the lowest code of any colliding pair, 0 when free) and each colliding pair with
its penetration depth, or, when free, the pair with the least clearance. Joint values in rad
(revolute) and the robot's length unit (prismatic); distances in that length unit.
With --find-allowed-pairs N, writes instead an SRDF of the link pairs a check may skip, as MoveIt's
setup assistant finds them: adjacent, in collision at the default joint values, in collision in all
or in none of N random joint vectors.)";

void declareFlags(app::CommandLine& cli) {
  app::declareRobotFlags(
      cli, "robot description (.yaml with collision:, or .urdf with <collision> elements)");
  cli.addValue("q", "joint values, separated by spaces or commas");
  cli.addSwitch("all", "list every checked pair with its distance");
  cli.addSwitch("ignore-limits", "accept joint values outside the joint limits");
  cli.addSwitch("json", "print one JSON object on stdout");
  cli.addValue("find-allowed-pairs",
               "N: sample N joint vectors and write the pairs that need no check to --output");
  cli.addValue("output", "with --find-allowed-pairs: the SRDF file written");
  cli.addValue("seed", "with --find-allowed-pairs: random seed, a whole number >= 0 (default 1)");
}

/// --find-allowed-pairs: the SRDF of the pairs that need no check, written atomically.
int findAllowed(const app::CommandLine& cli) {
  const auto samples = static_cast<std::size_t>(
      app::parseInteger(cli.required("find-allowed-pairs"), "find-allowed-pairs", 1,
                        std::numeric_limits<int>::max()));
  const std::string output = cli.required("output");
  const std::uint64_t seed = app::readSeed(cli);
  const std::string path = cli.required("robot");
  app::checkOutputs({{"output", output}}, {{"robot", path}, {"srdf", cli.text("srdf", "")}});
  const Robot robot = app::readRobot(cli);
  const std::vector<DisabledCollision> pairs =
      findAllowedPairs(robot, loadRequiredCollisionModel(robot, path), samples, seed);
  io::writeWholeFile(output, srdfText(robot.name, pairs));
  std::map<std::string, int> reasons;
  for (const DisabledCollision& pair : pairs) ++reasons[pair.reason];
  std::cout << pairs.size() << " link pairs need no check over " << samples << " samples (";
  const char* sep = "";
  for (const auto& [reason, count] : reasons) {
    std::cout << sep << count << " " << reason;
    sep = ", ";
  }
  std::cout << ") -> " << output << "\n";
  return app::kExitOk;
}

/// Each pair's bodies are named by their URDF links (bodyLabel()), by the body for a YAML robot.
void printReport(const Robot& robot, const CollisionModel& model, std::uint32_t label,
                 std::size_t checked, const std::vector<PairReport>& shown) {
  std::cout << "label " << label << " (" << labelName(label) << "), " << checked
            << " pairs checked\n";
  for (const PairReport& pair : shown) {
    std::cout << std::setw(12) << bodyLabel(pair.body_a, model.link_bodies) << " - "
              << std::setw(12) << std::left << bodyLabel(pair.body_b, model.link_bodies)
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
    if (cli.has("find-allowed-pairs")) return findAllowed(cli);
    if (cli.has("output") || cli.has("seed")) {
      throw app::UsageError("--output and --seed need --find-allowed-pairs");
    }
    const std::string path = cli.required("robot");
    const Eigen::VectorXd q = app::parseNumberList(cli.required("q"), "q");

    const Robot robot = app::readRobot(cli);
    app::checkJointValues(
        robot, q, "q",
        cli.has("ignore-limits") ? app::JointLimits::kIgnore : app::JointLimits::kCheck);
    const CollisionModel model = loadRequiredCollisionModel(robot, path);
    const CollisionChecker checker(robot, model);

    const std::vector<PairReport> pairs = checker.report(q);
    const std::uint32_t label = reportedLabel(pairs);
    const std::vector<PairReport> shown = pairsToShow(pairs, cli.has("all"));
    if (cli.has("json")) {
      nlohmann::json out =
          collisionReportJson(robot, label, pairs.size(), shown, model.link_bodies);
      addRobotNames(out, robot);
      std::cout << out.dump() << "\n";
    } else {
      printReport(robot, model, label, pairs.size(), shown);
    }
    return app::kExitOk;
  });
}
