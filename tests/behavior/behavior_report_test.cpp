// What mcws_behave writes about a run: JSON log lines, the summary, the timeline CSV, the joint
// speed picture (Wang et al. 2018, Figure 10) and the state machines as Graphviz DOT.
#include "mcws/behavior/behavior_report.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "mcws/core/error.h"
#include "test_support.h"

namespace mcws {
namespace {

const std::string kPngSignature = "\x89PNG";

bool startsWith(const std::string& text, const std::string& prefix) {
  return text.rfind(prefix, 0) == 0;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// Sets PATH for the scope of the object, then puts the old value back.
class PathOverride {
 public:
  explicit PathOverride(const std::string& path) {
    if (const char* old = std::getenv("PATH")) old_ = old;
    ::setenv("PATH", path.c_str(), 1);
  }
  ~PathOverride() {
    if (old_) {
      ::setenv("PATH", old_->c_str(), 1);
    } else {
      ::unsetenv("PATH");
    }
  }
  PathOverride(const PathOverride&) = delete;
  PathOverride& operator=(const PathOverride&) = delete;

 private:
  std::optional<std::string> old_;
};

/// Whether Graphviz `dot` is installed (an executable `dot` in a PATH directory).
bool dotInstalled() { return test::run("command -v dot").exit_code == 0; }

TimelineRow rowAt(double t, const std::string& combined) {
  TimelineRow row;
  row.t = t;
  row.combined = combined;
  return row;
}

// ---- log lines --------------------------------------------------------------------------------

TEST(LogRecordJson, KeysInOrderTimeRoundedStringsEscapedNoSeqWhenUnset) {
  LogRecord record;
  record.t = 1.2345678;  // rounds to the microsecond: 1.234568
  record.step = 123;
  record.subtask = 2;
  record.task_state = "CB1";
  record.combined = "CB1";
  record.state = "q3";
  record.event = "behavior_end";
  record.behavior = "BB_MP_Extend";
  record.disc = 1;
  record.detail = "J3 \"move_to\"\n155 mm\\";
  const std::string expected =
      R"({"t":1.234568,"step":123,"subtask":2,"task_state":"CB1","cb":"CB1","state":"q3",)"
      R"("event":"behavior_end","behavior":"BB_MP_Extend","disc":1,)"
      R"("detail":"J3 \"move_to\"\n155 mm\\"})";
  EXPECT_EQ(logRecordJson(record), expected);
  EXPECT_EQ(logRecordJson(record), logRecordJson(record));
}

TEST(LogRecordJson, SeqBetweenBehaviorAndDiscWhenSet) {
  LogRecord record;
  record.t = 0.0300000000001;  // 0.03 after rounding
  record.step = 3;
  record.task_state = "CB2";
  record.combined = "CB2";
  record.state = "q7";
  record.event = "command";
  record.behavior = "BB_Brush_Spin";
  record.seq = 17;
  record.disc = 4;
  record.detail = "J6 spin 300 rpm";
  EXPECT_EQ(logRecordJson(record),
            R"({"t":0.03,"step":3,"subtask":0,"task_state":"CB2","cb":"CB2","state":"q7",)"
            R"("event":"command","behavior":"BB_Brush_Spin","seq":17,"disc":4,)"
            R"("detail":"J6 spin 300 rpm"})");
}

TEST(LogRecordJson, IsOneLine) {
  LogRecord record;
  record.detail = "a\nb\r\n";
  const std::string line = logRecordJson(record);
  EXPECT_EQ(line.find('\n'), std::string::npos) << line;
  EXPECT_EQ(line.find('\r'), std::string::npos) << line;
  EXPECT_TRUE(contains(line, R"("detail":"a\nb\r\n")")) << line;
}

TEST(LogHeaderJson, NamesModelInsulatorsAndFaultsOrNull) {
  EXPECT_EQ(logHeaderJson("robots/insulator_cleaner_behaviors.yaml", 3, ""),
            R"({"t":0,"event":"log_header","units":{"t":"s"},)"
            R"("model":"robots/insulator_cleaner_behaviors.yaml","insulators":3,"faults":null})");
  EXPECT_EQ(logHeaderJson("m.yaml", 28, "faults/link \"down\".yaml"),
            R"({"t":0,"event":"log_header","units":{"t":"s"},"model":"m.yaml","insulators":28,)"
            R"("faults":"faults/link \"down\".yaml"})");
}

