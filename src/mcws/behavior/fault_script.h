#pragma once
/// \file
/// \brief A rehearsal's faults and the operator's responses, read from a YAML file: what
/// `mcws_behave --faults F.yaml` injects into a simulated cleaning run
/// (Wang et al. 2018, section 2.4).
///
/// File format (every time and quantity carries its unit). Every section is optional, and so are
/// `policy`'s keys and a link_down's `duration`; every other key shown is required for its type:
/// \code
/// policy:
///   link_wait: 30 s                   # how long the robot waits for a lost link (default 30 s)
///   low_battery: finish_disc_and_return   # or alarm_only (default finish_disc_and_return)
/// faults:                             # any order; applied in order of `at`, file order on ties
///   - {at: 100 s, type: link_down, duration: 40 s}   # no duration: the link stays down
///   - {at: 12 s, type: zero_switch_stuck, clamp: fixed, reads: not_pressed}  # or moving, pressed
///   - {at: 50 s, type: corrupt_command}              # the next command arrives corrupted
///   - {at: 60 s, type: wrong_command, joint: J4, command: move_to, value: 200 mm}
///   - {at: 0 s, type: battery_drain, current: 8 A}   # extra current from then on
/// operator:                           # the k-th hand-over to the operator gets the k-th entry
///   - {after: 30 s, action: repair_and_resume}       # or resume, or return
/// \endcode
/// Times: s, ms or min; `at` >= 0, `after` >= 0, `duration` and `link_wait` > 0; `after` and
/// `link_wait` at most a day (86400 s). Currents: A
/// or mA, > 0. `wrong_command` takes a joint J1..J6, a command (close, release, stop, move_to,
/// spin) and, for move_to and spin only, a value (move_to: mm for J3, J4, deg for the others;
/// spin: rpm); it always runs at the joint's full speed. Whether the joint takes that command
/// and whether the value lies within its limits is not checked here: that is the run-time
/// interference check's job, which the fault exists to exercise. One YAML document per file.

#include <optional>
#include <string>
#include <vector>

#include "mcws/behavior/robot_simulator.h"

namespace mcws {

/// \brief What a fault does.
enum class FaultKind {
  kLinkDown,         ///< the radio link to the ground station goes down (for `duration`)
  kZeroSwitchStuck,  ///< a clamp's zero switch reads one value whatever the jaw (until repaired)
  kCorruptCommand,   ///< the first command sent at or after `at` arrives corrupted
  kWrongCommand,     ///< the first motion command sent at or after `at` is replaced by `command`
  kBatteryDrain,     ///< an extra current drawn from the battery from `at` on
};
/// \brief "link_down", "zero_switch_stuck", "corrupt_command", "wrong_command", "battery_drain".
const char* faultKindName(FaultKind kind);

/// \brief One injected fault.
struct InjectedFault {
  FaultKind kind{FaultKind::kLinkDown};
  double at_s{0.0};                  ///< simulated time it happens [s]
  std::optional<double> duration_s;  ///< kLinkDown: down for this long [s]; none = for good
  SimJoint clamp{kFixedClamp};       ///< kZeroSwitchStuck: kFixedClamp or kMovingClamp
  bool reads_pressed{false};         ///< kZeroSwitchStuck: the stuck reading
  double current_a{0.0};             ///< kBatteryDrain: the extra current [A]
  SimCommand command;                ///< kWrongCommand: what arrives instead
  int line{0};                       ///< line of the file [1-based]
};

/// \brief What the operator does when control is handed over (MANUAL).
enum class OperatorAction {
  kRepairAndResume,  ///< repairs the injected sensor faults, then resumes the behaviour
  kResume,           ///< resumes the interrupted behaviour without repairing anything
  kReturn,           ///< sends the robot back to the start (as after a lost link)
};
/// \brief "repair_and_resume", "resume", "return".
const char* operatorActionName(OperatorAction action);

/// \brief The operator's response to one hand-over.
struct OperatorResponse {
  double after_s{0.0};  ///< time from the hand-over to the action [s]
  OperatorAction action{OperatorAction::kRepairAndResume};
  int line{0};
};

/// \brief What the robot does beyond the alarm of Wang et al. 2018 when the battery runs low.
enum class LowBatteryPolicy {
  kAlarmOnly,            ///< the alarm only (the paper's rule); the job goes on
  kFinishDiscAndReturn,  ///< finish the disc in hand (its CB1 and CB2), then return to the start
};
/// \brief "alarm_only", "finish_disc_and_return".
const char* lowBatteryPolicyName(LowBatteryPolicy policy);

/// \brief A fault file as read.
struct FaultScript {
  std::string source;        ///< the file, for messages
  double link_wait_s{30.0};  ///< [s]
  LowBatteryPolicy low_battery{LowBatteryPolicy::kFinishDiscAndReturn};
  std::vector<InjectedFault> faults;                 ///< sorted by at_s, file order on ties
  std::vector<OperatorResponse> operator_responses;  ///< in file order
};

/// \brief Parses a fault file's text.
/// \param source the file name used in messages.
/// \throws mcws::Error "source:line: item: ..." for YAML syntax, an unknown or duplicate key, a
///   missing field, an unknown type, action, policy, clamp, joint or command, a bad number or
///   unit, a negative time, a non-positive duration or current, a field that does not belong to
///   the fault's type.
FaultScript parseFaultScript(const std::string& text, const std::string& source);

/// \brief parseFaultScript() of a file. \throws mcws::Error naming the file when it cannot be read.
FaultScript loadFaultScript(const std::string& path);

}  // namespace mcws
