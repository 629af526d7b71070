#include "mcws/behavior/behavior_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <utility>

#include "mcws/core/decimal.h"
#include "mcws/core/error.h"
#include "mcws/io/atomic_file.h"
#include "mcws/io/gnuplot.h"
#include "mcws/io/process.h"

namespace mcws {

namespace fs = std::filesystem;
using ordered_json = nlohmann::ordered_json;

namespace {

/// Where in the run (RunPlace), as the summary's JSON names it.
ordered_json placeJson(const RunPlace& place) {
  ordered_json out;
  out["step"] = place.step;
  out["t_s"] = place.t;
  out["subtask"] = place.subtask;
  out["cb"] = place.combined;
  out["state"] = place.state;
  out["behavior"] = place.behavior;
  return out;
}

/// Compact JSON text; invalid UTF-8 in strings is replaced rather than thrown about.
std::string dumpLine(const ordered_json& value) {
  return value.dump(-1, ' ', false, ordered_json::error_handler_t::replace);
}

/// A time [s] rounded to the microsecond (no negative zero).
double roundedTime(double t) {
  const double rounded = std::round(t * 1e6) / 1e6;
  return rounded == 0.0 ? 0.0 : rounded;
}

/// A number with up to 9 significant digits ("0" for negative zero).
std::string number(double value) { return value == 0.0 ? "0" : formatNumber(value, 9); }

/// A CSV field: quoted (RFC 4180) when it holds a comma, a quote or a line break.
std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

const char* bit(bool value) { return value ? "1" : "0"; }

/// Renders the DOT text `text` to PNG bytes with `dot` (from a copy in a scratch directory: the
/// DOT file itself has no name until the run's outputs are committed together).
/// \throws mcws::Error naming `dot_path`, where the DOT text is written.
std::string renderPng(const std::string& dot, const std::string& text,
                      const std::string& dot_path) {
  io::ScratchDir scratch;
  const std::string graph = scratch.file("graph.dot"), png = scratch.file("graph.png"),
                    log = scratch.file("dot.log");
  {
    std::ofstream out(graph, std::ios::binary);  // scratch, not an output of the run
    out << text;
    if (!out.flush()) throw Error("cannot write a scratch copy of '" + dot_path + "'");
  }
  int spawn_errno = 0;
  const int status = io::runProgram({dot, "-Tpng", graph, "-o", png}, log, spawn_errno);
  if (status < 0) {
    throw Error("cannot run '" + dot + "' on '" + dot_path + "': " + std::strerror(spawn_errno));
  }
  const std::string bytes = io::readFile(png);
  if (status != 0 || bytes.rfind("\x89PNG", 0) != 0) {
    const std::string message = io::lastLine(io::readFile(log), " \t\r");
    throw Error("dot failed on '" + dot_path + "' (exit status " + std::to_string(status) + ")" +
                (message.empty() ? "" : ": " + message));
  }
  return bytes;
}

}  // namespace

std::string logRecordJson(const LogRecord& record) {
  ordered_json line;
  line["t"] = roundedTime(record.t);
  line["step"] = record.step;
  line["subtask"] = record.subtask;
  line["task_state"] = record.task_state;
  line["cb"] = record.combined;
  line["state"] = record.state;
  line["event"] = record.event;
  line["behavior"] = record.behavior;
  if (record.seq) line["seq"] = *record.seq;
  line["disc"] = record.disc;
  line["detail"] = record.detail;
  return dumpLine(line);
}

std::string logHeaderJson(const std::string& model_path, int insulators,
                          const std::string& faults_path) {
  ordered_json line;
  line["t"] = 0;
  line["event"] = "log_header";
  line["units"] = ordered_json::object({{"t", "s"}});
  line["model"] = model_path;
  line["insulators"] = insulators;
  line["faults"] = faults_path.empty() ? ordered_json(nullptr) : ordered_json(faults_path);
  return dumpLine(line);
}

nlohmann::ordered_json summaryJson(const RunSummary& summary) {
  ordered_json out;
  out["status"] = runStatusName(summary.status);
  out["discs_requested"] = summary.discs_requested;
  out["discs_cleaned"] = summary.discs_cleaned;
  out["final_disc"] = summary.final_disc;
  out["duration_s"] = summary.duration_s;
  out["steps"] = summary.steps;
  out["subtasks_completed"] = summary.subtasks_completed;
  out["behaviors_run"] = summary.behaviors_run;
  out["commands_sent"] = summary.commands_sent;
  out["phase_one_s"] = summary.phase_one_s;
  out["phase_two_s"] = summary.phase_two_s;
  out["battery_voltage_end_V"] = summary.battery_voltage_end;
  out["battery_charge_used_Ah"] = summary.battery_charge_used;
  out["battery_alarm_t_s"] =
      summary.battery_alarm_t ? ordered_json(*summary.battery_alarm_t) : ordered_json(nullptr);
  ordered_json faults = ordered_json::array();
  for (const FaultReaction& fault : summary.faults) {
    ordered_json item;
    const auto time = [](const std::optional<double>& t) {
      return t ? ordered_json(*t) : ordered_json(nullptr);
    };
    item["fault"] = fault.fault;
    item["injected_t_s"] = time(fault.injected_t);
    item["detected_t_s"] = time(fault.detected_t);
    item["resolved_t_s"] = time(fault.resolved_t);
    item["reaction"] = fault.reaction;
    faults.push_back(std::move(item));
  }
  out["faults"] = std::move(faults);
  ordered_json invariant;
  invariant["holds"] = !summary.violation.has_value();
  if (const auto& v = summary.violation) {
    ordered_json violation = placeJson(*v);
    violation["message"] = v->message;
    invariant["violation"] = std::move(violation);
  } else {
    invariant["violation"] = nullptr;
  }
  out["invariant"] = std::move(invariant);
  if (const auto& stop = summary.safety_stop) {
    ordered_json item = placeJson(*stop);
    item["command"] = stop->command;
    item["reason"] = stop->reason;
    item["message"] = stop->message;
    out["safety_stop"] = std::move(item);
  } else {
    out["safety_stop"] = nullptr;
  }
  ordered_json plan = ordered_json::array();
  for (const Subtask& subtask : summary.plan) {
    ordered_json item;
    item["cb"] = subtask.behavior;
    item["action"] = subtask.action;
    item["disc"] = subtask.disc;
    plan.push_back(std::move(item));
  }
  out["plan"] = std::move(plan);
  return out;
}

TimelineRecorder::TimelineRecorder(double period, double dt) {
  if (!(period > 0.0) || !std::isfinite(period)) {
    throw Error("timeline: period = " + number(period) + " s, must be > 0");
  }
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    throw Error("timeline: dt = " + number(dt) + " s, must be > 0");
  }
  constexpr double kWhole = 1e-6;  // period / dt within this of a whole number counts as one
  const double ratio = period / dt;
  const double k = std::round(ratio);
  if (ratio < 1.0 - kWhole) {
    throw Error("timeline: period = " + number(period) + " s is below the simulator's step " +
                number(dt) + " s: there are no rows between steps");
  }
  if (std::abs(ratio - k) > kWhole) {
    throw Error("timeline: period = " + number(period) + " s is not a whole multiple of the " +
                "simulator's step " + number(dt) + " s (the rows come every " + number(k * dt) +
                " s or so)");
  }
  every_ = static_cast<std::uint64_t>(k);
}