// ---- summary ----------------------------------------------------------------------------------

TEST(SummaryJson, KeysInDocumentedOrderWithAViolation) {
  RunSummary summary;
  summary.status = RunStatus::kInvariantViolated;
  summary.discs_requested = 2;
  summary.discs_cleaned = 1;
  summary.final_disc = 2;
  summary.plan = {{"CB1", "move down one disc", 1}, {"CB2", "clean disc", 1}};
  summary.subtasks_completed = 3;
  summary.behaviors_run = 15;
  summary.commands_sent = 16;
  summary.duration_s = 75.25;
  summary.steps = 7525;
  summary.faults = {{"link_down", 10.5, 10.5, 12.5, "stopped; link back after 2 s: q3 again"},
                    {"battery_low", std::nullopt, 70.5, std::nullopt, "alarm"}};
  InvariantViolation violation;
  static_cast<RunPlace&>(violation) = {7525, 75.25, 3, "CB1", "q2", "BB_LG_Release"};
  violation.message = "step 7525 (t = 75.25 s): both clamps open";
  summary.violation = violation;
  summary.battery_voltage_end = 24.5;
  summary.battery_charge_used = 0.125;
  summary.battery_alarm_t = 70.5;
  summary.phase_one_s = 50.0;
  summary.phase_two_s = 25.25;

  const nlohmann::ordered_json json = summaryJson(summary);
  std::vector<std::string> keys;
  for (auto it = json.begin(); it != json.end(); ++it) keys.push_back(it.key());
  const std::vector<std::string> expected_keys = {"status",
                                                  "discs_requested",
                                                  "discs_cleaned",
                                                  "final_disc",
                                                  "duration_s",
                                                  "steps",
                                                  "subtasks_completed",
                                                  "behaviors_run",
                                                  "commands_sent",
                                                  "phase_one_s",
                                                  "phase_two_s",
                                                  "battery_voltage_end_V",
                                                  "battery_charge_used_Ah",
                                                  "battery_alarm_t_s",
                                                  "faults",
                                                  "invariant",
                                                  "safety_stop",
                                                  "plan"};
  EXPECT_EQ(keys, expected_keys);

  EXPECT_EQ(json.dump(),
            R"({"status":"invariant_violated","discs_requested":2,"discs_cleaned":1,)"
            R"("final_disc":2,"duration_s":75.25,"steps":7525,"subtasks_completed":3,)"
            R"("behaviors_run":15,"commands_sent":16,"phase_one_s":50.0,"phase_two_s":25.25,)"
            R"("battery_voltage_end_V":24.5,"battery_charge_used_Ah":0.125,)"
            R"("battery_alarm_t_s":70.5,)"
            R"("faults":[{"fault":"link_down","injected_t_s":10.5,"detected_t_s":10.5,)"
            R"("resolved_t_s":12.5,"reaction":"stopped; link back after 2 s: q3 again"},)"
            R"({"fault":"battery_low","injected_t_s":null,"detected_t_s":70.5,)"
            R"("resolved_t_s":null,"reaction":"alarm"}],)"
            R"("invariant":{"holds":false,"violation":{"step":7525,"t_s":75.25,"subtask":3,)"
            R"("cb":"CB1","state":"q2","behavior":"BB_LG_Release",)"
            R"("message":"step 7525 (t = 75.25 s): both clamps open"}},"safety_stop":null,)"
            R"("plan":[{"cb":"CB1","action":"move down one disc","disc":1},)"
            R"({"cb":"CB2","action":"clean disc","disc":1}]})");
}

