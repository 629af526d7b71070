// Every tool that reads files and writes files refuses an output that is one of its inputs: by
// the same name, as "./name" and through a symbolic link. Exit code 2, a message naming both
// flags, and the input byte for byte as it was.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>

#include "apps/output_test_inputs.h"
#include "apps/tool_paths.h"
#include "test_support.h"

namespace mcws {
namespace {

namespace fs = std::filesystem;

/// One tool writing one of its inputs.
struct SamePathCase {
  std::string name;         ///< the test's name
  std::string tool;         ///< executable
  std::string args;         ///< every flag but the output; "{in}" stands for the input's path
  std::string output_flag;  ///< the flag that names the input as output
  std::string input_label;  ///< how the message names the input ("input": "--input")
  std::string source;       ///< copied into a fresh directory as the input
};

const std::string kLowBatteryFaults = std::string(MCWS_SCENARIOS_DIR) + "/faults/low_battery.yaml";
const std::string kTrajArgs = " --from '0 0' --to '0.1 0.2' --duration 1 --rate 10";

void PrintTo(const SamePathCase& c, std::ostream* out) { *out << c.name; }

class SamePath : public ::testing::TestWithParam<SamePathCase> {};

TEST_P(SamePath, RefusedWithExitTwoNamingBothFlagsAndTheInputUntouched) {
  const SamePathCase& c = GetParam();
  test::TempDir dir, other;
  const std::string name = "in" + fs::path(c.source).extension().string();
  const std::string input = dir.file(name);
  // A scenario names its robot relative to itself: the copy names the original.
  std::string text = test::readFile(c.source);
  test::replaceAll(text, "../robots/planar2.yaml", test::kPlanar2Robot);
  test::writeFile(input, text);
  fs::create_symlink(name, dir.file("link"));
  // mcws_plan's robot comes from the scenario: a scenario (elsewhere) that names the copy.
  std::string scenario = test::readFile(test::kPlanar2Scenario);
  test::replaceAll(scenario, "../robots/planar2.yaml", input);
  test::writeFile(other.file("scenario.yaml"), scenario);
  std::string args = c.args;
  test::replaceAll(args, "{in}", input);
  test::replaceAll(args, "{scenario}", other.file("scenario.yaml"));
  test::replaceAll(args, "{other}", other.file(""));
  const std::string original = test::readFile(input);
  const std::set<std::string> before = test::listing(dir.file(""));

  for (const std::string& output : {input, "./" + name, dir.file("link")}) {
    const test::RunResult r = test::run("cd " + dir.file("") + " && " + c.tool + " " + args +
                                        " --" + c.output_flag + " " + output);
    EXPECT_EQ(r.exit_code, 2) << output << "\n" << r.err;
    EXPECT_NE(r.err.find("--" + c.output_flag + ": '" + output + "' is the same file as --" +
                         c.input_label),
              std::string::npos)
        << r.err;
    EXPECT_EQ(test::lineCount(r.err), 1) << r.err;
    EXPECT_TRUE(test::readFile(input) == original) << output << ": the input changed";
    EXPECT_EQ(test::listing(dir.file("")), before) << output;
    EXPECT_TRUE(fs::is_symlink(dir.file("link")));
  }
  EXPECT_EQ(test::listing(other.file("")), std::set<std::string>{"scenario.yaml"});
}

INSTANTIATE_TEST_SUITE_P(
    EveryTool, SamePath,
    ::testing::Values(
        SamePathCase{"SampleRobot", MCWS_SAMPLE_EXE, "--robot {in}", "output", "robot",
                     test::kPlanar2Robot},
        SamePathCase{"RefineRobot", MCWS_REFINE_EXE,
                     "--robot {in} --input " + test::kAnnulusCloud + " --samples 10", "output",
                     "robot", test::kPlanar2Robot},
        SamePathCase{"RefineInput", MCWS_REFINE_EXE,
                     "--robot " + test::kPlanar2Robot + " --input {in} --samples 10", "output",
                     "input", test::kAnnulusCloud},
        SamePathCase{"RefineCloud", MCWS_REFINE_EXE,
                     "--robot " + test::kPlanar2Robot + " --input " + test::kAnnulusCloud +
                         " --cloud {in} --samples 10",
                     "output", "cloud", test::kAnnulusCloud},
        SamePathCase{"SelectInput", MCWS_SELECT_EXE, "--input {in} --label 0", "output", "input",
                     test::kAnnulusCloud},
        SamePathCase{"TrajRobot", MCWS_TRAJ_EXE, "--robot {in}" + kTrajArgs, "output", "robot",
                     test::kPlanar2Robot},
        SamePathCase{"TrajPlot", MCWS_TRAJ_EXE, "--robot {in} --output {other}t.csv" + kTrajArgs,
                     "plot", "robot", test::kPlanar2Robot},
        SamePathCase{"BoundaryInput", MCWS_BOUNDARY_EXE, "--input {in}", "output", "input",
                     test::kAnnulusCloud},
        SamePathCase{"BoundaryInterior", MCWS_BOUNDARY_EXE, "--input {in} --output {other}b.pcd",
                     "interior", "input", test::kAnnulusCloud},
        SamePathCase{"ReachRobot", MCWS_REACH_EXE, "--robot {in} --resolution 10cm", "output",
                     "robot", test::kPlanar2Robot},
        SamePathCase{"ReachTargets", MCWS_REACH_EXE,
                     "--robot " + test::kPlanar2Robot + " --targets {in}", "output", "targets",
                     test::kAnnulusCloud},
        SamePathCase{
            "PlaceTargets", MCWS_PLACE_EXE,
            "--robot " + test::kPlanar2Robot + " --targets {in} --along '0 10 5' --resolution 10cm",
            "output", "targets", test::kAnnulusCloud},
        SamePathCase{"PlanScenario", MCWS_PLAN_EXE, "--scenario {in}", "output", "scenario",
                     test::kPlanar2Scenario},
        SamePathCase{"PlanScenariosRobot", MCWS_PLAN_EXE, "--scenario {scenario}", "output",
                     "scenario's robot", test::kPlanar2Robot},
        SamePathCase{"BehaveModel", MCWS_BEHAVE_EXE, "--model {in} --insulators 1", "log", "model",
                     test::kCleanerBehaviors},
        SamePathCase{"BehaveFaults", MCWS_BEHAVE_EXE,
                     "--model " + test::kCleanerBehaviors + " --insulators 1 --faults {in}",
                     "timeline", "faults", kLowBatteryFaults}),
    [](const ::testing::TestParamInfo<SamePathCase>& info) { return info.param.name; });

}  // namespace
}  // namespace mcws
