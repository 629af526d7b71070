// Wang et al. 2018, section 3.2: the executor under injected faults (a lost link, a stuck zero
// switch, a low or empty battery, corrupted and wrong commands) and the operator's repairs; the
// fault-free runs are in behavior_executor_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "behavior/behavior_executor_fixture.h"
#include "mcws/behavior/behavior_executor.h"
#include "mcws/core/error.h"
#include "test_support.h"

namespace mcws {
namespace {

using test::answeredFaults;
using test::fault;
using test::faultScript;
using test::model;
using test::Recorded;
using test::runJob;

TEST(Executor, ALinkLostForLessThanTheWaitStopsThenResumes) {
  const FaultScript faults =
      faultScript(60.0, {fault(FaultKind::kLinkDown, 10.0, 40.0)});  // during CB1's J3 extension
  const Recorded rec = runJob(model(), 2, faults);
  EXPECT_EQ(rec.summary.status, RunStatus::kCompleted);
  EXPECT_EQ(rec.summary.discs_cleaned, 2);
  ASSERT_EQ(rec.events("link_lost").size(), 1u);
  ASSERT_EQ(rec.events("link_restored").size(), 1u);
  EXPECT_NEAR(rec.events("link_lost")[0].t, 10.0, 1e-9);
  EXPECT_NEAR(rec.events("link_restored")[0].t, 50.0, 1e-9);
  EXPECT_EQ(rec.events("link_lost")[0].task_state, "FAULT");
  EXPECT_EQ(rec.events("link_restored")[0].task_state, "CB1");
  // J3 brakes from 10 mm/s at 40 mm/s^2 (0.25 s) and then stands still until the link is back.
  double first = -1.0;
  for (std::size_t k = 0; k < rec.steps.size(); ++k) {
    const double t = rec.steps[k].time;
    if (t < 10.3 || t > 50.0) continue;
    const double j3 = rec.steps[k].joint(SimJoint::kJ3).position;
    if (first < 0.0) first = j3;
    EXPECT_EQ(j3, first) << t;
  }
  // The interrupted behaviour was sent again after the outage: seven commands in sub-task 1.
  int commands = 0;
  for (const LogRecord& r : rec.subtask(1)) commands += r.event == "command";
  EXPECT_EQ(commands, 7);
  ASSERT_EQ(rec.summary.faults.size(), 1u);
  EXPECT_EQ(rec.summary.faults[0].fault, "link_down");
  EXPECT_EQ(rec.unsafe_steps, 0);
}

TEST(Executor, ALinkLostForGoodBringsTheRobotBackToTheStart) {
  // Lost in the second CB1 with the fixed clamp open (q2, J3 extending): CB1 goes on to q4
  // (both clamps closed), CB3 from q4 undoes the half move, then one CB3 for disc 1.
  const Recorded clean = runJob(model(), 3);
  const double second_cb1 = clean.events("subtask_start")[2].t;
  const FaultScript faults = faultScript(30.0, {fault(FaultKind::kLinkDown, second_cb1 + 10.0)});
  const Recorded rec = runJob(model(), 3, faults);
  EXPECT_EQ(rec.summary.status, RunStatus::kReturned);
  EXPECT_EQ(rec.summary.discs_cleaned, 1);
  EXPECT_EQ(rec.summary.final_disc, 0);
  ASSERT_EQ(rec.events("return_start").size(), 1u);
  EXPECT_NEAR(rec.events("return_start")[0].t, second_cb1 + 40.0, 1e-9);
  const std::vector<LogRecord> starts = rec.events("subtask_start");
  ASSERT_EQ(starts.size(), 5u);  // CB1, CB2, CB1 (cut), CB3 from q4, CB3
  EXPECT_EQ(starts[3].combined, "CB3");
  EXPECT_EQ(starts[3].state, "q4");
  EXPECT_EQ(starts[4].combined, "CB3");
  EXPECT_EQ(starts[4].state, "q1");
  EXPECT_NEAR(rec.steps.back().fixed_platform_position, 0.0, 1e-9);
  EXPECT_NEAR(rec.steps.back().moving_platform_position, 310.0, 1e-9);
  EXPECT_TRUE(rec.steps.back().joint(kFixedClamp).gripping);
  EXPECT_TRUE(rec.steps.back().joint(kMovingClamp).gripping);
  EXPECT_EQ(rec.unsafe_steps, 0);
}

TEST(Executor, ALinkLostForGoodAtAnyTimeEndsSafelyAtTheStart) {
  // The link lost for good every 2.5 s through a 2-disc job, in every state of CB1, CB2 and CB3
  // and mid-behaviour (a jaw half open, J3 half way): the robot must end where the worker
  // mounted it (checked on the simulator's body position, not the executor's count), holding the
  // string with both clamps, and never let go of it.
  const Recorded clean = runJob(model(), 2);
  const double end = clean.summary.duration_s;
  int returned = 0;
  for (double at = 0.0; at < end; at += 2.5) {
    RunOptions options = RunOptions::forModel(model(), 2);
    options.faults = faultScript(5.0, {fault(FaultKind::kLinkDown, at)});
    int unsafe = 0;
    SimSnapshot last;
    RunObserver observer;
    observer.on_step = [&](const SimSnapshot& s, const StepContext&) {
      unsafe += !s.joint(kFixedClamp).gripping && !s.joint(kMovingClamp).gripping;
      last = s;
    };
    const RunSummary summary = runCleaningJob(model(), options, observer);
    EXPECT_EQ(unsafe, 0) << "link lost at " << at << " s";
    EXPECT_TRUE(summary.status == RunStatus::kReturned || summary.status == RunStatus::kCompleted)
        << at << ": " << runStatusName(summary.status);
    EXPECT_NEAR(last.fixed_platform_position, 0.0, 1e-9) << at;
    EXPECT_NEAR(last.moving_platform_position, 310.0, 1e-9) << at;
    EXPECT_TRUE(last.joint(kFixedClamp).gripping && last.joint(kMovingClamp).gripping) << at;
    EXPECT_EQ(summary.final_disc, 0) << at;
    returned += summary.status == RunStatus::kReturned;
  }
  EXPECT_GT(returned, 50);
}

TEST(Executor, ALinkLostWhileCleaningFinishesTheDiscThenReturns) {
  const Recorded clean = runJob(model(), 2);
  const double first_cb2 = clean.events("subtask_start")[1].t;
  const FaultScript faults =
      faultScript(5.0, {fault(FaultKind::kLinkDown, first_cb2 + 20.0)});  // the guide turning, q8
  const Recorded rec = runJob(model(), 2, faults);
  EXPECT_EQ(rec.summary.status, RunStatus::kReturned);
  EXPECT_EQ(rec.summary.discs_cleaned, 1);
  EXPECT_EQ(rec.summary.final_disc, 0);
  // The brush was stopped with everything else and spun up again before the guide resumed.
  ASSERT_EQ(rec.events("restore").size(), 1u);
  EXPECT_EQ(rec.events("restore")[0].behavior, "BB_Brush");
  EXPECT_EQ(rec.events("restore")[0].state, "q8");
  EXPECT_NEAR(rec.steps.back().fixed_platform_position, 0.0, 1e-9);
  EXPECT_EQ(rec.unsafe_steps, 0);
}

TEST(Executor, AStuckZeroSwitchTimesOutToTheOperatorWhoRepairsIt) {
  FaultScript faults;
  InjectedFault stuck = fault(FaultKind::kZeroSwitchStuck, 0.0);
  stuck.clamp = kFixedClamp;
  stuck.reads_pressed = false;
  faults.faults = std::vector<InjectedFault>{stuck};
  faults.operator_responses = {{30.0, OperatorAction::kRepairAndResume, 0}};
  const Recorded rec = runJob(model(), 1, faults);
  EXPECT_EQ(rec.summary.status, RunStatus::kCompleted);
  // BB_UG_Release's timeout is 15 s from q1's entry at 0 s; the operator acts 30 s later; the
  // re-sent release finds the repaired switch pressed at once (the jaw is fully open).
  ASSERT_EQ(rec.events("timeout").size(), 1u);
  EXPECT_NEAR(rec.events("timeout")[0].t, 15.0, 1e-9);
  EXPECT_EQ(rec.events("timeout")[0].behavior, "BB_UG_Release");
  ASSERT_EQ(rec.events("operator").size(), 1u);
  EXPECT_NEAR(rec.events("operator")[0].t, 45.0, 1e-9);
  EXPECT_EQ(rec.events("manual")[0].task_state, "MANUAL");
  EXPECT_NEAR(rec.events("zero_switch")[0].t, 45.01, 1e-9);
  EXPECT_EQ(rec.unsafe_steps, 0);

  // Resumed without a repair: the release times out again 15 s after the state is re-entered
  // (the timeout restarts on re-entry), and with no response left the run ends in MANUAL.
  faults.operator_responses = {{30.0, OperatorAction::kResume, 0}};
  const Recorded again = runJob(model(), 1, faults);
  ASSERT_EQ(again.events("timeout").size(), 2u);
  EXPECT_NEAR(again.events("timeout")[1].t, 45.0 + 15.0, 1e-9);
  EXPECT_EQ(again.summary.status, RunStatus::kHaltedInManual);

  // With no scripted response the run ends in MANUAL, the robot stopped and holding.
  faults.operator_responses.clear();
  const Recorded halted = runJob(model(), 1, faults);
  EXPECT_EQ(halted.summary.status, RunStatus::kHaltedInManual);
  EXPECT_NEAR(halted.summary.duration_s, 15.0, 1e-9);
  EXPECT_TRUE(halted.steps.back().joint(kMovingClamp).gripping);
}

/// A run watched only through the simulator's sensors: the first low-battery step, the guide's
/// full turns (one per cleaned shed pair: J5 reaching 360 deg), where the body ends.
struct BatteryWatch {
  double first_low{-1.0};
  int turns_before_low{0}, turns{0};
  bool at_turn{false};
  int unsafe{0};
  SimSnapshot last;
  RunSummary summary;
};

BatteryWatch watchBattery(int discs, double capacity, double drain, LowBatteryPolicy policy) {
  RunOptions options = RunOptions::forModel(model(), discs);
  options.simulator.battery.capacity = capacity;
  options.faults.low_battery = policy;
  if (drain > 0.0) {
    InjectedFault f = fault(FaultKind::kBatteryDrain, 0.0);
    f.current_a = drain;
    options.faults.faults = std::vector<InjectedFault>{f};
  }
  BatteryWatch w;
  RunObserver observer;
  observer.on_step = [&](const SimSnapshot& s, const StepContext&) {
    if (s.battery_low && w.first_low < 0.0) w.first_low = s.time;
    const bool at_turn = s.joint(SimJoint::kJ5).position >= 359.99;
    if (at_turn && !w.at_turn) {
      ++w.turns;
      if (w.first_low < 0.0) ++w.turns_before_low;
    }
    w.at_turn = at_turn;
    w.unsafe += !s.joint(kFixedClamp).gripping && !s.joint(kMovingClamp).gripping;
    w.last = s;
  };
  w.summary = runCleaningJob(model(), options, observer);
  return w;
}

TEST(Executor, LowBatteryRaisesTheAlarmAndFinishesTheDiscBeforeReturning) {
  // A 0.5 A h battery and no fault: the voltage falls below 22.2 V when (22.2 - 21) / (25.2 - 21)
  // = 2/7 of the charge is left, about 1000 s into the job (about 1.3 A on average), on the
  // way down a 10-disc string. The robot finishes the disc in hand and returns; the rest of the
  // charge (0.4 of the time spent) covers one disc and the climb (42 s a disc).
  const BatteryWatch w = watchBattery(10, 0.5, 0.0, LowBatteryPolicy::kFinishDiscAndReturn);
  ASSERT_GT(w.first_low, 0.0);
  ASSERT_TRUE(w.summary.battery_alarm_t);
  EXPECT_EQ(*w.summary.battery_alarm_t, w.first_low);
  EXPECT_EQ(w.summary.status, RunStatus::kReturned);
  // The guide reaches 360 deg once a disc (then turns back); the alarm came during disc k + 1,
  // which is finished: k + 1 turns in all.
  const int disc_in_hand = w.turns_before_low + 1;
  EXPECT_EQ(w.turns, disc_in_hand);
  EXPECT_EQ(w.summary.discs_cleaned, disc_in_hand);
  EXPECT_LT(disc_in_hand, 10);
  EXPECT_NEAR(w.last.fixed_platform_position, 0.0, 1e-9);
  EXPECT_EQ(w.unsafe, 0);
  // Policy alarm_only (the paper's rule alone): the same alarm; the job goes on down the string and
  // the battery runs empty before the robot is back.
  const BatteryWatch on = watchBattery(10, 0.5, 0.0, LowBatteryPolicy::kAlarmOnly);
  EXPECT_EQ(on.first_low, w.first_low);
  EXPECT_EQ(on.summary.status, RunStatus::kBatteryEmpty);
  EXPECT_GT(on.turns, w.turns);
  EXPECT_EQ(on.unsafe, 0);
}

TEST(Executor, AnEmptyBatteryStopsTheRobotWhereItHangs) {
  // 100 A drawn from a 5 A h battery: empty after 5 / 100.3 h (about 180 s) or less; every joint
  // stops and the run ends, the robot still holding the string.
  const BatteryWatch w = watchBattery(3, 5.0, 100.0, LowBatteryPolicy::kFinishDiscAndReturn);
  EXPECT_EQ(w.summary.status, RunStatus::kBatteryEmpty);
  EXPECT_LE(w.summary.duration_s, 5.0 / 100.3 * 3600.0 + 0.01);
  EXPECT_EQ(w.last.battery_charge, 0.0);
  EXPECT_EQ(w.unsafe, 0);
  EXPECT_TRUE(w.last.joint(kFixedClamp).gripping || w.last.joint(kMovingClamp).gripping);
}

TEST(Executor, ACorruptedCommandIsRejectedAndResent) {
  FaultScript faults;
  faults.faults = std::vector<InjectedFault>{
      fault(FaultKind::kCorruptCommand, 2.0)};  // hits q2's J3 command at 2.5 s
  const Recorded rec = runJob(model(), 1, faults);
  EXPECT_EQ(rec.summary.status, RunStatus::kCompleted);
  const std::vector<LogRecord> rejected = rec.events("command_rejected");
  ASSERT_EQ(rejected.size(), 1u);
  EXPECT_EQ(rejected[0].behavior, "BB_MP_Extend");  // the first command sent after 2 s
  ASSERT_TRUE(rejected[0].seq);
  // The same command goes again with the next sequence number, at the same step.
  const std::vector<LogRecord> commands = rec.events("command");
  bool resent = false;
  for (const LogRecord& c : commands) {
    resent = resent || (c.seq && *c.seq == *rejected[0].seq + 1 && c.behavior == "BB_MP_Extend" &&
                        c.step == rejected[0].step);
  }
  EXPECT_TRUE(resent);
  EXPECT_EQ(rec.summary.commands_sent, 20u + 1u);
}

TEST(Executor, TheInterferenceCheckRefusesWrongCommands) {
  // Beyond J4's 130 mm limit: the simulator's (the robot file's) joint limits.
  FaultScript faults;
  InjectedFault beyond = fault(FaultKind::kWrongCommand, 0.0);
  beyond.command = SimCommand::moveTo(SimJoint::kJ4, 200.0);
  // J4 in over the upper shed while the fixed clamp is open (CB1's q2): the pose rule
  // fixed_clamp_open_parks_the_cleaner forbids it.
  InjectedFault forbidden = fault(FaultKind::kWrongCommand, 1.0);
  forbidden.command = SimCommand::moveTo(SimJoint::kJ4, 60.0);
  faults.faults = std::vector<InjectedFault>{beyond, forbidden};
  const Recorded rec = runJob(model(), 1, faults);
  const std::vector<LogRecord> refused = rec.events("refused");
  ASSERT_EQ(refused.size(), 2u);
  EXPECT_NE(refused[0].detail.find("J4"), std::string::npos) << refused[0].detail;
  EXPECT_NE(refused[0].detail.find("200"), std::string::npos) << refused[0].detail;
  EXPECT_EQ(refused[1].state, "q2");
  EXPECT_NE(refused[1].detail.find("fixed_clamp_open_parks_the_cleaner"), std::string::npos)
      << refused[1].detail;
  EXPECT_EQ(rec.summary.status, RunStatus::kCompleted);
  EXPECT_EQ(rec.summary.faults.size(), 2u);
  // The refused commands never reached J4 in CB1.
  for (std::size_t k = 0; k < rec.steps.size(); ++k) {
    if (rec.contexts[k].combined == "CB1") {
      EXPECT_EQ(rec.steps[k].joint(SimJoint::kJ4).position, 0.0);
    }
  }
}

InjectedFault stuckSwitch(SimJoint clamp, double at, bool reads_pressed) {
  InjectedFault f = fault(FaultKind::kZeroSwitchStuck, at);
  f.clamp = clamp;
  f.reads_pressed = reads_pressed;
  return f;
}

TEST(Executor, AWrongReleaseThatPassesTheCheckNeverDropsTheRobot) {
  // The moving clamp released by a wrong command in q1 (allowed: the fixed one grips); the
  // state's own release then never went out, times out, and the operator resumes it: sending
  // it would open both clamps, so the run stops before the command (exit 1 in mcws_behave).
  InjectedFault wrong = fault(FaultKind::kWrongCommand, 0.0);
  wrong.command = SimCommand::release(kMovingClamp);
  const FaultScript faults = answeredFaults({wrong}, 10.0, OperatorAction::kResume);
  const Recorded rec = runJob(model(), 2, faults);
  EXPECT_EQ(rec.summary.status, RunStatus::kInvariantViolated);
  ASSERT_TRUE(rec.summary.violation);
  EXPECT_NEAR(rec.summary.violation->t, 25.0, 1e-9);  // timeout 15 s + operator 10 s
  EXPECT_EQ(rec.summary.violation->behavior, "BB_UG_Release");
  EXPECT_EQ(rec.unsafe_steps, 0);
  EXPECT_TRUE(rec.steps.back().joint(kFixedClamp).gripping);
}

TEST(Executor, AZeroSwitchStuckPressedIsCaughtByTheEncoder) {
  // The fixed clamp's switch reads pressed from 100 s, while its jaw grips the string (CB2 of
  // disc 1; the second CB1 starts at 111.17 s): the encoder (25 deg) contradicts it at once, so
  // the robot stops at 100 s, not at the next release, and the operator repairs the switch.
  const FaultScript faults = answeredFaults({stuckSwitch(kFixedClamp, 100.0, true)}, 20.0,
                                            OperatorAction::kRepairAndResume);
  const Recorded rec = runJob(model(), 2, faults);
  const std::vector<LogRecord> mismatch = rec.events("sensor_mismatch");
  ASSERT_EQ(mismatch.size(), 1u);
  EXPECT_NEAR(mismatch[0].t, 100.0, 1e-9);
  EXPECT_EQ(mismatch[0].combined, "CB2");
  EXPECT_EQ(rec.summary.status, RunStatus::kCompleted);
  ASSERT_EQ(rec.summary.faults.size(), 1u);
  const FaultReaction& f = rec.summary.faults[0];
  EXPECT_EQ(f.fault, "sensor_mismatch");
  EXPECT_NEAR(*f.injected_t, 100.0, 1e-9);
  EXPECT_NEAR(*f.detected_t, 100.0, 1e-9);
  EXPECT_NEAR(*f.resolved_t, 120.0, 1e-9);  // the operator's repair 20 s later
  // J3 never moved while the fixed jaw was not fully open in CB1's q2.
  for (std::size_t k = 0; k < rec.steps.size(); ++k) {
    if (rec.contexts[k].state == "q2" && rec.contexts[k].combined == "CB1") {
      EXPECT_LE(rec.steps[k].joint(kFixedClamp).position, 0.05) << rec.steps[k].time;
    }
  }
  EXPECT_EQ(rec.unsafe_steps, 0);
}

TEST(Executor, AZeroSwitchStuckPressedIsCaughtWheneverTheEncoderContradictsIt) {
  // Other members of the class: the moving clamp's switch, stuck while its jaw grips (at 1 s,
  // CB1's q1 -> q2 running on the other clamp): found at 1 s. And the fixed clamp's switch stuck
  // while its jaw is open (CB1's q2, J3 extending): nothing contradicts it until BB_UG_Clamp
  // closes the jaw; it is found at the first step whose encoder reads more than 0.5 deg
  // (10 counts), taken from the simulator's own snapshots.
  {
    const FaultScript faults = answeredFaults({stuckSwitch(kMovingClamp, 1.0, true)}, 45.0,
                                              OperatorAction::kRepairAndResume);
    const Recorded rec = runJob(model(), 1, faults);
    ASSERT_EQ(rec.summary.faults.size(), 1u);
    const FaultReaction& f = rec.summary.faults[0];
    EXPECT_NEAR(*f.injected_t, 1.0, 1e-9);
    EXPECT_NEAR(*f.detected_t, 1.0, 1e-9);
    EXPECT_NEAR(*f.resolved_t, 46.0, 1e-9);
    EXPECT_EQ(rec.summary.status, RunStatus::kCompleted);
  }
  {
    const FaultScript faults = answeredFaults({stuckSwitch(kFixedClamp, 5.0, true)}, 10.0,
                                              OperatorAction::kRepairAndResume);
    const Recorded rec = runJob(model(), 1, faults);
    double contradicted = -1.0;
    for (const SimSnapshot& s : rec.steps) {
      if (s.time >= 5.0 && s.joint(kFixedClamp).encoder > 10) {
        contradicted = s.time;
        break;
      }
    }
    ASSERT_GT(contradicted, 5.0);
    ASSERT_EQ(rec.summary.faults.size(), 1u);
    EXPECT_NEAR(*rec.summary.faults[0].injected_t, 5.0, 1e-9);
    EXPECT_NEAR(*rec.summary.faults[0].detected_t, contradicted, 1e-9);
    ASSERT_EQ(rec.events("sensor_mismatch").size(), 1u);
    EXPECT_EQ(rec.events("sensor_mismatch")[0].behavior, "BB_UG_Clamp");
    EXPECT_EQ(rec.unsafe_steps, 0);
  }
  {
    // Stuck while the robot stands still, waiting for the link (down 10 s to 50 s): found at
    // 20 s, handed to the operator when the robot would run again (50 s), repaired 5 s later.
    FaultScript faults = faultScript(
        60.0, {fault(FaultKind::kLinkDown, 10.0, 40.0), stuckSwitch(kMovingClamp, 20.0, true)});
    faults.operator_responses = {{5.0, OperatorAction::kRepairAndResume, 0}};
    const Recorded rec = runJob(model(), 1, faults);
    ASSERT_EQ(rec.summary.faults.size(), 2u);
    const FaultReaction& f = rec.summary.faults[1];
    EXPECT_EQ(f.fault, "sensor_mismatch");
    EXPECT_NEAR(*f.injected_t, 20.0, 1e-9);
    EXPECT_NEAR(*f.detected_t, 20.0, 1e-9);
    EXPECT_NEAR(*f.resolved_t, 55.0, 1e-9);
    ASSERT_EQ(rec.events("sensor_mismatch").size(), 1u);
    EXPECT_NEAR(rec.events("manual")[0].t, 50.0, 1e-9);
    EXPECT_EQ(rec.summary.status, RunStatus::kCompleted);
    EXPECT_EQ(rec.unsafe_steps, 0);
  }
}

TEST(Executor, FaultsCarryTheirInjectedDetectedAndResolvedTimes) {
  // Hand-worked from the fault script and the executor's timing: the link supervision runs in
  // the step the fault is applied, so a link lost at 10 s for 40 s is detected at 10 s and
  // resolved when it is back and the behaviour resent, at 50 s. A corrupted command armed at 2 s
  // is caught (and resent) when the next command goes out: J3's extension after the fixed
  // clamp's release, which takes 25 deg / 10 deg/s = 2.5 s. A stuck switch (never pressed)
  // injected at 0 s times out BB_UG_Release after its 15 s; the operator repairs it 30 s later.
  FaultScript faults = faultScript(
      60.0, {fault(FaultKind::kCorruptCommand, 2.0), fault(FaultKind::kLinkDown, 10.0, 40.0)});
  const Recorded rec = runJob(model(), 1, faults);
  ASSERT_EQ(rec.summary.faults.size(), 2u);
  const FaultReaction& corrupt = rec.summary.faults[0];
  EXPECT_EQ(corrupt.fault, "corrupt_command");
  EXPECT_NEAR(*corrupt.injected_t, 2.0, 1e-9);
  EXPECT_NEAR(*corrupt.detected_t, 2.5, 1e-9);
  EXPECT_NEAR(*corrupt.resolved_t, 2.5, 1e-9);
  const FaultReaction& link = rec.summary.faults[1];
  EXPECT_EQ(link.fault, "link_down");
  EXPECT_NEAR(*link.injected_t, 10.0, 1e-9);
  EXPECT_NEAR(*link.detected_t, 10.0, 1e-9);
  EXPECT_NEAR(*link.resolved_t, 50.0, 1e-9);

  FaultScript stuck;
  stuck.faults = std::vector<InjectedFault>{stuckSwitch(kFixedClamp, 0.0, false)};
  stuck.operator_responses = {{30.0, OperatorAction::kRepairAndResume, 0}};
  const Recorded timed_out = runJob(model(), 1, stuck);
  ASSERT_EQ(timed_out.summary.faults.size(), 1u);
  const FaultReaction& timeout = timed_out.summary.faults[0];
  EXPECT_EQ(timeout.fault, "timeout");
  EXPECT_NEAR(*timeout.injected_t, 0.0, 1e-9);
  EXPECT_NEAR(*timeout.detected_t, 15.0, 1e-9);
  EXPECT_NEAR(*timeout.resolved_t, 45.0, 1e-9);

  // Lost for good at 10 s with a 5 s wait: detected at 10 s, resolved when the return it caused
  // reaches the start (the run's end).
  const FaultScript lost = faultScript(5.0, {fault(FaultKind::kLinkDown, 10.0)});
  const Recorded returned = runJob(model(), 1, lost);
  ASSERT_EQ(returned.summary.status, RunStatus::kReturned);
  ASSERT_FALSE(returned.summary.faults.empty());
  const FaultReaction& gone = returned.summary.faults[0];
  EXPECT_NEAR(*gone.injected_t, 10.0, 1e-9);
  EXPECT_NEAR(*gone.detected_t, 10.0, 1e-9);
  EXPECT_NEAR(*gone.resolved_t, returned.summary.duration_s, 1e-9);
}

TEST(Executor, TheReturnsDiscCountIsTheNumberOfDiscsItClimbs) {
  // The link lost for good every 2.5 s through a 2-disc job (every state of CB1, CB2, CB3, mid
  // behaviour): the count return_start gives must be the discs the return then climbs, counted
  // on the log's own `disc` field (each decrease after return_start is one disc climbed; a CB1
  // finished first raises it by one before).
  const double end = runJob(model(), 2).summary.duration_s;
  int with_cb1_finished = 0;
  for (double at = 0.0; at < end; at += 2.5) {
    RunOptions options = RunOptions::forModel(model(), 2);
    options.faults = faultScript(5.0, {fault(FaultKind::kLinkDown, at)});
    Recorded rec;  // the log only: the sweep stays cheap
    RunObserver observer;
    observer.on_log = [&](const LogRecord& r) { rec.log.push_back(r); };
    rec.summary = runCleaningJob(model(), options, observer);
    const std::vector<LogRecord> starts = rec.events("return_start");
    ASSERT_EQ(starts.size(), 1u) << at;
    const std::string& detail = starts[0].detail;
    const auto count_at = detail.rfind("; ");
    ASSERT_NE(count_at, std::string::npos) << detail;
    const int announced = std::stoi(detail.substr(count_at + 2));
    int climbed = 0, disc = starts[0].disc;
    bool after = false;
    for (const LogRecord& r : rec.log) {
      after = after || (r.event == "return_start");
      if (!after) continue;
      if (r.disc < disc) climbed += disc - r.disc;
      if (r.disc > disc) ++with_cb1_finished;
      disc = r.disc;
    }
    EXPECT_EQ(announced, climbed) << "link lost at " << at << " s: " << detail;
    EXPECT_EQ(disc, 0) << at;
  }
  EXPECT_GT(with_cb1_finished, 0);  // the sweep met the case a CB1 is finished first
}

TEST(Executor, TheOperatorActsOnlyOverALiveLink) {
  // Stuck switch -> timeout at 15 s -> MANUAL; the link drops at 20 s for 60 s; the operator's
  // repair due at 15 + 30 = 45 s waits for the link (80 s).
  FaultScript faults = answeredFaults(
      {stuckSwitch(kFixedClamp, 0.0, false), fault(FaultKind::kLinkDown, 20.0, 60.0)}, 30.0,
      OperatorAction::kRepairAndResume);
  const Recorded rec = runJob(model(), 1, faults);
  ASSERT_EQ(rec.events("operator").size(), 1u);
  EXPECT_NEAR(rec.events("operator")[0].t, 80.0, 1e-9);
  EXPECT_EQ(rec.summary.status, RunStatus::kCompleted);
  // Down for good instead: the operator can never act; the run ends in MANUAL, robot holding.
  faults.faults[1].duration_s.reset();
  const Recorded lost = runJob(model(), 1, faults);
  EXPECT_EQ(lost.summary.status, RunStatus::kHaltedInManual);
  EXPECT_NEAR(lost.summary.duration_s, 45.0, 1e-9);
  EXPECT_EQ(lost.events("operator").size(), 0u);
  EXPECT_EQ(lost.unsafe_steps, 0);
}

TEST(Executor, AShortOutageDoesNotEndOneForGood) {
  const FaultScript faults = faultScript(
      10.0, {fault(FaultKind::kLinkDown, 10.0), fault(FaultKind::kLinkDown, 12.0, 3.0)});
  const Recorded rec = runJob(model(), 2, faults);
  EXPECT_EQ(rec.events("link_up").size(), 0u);
  EXPECT_EQ(rec.events("link_restored").size(), 0u);
  ASSERT_EQ(rec.events("return_start").size(), 1u);
  EXPECT_NEAR(rec.events("return_start")[0].t, 20.0, 1e-9);
  EXPECT_EQ(rec.summary.status, RunStatus::kReturned);
  EXPECT_FALSE(rec.steps.back().link_up);
}

TEST(Executor, ALinkDownFromTheStartSendsNothingAndMovesNothing) {
  // Nothing has moved: the return is to stay. No command goes over the dead link, J3 never
  // moves, and the robot ends where it was mounted, holding with both clamps.
  const FaultScript faults = faultScript(5.0, {fault(FaultKind::kLinkDown, 0.0)});
  const Recorded rec = runJob(model(), 2, faults);
  for (const LogRecord& r : rec.events("command"))
    EXPECT_EQ(r.detail.find("echo"), std::string::npos);
  EXPECT_EQ(rec.summary.status, RunStatus::kReturned);
  EXPECT_EQ(rec.summary.discs_cleaned, 0);
  for (const SimSnapshot& s : rec.steps) EXPECT_EQ(s.joint(SimJoint::kJ3).position, 0.0);
  EXPECT_NEAR(rec.steps.back().fixed_platform_position, 0.0, 1e-9);
  EXPECT_TRUE(rec.steps.back().joint(kFixedClamp).gripping);
  EXPECT_TRUE(rec.steps.back().joint(kMovingClamp).gripping);
  EXPECT_EQ(rec.unsafe_steps, 0);
}

TEST(Executor, TheOperatorsReturnReclosesAStuckReleaseAndUndoesTheHalfMove) {
  // The moving clamp's switch sticks (never pressed) in CB1's q4 (fixed clamp already one pitch
  // down): BB_LG_Release times out; the operator orders the return: J2 closes again (q4, both
  // gripping), CB3 from q4 brings the body back up, and the robot ends at the start.
  const FaultScript faults =
      answeredFaults({stuckSwitch(kMovingClamp, 20.0, false)}, 5.0, OperatorAction::kReturn);
  const Recorded rec = runJob(model(), 2, faults);
  ASSERT_EQ(rec.events("reclose").size(), 1u);
  EXPECT_EQ(rec.events("reclose")[0].behavior, "BB_LG_Clamp");
  EXPECT_EQ(rec.events("reclose")[0].state, "q4");
  EXPECT_EQ(rec.summary.status, RunStatus::kReturned);
  EXPECT_EQ(rec.summary.discs_cleaned, 0);
  EXPECT_NEAR(rec.steps.back().fixed_platform_position, 0.0, 1e-9);
  EXPECT_EQ(rec.unsafe_steps, 0);
}

TEST(Executor, FaultsThatFindNoGroundCommandAreReported) {
  // Armed while the robot returns on its own: no command from the ground station ever comes.
  const FaultScript faults = faultScript(
      5.0, {fault(FaultKind::kLinkDown, 10.0), fault(FaultKind::kCorruptCommand, 20.0)});
  const Recorded rec = runJob(model(), 2, faults);
  bool reported = false;
  for (const FaultReaction& f : rec.summary.faults) {
    reported = reported || (f.fault == "corrupt_command" &&
                            f.reaction.find("never acted") != std::string::npos);
  }
  EXPECT_TRUE(reported);
}

}  // namespace
}  // namespace mcws