TEST(SummaryJson, NoAlarmNoFaultsNoViolation) {
  RunSummary summary;
  summary.status = RunStatus::kCompleted;
  const nlohmann::ordered_json json = summaryJson(summary);
  EXPECT_EQ(json["status"], "completed");
  EXPECT_TRUE(json["battery_alarm_t_s"].is_null());
  EXPECT_TRUE(json["faults"].is_array());
  EXPECT_TRUE(json["faults"].empty());
  EXPECT_TRUE(json["plan"].is_array());
  EXPECT_TRUE(json["plan"].empty());
  EXPECT_EQ(json["invariant"].dump(), R"({"holds":true,"violation":null})");
  EXPECT_TRUE(json["safety_stop"].is_null());
}

TEST(SummaryJson, ASafetyStopNamesTheCommandAndTheReason) {
  RunSummary summary;
  summary.status = RunStatus::kSafetyStop;
  SafetyStop stop;
  static_cast<RunPlace&>(stop) = {10869, 108.69, 2, "CB2", "q1", "BB_Brush"};
  stop.command = "J6 spin 300 rpm";
  stop.reason = "rule 'r'";
  stop.message = "step 10869 (t = 108.69 s): refused";
  summary.safety_stop = stop;
  EXPECT_EQ(summaryJson(summary)["status"], "safety_stop");
  EXPECT_EQ(summaryJson(summary)["safety_stop"].dump(),
            R"({"step":10869,"t_s":108.69,"subtask":2,"cb":"CB2","state":"q1",)"
            R"("behavior":"BB_Brush","command":"J6 spin 300 rpm","reason":"rule 'r'",)"
            R"("message":"step 10869 (t = 108.69 s): refused"})");
  EXPECT_NE(summaryText(summary).find("safety stop: step 10869 (t = 108.69 s): refused"),
            std::string::npos);
}

// ---- timeline ---------------------------------------------------------------------------------

const char* const kCsvHeader =
    "t_s,step,subtask,task_state,cb,state,J1_deg,J2_deg,J3_mm,J4_mm,J5_deg,J6_deg,J1_deg_per_s,"
    "J2_deg_per_s,J3_mm_per_s,J4_mm_per_s,J5_deg_per_s,J6_rpm,J1_A,J2_A,J3_A,J4_A,J5_A,J6_A,"
    "J1_zero_switch,J2_zero_switch,J1_gripping,J2_gripping,battery_V,battery_low,link_up";

TEST(TimelineCsv, HeaderOnlyForNoRows) {
  std::ostringstream out;
  writeTimelineCsv(out, {});
  EXPECT_EQ(out.str(), std::string(kCsvHeader) + "\n");
}

TEST(TimelineCsv, OneRowWithNineSignificantDigitsAndBooleansAsBits) {
  TimelineRow row;
  row.t = 0.1 + 0.2;  // 0.30000000000000004: 0.3 with 9 digits
  row.step = 30;
  row.subtask = 1;
  row.task_state = "CB1";
  row.combined = "CB1";
  row.state = "q2";
  row.position = {12.5, 25.0, 1.0 / 3.0, 0.0, 359.999999999, 123456789012.0};
  row.velocity = {-10.0, -0.0, 20.0, 0.0, 1e-7, 300.0};
  row.current = {0.4, 0.0, 0.8, 0.0, 0.0, 1.2};
  row.fixed_zero_switch = false;
  row.moving_zero_switch = true;
  row.fixed_gripping = false;
  row.moving_gripping = true;
  row.battery_voltage = 25.1996;
  row.battery_low = false;
  row.link_up = true;
  std::ostringstream out;
  writeTimelineCsv(out, {row});
  // 1/3 -> 0.333333333; 359.999999999 -> 360; 123456789012 -> 1.23456789e+11; -0 -> 0.
  const std::string line =
      "0.3,30,1,CB1,CB1,q2,12.5,25,0.333333333,0,360,1.23456789e+11,-10,0,20,0,1e-07,300,"
      "0.4,0,0.8,0,0,1.2,0,1,0,1,25.1996,0,1";
  EXPECT_EQ(out.str(), std::string(kCsvHeader) + "\n" + line + "\n");
}

