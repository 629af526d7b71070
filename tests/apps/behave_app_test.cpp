// mcws_behave through its command line: --check, a clean run with its log, timeline, plot, DOT
// and JSON summary, the literal model stopped by the invariant (exit 1), faults from a file, the
// same log bytes twice, and bad command lines and files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "apps/tool_paths.h"
#include "png_image.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

const std::string kModel = test::robotPath("insulator_cleaner_behaviors");
const std::string kLiteral = std::string(MCWS_ROBOTS_DIR) +
                             "/../tests/behavior/data/insulator_cleaner_behaviors_literal.yaml";
const std::string kFaults = std::string(MCWS_SCENARIOS_DIR) + "/faults/";

std::vector<nlohmann::json> jsonLines(const std::string& text) {
  std::vector<nlohmann::json> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) out.push_back(nlohmann::json::parse(line));
  return out;
}

TEST(BehaveApp, CheckPrintsTheCountsOfTheShippedModel) {
  const test::RunResult r = test::run(kBehave + " --model " + kModel + " --check");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("96 combinations, 17 allowed, 79 forbidden"));
  EXPECT_THAT(r.out, HasSubstr("valid"));
  const test::RunResult j = test::run(kBehave + " --model " + kModel + " --check --json");
  ASSERT_EQ(j.exit_code, 0) << j.err;
  const nlohmann::json report = nlohmann::json::parse(j.out);
  EXPECT_EQ(report["state_vector_combinations"], 96);
  EXPECT_EQ(report["allowed_poses"], 17);
  EXPECT_EQ(report["basic_behaviors"], 9);
  EXPECT_EQ(report["valid"], true);
  ASSERT_EQ(report["combined_behaviors"].size(), 3u);
  EXPECT_EQ(report["combined_behaviors"][0]["name"], "CB1");
  EXPECT_EQ(report["combined_behaviors"][0]["transitions"], 6);
  EXPECT_EQ(report["combined_behaviors"][1]["transitions"], 8);
}

TEST(BehaveApp, CheckFlagsThePapersLiteralCb1) {
  const test::RunResult r = test::run(kBehave + " --model " + kLiteral + " --check");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("q6 -> q1"));
  EXPECT_THAT(r.out, HasSubstr("1 pose finding"));
}

