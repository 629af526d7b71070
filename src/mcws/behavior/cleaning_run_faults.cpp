// CleaningRun (cleaning_run.h): faults and exceptions (section 2.4 of Wang et al. 2018): injected
// faults, the link, the operator, the battery, sensor disagreements.

#include "mcws/behavior/cleaning_run.h"

#include <cmath>
#include <utility>

#include "mcws/core/decimal.h"

namespace mcws {
namespace cleaning {

void CleaningRun::applyFaults() {
  const double t = sim_.time();
  while (next_fault_ < faults_.size() && faults_[next_fault_].at_s <= t + 1e-9) {
    const InjectedFault& f = faults_[next_fault_++];
    std::string detail = faultKindName(f.kind);
    switch (f.kind) {
      case FaultKind::kLinkDown:
        if (sim_.snapshot().link_up) outage_injected_at_ = t;  // an outage starts
        sim_.setLinkUp(false);
        if (f.duration_s) {
          link_back_at_.push_back(t + *f.duration_s);
        } else {
          link_down_for_good_ = true;
        }
        detail += f.duration_s ? " for " + formatNumber(*f.duration_s) + " s" : " for good";
        break;
      case FaultKind::kZeroSwitchStuck: {
        const bool fixed = f.clamp == kFixedClamp;
        const SimFault sf = fixed ? (f.reads_pressed ? SimFault::kFixedZeroSwitchAlwaysPressed
                                                     : SimFault::kFixedZeroSwitchNeverPressed)
                                  : (f.reads_pressed ? SimFault::kMovingZeroSwitchAlwaysPressed
                                                     : SimFault::kMovingZeroSwitchNeverPressed);
        sim_.setFault(sf);
        switch_fault_at_[fixed ? 0 : 1] = t;
        detail += std::string(": ") + simJointName(f.clamp) + " reads " +
                  (f.reads_pressed ? "pressed" : "not pressed");
        break;
      }
      case FaultKind::kBatteryDrain:
        drain_ += f.current_a;
        sim_.setFault(SimFault::kBatteryDrain, drain_);
        detail += ": +" + formatNumber(f.current_a) + " A";
        break;
      case FaultKind::kCorruptCommand:
      case FaultKind::kWrongCommand:
        pending_.push_back(f);
        detail += ": armed for the next command";
        break;
    }
    log("fault_injected", "", detail);
  }
  for (auto it = link_back_at_.begin(); it != link_back_at_.end();) {
    if (*it <= t + 1e-9) {
      it = link_back_at_.erase(it);
      if (link_back_at_.empty() && !link_down_for_good_) {
        sim_.setLinkUp(true);
        log("link_up", "", "the radio link is back");
        resolve(until_link_);
      }
    } else {
      ++it;
    }
  }
}

void CleaningRun::superviseLink() {
  const bool up = sim_.snapshot().link_up;
  if (up) link_loss_noted_ = false;
  if (!up && !link_loss_noted_ && (returning_ || mode_ == Mode::kManual)) {
    link_loss_noted_ = true;
    const std::string what = returning_ ? "during the return: nothing changes, the robot "
                                          "returns on its own"
                                        : "in MANUAL: the robot stays stopped; the operator "
                                          "acts once the link is back";
    log("link_lost", active_ ? active_->behavior : "", what);
    until_link_.push_back(react("link_down", what, outage_injected_at_, sim_.time(), std::nullopt));
  }
  if (mode_ == Mode::kRunning && !returning_ && !up) {
    link_loss_noted_ = true;
    stopAll();
    link_lost_at_ = sim_.time();
    mode_ = Mode::kWaitingForLink;
    fireTask("link_lost");
    log("link_lost", active_ ? active_->behavior : "",
        "every joint stopped; waiting up to " + formatNumber(options_.faults.link_wait_s) +
            " s for the link");
    return;
  }
  if (mode_ != Mode::kWaitingForLink) return;
  if (up) {
    const double waited = sim_.time() - link_lost_at_;
    react("link_down", "stopped, link back after " + formatNumber(waited) + " s, resumed",
          outage_injected_at_, link_lost_at_, sim_.time());
    mode_ = Mode::kRunning;
    fireTask("resume_" + segment_->combined);  // back to the interrupted superstate
    log("link_restored", "", "resuming " + stateName());
    startBehavior(true);
  } else if (sim_.time() - link_lost_at_ >= options_.faults.link_wait_s - 1e-9) {
    until_start_.push_back(react("link_down",
                                 "stopped, no link after " +
                                     formatNumber(options_.faults.link_wait_s) +
                                     " s, returned to the start on its own",
                                 outage_injected_at_, link_lost_at_, std::nullopt));
    mode_ = Mode::kRunning;
    fireTask("resume_" + segment_->combined);  // back to the interrupted superstate
    startReturn("no link for " + formatNumber(options_.faults.link_wait_s) + " s");
  }
}

void CleaningRun::handOver(const std::string& fault, const std::string& what,
                           std::optional<double> injected, std::optional<double> detected) {
  if (!detected) detected = sim_.time();
  mode_ = Mode::kManual;
  fireTask("hand_over");
  const auto& responses = options_.faults.operator_responses;
  if (next_response_ >= responses.size()) {
    react(fault, what + "; control to the operator; no scripted response: the run stops", injected,
          detected, std::nullopt);
    finish(RunStatus::kHaltedInManual, "waiting for the operator after: " + what);
    return;
  }
  response_ = responses[next_response_++];
  response_at_ = sim_.time() + response_->after_s;
  until_operator_.push_back(react(fault,
                                  what + "; control to the operator; scripted response " +
                                      operatorActionName(response_->action) + " after " +
                                      formatNumber(response_->after_s) + " s",
                                  injected, detected, std::nullopt));
  log("manual", "", "control to the operator: " + what);
}

void CleaningRun::superviseOperator() {
  if (mode_ != Mode::kManual || sim_.time() < response_at_ - 1e-9) return;
  if (!returning_ && !sim_.snapshot().link_up) {  // the operator works from the ground
    if (link_back_at_.empty() || link_down_for_good_) {
      finish(RunStatus::kHaltedInManual,
             "the operator cannot reach the robot: the link is down for good");
    }
    return;
  }
  const OperatorAction action = response_->action;
  response_.reset();
  resolve(until_operator_);
  if (action == OperatorAction::kRepairAndResume) {
    for (const SimFault f :
         {SimFault::kFixedZeroSwitchNeverPressed, SimFault::kFixedZeroSwitchAlwaysPressed,
          SimFault::kMovingZeroSwitchNeverPressed, SimFault::kMovingZeroSwitchAlwaysPressed}) {
      sim_.setFault(f, 0.0);
    }
    switch_fault_at_ = {};
  }
  mode_ = Mode::kRunning;
  fireTask("resume_" + segment_->combined);  // back to the interrupted superstate
  log("operator", "", operatorActionName(action));
  if (action == OperatorAction::kReturn) {
    startReturn("the operator's order");
  } else {
    startBehavior(true);
  }
}

void CleaningRun::superviseBattery() {
  if (battery_alarm_ || !sim_.snapshot().battery_low) return;
  battery_alarm_ = true;
  summary_.battery_alarm_t = sim_.time();
  const std::string voltage = formatNumber(sim_.snapshot().battery_voltage) + " V";
  log("battery_low", active_ ? active_->behavior : "", "alarm: battery at " + voltage);
  if (options_.faults.low_battery == LowBatteryPolicy::kAlarmOnly) {
    react("battery_low", "alarm at " + voltage + "; the job goes on (policy alarm_only)",
          std::nullopt, sim_.time(), sim_.time());
  } else if (returning_ || (segment_ && segment_->combined == "CB3")) {
    until_start_.push_back(react("battery_low", "alarm at " + voltage + "; already on the way back",
                                 std::nullopt, sim_.time(), std::nullopt));
  } else {
    return_after_disc_ = true;
    until_start_.push_back(react("battery_low",
                                 "alarm at " + voltage + "; finishing disc " +
                                     std::to_string(disc_ + (segment_->combined == "CB1" ? 1 : 0)) +
                                     ", then returning",
                                 std::nullopt, sim_.time(), std::nullopt));
  }
}

std::optional<std::pair<SimJoint, std::string>> CleaningRun::sensorMismatch() const {
  for (const SimJoint clamp : {kFixedClamp, kMovingClamp}) {
    const SimJointState& j = sim_.snapshot().joint(clamp);
    const SimClampConfig& c =
        clamp == kFixedClamp ? sim_.config().fixed_clamp : sim_.config().moving_clamp;
    if (!j.zero_switch || std::abs(static_cast<double>(j.encoder)) <= 0.5 * c.counts_per_deg) {
      continue;
    }
    return std::make_pair(
        clamp, std::string(simJointName(clamp)) +
                   "'s zero switch reads pressed but its encoder reads " +
                   formatNumber(static_cast<double>(j.encoder) / c.counts_per_deg) + " deg");
  }
  return std::nullopt;
}

bool CleaningRun::superviseSensors() {
  const auto mismatch = sensorMismatch();
  const std::optional<double> seen = std::exchange(mismatch_seen_at_, std::nullopt);
  mismatch_handed_over_ = mismatch.has_value();
  if (!mismatch) {
    if (seen) {  // found while stopped, gone before the robot ran again: the operator's repair
      react("sensor_mismatch", "found while the robot stood still; repaired before it ran again",
            std::nullopt, seen, sim_.time());
    }
    return true;
  }
  stopAll();
  if (!seen) log("sensor_mismatch", active_ ? active_->behavior : "", mismatch->second);
  handOver("sensor_mismatch", mismatch->second, sensorFaultAt(mismatch->first), seen);
  return false;
}

void CleaningRun::noteSensors() {
  if (mismatch_seen_at_ || mismatch_handed_over_) return;
  if (const auto mismatch = sensorMismatch()) {
    mismatch_seen_at_ = sim_.time();
    log("sensor_mismatch", active_ ? active_->behavior : "",
        mismatch->second + "; the robot stands still: handled when it runs again");
  }
}

std::optional<double> CleaningRun::sensorFaultAt(SimJoint joint) const {
  if (joint == kFixedClamp) return switch_fault_at_[0];
  if (joint == kMovingClamp) return switch_fault_at_[1];
  return std::nullopt;
}

}  // namespace cleaning
}  // namespace mcws