TEST(TimelineCsv, QuotesTextWithCommas) {
  TimelineRow row = rowAt(0.0, "CB,2");
  std::ostringstream out;
  writeTimelineCsv(out, {row});
  const std::string text = out.str();
  EXPECT_TRUE(contains(text, "\n0,0,0,,\"CB,2\",,")) << text;
}

SimSnapshot snapshotAt(std::uint64_t step, double dt) {
  SimSnapshot s;
  s.step = step;
  s.time = static_cast<double>(step) * dt;
  for (std::size_t j = 0; j < kSimJointCount; ++j) {
    s.joints[j].position = 100.0 * static_cast<double>(step) + static_cast<double>(j);
    s.joints[j].velocity = -static_cast<double>(j) - 0.5;
    s.joints[j].current = 0.1 * static_cast<double>(j + 1);
  }
  s.joints[simJointIndex(SimJoint::kJ1)].zero_switch = step == 5;
  s.joints[simJointIndex(SimJoint::kJ2)].zero_switch = step == 10;
  s.joints[simJointIndex(SimJoint::kJ1)].gripping = step != 5;
  s.joints[simJointIndex(SimJoint::kJ2)].gripping = step != 10;
  s.battery_voltage = 25.2 - 0.001 * static_cast<double>(step);
  s.battery_low = step == 10;
  s.link_up = step != 5;
  return s;
}

TEST(TimelineRecorder, KeepsStepZeroAndEveryFifthStepForAPeriodOfFiveSteps) {
  const double dt = 0.01;
  TimelineRecorder recorder(0.05, dt);  // k = 5
  for (std::uint64_t step = 0; step <= 12; ++step) {
    StepContext context;
    context.subtask = static_cast<int>(step);
    context.task_state = step < 10 ? "CB1" : "CB2";
    context.combined = step < 10 ? "CB1" : "CB2";
    context.state = "q" + std::to_string(step);
    context.behavior = "BB";
    recorder(snapshotAt(step, dt), context);
  }
  const std::vector<TimelineRow>& rows = recorder.rows();
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].step, 0u);
  EXPECT_EQ(rows[1].step, 5u);
  EXPECT_EQ(rows[2].step, 10u);
  EXPECT_DOUBLE_EQ(rows[1].t, 0.05);

  // Row of step 5: everything copied from its snapshot and context.
  const TimelineRow& r = rows[1];
  EXPECT_EQ(r.subtask, 5);
  EXPECT_EQ(r.task_state, "CB1");
  EXPECT_EQ(r.combined, "CB1");
  EXPECT_EQ(r.state, "q5");
  for (std::size_t j = 0; j < kSimJointCount; ++j) {
    EXPECT_EQ(r.position[j], 500.0 + static_cast<double>(j)) << j;
    EXPECT_EQ(r.velocity[j], -static_cast<double>(j) - 0.5) << j;
    EXPECT_EQ(r.current[j], 0.1 * static_cast<double>(j + 1)) << j;
  }
  EXPECT_TRUE(r.fixed_zero_switch);
  EXPECT_FALSE(r.moving_zero_switch);
  EXPECT_FALSE(r.fixed_gripping);
  EXPECT_TRUE(r.moving_gripping);
  EXPECT_EQ(r.battery_voltage, 25.2 - 0.005);
  EXPECT_FALSE(r.battery_low);
  EXPECT_FALSE(r.link_up);

  // Row of step 10: the other clamp's switches, the low battery, the link up.
  const TimelineRow& s = rows[2];
  EXPECT_EQ(s.combined, "CB2");
  EXPECT_FALSE(s.fixed_zero_switch);
  EXPECT_TRUE(s.moving_zero_switch);
  EXPECT_TRUE(s.fixed_gripping);
  EXPECT_FALSE(s.moving_gripping);
  EXPECT_TRUE(s.battery_low);
  EXPECT_TRUE(s.link_up);
}

