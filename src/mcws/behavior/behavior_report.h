#pragma once
/// \file
/// \brief What `mcws_behave` writes about a simulated cleaning run: the event log as JSON lines,
/// the timeline of joints, currents, switches and battery as CSV, a picture of the joint speeds
/// like Figure 10 of Wang et al. 2018, the summary as JSON, and the state machines as Graphviz DOT.
///
/// Units: time [s]; J1, J2, J5 positions [deg] and speeds [deg/s]; J3, J4 [mm] and [mm/s]; J6
/// angle [deg] and speed [rpm]; currents [A]; battery [V] and [A h]. CSV headers and JSON keys
/// name their units.

#include <array>
#include <cstdint>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "mcws/behavior/behavior_executor.h"
#include "mcws/behavior/behavior_model.h"
#include "mcws/behavior/robot_simulator.h"

namespace mcws {

/// \brief One log record as one line of JSON (no line break), keys in this order: t (simulated
/// time [s], rounded to the microsecond), step, subtask, task_state, cb, state, event, behavior,
/// seq (only when set), disc, detail. Strings escaped as JSON requires.
std::string logRecordJson(const LogRecord& record);

/// \brief The first line of a log: {"t": 0, "event": "log_header", "units": {"t": "s"}, "model":
///   ..., "insulators": N, "faults": ... or null}.
std::string logHeaderJson(const std::string& model_path, int insulators,
                          const std::string& faults_path);

/// \brief The run summary: status, discs_requested, discs_cleaned, final_disc, duration_s,
/// steps, subtasks_completed, behaviors_run, commands_sent, phase_one_s, phase_two_s,
/// battery_voltage_end_V, battery_charge_used_Ah, battery_alarm_t_s (null when none),
/// faults [{fault, injected_t_s, detected_t_s, resolved_t_s (each null when none, see
/// FaultReaction), reaction}], invariant {holds, violation: null or {step, t_s, subtask, cb,
/// state, behavior, message}}, safety_stop (null or {step, t_s, subtask, cb, state, behavior,
/// command, reason, message}), plan [{cb, action, disc}].
nlohmann::ordered_json summaryJson(const RunSummary& summary);

/// \brief The summary as text for a person: status, discs, durations by phase, counts, battery,
/// every fault with its reaction, the invariant; numbers with their units.
std::string summaryText(const RunSummary& summary);

/// \brief Why a run failed, in one line ("the simulated time limit was reached"), or empty for a
/// run that ended as planned: a violated invariant, an empty battery, a safety stop and the time
/// limit are failures; a completed run, a return to the start and a halt in manual are not.
std::string runFailure(const RunSummary& summary);

/// \brief `mcws_behave --check --json`: valid (no pose findings), the state vector's counts
/// (state_vector_combinations, allowed_poses, forbidden_poses, states_with_poses, poses_used),
/// basic_behaviors, events, combined_behaviors [{name, states, transitions, events}],
/// pose_findings [messages].
nlohmann::ordered_json checkJson(const ValidationReport& report,
                                 const std::vector<PoseFinding>& findings);

/// \brief One timeline row: the snapshot's values and what ran.
struct TimelineRow {
  double t{0.0};  ///< [s]
  std::uint64_t step{0};
  int subtask{0};
  std::string task_state, combined, state;
  /// J1..J6 positions (J1, J2, J5 [deg]; J3, J4 [mm]; J6 [deg]).
  std::array<double, kSimJointCount> position{};
  /// J1..J6 speeds (J1, J2, J5 [deg/s]; J3, J4 [mm/s]; J6 [rpm]).
  std::array<double, kSimJointCount> velocity{};
  std::array<double, kSimJointCount> current{};  ///< [A]
  bool fixed_zero_switch{false}, moving_zero_switch{false};
  bool fixed_gripping{false}, moving_gripping{false};
  double battery_voltage{0.0};  ///< [V]
  bool battery_low{false}, link_up{true};
};

/// \brief Keeps every k-th step of a run (k = round(period / dt), at least 1; the step at time 0
/// is always kept), to be passed as RunObserver::on_step.
class TimelineRecorder {
 public:
  /// \param period time between rows [s], a whole multiple of dt (to 1e-6 of dt).
  /// \param dt the simulator's time step [s].
  /// \throws mcws::Error naming `period` when it is not > 0, below dt or not a multiple of it.
  TimelineRecorder(double period, double dt);
  void operator()(const SimSnapshot& snapshot, const StepContext& context);
  const std::vector<TimelineRow>& rows() const { return rows_; }

 private:
  std::uint64_t every_{1};
  std::vector<TimelineRow> rows_;
};

/// \brief The rows as CSV: a header naming each column with its unit (t_s, step, subtask,
/// task_state, cb, state, J1_deg, ..., J3_mm, ..., J1_deg_per_s, ..., J6_rpm, J1_A, ..., J6_A,
/// J1_zero_switch, J2_zero_switch, J1_gripping, J2_gripping, battery_V, battery_low, link_up),
/// then one line per row; booleans 0/1; numbers with up to 9 significant digits.
void writeTimelineCsv(std::ostream& out, const std::vector<TimelineRow>& rows);

/// \brief A PNG like Figure 10 of Wang et al. 2018: two panels over simulated time, (I) the joint
/// speeds of the moving mechanism J1, J2 [deg/s] and J3 [mm/s]; (II) those of the cleaning
/// mechanism J4 [mm/s], J5 [deg/s] and J6 [rpm, on a second axis]; phases shaded by the combined
/// behaviour (CB1/CB3 = phase I, CB2 = phase II).
/// \param rows the timeline; only rows with from_s <= t <= to_s are drawn.
/// \param title drawn above the panels.
/// \return the PNG file's bytes.
/// \throws mcws::Error when there are fewer than two rows in the window, or gnuplot fails.
std::string plotJointSpeeds(const std::vector<TimelineRow>& rows, double from_s, double to_s,
                            const std::string& title);

/// \brief The time window of the first disc's cycle: from the start of the first CB1 to the end
/// of the first CB2 (the rows' `combined`), the whole run when there is none. [s]
std::pair<double, double> firstDiscWindow(const std::vector<TimelineRow>& rows);

/// \brief Writes `<dir>/<name>.dot` for every combined behaviour of the model and `task.dot`
/// for taskMachine(), and renders each to `<name>.png` with Graphviz `dot` when it is installed
/// (found on PATH).
/// \return the files written, in order (each .dot followed by its .png when rendered).
/// \throws mcws::Error naming the file when a file cannot be written or `dot` fails, and before
///   writing anything when a combined behaviour's name is not a plain file name
///   (fileStemProblem()) or its file would be another diagram's (the same name as kTaskDiagramName
///   or another combined behaviour, ignoring ASCII case).
std::vector<std::string> writeStateMachineDots(const BehaviorModel& model, const std::string& dir);

}  // namespace mcws