TEST(BehaveApp, ACleanRunWritesLogTimelinePlotDotAndSummary) {
  test::TempDir dir;
  const std::string log = dir.file("run.jsonl"), csv = dir.file("run.csv"),
                    png = dir.file("run.png"), dot = dir.file("dot");
  const test::RunResult r =
      test::run(kBehave + " --model " + kModel + " --insulators 3 --log " + log + " --timeline " +
                csv + " --plot " + png + " --plot-all --dot " + dot + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The plan is echoed for the worker to confirm.
  EXPECT_THAT(r.err, HasSubstr("1 CB1 move down one disc -> disc 1"));
  EXPECT_THAT(r.err, HasSubstr("9 CB3 move up one disc -> disc 0"));
  const nlohmann::json summary = nlohmann::json::parse(r.out);
  EXPECT_EQ(summary["status"], "completed");
  EXPECT_EQ(summary["discs_cleaned"], 3);
  EXPECT_EQ(summary["final_disc"], 0);
  EXPECT_EQ(summary["behaviors_run"], 60);
  EXPECT_EQ(summary["invariant"]["holds"], true);

  const std::vector<nlohmann::json> lines = jsonLines(test::readFile(log));
  ASSERT_GT(lines.size(), 60u);
  EXPECT_EQ(lines[0]["event"], "log_header");
  int transitions = 0;
  for (std::size_t k = 1; k < lines.size(); ++k) {
    for (const char* key : {"t", "subtask", "state", "event", "behavior"}) {
      EXPECT_TRUE(lines[k].contains(key)) << key << " in " << lines[k].dump();
    }
    const std::string event = lines[k]["event"];
    transitions += event == "zero_switch" || event == "encoder_reached" ||
                   event == "encoder_zero" || event == "current_held" || event == "speed_reached" ||
                   event == "speed_zero";
  }
  EXPECT_EQ(transitions, 60);  // every behaviour ended on its event and fired its transition
  EXPECT_EQ(lines.back()["event"], "run_end");

  const std::string timeline = test::readFile(csv);
  EXPECT_EQ(timeline.rfind("t_s,step,subtask,task_state,cb,state,J1_deg,", 0), 0u);
  // One row every 0.1 s of the simulated duration, plus the header and the row at 0.
  const double duration = summary["duration_s"];
  EXPECT_NEAR(test::lineCount(timeline), duration / 0.1 + 2, 1.0);
  // The plot (--plot-all: the whole run, the first and last timeline rows at the frame's
  // edges; firstDiscWindow() has its own test): phase II (CB2)
  // shaded #d6e6f5 from the first row the timeline gives to CB2, within 3 pixels.
  double t_cb2 = -1.0, t_last = 0.0;
  {
    std::istringstream rows(timeline);
    std::string row;
    std::getline(rows, row);  // header: t_s is column 0, cb column 4
    while (std::getline(rows, row)) {
      std::vector<std::string> cells;
      std::istringstream fields(row);
      for (std::string cell; std::getline(fields, cell, ',');) cells.push_back(cell);
      ASSERT_GT(cells.size(), 4u) << row;
      t_last = std::stod(cells[0]);
      if (t_cb2 < 0.0 && cells[4] == "CB2") t_cb2 = t_last;
    }
  }
  ASSERT_GT(t_cb2, 0.0);
  const test::PngImage picture(png);
  ASSERT_EQ(picture.width(), 1200);
  ASSERT_EQ(picture.height(), 800);
  const test::PixelBox frame = picture.frame();
  ASSERT_FALSE(frame.empty());
  const test::PixelBox upper{frame.x0, frame.x1, frame.y0, frame.y0 + 100};
  const test::PixelBox phase2 = picture.box(0xd6e6f5, 0, upper);
  ASSERT_FALSE(phase2.empty());
  EXPECT_NEAR(phase2.x0, frame.x0 + t_cb2 / t_last * frame.width(), 3.0) << "CB2 at " << t_cb2;
  EXPECT_FALSE(picture.box(0xfbf0d9, 0, upper).empty());  // phase I before it
  for (const char* name : {"CB1.dot", "CB2.dot", "CB3.dot", "task.dot"}) {
    EXPECT_THAT(test::readFile(dot + "/" + name), HasSubstr("digraph")) << name;
  }
}

TEST(BehaveApp, SameInputsSameLogBytes) {
  test::TempDir dir;
  const std::string args = " --model " + kModel + " --insulators 2 --faults " + kFaults +
                           "rehearsal.yaml --timeline-period 0.5";
  ASSERT_EQ(test::run(kBehave + args + " --log " + dir.file("a.jsonl") + " --timeline " +
                      dir.file("a.csv"))
                .exit_code,
            0);
  ASSERT_EQ(test::run(kBehave + args + " --log " + dir.file("b.jsonl") + " --timeline " +
                      dir.file("b.csv"))
                .exit_code,
            0);
  EXPECT_EQ(test::readFile(dir.file("a.jsonl")), test::readFile(dir.file("b.jsonl")));
  EXPECT_EQ(test::readFile(dir.file("a.csv")), test::readFile(dir.file("b.csv")));
  EXPECT_GT(test::readFile(dir.file("a.jsonl")).size(), 1000u);
}

TEST(BehaveApp, TheLiteralModelEndsInASafetyStopWithExit1) {
  test::TempDir dir;
  const std::string log = dir.file("literal.jsonl");
  const test::RunResult r =
      test::run(kBehave + " --model " + kLiteral + " --insulators 3 --log " + log + " --json");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("mcws_behave: safety stop: "));
  EXPECT_THAT(r.err, HasSubstr("refused BB_Brush's own command J6 spin 300 rpm in CB2 q1"));
  EXPECT_THAT(r.err, HasSubstr("moving_clamp_open_parks_the_cleaner"));
  const nlohmann::json summary = nlohmann::json::parse(r.out);
  EXPECT_EQ(summary["status"], "safety_stop");
  EXPECT_EQ(summary["invariant"]["holds"], true);
  EXPECT_EQ(summary["safety_stop"]["cb"], "CB2");
  EXPECT_EQ(summary["safety_stop"]["state"], "q1");
  EXPECT_EQ(summary["safety_stop"]["behavior"], "BB_Brush");
  EXPECT_EQ(summary["safety_stop"]["command"], "J6 spin 300 rpm");
  EXPECT_EQ(summary["discs_cleaned"], 0);
  // The log is kept: it shows the engineer how the robot got there, with the state the
  // sensors read at the end of CB1.
  const std::vector<nlohmann::json> lines = jsonLines(test::readFile(log));
  ASSERT_GE(lines.size(), 3u);
  EXPECT_EQ(lines[lines.size() - 2]["event"], "refused");
  bool sensed = false;
  for (const auto& line : lines) {
    sensed =
        sensed || (line["event"] == "subtask_done" &&
                   std::string(line["detail"]).find("the sensors read q6") != std::string::npos);
  }
  EXPECT_TRUE(sensed);
}