TEST(TimelineRecorder, RejectsAPeriodBelowTheStepOrNotAWholeNumberOfSteps) {
  // Below the step there is nothing between two steps to record; 0.015 s with 0.01 s steps
  // would silently give rows every 0.02 s.
  for (const double period : {0.001, 0.005, 0.0099, 0.015, 0.105}) {
    const std::string message = test::errorOf([&] { TimelineRecorder(period, 0.01); });
    EXPECT_TRUE(contains(message, "period = ")) << period << ": " << message;
    EXPECT_TRUE(contains(message, "0.01 s")) << message;
  }
  // The step itself and whole multiples (0.1 / 0.01 is 10.000000000000002 in doubles).
  for (const double period : {0.01, 0.02, 0.1, 0.3, 2.5}) {
    TimelineRecorder recorder(period, 0.01);
    const auto every = static_cast<std::uint64_t>(std::llround(period / 0.01));
    for (std::uint64_t step = 0; step <= 3 * every; ++step) {
      recorder(snapshotAt(step, 0.01), StepContext{});
    }
    EXPECT_EQ(recorder.rows().size(), 4u) << period;
  }
}

TEST(TimelineRecorder, RejectsAPeriodThatIsNotPositive) {
  for (double period : {0.0, -0.05}) {
    const std::string message = test::errorOf([&] { TimelineRecorder(period, 0.01); });
    EXPECT_TRUE(contains(message, "period")) << message;
  }
}

// ---- first disc window ------------------------------------------------------------------------

TEST(FirstDiscWindow, FromTheFirstCb1ToTheEndOfTheFollowingCb2) {
  const std::vector<TimelineRow> rows = {rowAt(0.0, ""),    rowAt(0.5, "CB1"), rowAt(1.0, "CB1"),
                                         rowAt(1.5, "CB2"), rowAt(2.0, "CB2"), rowAt(2.5, "CB1"),
                                         rowAt(3.0, "CB2"), rowAt(3.5, "CB3")};
  const auto [from, to] = firstDiscWindow(rows);
  EXPECT_EQ(from, 0.5);
  EXPECT_EQ(to, 2.0);
}

TEST(FirstDiscWindow, ACb2BeforeTheFirstCb1DoesNotCount) {
  const std::vector<TimelineRow> rows = {rowAt(0.0, "CB2"), rowAt(1.0, "CB1"), rowAt(2.0, "CB1"),
                                         rowAt(3.0, "CB2"), rowAt(4.0, "CB3")};
  const auto [from, to] = firstDiscWindow(rows);
  EXPECT_EQ(from, 1.0);
  EXPECT_EQ(to, 3.0);
}

TEST(FirstDiscWindow, TheWholeRunWithoutACb1ThenCb2) {
  const std::vector<TimelineRow> no_cb1 = {rowAt(0.25, "CB3"), rowAt(1.0, "CB2"), rowAt(2.75, "")};
  EXPECT_EQ(firstDiscWindow(no_cb1), std::make_pair(0.25, 2.75));
  const std::vector<TimelineRow> no_cb2 = {rowAt(0.0, "CB1"), rowAt(1.0, "CB1"),
                                           rowAt(2.0, "MANUAL")};
  EXPECT_EQ(firstDiscWindow(no_cb2), std::make_pair(0.0, 2.0));
}

// ---- joint speed picture ----------------------------------------------------------------------

