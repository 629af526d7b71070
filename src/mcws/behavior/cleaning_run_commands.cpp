// CleaningRun (cleaning_run.h): sending a command (the link, the sequence number and its echo,
// injected corrupt and wrong commands), safety stops and the safety invariant.

#include "mcws/behavior/cleaning_run.h"

#include <sstream>

namespace mcws {
namespace cleaning {

bool CleaningRun::send(const SimCommand& command, const std::string& behavior) {
  const bool ground = !returning_;  // on the way back the robot runs on its own
  if (ground && !sim_.snapshot().link_up) {
    log("command_not_sent", behavior, describe(command) + ": the link is down");
    return true;  // the link supervision stops everything and resends it
  }
  if (const auto both = opensBothClamps(command)) {
    violate("before sending " + describe(command) + ": " + *both);
    return false;
  }
  if (ground) {
    if (const auto corrupt = takeFault(FaultKind::kCorruptCommand)) {
      const std::uint64_t seq = ++seq_;
      const std::string what = "seq " + std::to_string(seq) + " (" + describe(command) +
                               ") failed the robot's command check; its echo (seq " +
                               std::to_string(seq - 1) + ", " + stateName() +
                               ") did not match; resent";
      log("command_rejected", behavior, what, seq);
      react("corrupt_command", what, corrupt->at_s, sim_.time(), sim_.time());
    }
    if (command.kind != SimCommandKind::kStop) {
      if (auto f = takeFault(FaultKind::kWrongCommand)) {
        const std::uint64_t seq = ++seq_;
        log("command", behavior, "received " + describe(f->command) + " (wrong command)", seq);
        if (const auto reason = interference(f->command)) {
          log("refused", behavior, describe(f->command) + ": " + *reason, seq);
          react("wrong_command",
                "refused " + describe(f->command) + " (" + *reason +
                    "); the behaviour's own command sent instead",
                f->at_s, sim_.time(), sim_.time());
        } else {
          sim_.command(f->command);
          react("wrong_command",
                describe(f->command) + " passed the interference check and was executed", f->at_s,
                std::nullopt, std::nullopt);
          return true;
        }
      }
    }
  }
  const std::uint64_t seq = ++seq_;
  if (const auto reason = interference(command)) {
    log("refused", behavior, describe(command) + ": " + *reason, seq);
    safetyStop(command, behavior, *reason);
    return false;
  }
  sim_.command(command);
  log("command", behavior,
      describe(command) + (ground ? "; echo seq " + std::to_string(seq) + " " + stateName() +
                                        (sensorsFit(stateName())
                                             ? " matches"
                                             : ": " + sensedText("in " + stateName(), stateName()))
                                  : "; on board"),
      seq);
  return true;
}

std::optional<InjectedFault> CleaningRun::takeFault(FaultKind kind) {
  for (auto it = pending_.begin(); it != pending_.end(); ++it) {
    if (it->kind == kind) {
      InjectedFault f = *it;
      pending_.erase(it);
      return f;
    }
  }
  return std::nullopt;
}

RunPlace CleaningRun::place(const std::string& behavior) const {
  const SimSnapshot& s = sim_.snapshot();
  return {s.step, s.time, subtask_, segment_ ? segment_->combined : "", stateName(), behavior};
}

void CleaningRun::safetyStop(const SimCommand& command, const std::string& behavior,
                             const std::string& reason) {
  stopAll();
  SafetyStop stop;
  static_cast<RunPlace&>(stop) = place(behavior);
  stop.command = describe(command);
  stop.reason = reason;
  std::ostringstream text;
  text << "step " << stop.step << " (t = " << stop.t << " s): refused " << behavior
       << "'s own command " << stop.command << " in " << stop.combined << " " << stop.state
       << " (sub-task " << stop.subtask << "): " << reason;
  stop.message = text.str();
  summary_.safety_stop = stop;
  react("refused_own_command", "every joint stopped; the run ends (safety stop)", std::nullopt,
        sim_.time(), std::nullopt);
  finish(RunStatus::kSafetyStop, stop.message);
}

std::optional<std::string> CleaningRun::opensBothClamps(const SimCommand& command) const {
  if (command.kind != SimCommandKind::kRelease) return std::nullopt;
  const SimJoint other = command.joint == kFixedClamp ? kMovingClamp : kFixedClamp;
  if (sim_.snapshot().joint(other).gripping) return std::nullopt;
  return std::string("it would open ") + simJointName(command.joint) + " while " +
         simJointName(other) + " does not grip: both clamps open";
}

bool CleaningRun::checkInvariant() {
  const SimSnapshot& s = sim_.snapshot();
  if (s.joint(kFixedClamp).gripping || s.joint(kMovingClamp).gripping) return true;
  violate("both clamps open");
  return false;
}

void CleaningRun::violate(const std::string& what) {
  InvariantViolation v;
  static_cast<RunPlace&>(v) = place(active_ ? active_->behavior : "");
  std::ostringstream text;
  text << "step " << v.step << " (t = " << v.t << " s): " << what << ": sub-task " << v.subtask
       << " (" << v.combined << "), state " << v.state << ", behaviour "
       << (v.behavior.empty() ? "none" : v.behavior);
  v.message = text.str();
  summary_.violation = v;
  log("invariant_violated", v.behavior, v.message);
  stopAll();
  finish(RunStatus::kInvariantViolated, v.message);
}

}  // namespace cleaning
}  // namespace mcws