void TimelineRecorder::operator()(const SimSnapshot& snapshot, const StepContext& context) {
  if (snapshot.step % every_ != 0) return;
  TimelineRow row;
  row.t = snapshot.time;
  row.step = snapshot.step;
  row.subtask = context.subtask;
  row.task_state = context.task_state;
  row.combined = context.combined;
  row.state = context.state;
  for (std::size_t j = 0; j < kSimJointCount; ++j) {
    row.position[j] = snapshot.joints[j].position;
    row.velocity[j] = snapshot.joints[j].velocity;
    row.current[j] = snapshot.joints[j].current;
  }
  row.fixed_zero_switch = snapshot.joint(kFixedClamp).zero_switch;
  row.moving_zero_switch = snapshot.joint(kMovingClamp).zero_switch;
  row.fixed_gripping = snapshot.joint(kFixedClamp).gripping;
  row.moving_gripping = snapshot.joint(kMovingClamp).gripping;
  row.battery_voltage = snapshot.battery_voltage;
  row.battery_low = snapshot.battery_low;
  row.link_up = snapshot.link_up;
  rows_.push_back(std::move(row));
}

void writeTimelineCsv(std::ostream& out, const std::vector<TimelineRow>& rows) {
  static const char* const kPositionUnits[kSimJointCount] = {"deg", "deg", "mm",
                                                             "mm",  "deg", "deg"};
  static const char* const kSpeedUnits[kSimJointCount] = {"deg_per_s", "deg_per_s", "mm_per_s",
                                                          "mm_per_s",  "deg_per_s", "rpm"};
  std::string header = "t_s,step,subtask,task_state,cb,state";
  for (std::size_t j = 0; j < kSimJointCount; ++j) {
    header += ",J" + std::to_string(j + 1) + "_" + kPositionUnits[j];
  }
  for (std::size_t j = 0; j < kSimJointCount; ++j) {
    header += ",J" + std::to_string(j + 1) + "_" + kSpeedUnits[j];
  }
  for (std::size_t j = 0; j < kSimJointCount; ++j) header += ",J" + std::to_string(j + 1) + "_A";
  header += ",J1_zero_switch,J2_zero_switch,J1_gripping,J2_gripping,battery_V,battery_low,link_up";
  out << header << "\n";
  for (const TimelineRow& row : rows) {
    std::string line = number(row.t) + "," + std::to_string(row.step) + "," +
                       std::to_string(row.subtask) + "," + csvField(row.task_state) + "," +
                       csvField(row.combined) + "," + csvField(row.state);
    for (double v : row.position) line += "," + number(v);
    for (double v : row.velocity) line += "," + number(v);
    for (double v : row.current) line += "," + number(v);
    line += std::string(",") + bit(row.fixed_zero_switch) + "," + bit(row.moving_zero_switch) +
            "," + bit(row.fixed_gripping) + "," + bit(row.moving_gripping) + "," +
            number(row.battery_voltage) + "," + bit(row.battery_low) + "," + bit(row.link_up);
    out << line << "\n";
  }
}