std::vector<TimelineRow> speedRows() {
  std::vector<TimelineRow> rows;
  for (int i = 0; i <= 40; ++i) {
    TimelineRow row = rowAt(0.25 * i, i < 20 ? "CB1" : (i < 35 ? "CB2" : "CB3"));
    if (i < 20) {
      row.velocity[2] = i % 10 < 5 ? 20.0 : -20.0;  // J3 [mm/s]
      row.velocity[0] = i % 10 == 0 ? -10.0 : 0.0;  // J1 [deg/s]
    } else if (i < 35) {
      row.velocity[3] = 20.0;   // J4 [mm/s]
      row.velocity[4] = 30.0;   // J5 [deg/s]
      row.velocity[5] = 300.0;  // J6 [rpm]
    }
    rows.push_back(row);
  }
  return rows;
}

TEST(PlotJointSpeeds, DrawsAPng) {
  const std::string png = plotJointSpeeds(speedRows(), 1.0, 9.0, "disc 1: \"CB1\" then CB2");
  EXPECT_TRUE(startsWith(png, kPngSignature));
  EXPECT_GT(png.size(), 1000u);
}

TEST(PlotJointSpeeds, NeedsTwoRowsInTheWindow) {
  const std::vector<TimelineRow> rows = speedRows();
  const std::string empty = test::errorOf([&] { plotJointSpeeds(rows, 20.0, 30.0, "late"); });
  EXPECT_TRUE(contains(empty, "0 timeline row")) << empty;
  const std::string one = test::errorOf([&] { plotJointSpeeds(rows, 1.0, 1.1, "one"); });
  EXPECT_TRUE(contains(one, "1 timeline row")) << one;
  const std::string none = test::errorOf([&] { plotJointSpeeds({}, 0.0, 1.0, "none"); });
  EXPECT_FALSE(none.empty());
}

// ---- state machines as DOT --------------------------------------------------------------------

BehaviorModel shippedModel() {
  return loadBehaviorModel(std::string(MCWS_ROBOTS_DIR) + "/insulator_cleaner_behaviors.yaml");
}

TEST(WriteStateMachineDots, OneDotPerCombinedBehaviourAndTheTaskMachine) {
  const BehaviorModel model = shippedModel();
  test::TempDir tmp;
  const std::string dir = tmp.file("graphs/fsm");  // created, parents too
  const bool rendered = dotInstalled();
  const std::vector<std::string> written = writeStateMachineDots(model, dir);

  std::vector<std::string> expected;
  for (const char* name : {"CB1", "CB2", "CB3", "task"}) {
    expected.push_back(dir + "/" + name + ".dot");
    if (rendered) expected.push_back(dir + "/" + name + ".png");
  }
  EXPECT_EQ(written, expected);

  for (const std::string& file : expected) {
    const std::string text = test::readFile(file);
    if (file.size() > 4 && file.compare(file.size() - 4, 4, ".png") == 0) {
      EXPECT_TRUE(startsWith(text, kPngSignature)) << file;
    } else {
      EXPECT_TRUE(startsWith(text, "digraph ")) << file;
    }
  }

  // CB1's six transitions, from robots/insulator_cleaner_behaviors.yaml: each edge labelled with
  // its behaviour and event (a DOT "\n" between them).
  const std::string cb1 = test::readFile(dir + "/CB1.dot");
  for (const char* edge : {R"("q1" -> "q2" [label="BB_UG_Release\nzero_switch"])",
                           R"("q2" -> "q3" [label="BB_MP_Extend\nencoder_reached"])",
                           R"("q3" -> "q4" [label="BB_UG_Clamp\ncurrent_held"])",
                           R"("q4" -> "q5" [label="BB_LG_Release\nzero_switch"])",
                           R"("q5" -> "q6" [label="BB_MP_Home\nencoder_zero"])",
                           R"("q6" -> "q1" [label="BB_LG_Clamp\ncurrent_held"])"}) {
    EXPECT_TRUE(contains(cb1, edge)) << edge << "\n" << cb1;
  }
  const std::string task = test::readFile(dir + "/task.dot");
  EXPECT_TRUE(startsWith(task, "digraph \"task\"")) << task;
  EXPECT_TRUE(contains(task, R"("idle" -> "CB1" [label="next_CB1"])")) << task;
}

