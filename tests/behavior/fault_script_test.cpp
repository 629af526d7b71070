// The fault file of a rehearsal (mcws::parseFaultScript, loadFaultScript): every field of a full
// file with its units converted, the order of the faults, the defaults, and every class of bad
// input rejected with one line naming the file line, the item and the bad value.
#include "mcws/behavior/fault_script.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "mcws/core/error.h"
#include "test_support.h"

namespace mcws {
namespace {

using test::errorOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;

FaultScript parse(const std::string& text) { return parseFaultScript(text, "f.yaml"); }

/// Checks that `text` is rejected with one line "f.yaml:<line>: <item>: ..." that contains every
/// one of `parts` (the bad key or value, the allowed names).
void expectRejected(const std::string& text, int line, const std::string& item,
                    const std::vector<std::string>& parts) {
  const std::string message = errorOf([&] { parse(text); });
  EXPECT_THAT(message, StartsWith("f.yaml:" + std::to_string(line) + ": " + item + ": "))
      << "file:\n"
      << text;
  for (const std::string& part : parts) EXPECT_THAT(message, HasSubstr(part)) << "file:\n" << text;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

const std::string kFullExample =
    "# a rehearsal with every kind of fault\n"                                             // 1
    "policy:\n"                                                                            // 2
    "  link_wait: 1.5 min\n"                                                               // 3
    "  low_battery: alarm_only\n"                                                          // 4
    "faults:\n"                                                                            // 5
    "  - {at: 100 s, type: link_down, duration: 40 s}\n"                                   // 6
    "  - {at: 12 s, type: zero_switch_stuck, clamp: moving, reads: pressed}\n"             // 7
    "  - {at: 50 s, type: corrupt_command}\n"                                              // 8
    "  - {at: 60 s, type: wrong_command, joint: J4, command: move_to, value: 200 mm}\n"    // 9
    "  - {at: 250 ms, type: battery_drain, current: 500 mA}\n"                             // 10
    "  - {at: 0.5 min, type: link_down}\n"                                                 // 11
    "  - {at: 70 s, type: wrong_command, joint: J6, command: spin, value: -300 rpm}\n"     // 12
    "  - {at: 80 s, type: wrong_command, joint: J1, command: close}\n"                     // 13
    "  - {at: 90 s, type: wrong_command, joint: J5, command: move_to, value: 45.5 deg}\n"  // 14
    "  - at: 95 s\n"                                                                       // 15
    "    type: zero_switch_stuck\n"                                                        // 16
    "    clamp: fixed\n"                                                                   // 17
    "    reads: not_pressed\n"                                                             // 18
    "  - {at: 1 min, type: battery_drain, current: 8 A}\n"                                 // 19
    "operator:\n"                                                                          // 20
    "  - {after: 30 s, action: repair_and_resume}\n"                                       // 21
    "  - {after: 0 s, action: resume}\n"                                                   // 22
    "  - {after: 2 min, action: return}\n";                                                // 23

TEST(FaultScript, FullExampleReadsEveryFieldWithUnitsConverted) {
  const FaultScript s = parse(kFullExample);
  EXPECT_EQ(s.source, "f.yaml");
  EXPECT_DOUBLE_EQ(s.link_wait_s, 90.0);
  EXPECT_EQ(s.low_battery, LowBatteryPolicy::kAlarmOnly);

  // Sorted by time: 0.25 s, 12 s, 30 s, 50 s, 60 s, 60 s (line 9 before 19), 70 .. 100 s.
  ASSERT_EQ(s.faults.size(), 11u);
  const std::vector<int> lines = {10, 7, 11, 8, 9, 19, 12, 13, 14, 15, 6};
  for (std::size_t i = 0; i < lines.size(); ++i) EXPECT_EQ(s.faults[i].line, lines[i]) << i;

  const InjectedFault& drain = s.faults[0];
  EXPECT_EQ(drain.kind, FaultKind::kBatteryDrain);
  EXPECT_DOUBLE_EQ(drain.at_s, 0.25);
  EXPECT_DOUBLE_EQ(drain.current_a, 0.5);
  EXPECT_FALSE(drain.duration_s.has_value());

  const InjectedFault& stuck = s.faults[1];
  EXPECT_EQ(stuck.kind, FaultKind::kZeroSwitchStuck);
  EXPECT_DOUBLE_EQ(stuck.at_s, 12.0);
  EXPECT_EQ(stuck.clamp, kMovingClamp);
  EXPECT_TRUE(stuck.reads_pressed);

  const InjectedFault& lost = s.faults[2];
  EXPECT_EQ(lost.kind, FaultKind::kLinkDown);
  EXPECT_DOUBLE_EQ(lost.at_s, 30.0);
  EXPECT_FALSE(lost.duration_s.has_value());  // down for good

  const InjectedFault& corrupt = s.faults[3];
  EXPECT_EQ(corrupt.kind, FaultKind::kCorruptCommand);
  EXPECT_DOUBLE_EQ(corrupt.at_s, 50.0);

  const InjectedFault& move = s.faults[4];
  EXPECT_EQ(move.kind, FaultKind::kWrongCommand);
  EXPECT_DOUBLE_EQ(move.at_s, 60.0);
  EXPECT_EQ(move.command.joint, SimJoint::kJ4);
  EXPECT_EQ(move.command.kind, SimCommandKind::kMoveTo);
  EXPECT_DOUBLE_EQ(move.command.value, 200.0);
  EXPECT_DOUBLE_EQ(move.command.speed, 0.0);

  const InjectedFault& drain8 = s.faults[5];
  EXPECT_EQ(drain8.kind, FaultKind::kBatteryDrain);
  EXPECT_DOUBLE_EQ(drain8.at_s, 60.0);
  EXPECT_DOUBLE_EQ(drain8.current_a, 8.0);

  const InjectedFault& spin = s.faults[6];
  EXPECT_EQ(spin.kind, FaultKind::kWrongCommand);
  EXPECT_DOUBLE_EQ(spin.at_s, 70.0);
  EXPECT_EQ(spin.command.joint, SimJoint::kJ6);
  EXPECT_EQ(spin.command.kind, SimCommandKind::kSpin);
  EXPECT_DOUBLE_EQ(spin.command.value, -300.0);

  const InjectedFault& close = s.faults[7];
  EXPECT_EQ(close.kind, FaultKind::kWrongCommand);
  EXPECT_DOUBLE_EQ(close.at_s, 80.0);
  EXPECT_EQ(close.command.joint, SimJoint::kJ1);
  EXPECT_EQ(close.command.kind, SimCommandKind::kClose);
  EXPECT_DOUBLE_EQ(close.command.value, 0.0);

  const InjectedFault& turn = s.faults[8];
  EXPECT_EQ(turn.command.joint, SimJoint::kJ5);
  EXPECT_EQ(turn.command.kind, SimCommandKind::kMoveTo);
  EXPECT_DOUBLE_EQ(turn.command.value, 45.5);
  EXPECT_DOUBLE_EQ(turn.at_s, 90.0);

  const InjectedFault& block = s.faults[9];  // written as a block map
  EXPECT_EQ(block.kind, FaultKind::kZeroSwitchStuck);
  EXPECT_DOUBLE_EQ(block.at_s, 95.0);
  EXPECT_EQ(block.clamp, kFixedClamp);
  EXPECT_FALSE(block.reads_pressed);

  const InjectedFault& outage = s.faults[10];
  EXPECT_EQ(outage.kind, FaultKind::kLinkDown);
  EXPECT_DOUBLE_EQ(outage.at_s, 100.0);
  ASSERT_TRUE(outage.duration_s.has_value());
  EXPECT_DOUBLE_EQ(*outage.duration_s, 40.0);

  ASSERT_EQ(s.operator_responses.size(), 3u);  // file order, not sorted
  EXPECT_DOUBLE_EQ(s.operator_responses[0].after_s, 30.0);
  EXPECT_EQ(s.operator_responses[0].action, OperatorAction::kRepairAndResume);
  EXPECT_EQ(s.operator_responses[0].line, 21);
  EXPECT_DOUBLE_EQ(s.operator_responses[1].after_s, 0.0);
  EXPECT_EQ(s.operator_responses[1].action, OperatorAction::kResume);
  EXPECT_EQ(s.operator_responses[1].line, 22);
  EXPECT_DOUBLE_EQ(s.operator_responses[2].after_s, 120.0);
  EXPECT_EQ(s.operator_responses[2].action, OperatorAction::kReturn);
  EXPECT_EQ(s.operator_responses[2].line, 23);
}

TEST(FaultScript, MillisecondsAndMilliamperesConvert) {
  const FaultScript s = parse(
      "policy: {link_wait: 250 ms}\n"
      "faults: [{at: 1500 ms, type: battery_drain, current: 2.5e3 mA},\n"
      "         {at: 2 min, type: link_down, duration: 250 ms}]\n");
  EXPECT_DOUBLE_EQ(s.link_wait_s, 0.25);
  ASSERT_EQ(s.faults.size(), 2u);
  EXPECT_DOUBLE_EQ(s.faults[0].at_s, 1.5);
  EXPECT_DOUBLE_EQ(s.faults[0].current_a, 2.5);
  EXPECT_DOUBLE_EQ(s.faults[1].at_s, 120.0);
  ASSERT_TRUE(s.faults[1].duration_s.has_value());
  EXPECT_DOUBLE_EQ(*s.faults[1].duration_s, 0.25);
}

TEST(FaultScript, FaultsAreSortedByTimeWithTiesInFileOrder) {
  const FaultScript s = parse(
      "faults:\n"
      "  - {at: 5 s, type: corrupt_command}\n"                    // 2
      "  - {at: 1 s, type: link_down}\n"                          // 3
      "  - {at: 5 s, type: link_down}\n"                          // 4
      "  - {at: 1000 ms, type: corrupt_command}\n"                // 5
      "  - {at: 0 s, type: battery_drain, current: 1 A}\n"        // 6
      "  - {at: 5000 ms, type: battery_drain, current: 2 A}\n");  // 7
  ASSERT_EQ(s.faults.size(), 6u);
  const std::vector<int> lines = {6, 3, 5, 2, 4, 7};
  const std::vector<double> times = {0.0, 1.0, 1.0, 5.0, 5.0, 5.0};
  for (std::size_t i = 0; i < lines.size(); ++i) {
    EXPECT_EQ(s.faults[i].line, lines[i]) << i;
    EXPECT_DOUBLE_EQ(s.faults[i].at_s, times[i]) << i;
  }
  EXPECT_EQ(s.faults[1].kind, FaultKind::kLinkDown);
  EXPECT_EQ(s.faults[2].kind, FaultKind::kCorruptCommand);
}

TEST(FaultScript, ManyTiesKeepFileOrder) {
  // Enough faults for an unstable sort (introsort beyond 16 elements) to mix up the ties.
  std::string text = "faults:\n";
  for (int i = 0; i < 100; ++i) {
    text += "  - {at: " + std::to_string((i * 7) % 3) + " s, type: corrupt_command}\n";
  }
  const FaultScript s = parse(text);
  ASSERT_EQ(s.faults.size(), 100u);
  for (std::size_t i = 1; i < s.faults.size(); ++i) {
    const InjectedFault &a = s.faults[i - 1], &b = s.faults[i];
    EXPECT_TRUE(a.at_s < b.at_s || (a.at_s == b.at_s && a.line < b.line))
        << i << ": line " << a.line << " at " << a.at_s << " s before line " << b.line << " at "
        << b.at_s << " s";
  }
}

TEST(FaultScript, EmptyDocumentGivesTheDefaults) {
  for (const std::string text : {"", "# nothing injected\n\n# at all\n", "policy:\nfaults:\n",
                                 "faults: []\noperator: []\npolicy: {}\n"}) {
    const FaultScript s = parseFaultScript(text, "empty.yaml");
    EXPECT_EQ(s.source, "empty.yaml") << text;
    EXPECT_DOUBLE_EQ(s.link_wait_s, 30.0) << text;
    EXPECT_EQ(s.low_battery, LowBatteryPolicy::kFinishDiscAndReturn) << text;
    EXPECT_TRUE(s.faults.empty()) << text;
    EXPECT_TRUE(s.operator_responses.empty()) << text;
  }
}

TEST(FaultScript, NamesMatchTheFileWords) {
  EXPECT_STREQ(faultKindName(FaultKind::kLinkDown), "link_down");
  EXPECT_STREQ(faultKindName(FaultKind::kZeroSwitchStuck), "zero_switch_stuck");
  EXPECT_STREQ(faultKindName(FaultKind::kCorruptCommand), "corrupt_command");
  EXPECT_STREQ(faultKindName(FaultKind::kWrongCommand), "wrong_command");
  EXPECT_STREQ(faultKindName(FaultKind::kBatteryDrain), "battery_drain");
  EXPECT_STREQ(operatorActionName(OperatorAction::kRepairAndResume), "repair_and_resume");
  EXPECT_STREQ(operatorActionName(OperatorAction::kResume), "resume");
  EXPECT_STREQ(operatorActionName(OperatorAction::kReturn), "return");
  EXPECT_STREQ(lowBatteryPolicyName(LowBatteryPolicy::kAlarmOnly), "alarm_only");
  EXPECT_STREQ(lowBatteryPolicyName(LowBatteryPolicy::kFinishDiscAndReturn),
               "finish_disc_and_return");
  // The policy names read back as what they name.
  for (LowBatteryPolicy p :
       {LowBatteryPolicy::kAlarmOnly, LowBatteryPolicy::kFinishDiscAndReturn}) {
    EXPECT_EQ(
        parse(std::string("policy: {low_battery: ") + lowBatteryPolicyName(p) + "}\n").low_battery,
        p);
  }
}

TEST(FaultScript, RejectsUnknownTopLevelKey) {
  expectRejected("policy: {link_wait: 10 s}\nfault:\n  - {at: 1 s, type: link_down}\n", 2,
                 "fault file", {"unknown key 'fault'", "faults, operator, policy"});
}

TEST(FaultScript, RejectsATopLevelThatIsNotAMap) {
  expectRejected("\n- {at: 1 s, type: link_down}\n", 2, "fault file", {"must be a map"});
  expectRejected("faults: {at: 1 s, type: link_down}\n", 1, "faults", {"must be a list"});
  expectRejected("faults:\n  - link_down\n", 2, "faults[1]", {"must be a map"});
  expectRejected("operator: resume\n", 1, "operator", {"must be a list"});
  expectRejected("policy: alarm_only\n", 1, "policy", {"must be a map"});
}

TEST(FaultScript, RejectsUnknownFaultType) {
  expectRejected("faults:\n  - {at: 1 s, type: link_down}\n  - {at: 2 s, type: link_dwn}\n", 3,
                 "faults[2]",
                 {"unknown type 'link_dwn'",
                  "(battery_drain, corrupt_command, link_down, wrong_command, zero_switch_stuck)"});
}

TEST(FaultScript, RejectsMissingFields) {
  expectRejected("faults:\n  - {type: link_down, duration: 4 s}\n", 2, "faults[1]",
                 {"missing field 'at'"});
  expectRejected("faults:\n  - {at: 4 s}\n", 2, "faults[1]", {"missing field 'type'"});
  expectRejected("faults:\n  - {at: 4 s, type: zero_switch_stuck, reads: pressed}\n", 2,
                 "faults[1]", {"missing field 'clamp'"});
  expectRejected("faults:\n  - {at: 4 s, type: zero_switch_stuck, clamp: fixed}\n", 2, "faults[1]",
                 {"missing field 'reads'"});
  expectRejected("faults:\n  - {at: 4 s, type: battery_drain}\n", 2, "faults[1]",
                 {"missing field 'current'"});
  expectRejected("faults:\n  - {at: 4 s, type: wrong_command, command: stop}\n", 2, "faults[1]",
                 {"missing field 'joint'"});
  expectRejected("faults:\n  - {at: 4 s, type: wrong_command, joint: J3}\n", 2, "faults[1]",
                 {"missing field 'command'"});
  expectRejected("operator:\n  - {action: resume}\n", 2, "operator[1]", {"missing field 'after'"});
  expectRejected("operator:\n  - {after: 3 s}\n", 2, "operator[1]", {"missing field 'action'"});
  expectRejected("faults:\n  - {at: , type: link_down}\n", 2, "faults[1]: at", {"no value"});
  expectRejected("faults:\n  - at:\n    type: link_down\n", 2, "faults[1]: at", {"no value"});
  expectRejected("policy:\n  link_wait:\n  low_battery: alarm_only\n", 2, "policy: link_wait",
                 {"no value"});
}

TEST(FaultScript, RejectsNegativeTimes) {
  expectRejected("faults:\n  - {at: 1 s, type: link_down}\n  - {at: -5 s, type: link_down}\n", 3,
                 "faults[2]: at", {"'-5 s'", ">= 0"});
  expectRejected("operator:\n  - {after: -1 ms, action: resume}\n", 2, "operator[1]: after",
                 {"'-1 ms'", ">= 0"});
}

TEST(FaultScript, RejectsNonPositiveDurationsAndCurrents) {
  expectRejected("faults:\n  - {at: 1 s, type: link_down, duration: 0 s}\n", 2,
                 "faults[1]: duration", {"'0 s'", "> 0"});
  expectRejected("policy:\n  link_wait: 0 min\n", 2, "policy: link_wait", {"'0 min'", "> 0"});
  expectRejected("faults:\n  - {at: 1 s, type: battery_drain, current: -2 A}\n", 2,
                 "faults[1]: current", {"'-2 A'", "> 0"});
  expectRejected("faults:\n  - {at: 1 s, type: battery_drain, current: 0 mA}\n", 2,
                 "faults[1]: current", {"'0 mA'", "> 0"});
}

TEST(FaultScript, RejectsWaitsOfMoreThanADay) {
  // The run would step through them 0.01 s at a time.
  expectRejected("operator:\n  - {after: 1441 min, action: resume}\n", 2, "operator[1]: after",
                 {"'1441 min'", "more than a day"});
  expectRejected("policy:\n  link_wait: 86401 s\n", 2, "policy: link_wait",
                 {"'86401 s'", "more than a day"});
  const FaultScript day = parseFaultScript(
      "policy: {link_wait: 1440 min}\noperator:\n  - {after: 86400 s, action: resume}\n", "f");
  EXPECT_EQ(day.link_wait_s, 86400.0);
  EXPECT_EQ(day.operator_responses[0].after_s, 86400.0);
}

TEST(FaultScript, RejectsBadUnits) {
  expectRejected("faults:\n  - {at: 5 h, type: link_down}\n", 2, "faults[1]: at",
                 {"unknown unit 'h'", "'5 h'", "(min, ms, s)"});
  expectRejected("faults:\n  - {at: 5 s, type: battery_drain, current: 8 V}\n", 2,
                 "faults[1]: current", {"unknown unit 'V'", "(A, mA)"});
  expectRejected(
      "faults:\n  - {at: 5 s, type: wrong_command, joint: J4, command: move_to, "
      "value: 20 deg}\n",
      2, "faults[1]: value", {"unknown unit 'deg'", "(mm)"});
  expectRejected(
      "faults:\n  - {at: 5 s, type: wrong_command, joint: J6, command: spin, value: 20 deg}\n", 2,
      "faults[1]: value", {"unknown unit 'deg'", "(rpm)"});
  expectRejected("operator:\n  - {after: 5, action: resume}\n", 2, "operator[1]: after",
                 {"'5'", "not a number and a unit"});
}

TEST(FaultScript, RejectsNonNumbers) {
  for (const std::string bad : {"abc s", "5s", "0x10 s", "nan s", "1.2.3 s", "5 s s"}) {
    expectRejected("faults:\n  - {at: " + bad + ", type: link_down}\n", 2, "faults[1]: at",
                   {"'" + bad + "'", "not a number and a unit"});
  }
  expectRejected("faults:\n  - {at: 1e400 min, type: link_down}\n", 2, "faults[1]: at",
                 {"'1e400 min'"});
  expectRejected("faults:\n  - {at: 1e307 min, type: link_down}\n", 2, "faults[1]: at",
                 {"'1e307 min'", "out of range"});
  expectRejected("faults:\n  - {at: [1, s], type: link_down}\n", 2, "faults[1]: at",
                 {"single value"});
}

TEST(FaultScript, RejectsFieldsThatDoNotBelongToTheType) {
  expectRejected("faults:\n  - {at: 1 s, type: corrupt_command, duration: 4 s}\n", 2, "faults[1]",
                 {"'duration'", "corrupt_command", "(allowed: at, type)"});
  expectRejected("faults:\n  - {at: 1 s, type: link_down, current: 4 A}\n", 2, "faults[1]",
                 {"'current'", "link_down", "(allowed: at, duration, type)"});
  expectRejected(
      "faults:\n  - at: 1 s\n    type: zero_switch_stuck\n    clamp: fixed\n    reads: pressed\n"
      "    joint: J1\n",
      6, "faults[1]", {"'joint'", "zero_switch_stuck"});
  // A key no fault takes is unknown rather than misplaced.
  expectRejected("faults:\n  - {at: 1 s, type: link_down, until: 4 s}\n", 2, "faults[1]",
                 {"unknown key 'until'"});
}

TEST(FaultScript, RejectsUnknownOperatorAction) {
  expectRejected("operator:\n  - {after: 1 s, action: resume}\n  - {after: 1 s, action: repair}\n",
                 3, "operator[2]",
                 {"unknown action 'repair'", "(repair_and_resume, resume, return)"});
  expectRejected("operator:\n  - {after: 1 s, action: resume, note: x}\n", 2, "operator[1]",
                 {"unknown key 'note'"});
}

TEST(FaultScript, RejectsUnknownPolicy) {
  expectRejected("policy:\n  link_wait: 10 s\n  low_battery: panic\n", 3, "policy",
                 {"'panic'", "(alarm_only, finish_disc_and_return)"});
  expectRejected("policy:\n  link_wait: 10 s\n  battery: alarm_only\n", 3, "policy",
                 {"unknown key 'battery'", "link_wait, low_battery"});
}

TEST(FaultScript, RejectsBadClampOrReading) {
  expectRejected("faults:\n  - {at: 1 s, type: zero_switch_stuck, clamp: J1, reads: pressed}\n", 2,
                 "faults[1]", {"unknown clamp 'J1'", "(fixed, moving)"});
  expectRejected("faults:\n  - {at: 1 s, type: zero_switch_stuck, clamp: fixed, reads: true}\n", 2,
                 "faults[1]", {"'true'", "(not_pressed, pressed)"});
}

TEST(FaultScript, RejectsBadJointOrCommand) {
  expectRejected("faults:\n  - {at: 1 s, type: wrong_command, joint: J7, command: stop}\n", 2,
                 "faults[1]", {"unknown joint 'J7'", "J1 .. J6"});
  expectRejected("faults:\n  - {at: 1 s, type: wrong_command, joint: j3, command: stop}\n", 2,
                 "faults[1]", {"'j3'"});
  expectRejected("faults:\n  - {at: 1 s, type: wrong_command, joint: J3, command: jump}\n", 2,
                 "faults[1]", {"unknown command 'jump'", "move_to"});
}

TEST(FaultScript, RejectsMoveToOrSpinWithoutValue) {
  expectRejected("faults:\n  - {at: 1 s, type: wrong_command, joint: J3, command: move_to}\n", 2,
                 "faults[1]", {"missing field 'value'", "move_to", "mm"});
  expectRejected("faults:\n  - {at: 1 s, type: wrong_command, joint: J5, command: move_to}\n", 2,
                 "faults[1]", {"missing field 'value'", "deg"});
  expectRejected("faults:\n  - {at: 1 s, type: wrong_command, joint: J6, command: spin}\n", 2,
                 "faults[1]", {"missing field 'value'", "spin", "rpm"});
}

TEST(FaultScript, RejectsValueOnCommandsThatTakeNone) {
  expectRejected(
      "faults:\n  - {at: 1 s, type: wrong_command, joint: J1, command: close, value: 5 deg}\n", 2,
      "faults[1]", {"close", "takes no value", "'5 deg'"});
  expectRejected(
      "faults:\n  - {at: 1 s, type: wrong_command, joint: J2, command: release, value: 1 deg}\n", 2,
      "faults[1]", {"release", "takes no value"});
  expectRejected(
      "faults:\n  - {at: 1 s, type: wrong_command, joint: J3, command: stop, value: 1 mm}\n", 2,
      "faults[1]", {"stop", "takes no value"});
}

TEST(FaultScript, LeavesJointLimitsAndKindsToTheSimulator) {
  // Out of limits, or a kind the joint does not take: parsed as written, refused at run time.
  const FaultScript s = parse(
      "faults:\n"
      "  - {at: 1 s, type: wrong_command, joint: J3, command: move_to, value: 900 mm}\n"
      "  - {at: 2 s, type: wrong_command, joint: J3, command: close}\n");
  ASSERT_EQ(s.faults.size(), 2u);
  EXPECT_DOUBLE_EQ(s.faults[0].command.value, 900.0);
  EXPECT_EQ(s.faults[1].command.joint, SimJoint::kJ3);
  EXPECT_EQ(s.faults[1].command.kind, SimCommandKind::kClose);
  EXPECT_TRUE(RobotSimulator().refuse(s.faults[0].command).has_value());
  EXPECT_TRUE(RobotSimulator().refuse(s.faults[1].command).has_value());
}

TEST(FaultScript, RejectsDuplicateKeys) {
  expectRejected("faults:\n  - {at: 1 s, type: link_down, at: 2 s}\n", 2, "faults[1]",
                 {"key 'at' given twice"});
  expectRejected("policy: {link_wait: 10 s}\nfaults: []\npolicy: {link_wait: 20 s}\n", 3,
                 "fault file", {"key 'policy' given twice"});
}

TEST(FaultScript, RejectsYamlSyntaxErrors) {
  const std::string message =
      errorOf([] { parse("faults:\n  - {at: 1 s, type: link_down}\n  - {at: 2 s\n"); });
  EXPECT_THAT(message, StartsWith("f.yaml:"));
  EXPECT_THAT(message, HasSubstr("YAML syntax"));
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  expectRejected("faults:\n  - {at: 1 s, type: link_down}\n   bad: [\n", 3, "YAML syntax", {});
  EXPECT_THAT(errorOf([] { parse("faults: []\n---\nfaults: []\n"); }),
              StartsWith("f.yaml: holds more than one YAML document"));
}

TEST(FaultScript, LoadReadsAFileAndNamesItInMessages) {
  test::TempDir dir;
  const std::string good = dir.file("good.yaml"), bad = dir.file("bad.yaml");
  test::writeFile(good, kFullExample);
  test::writeFile(bad, "faults:\n  - {at: 1 s, type: link_dwn}\n");
  const FaultScript s = loadFaultScript(good);
  EXPECT_EQ(s.source, good);
  EXPECT_EQ(s.faults.size(), 11u);
  EXPECT_EQ(s.operator_responses.size(), 3u);
  EXPECT_THAT(errorOf([&] { loadFaultScript(bad); }),
              StartsWith(bad + ":2: faults[1]: unknown type 'link_dwn'"));
}

TEST(FaultScript, LoadRejectsAMissingFile) {
  test::TempDir dir;
  const std::string missing = dir.file("missing.yaml");
  EXPECT_EQ(errorOf([&] { loadFaultScript(missing); }), missing + ": cannot read");
  EXPECT_EQ(errorOf([&] { loadFaultScript(dir.file("")); }), dir.file("") + ": cannot read");
}

}  // namespace
}  // namespace mcws