namespace {

/// Writes the window's joint speeds to `path`: a header line, then per row the time and the six
/// speeds. \throws mcws::Error naming the file when it cannot be written.
void writeSpeedData(const std::vector<const TimelineRow*>& window, const std::string& path) {
  std::ofstream file(path, std::ios::binary);
  file << "# t_s J1_deg_per_s J2_deg_per_s J3_mm_per_s J4_mm_per_s J5_deg_per_s J6_rpm\n";
  for (const TimelineRow* row : window) {
    file << number(row->t);
    for (double v : row->velocity) file << " " << number(v);
    file << "\n";
  }
  if (!file) throw Error("joint speed plot: cannot write '" + path + "'");
}

/// gnuplot's phase shading: a rectangle per run of rows of one phase, from its first row to the
/// next row of another phase (the last row at the end of the window).
std::string phaseShading(const std::vector<const TimelineRow*>& window) {
  const auto phaseOf = [](const TimelineRow& row) {
    if (row.combined == "CB2") return 2;
    if (row.combined == "CB1" || row.combined == "CB3") return 1;
    return 0;
  };
  std::ostringstream gp;
  int object = 1;
  for (std::size_t i = 0; i < window.size();) {
    const int phase = phaseOf(*window[i]);
    std::size_t end = i + 1;
    while (end < window.size() && phaseOf(*window[end]) == phase) ++end;
    const double x0 = window[i]->t;
    const double x1 = end < window.size() ? window[end]->t : window.back()->t;
    if (phase != 0 && x1 > x0) {
      gp << "set object " << object++ << " rect from " << number(x0) << ", graph 0 to "
         << number(x1) << ", graph 1 behind fillcolor rgb "
         << (phase == 2 ? "'#d6e6f5'" : "'#fbf0d9'") << " fillstyle solid 1.0 noborder\n";
    }
    i = end;
  }
  return gp.str();
}

/// J6 on y2: its speed range over the window [rpm], padded as `set offsets` pads y1 (which it
/// does not do for y2).
std::pair<double, double> j6Range(const std::vector<const TimelineRow*>& window) {
  double j6_low = 0.0, j6_high = 0.0;
  for (const TimelineRow* row : window) {
    const double v = row->velocity[simJointIndex(SimJoint::kJ6)];
    if (std::isfinite(v)) j6_low = std::min(j6_low, v), j6_high = std::max(j6_high, v);
  }
  if (j6_high - j6_low <= 0.0) j6_high = j6_low + 1.0;
  const double j6_pad = 0.05 * (j6_high - j6_low);
  return {j6_low - j6_pad, j6_high + j6_pad};
}

}  // namespace