TEST(WriteStateMachineDots, OnlyDotFilesWhenGraphvizIsNotOnThePath) {
  const BehaviorModel model = shippedModel();
  test::TempDir tmp;
  const std::string dir = tmp.file("out");
  std::vector<std::string> written;
  {
    PathOverride path(tmp.file("no_such_dir") + ":" + tmp.file(""));
    written = writeStateMachineDots(model, dir);
  }
  EXPECT_EQ(written, (std::vector<std::string>{dir + "/CB1.dot", dir + "/CB2.dot", dir + "/CB3.dot",
                                               dir + "/task.dot"}));
  EXPECT_FALSE(std::filesystem::exists(dir + "/CB1.png"));
}

TEST(WriteStateMachineDots, AFailingDotIsAnErrorNamingTheFileAndTheExitStatus) {
  const BehaviorModel model = shippedModel();
  test::TempDir tmp;
  const std::string bin = tmp.file("bin");
  std::filesystem::create_directory(bin);
  test::writeFile(bin + "/dot", "#!/bin/sh\necho 'dot: syntax error in line 1' >&2\nexit 3\n");
  ASSERT_EQ(::chmod((bin + "/dot").c_str(), 0755), 0);
  const std::string dir = tmp.file("out");
  std::string message;
  {
    PathOverride path(bin);
    message = test::errorOf([&] { writeStateMachineDots(model, dir); });
  }
  EXPECT_TRUE(contains(message, dir + "/CB1.dot")) << message;
  EXPECT_TRUE(contains(message, "exit status 3")) << message;
  EXPECT_TRUE(contains(message, "syntax error in line 1")) << message;
  EXPECT_FALSE(std::filesystem::exists(dir + "/CB1.png"));
}

TEST(WriteStateMachineDots, ADirectoryThatCannotBeCreatedIsNamed) {
  const BehaviorModel model = shippedModel();
  test::TempDir tmp;
  const std::string file = tmp.file("plain_file");
  test::writeFile(file, "not a directory");
  const std::string message =
      test::errorOf([&] { writeStateMachineDots(model, file + "/graphs"); });
  EXPECT_TRUE(contains(message, file + "/graphs")) << message;
}

TEST(WriteStateMachineDots, RefusesNamesThatLeaveTheDirectoryOrOverwriteAnotherDiagram) {
  // A model built in code (the loader refuses these names already): nothing is written, not
  // even the good diagrams, and nothing appears outside the directory.
  test::TempDir tmp;
  const std::string dir = tmp.file("a/b/out");
  for (const std::string& bad :
       {std::string("../../x"), std::string("/tmp/mcws_dot_escape"), std::string(".."),
        std::string(".hidden"), std::string("task"), std::string("TASK"), std::string("cb1"),
        std::string("a\nb"), std::string("a\\b"), std::string(""), std::string(201, 'c')}) {
    BehaviorModel model = shippedModel();
    model.combined[2].name = bad;
    const std::string message = test::errorOf([&] { writeStateMachineDots(model, dir); });
    EXPECT_TRUE(contains(message, "not written to '" + dir + "'")) << message;
    EXPECT_TRUE(contains(message, quotedName(bad))) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_FALSE(std::filesystem::exists(dir + "/CB1.dot")) << bad;
  }
  EXPECT_FALSE(std::filesystem::exists(tmp.file("a/x.dot")));
  EXPECT_FALSE(std::filesystem::exists("/tmp/mcws_dot_escape.dot"));
}

}  // namespace
}  // namespace mcws
