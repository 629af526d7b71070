// Wang et al. 2018, sections 2.2-2.4 and 3.2: the executor runs the task plan on the simulated
// robot. Expectations are the paper's CB1 table, the model file's CB2 and CB3, and times worked by
// hand from the simulator's closed-form motions. Runs under injected faults are in
// behavior_executor_faults_test.cpp.
#include "mcws/behavior/behavior_executor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "behavior/behavior_executor_fixture.h"
#include "mcws/core/error.h"
#include "test_support.h"

namespace mcws {
namespace {

using test::fault;
using test::model;
using test::Recorded;
using test::runJob;

const BehaviorModel& literalModel() {
  static const BehaviorModel m =
      loadBehaviorModel(std::string(MCWS_ROBOTS_DIR) +
                        "/../tests/behavior/data/insulator_cleaner_behaviors_literal.yaml");
  return m;
}

/// The transitions fired in sub-task k: "from -> to" with behaviour and event.
struct Fired {
  std::string from, to, behavior, event;
};
std::vector<Fired> firedIn(const Recorded& rec, int k) {
  std::vector<Fired> out;
  for (const LogRecord& r : rec.subtask(k)) {
    const auto arrow = r.detail.find(" -> ");
    if (r.event == "subtask_start" || r.event == "subtask_done" || arrow == std::string::npos ||
        r.seq) {
      continue;
    }
    out.push_back({r.detail.substr(0, arrow), r.detail.substr(arrow + 4), r.behavior, r.event});
  }
  return out;
}

TEST(Executor, Cb1FollowsThePapersTableSixBehavioursOnePitchDown) {
  const Recorded rec = runJob(model(), 1);
  // The section 3.2 walk-through of Wang et al. 2018, with the corrected q6 -> q1 (the moving clamp
  // closes).
  const std::vector<Fired> expected = {
      {"q1", "q2", "BB_UG_Release", "zero_switch"}, {"q2", "q3", "BB_MP_Extend", "encoder_reached"},
      {"q3", "q4", "BB_UG_Clamp", "current_held"},  {"q4", "q5", "BB_LG_Release", "zero_switch"},
      {"q5", "q6", "BB_MP_Home", "encoder_zero"},   {"q6", "q1", "BB_LG_Clamp", "current_held"}};
  const std::vector<Fired> fired = firedIn(rec, 1);
  ASSERT_EQ(fired.size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    EXPECT_EQ(fired[k].from, expected[k].from) << k;
    EXPECT_EQ(fired[k].to, expected[k].to) << k;
    EXPECT_EQ(fired[k].behavior, expected[k].behavior) << k;
    EXPECT_EQ(fired[k].event, expected[k].event) << k;
  }
  int commands = 0;
  for (const LogRecord& r : rec.subtask(1)) commands += r.event == "command";
  EXPECT_EQ(commands, 6);
  // The robot body (fixed platform) went down exactly one pitch; J3 out to one pitch and home.
  double j3_peak = 0.0, body_at_end = 0.0;
  for (std::size_t k = 0; k < rec.steps.size(); ++k) {
    if (rec.contexts[k].subtask != 1) continue;
    j3_peak = std::max(j3_peak, rec.steps[k].joint(SimJoint::kJ3).position);
    body_at_end = rec.steps[k].fixed_platform_position;
  }
  EXPECT_DOUBLE_EQ(j3_peak, 155.0);
  EXPECT_NEAR(body_at_end, 155.0, 1e-9);
  // Hand-worked times: the fixed jaw opens from its 25 deg contact angle at 10 deg/s, so its
  // zero switch closes at 2.5 s; J3 then runs 155 mm at 10 mm/s with 40 mm/s^2 ramps:
  // 155 / 10 + 10 / 40 = 15.75 s, and the encoder (100 counts/mm) reads 15500 once the
  // remaining distance 40 tau^2 / 2 is below 0.005 mm, i.e. tau < 0.0158 s before the end.
  EXPECT_NEAR(rec.subtask(1)[2 + 1].t, 2.5, 1e-9);  // subtask_start, command, zero_switch
  const double extended = firedIn(rec, 1).size() ? rec.events("encoder_reached")[0].t : 0.0;
  EXPECT_LE(extended, 2.5 + 15.75 + 1e-9);
  EXPECT_GE(extended, 2.5 + 15.75 - 0.0159);
  EXPECT_EQ(rec.unsafe_steps, 0);
}

TEST(Executor, Cb2VisitsQ7ToQ13AndCleansBothShedsAllRound) {
  const Recorded rec = runJob(model(), 1);
  const std::vector<Fired> fired = firedIn(rec, 2);
  const std::vector<std::string> states = {"q1",  "q7",  "q8",  "q9", "q10",
                                           "q11", "q12", "q13", "q1"};
  ASSERT_EQ(fired.size(), states.size() - 1);
  for (std::size_t k = 0; k < fired.size(); ++k) {
    EXPECT_EQ(fired[k].from, states[k]) << k;
    EXPECT_EQ(fired[k].to, states[k + 1]) << k;
  }
  // While the guide turns in q8 (upper shed) and q11 (lower shed), J4 holds the shed's position
  // (60 and 100 mm in the model), the brush spins at 300 rpm, and J5 sweeps the whole circle.
  struct Sweep {
    double j4, lo{1e9}, hi{-1e9};
    bool held{true};
  };
  Sweep upper{60.0}, lower{100.0};
  for (std::size_t k = 0; k < rec.steps.size(); ++k) {
    if (rec.contexts[k].subtask != 2) continue;
    Sweep* s = rec.contexts[k].state == "q8"    ? &upper
               : rec.contexts[k].state == "q11" ? &lower
                                                : nullptr;
    if (!s) continue;
    const SimSnapshot& snap = rec.steps[k];
    s->lo = std::min(s->lo, snap.joint(SimJoint::kJ5).position);
    s->hi = std::max(s->hi, snap.joint(SimJoint::kJ5).position);
    s->held = s->held && snap.joint(SimJoint::kJ4).position == s->j4 &&
              snap.joint(SimJoint::kJ6).velocity == 300.0;
  }
  for (const Sweep* s : {&upper, &lower}) {
    EXPECT_TRUE(s->held) << s->j4;
    // The turn's ending event fires when the encoder (50 counts/deg) reads the target count,
    // i.e. within half a count, 0.01 deg, of the end.
    EXPECT_NEAR(s->lo, 0.0, 0.01) << s->j4;
    EXPECT_NEAR(s->hi, 360.0, 0.01) << s->j4;
  }
  EXPECT_EQ(rec.summary.discs_cleaned, 1);
}

TEST(Executor, ThreeDiscsRunThePlanInOrderAndEndWhereMounted) {
  const Recorded rec = runJob(model(), 3);
  const std::vector<std::string> expected = {"CB1", "CB2", "CB1", "CB2", "CB1",
                                             "CB2", "CB3", "CB3", "CB3"};
  const std::vector<LogRecord> starts = rec.events("subtask_start");
  ASSERT_EQ(starts.size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    EXPECT_EQ(starts[k].combined, expected[k]) << k;
    EXPECT_EQ(starts[k].subtask, static_cast<int>(k + 1));
  }
  EXPECT_EQ(rec.summary.status, RunStatus::kCompleted);
  EXPECT_EQ(rec.summary.discs_cleaned, 3);
  EXPECT_EQ(rec.summary.final_disc, 0);
  EXPECT_EQ(rec.summary.subtasks_completed, 9);
  EXPECT_EQ(rec.summary.behaviors_run, 3u * 6 + 3 * 8 + 3 * 6);
  // Where the worker mounted it: fixed clamp on the fitting (0 mm), moving clamp two pitches below.
  EXPECT_NEAR(rec.steps.back().fixed_platform_position, 0.0, 1e-9);
  EXPECT_NEAR(rec.steps.back().moving_platform_position, 310.0, 1e-9);
  EXPECT_NEAR(rec.summary.phase_one_s + rec.summary.phase_two_s, rec.summary.duration_s, 1e-6);
  EXPECT_EQ(rec.unsafe_steps, 0);
  EXPECT_EQ(rec.summary.faults.size(), 0u);
}

TEST(Executor, ThePapersLiteralCb1IsSafetyStoppedAtItsFirstOwnCommandTheRulesForbid) {
  // Read literally, q6 -> q1 closes the fixed clamp (already closed) and leaves the moving clamp
  // open: the machine says q1, the sensors say q6's pose. CB2's first command (the brush spun up,
  // 300 rpm) would break the rule moving_clamp_open_parks_the_cleaner on the pose the sensors
  // read, so it is refused and the run stops there, before anything of CB2 moves.
  const Recorded rec = runJob(literalModel(), 3);
  ASSERT_EQ(rec.summary.status, RunStatus::kSafetyStop);
  ASSERT_TRUE(rec.summary.safety_stop);
  EXPECT_FALSE(rec.summary.violation);
  const SafetyStop& stop = *rec.summary.safety_stop;
  EXPECT_EQ(stop.subtask, 2);
  EXPECT_EQ(stop.combined, "CB2");
  EXPECT_EQ(stop.state, "q1");
  EXPECT_EQ(stop.behavior, "BB_Brush");
  EXPECT_EQ(stop.command, "J6 spin 300 rpm");
  EXPECT_NE(stop.reason.find("moving_clamp_open_parks_the_cleaner"), std::string::npos)
      << stop.reason;
  EXPECT_NE(stop.message.find("J6 spin 300 rpm"), std::string::npos) << stop.message;
  // Stopped at CB2's start, with J2 open as the simulator has it; nothing of CB2 ever moved.
  EXPECT_EQ(stop.step, rec.events("subtask_start")[1].step);
  EXPECT_FALSE(rec.steps.back().joint(kMovingClamp).gripping);
  EXPECT_TRUE(rec.steps.back().joint(kFixedClamp).gripping);
  for (const SimSnapshot& s : rec.steps) {
    EXPECT_EQ(s.joint(SimJoint::kJ6).velocity, 0.0) << s.time;
    EXPECT_EQ(s.joint(SimJoint::kJ4).position, 0.0) << s.time;
  }
  EXPECT_EQ(rec.unsafe_steps, 0);
  // The log says where the sensors put the robot, not where the machine thinks it is.
  const LogRecord done = rec.events("subtask_done")[0];
  EXPECT_EQ(done.state, "q1");
  EXPECT_NE(done.detail.find("the sensors read q6"), std::string::npos) << done.detail;
  EXPECT_NE(done.detail.find("moving_clamp=open"), std::string::npos) << done.detail;
  // The shipped model runs the same plan to the end, its log "back in q1" after every CB.
  const Recorded shipped = runJob(model(), 3);
  EXPECT_EQ(shipped.summary.status, RunStatus::kCompleted);
  for (const LogRecord& r : shipped.events("subtask_done")) EXPECT_EQ(r.detail, "back in q1");
}

TEST(Executor, AnOwnCommandIsCheckedOnTheSensedPoseAfterAWrongCommandToo) {
  // Another way to a machine state the robot is not in: a wrong command that passes the check
  // (J2 released at CB2's q1: allowed, the fixed clamp grips and the cleaner is parked) is sent
  // instead of the brush's spin-up; BB_Brush times out (10 s) and the operator resumes it 5 s
  // later. The machine is still in q1 (both clamps closed), the sensors read J2 open: the
  // spin-up is refused by the same rule, the run stops, the brush never turns.
  const Recorded clean = runJob(model(), 1);
  const double cb2 = clean.events("subtask_start")[1].t;
  FaultScript faults;
  // Armed one step before CB2 starts: CB1's last behaviour ends, and CB2's first command (the
  // next one) goes out, in the step to cb2.
  InjectedFault wrong = fault(FaultKind::kWrongCommand, cb2 - 0.01);
  wrong.command = SimCommand::release(kMovingClamp);
  faults.faults = std::vector<InjectedFault>{wrong};
  faults.operator_responses = {{5.0, OperatorAction::kResume, 0}};
  const Recorded rec = runJob(model(), 1, faults);
  ASSERT_EQ(rec.summary.status, RunStatus::kSafetyStop) << runStatusName(rec.summary.status);
  const SafetyStop& stop = *rec.summary.safety_stop;
  EXPECT_EQ(stop.behavior, "BB_Brush");
  EXPECT_EQ(stop.state, "q1");
  EXPECT_NEAR(stop.t, cb2 + 10.0 + 5.0, 1e-9);
  EXPECT_NE(stop.reason.find("moving_clamp_open_parks_the_cleaner"), std::string::npos)
      << stop.reason;
  for (const SimSnapshot& s : rec.steps) EXPECT_EQ(s.joint(SimJoint::kJ6).velocity, 0.0);
  EXPECT_EQ(rec.unsafe_steps, 0);
}

TEST(Executor, SameInputsSameLog) {
  FaultScript faults;
  faults.faults = {fault(FaultKind::kLinkDown, 70.0, 12.0),
                   fault(FaultKind::kCorruptCommand, 100.0)};
  const Recorded a = runJob(model(), 2, faults), b = runJob(model(), 2, faults);
  ASSERT_EQ(a.log.size(), b.log.size());
  for (std::size_t k = 0; k < a.log.size(); ++k) {
    const LogRecord &x = a.log[k], &y = b.log[k];
    EXPECT_TRUE(x.t == y.t && x.step == y.step && x.subtask == y.subtask &&
                x.task_state == y.task_state && x.combined == y.combined && x.state == y.state &&
                x.event == y.event && x.behavior == y.behavior && x.seq == y.seq &&
                x.disc == y.disc && x.detail == y.detail)
        << k;
  }
  for (std::size_t k = 0; k < a.steps.size(); ++k) ASSERT_TRUE(a.steps[k] == b.steps[k]) << k;
  ASSERT_EQ(a.steps.size(), b.steps.size());
  EXPECT_TRUE(a.steps.back() == b.steps.back());
}

TEST(Executor, TheTaskMachineHasThePapersSuperstates) {
  StateMachine task = taskMachine();
  for (const char* s : {"CB1", "CB2", "CB3", "FAULT", "MANUAL"}) EXPECT_TRUE(task.hasState(s)) << s;
  EXPECT_EQ(task.current(), "idle");
  EXPECT_TRUE(task.fire("next_CB1"));
  EXPECT_TRUE(task.fire("link_lost"));
  EXPECT_EQ(task.current(), "FAULT");
  EXPECT_FALSE(task.fire("next_CB2"));  // nothing runs while the link is down
  EXPECT_TRUE(task.fire("resume_CB1"));
  EXPECT_TRUE(task.fire("hand_over"));
  EXPECT_EQ(task.current(), "MANUAL");
  EXPECT_TRUE(task.fire("resume_CB1"));
  EXPECT_TRUE(task.fire("next_CB2"));
  EXPECT_TRUE(task.fire("next_CB3"));
  EXPECT_TRUE(task.fire("job_done"));
  EXPECT_TRUE(task.inFinal());
  // What it must not allow: cleaning or climbing before moving down, a second CB2 in a row,
  // resuming another superstate than the interrupted one's kind, leaving done.
  task.reset();
  EXPECT_FALSE(task.fire("next_CB2"));
  EXPECT_FALSE(task.fire("next_CB3"));
  EXPECT_FALSE(task.fire("job_done"));
  ASSERT_TRUE(task.fire("next_CB1"));
  ASSERT_TRUE(task.fire("next_CB2"));
  EXPECT_FALSE(task.fire("next_CB2"));
  EXPECT_FALSE(task.fire("resume_CB2"));
  ASSERT_TRUE(task.fire("next_CB3"));
  EXPECT_FALSE(task.fire("next_CB1"));  // no way down again once climbing
  EXPECT_FALSE(task.fire("next_CB2"));
  ASSERT_TRUE(task.fire("job_done"));
  for (const std::string& e : task.events()) EXPECT_FALSE(task.fire(e)) << e;
}

TEST(Executor, BadOptionsAreRejected) {
  RunOptions options = RunOptions::forModel(model(), 0);
  EXPECT_NE(test::errorOf([&] { runCleaningJob(model(), options); }).find("insulators"),
            std::string::npos);
  options = RunOptions::forModel(model(), 2);
  options.max_time_s = 100.0;
  EXPECT_EQ(runCleaningJob(model(), options).status, RunStatus::kTimeLimit);
}

}  // namespace
}  // namespace mcws