std::string plotJointSpeeds(const std::vector<TimelineRow>& rows, double from_s, double to_s,
                            const std::string& title) {
  std::vector<const TimelineRow*> window;
  for (const TimelineRow& row : rows) {
    if (from_s <= row.t && row.t <= to_s) window.push_back(&row);
  }
  if (window.size() < 2) {
    throw Error("joint speed plot: " + std::to_string(window.size()) + " timeline row(s) in [" +
                number(from_s) + ", " + number(to_s) + "] s, need at least 2");
  }
  io::ScratchDir dir;
  const std::string data = dir.file("speeds.dat"), png = dir.file("speeds.png");
  writeSpeedData(window, data);
  std::ostringstream gp;
  gp << "set terminal pngcairo noenhanced size 1200,800 font 'Sans,11'\n"
     << "set output " << io::gnuplotQuoted(png) << "\n"
     << phaseShading(window);
  const double t0 = window.front()->t, t1 = window.back()->t;
  if (t1 > t0) gp << "set xrange [" << number(t0) << ":" << number(t1) << "]\n";
  const auto [j6_low, j6_high] = j6Range(window);
  const std::string source = io::gnuplotQuoted(data);
  const std::string shading =
      "keyentry with boxes fillcolor rgb '#fbf0d9' fillstyle solid 1.0 noborder "
      "title 'phase I (CB1, CB3)', keyentry with boxes fillcolor rgb '#d6e6f5' fillstyle solid "
      "1.0 noborder title 'phase II (CB2)'";
  gp << "set multiplot layout 2,1 title " << io::gnuplotQuoted(title) << "\n"
     << "set grid\nset key at screen 0.995, graph 1 right top vertical box opaque\n"
     << "set xlabel 'time [s]'\nset lmargin at screen 0.07\nset rmargin at screen 0.74\n"
     << "set offsets 0, 0, graph 0.05, graph 0.05\n"
     << "set title 'I: moving mechanism (J1-J3)'\n"
     << "set ylabel 'J1, J2 [deg/s]; J3 [mm/s]'\n"
     << "plot " << source << " using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'J1 [deg/s]', "
     << source << " using 1:3 with lines lw 2 lc rgb '#ff7f0e' title 'J2 [deg/s]', " << source
     << " using 1:4 with lines lw 2 lc rgb '#2ca02c' title 'J3 [mm/s]', " << shading << "\n"
     << "set title 'II: cleaning mechanism (J4-J6)'\n"
     << "set ylabel 'J4 [mm/s]; J5 [deg/s]'\nset y2label 'J6 [rpm]'\n"
     << "set ytics nomirror\nset y2tics\nset y2range [" << number(j6_low) << ":" << number(j6_high)
     << "]\n"
     << "plot " << source << " using 1:5 with lines lw 2 lc rgb '#9467bd' title 'J4 [mm/s]', "
     << source << " using 1:6 with lines lw 2 lc rgb '#8c564b' title 'J5 [deg/s]', " << source
     << " using 1:7 axes x1y2 with lines lw 2 dt 2 lc rgb '#d62728' title 'J6 [rpm] (right)', "
     << shading << "\n"
     << "unset multiplot\n";
  return io::runGnuplot(dir, gp.str(), png);
}

std::pair<double, double> firstDiscWindow(const std::vector<TimelineRow>& rows) {
  if (rows.empty()) return {0.0, 0.0};
  std::size_t i = 0;
  while (i < rows.size() && rows[i].combined != "CB1") ++i;
  std::size_t j = i;
  while (j < rows.size() && rows[j].combined != "CB2") ++j;
  if (j < rows.size()) {
    while (j + 1 < rows.size() && rows[j + 1].combined == "CB2") ++j;
    return {rows[i].t, rows[j].t};
  }
  return {rows.front().t, rows.back().t};
}

std::vector<std::string> writeStateMachineDots(const BehaviorModel& model, const std::string& dir) {
  // The model's loader refuses such names already; a model built in code is checked here,
  // before anything is written: no name leaves `dir` or overwrites another diagram.
  std::vector<std::string> names;
  for (const CombinedBehavior& combined : model.combined) names.push_back(combined.name);
  names.push_back(kTaskDiagramName);
  std::map<std::string, std::string> taken;  // ASCII-lower-case name -> name
  for (const std::string& name : names) {
    if (const auto problem = fileStemProblem(name)) {
      throw Error(model.source + ": diagram " + quotedName(name) + ": not written to '" + dir +
                  "': its name " + *problem);
    }
    std::string folded = name;
    for (char& c : folded) {
      if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    }
    const auto [it, fresh] = taken.emplace(folded, name);
    if (!fresh) {
      throw Error(model.source + ": diagram " + quotedName(name) + ": not written to '" + dir +
                  "': its file would be that of diagram " + quotedName(it->second));
    }
  }
  std::vector<std::pair<std::string, std::string>> graphs;  // (name, DOT text)
  for (const CombinedBehavior& combined : model.combined) {
    graphs.emplace_back(combined.name, stateMachineOf(combined).toDot());
  }
  graphs.emplace_back(kTaskDiagramName, taskMachine().toDot());

  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir, ec)) {
    throw Error("cannot create the directory '" + dir + "'" +
                (ec ? ": " + ec.message() : ": it is not a directory"));
  }

  const std::string dot = io::findOnPath("dot");  // Graphviz; "" when it is not installed
  std::vector<std::string> written;
  for (const auto& [name, text] : graphs) {
    const std::string dot_path = (fs::path(dir) / (name + ".dot")).string();
    io::writeWholeFile(dot_path, text);
    written.push_back(dot_path);
    if (dot.empty()) continue;
    const std::string png_path = (fs::path(dir) / (name + ".png")).string();
    io::writeWholeFile(png_path, renderPng(dot, text, dot_path));
    written.push_back(png_path);
  }
  return written;
}