TEST(BehaveApp, FaultTimesAreInjectedDetectedAndResolved) {
  // link_outage.yaml: the link down at 10 s for 40 s; the robot stops at once and resumes when
  // it is back.
  const test::RunResult r = test::run(kBehave + " --model " + kModel + " --insulators 1 --faults " +
                                      kFaults + "link_outage.yaml --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json summary = nlohmann::json::parse(r.out);
  ASSERT_EQ(summary["faults"].size(), 1u);
  const nlohmann::json& f = summary["faults"][0];
  EXPECT_EQ(f["fault"], "link_down");
  EXPECT_FALSE(f.contains("t_s"));
  EXPECT_DOUBLE_EQ(f["injected_t_s"].get<double>(), 10.0);
  EXPECT_DOUBLE_EQ(f["detected_t_s"].get<double>(), 10.0);
  EXPECT_DOUBLE_EQ(f["resolved_t_s"].get<double>(), 50.0);
}

TEST(BehaveApp, ModelNamesThatWouldWriteOutsideTheDotDirectoryAreRefused) {
  test::TempDir in, out;
  const std::string shipped = test::readFile(kModel);
  for (const std::string& bad : {std::string("../../x"), std::string("task")}) {
    std::string text = shipped;
    const std::string from = "  - name: CB3\n";
    text.replace(text.find(from), from.size(), "  - name: \"" + bad + "\"\n");
    const std::string robot = "robot: insulator_cleaner.yaml";
    text.replace(text.find(robot), robot.size(),
                 "robot: " + std::string(MCWS_ROBOTS_DIR) + "/insulator_cleaner.yaml");
    const std::string model = in.file("bad.yaml");
    test::writeFile(model, text);
    test::expectToolFailure(kBehave,
                            "--model " + model + " --insulators 1 --dot " + out.file("a/b"), 1,
                            "bad.yaml:", out);
    const test::RunResult r =
        test::run(kBehave + " --model " + model + " --check --dot " + out.file("a/b"));
    EXPECT_THAT(r.err, HasSubstr("name '" + bad + "'"));
    EXPECT_FALSE(std::filesystem::exists(out.file("x.dot")));
    EXPECT_FALSE(std::filesystem::exists(out.file("a/b/task.dot")));
  }
}

TEST(BehaveApp, EachShippedFaultFileGivesItsDocumentedReaction) {
  struct Case {
    const char* file;
    int discs;
    const char* status;
    const char* fault;
  };
  for (const Case& c : {Case{"link_outage.yaml", 3, "completed", "link_down"},
                        Case{"link_lost.yaml", 3, "returned", "link_down"},
                        Case{"stuck_switch.yaml", 3, "completed", "timeout"},
                        Case{"low_battery.yaml", 28, "returned", "battery_low"},
                        Case{"rehearsal.yaml", 3, "completed", "wrong_command"}}) {
    const test::RunResult r =
        test::run(kBehave + " --model " + kModel + " --insulators " + std::to_string(c.discs) +
                  " --faults " + kFaults + c.file + " --json");
    ASSERT_EQ(r.exit_code, 0) << c.file << "\n" << r.err;
    const nlohmann::json summary = nlohmann::json::parse(r.out);
    EXPECT_EQ(summary["status"], c.status) << c.file;
    EXPECT_EQ(summary["invariant"]["holds"], true) << c.file;
    EXPECT_EQ(summary["final_disc"], 0) << c.file;
    bool seen = false;
    for (const auto& f : summary["faults"]) seen = seen || f["fault"] == c.fault;
    EXPECT_TRUE(seen) << c.file << ": " << summary["faults"].dump();
  }
}

TEST(BehaveApp, BadCommandLinesAndFilesAreOneLineErrors) {
  test::TempDir out;
  const std::string log = " --log " + out.file("run.jsonl");
  test::expectToolFailure(kBehave, "--model " + kModel + log, 2, "--check or --insulators", out);
  test::expectToolFailure(kBehave, "--model " + kModel + " --insulators 0" + log, 2, "insulators",
                          out);
  test::expectToolFailure(kBehave, "--model " + kModel + " --insulators 3x" + log, 2, "3x", out);
  test::expectToolFailure(kBehave, "--model " + kModel + " --check --insulators 3", 2,
                          "--check or --insulators", out);
  test::expectToolFailure(kBehave, "--insulators 3" + log, 2, "model", out);
  test::expectToolFailure(kBehave,
                          "--model " + kModel + " --insulators 3 --timeline-period 0" + log, 2,
                          "--timeline-period: 0 s is not a positive number", out);
  test::expectToolFailure(
      kBehave, "--model " + kModel + " --insulators 3 --timeline-period 0.005" + log, 2,
      "--timeline-period: period = 0.005 s is below the simulator's step 0.01 s", out);
  test::expectToolFailure(kBehave,
                          "--model " + kModel + " --insulators 3 --timeline-period 0.015" + log, 2,
                          "is not a whole multiple of the simulator's step 0.01 s", out);
  test::expectToolFailure(kBehave, "--model " + kModel + " --insulators 3 --log " + kModel, 2,
                          "log", out);
  // A bad fault file names its file and line.
  test::TempDir in;
  const std::string faults = in.file("f.yaml");
  test::writeFile(faults, "faults:\n  - {at: 10 s, type: link_dwn}\n");
  test::expectToolFailure(kBehave, "--model " + kModel + " --insulators 3 --faults " + faults + log,
                          1, "f.yaml:2", out);
  test::expectToolFailure(kBehave, "--model " + in.file("missing.yaml") + " --insulators 3" + log,
                          1, "missing.yaml", out);
  EXPECT_EQ(test::readFile(faults), "faults:\n  - {at: 10 s, type: link_dwn}\n");
}

}  // namespace
}  // namespace mcws