std::string runFailure(const RunSummary& summary) {
  switch (summary.status) {
    case RunStatus::kInvariantViolated:
      return "safety invariant violated at " + summary.violation->message;
    case RunStatus::kBatteryEmpty:
      return "the battery ran empty; the robot is stranded on the string";
    case RunStatus::kSafetyStop:
      return "safety stop: " + summary.safety_stop->message;
    case RunStatus::kTimeLimit:
      return "the simulated time limit was reached";
    default:
      return "";
  }
}

std::string summaryText(const RunSummary& s) {
  std::ostringstream out;
  out << "status: " << runStatusName(s.status) << "\n"
      << "discs cleaned: " << s.discs_cleaned << " of " << s.discs_requested << "; at the end "
      << s.final_disc << " disc(s) below the start\n"
      << "duration: " << formatFixed(s.duration_s, 2)
      << " s simulated (phase I, moving: " << formatFixed(s.phase_one_s, 2)
      << " s; phase II, cleaning: " << formatFixed(s.phase_two_s, 2) << " s), " << s.steps
      << " steps\n"
      << "sub-tasks completed: " << s.subtasks_completed
      << "; basic behaviours run: " << s.behaviors_run << "; commands sent: " << s.commands_sent
      << "\n"
      << "battery: " << formatFixed(s.battery_voltage_end, 2) << " V at the end, "
      << formatFixed(s.battery_charge_used, 3) << " A h used; "
      << (s.battery_alarm_t ? "low-battery alarm at " + formatFixed(*s.battery_alarm_t, 2) + " s"
                            : std::string("no alarm"))
      << "\n";
  out << "faults: " << (s.faults.empty() ? "none" : std::to_string(s.faults.size())) << "\n";
  const auto time = [](const std::optional<double>& t) {
    return t ? formatFixed(*t, 2) + " s" : std::string("-");
  };
  for (const FaultReaction& f : s.faults) {
    out << "  " << f.fault << " (injected " << time(f.injected_t) << ", detected "
        << time(f.detected_t) << ", resolved " << time(f.resolved_t) << "): " << f.reaction << "\n";
  }
  out << "safety invariant (a clamp grips the string at every step): "
      << (s.violation ? "VIOLATED at " + s.violation->message
                      : "held at all " + std::to_string(s.steps) + " steps")
      << "\n";
  if (s.safety_stop) out << "safety stop: " << s.safety_stop->message << "\n";
  return out.str();
}

nlohmann::ordered_json checkJson(const ValidationReport& report,
                                 const std::vector<PoseFinding>& findings) {
  nlohmann::ordered_json j;
  j["valid"] = findings.empty();
  j["state_vector_combinations"] = report.combinations;
  j["allowed_poses"] = report.allowed_poses;
  j["forbidden_poses"] = report.forbidden_poses;
  j["states_with_poses"] = report.states;
  j["poses_used"] = report.poses_used;
  j["basic_behaviors"] = report.behaviors;
  j["events"] = report.events;
  j["combined_behaviors"] = nlohmann::ordered_json::array();
  for (const CombinedBehaviorCounts& c : report.combined) {
    j["combined_behaviors"].push_back({{"name", c.name},
                                       {"states", c.states},
                                       {"transitions", c.transitions},
                                       {"events", c.events}});
  }
  j["pose_findings"] = nlohmann::ordered_json::array();
  for (const PoseFinding& f : findings) j["pose_findings"].push_back(f.message);
  return j;
}

}  // namespace mcws
