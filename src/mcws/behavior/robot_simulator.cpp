#include "mcws/behavior/robot_simulator.h"

#include <algorithm>
#include <cmath>

#include "mcws/core/decimal.h"
#include "mcws/core/error.h"

namespace mcws {
namespace {

constexpr double kSecondsPerHour = 3600.0;
constexpr double kDegPerSecondPerRpm = 6.0;  // 1 rpm = 360 deg / 60 s

constexpr const char* kJointNames[kSimJointCount] = {"J1", "J2", "J3", "J4", "J5", "J6"};
constexpr const char* kKindNames[] = {"close", "release", "stop", "move_to", "spin"};
constexpr const char* kFaultNames[] = {
    "fixed_zero_switch_never_pressed", "fixed_zero_switch_always_pressed",
    "moving_zero_switch_never_pressed", "moving_zero_switch_always_pressed", "battery_drain"};
constexpr std::size_t kFaultCount = sizeof(kFaultNames) / sizeof(kFaultNames[0]);

bool validJoint(SimJoint joint) {
  const int i = static_cast<int>(joint);
  return i >= 0 && i < static_cast<int>(kSimJointCount);
}

bool isClamp(SimJoint joint) { return joint == SimJoint::kJ1 || joint == SimJoint::kJ2; }
bool isAxis(SimJoint joint) {
  return joint == SimJoint::kJ3 || joint == SimJoint::kJ4 || joint == SimJoint::kJ5;
}

/// Unit of a joint's position (J6: of its spin command).
const char* unitOf(SimJoint joint) {
  switch (joint) {
    case SimJoint::kJ3:
    case SimJoint::kJ4:
      return "mm";
    case SimJoint::kJ6:
      return "rpm";
    default:
      return "deg";
  }
}

// ---- configuration checks: each names the field, its value and the rule ----

[[noreturn]] void fail(const std::string& field, double value, const char* unit,
                       const std::string& rule) {
  throw Error("simulator config: " + field + " = " + formatNumber(value) +
              (unit[0] ? std::string(" ") + unit : std::string()) + ", " + rule);
}
void requirePositive(const std::string& field, double value, const char* unit) {
  if (!(value > 0.0) || !std::isfinite(value)) fail(field, value, unit, "must be > 0");
}
void requireNonNegative(const std::string& field, double value, const char* unit) {
  if (!(value >= 0.0) || !std::isfinite(value)) fail(field, value, unit, "must be >= 0");
}

void validateClamp(const std::string& name, const SimClampConfig& c) {
  requirePositive(name + ".jaw_speed", c.jaw_speed, "deg/s");
  requirePositive(name + ".contact_angle", c.contact_angle, "deg");
  if (!(c.end_stop_angle > c.contact_angle) || !std::isfinite(c.end_stop_angle)) {
    fail(name + ".end_stop_angle", c.end_stop_angle, "deg",
         "must be > contact_angle " + formatNumber(c.contact_angle) + " deg");
  }
  requireNonNegative(name + ".running_current", c.running_current, "A");
  if (!(c.stall_current > c.running_current) || !std::isfinite(c.stall_current)) {
    fail(name + ".stall_current", c.stall_current, "A",
         "must be > running_current " + formatNumber(c.running_current) + " A");
  }
  requirePositive(name + ".time_constant", c.time_constant, "s");
  requirePositive(name + ".counts_per_deg", c.counts_per_deg, "counts/deg");
}

void validateAxis(const std::string& name, const SimAxisConfig& a, const char* unit,
                  const std::string& speed_unit, const std::string& acceleration_unit) {
  requirePositive(name + ".max_speed", a.max_speed, speed_unit.c_str());
  requirePositive(name + ".max_acceleration", a.max_acceleration, acceleration_unit.c_str());
  if (!(a.min_position <= 0.0) || !std::isfinite(a.min_position)) {
    fail(name + ".min_position", a.min_position, unit, "must be <= 0 (the start pose)");
  }
  if (!(a.max_position >= 0.0) || !std::isfinite(a.max_position)) {
    fail(name + ".max_position", a.max_position, unit, "must be >= 0 (the start pose)");
  }
  if (!(a.max_position > a.min_position)) {
    fail(name + ".max_position", a.max_position, unit,
         "must be > min_position " + formatNumber(a.min_position) + " " + unit);
  }
  requirePositive(name + ".counts_per_unit", a.counts_per_unit,
                  (std::string("counts/") + unit).c_str());
  requireNonNegative(name + ".running_current", a.running_current, "A");
}

}  // namespace

// ---- names ----

const char* simJointName(SimJoint joint) {
  return validJoint(joint) ? kJointNames[simJointIndex(joint)] : "J?";
}

SimJoint simJointFromName(const std::string& name) {
  for (std::size_t i = 0; i < kSimJointCount; ++i) {
    if (name == kJointNames[i]) return static_cast<SimJoint>(i);
  }
  throw Error("unknown joint '" + name + "' (expected J1 .. J6)");
}

const char* commandKindName(SimCommandKind kind) {
  const int i = static_cast<int>(kind);
  return i >= 0 && i < 5 ? kKindNames[i] : "?";
}

SimCommandKind commandKindFromName(const std::string& name) {
  for (int i = 0; i < 5; ++i) {
    if (name == kKindNames[i]) return static_cast<SimCommandKind>(i);
  }
  throw Error("unknown command '" + name + "' (expected close, release, stop, move_to, spin)");
}

const char* faultName(SimFault fault) {
  const auto i = static_cast<std::size_t>(fault);
  return i < kFaultCount ? kFaultNames[i] : "?";
}

SimFault faultFromName(const std::string& name) {
  for (std::size_t i = 0; i < kFaultCount; ++i) {
    if (name == kFaultNames[i]) return static_cast<SimFault>(i);
  }
  throw Error("unknown fault '" + name + "'");
}

std::string describe(const SimCommand& command) {
  std::string text = std::string(simJointName(command.joint)) + " " + commandKindName(command.kind);
  if (command.kind == SimCommandKind::kMoveTo || command.kind == SimCommandKind::kSpin) {
    text += " " + formatNumber(command.value) + " " + unitOf(command.joint);
  }
  if (command.kind == SimCommandKind::kMoveTo && command.speed != 0.0) {
    text += " at " + formatNumber(command.speed) + " " + unitOf(command.joint) + "/s";
  }
  return text;
}

// ---- configuration ----

void validateSimulatorConfig(const RobotSimulatorConfig& config) {
  requirePositive("dt", config.dt, "s");
  validateClamp("fixed_clamp", config.fixed_clamp);
  validateClamp("moving_clamp", config.moving_clamp);
  validateAxis("j3", config.j3, "mm", "mm/s", "mm/s^2");
  requireNonNegative("j3_stall_current", config.j3_stall_current, "A");
  validateAxis("j4", config.j4, "mm", "mm/s", "mm/s^2");
  validateAxis("j5", config.j5, "deg", "deg/s", "deg/s^2");
  requirePositive("j6.max_speed", config.j6.max_speed, "rpm");
  requirePositive("j6.max_acceleration", config.j6.max_acceleration, "rpm/s");
  requirePositive("j6.counts_per_rev", config.j6.counts_per_rev, "counts/rev");
  requireNonNegative("j6.running_current", config.j6.running_current, "A");

  const SimStringConfig& s = config.string;
  requirePositive("string.pitch", s.pitch, "mm");
  if (s.disc_count < 1) fail("string.disc_count", s.disc_count, "", "must be >= 1");
  if (!(s.tolerance >= 0.0 && s.tolerance < 0.5 * s.pitch)) {
    fail("string.tolerance", s.tolerance, "mm",
         "must be in [0, pitch / 2 = " + formatNumber(0.5 * s.pitch) + " mm)");
  }
  if (s.initial_disc < 0 || s.initial_disc > s.disc_count) {
    fail("string.initial_disc", s.initial_disc, "",
         "must be in [0, disc_count = " + std::to_string(s.disc_count) + "]");
  }
  requireNonNegative("string.home_gap", s.home_gap, "mm");
  const double moving = s.initial_disc * s.pitch + s.home_gap;
  const double nearest = std::round(moving / s.pitch);
  if (nearest > s.disc_count || std::abs(moving - nearest * s.pitch) > s.tolerance) {
    fail("string.home_gap", s.home_gap, "mm",
         "puts the moving clamp at " + formatNumber(moving) + " mm, at no grip position 0 .. " +
             std::to_string(s.disc_count));
  }

  const SimBatteryConfig& b = config.battery;
  requirePositive("battery.capacity", b.capacity, "A h");
  if (!(b.initial_charge > 0.0 && b.initial_charge <= 1.0)) {
    fail("battery.initial_charge", b.initial_charge, "", "must be in (0, 1]");
  }
  if (!std::isfinite(b.empty_voltage)) {
    fail("battery.empty_voltage", b.empty_voltage, "V", "must be finite");
  }
  if (!(b.full_voltage > b.empty_voltage) || !std::isfinite(b.full_voltage)) {
    fail("battery.full_voltage", b.full_voltage, "V",
         "must be > empty_voltage " + formatNumber(b.empty_voltage) + " V");
  }
  if (!(b.low_voltage >= b.empty_voltage && b.low_voltage <= b.full_voltage)) {
    fail("battery.low_voltage", b.low_voltage, "V",
         "must be in [empty_voltage, full_voltage] = [" + formatNumber(b.empty_voltage) + ", " +
             formatNumber(b.full_voltage) + "] V");
  }
  requireNonNegative("battery.idle_current", b.idle_current, "A");
}

// ---- snapshot equality ----

bool operator==(const SimJointState& a, const SimJointState& b) {
  return a.position == b.position && a.velocity == b.velocity && a.encoder == b.encoder &&
         a.current == b.current && a.moving == b.moving && a.zero_switch == b.zero_switch &&
         a.gripping == b.gripping;
}

bool operator==(const SimSnapshot& a, const SimSnapshot& b) {
  return a.time == b.time && a.step == b.step && a.joints == b.joints &&
         a.j3_stalled == b.j3_stalled && a.falling == b.falling &&
         a.fixed_platform_position == b.fixed_platform_position &&
         a.moving_platform_position == b.moving_platform_position &&
         a.fixed_platform_disc == b.fixed_platform_disc &&
         a.moving_platform_disc == b.moving_platform_disc &&
         a.battery_voltage == b.battery_voltage && a.battery_charge == b.battery_charge &&
         a.battery_current == b.battery_current && a.battery_low == b.battery_low &&
         a.link_up == b.link_up;
}

// ---- motion profiles ----

double RobotSimulator::Profile::endTime() const {
  double t = start_time;
  for (int i = 0; i < segment_count; ++i) t += segments[i].duration;
  return t;
}

void RobotSimulator::Profile::evaluate(double t, double& position, double& velocity) const {
  const double end = endTime();
  if (t >= end) {
    position = end_position + end_velocity * (t - end);
    velocity = end_velocity;
    return;
  }
  double tau = std::max(0.0, t - start_time);
  double p = start_position, v = start_velocity;
  for (int i = 0; i < segment_count; ++i) {
    const Segment& s = segments[i];
    if (tau <= s.duration) {
      position = p + v * tau + 0.5 * s.acceleration * tau * tau;
      velocity = v + s.acceleration * tau;
      return;
    }
    p += v * s.duration + 0.5 * s.acceleration * s.duration * s.duration;
    v += s.acceleration * s.duration;
    tau -= s.duration;
  }
  position = end_position;  // only reached through rounding at the very end
  velocity = end_velocity;
}

RobotSimulator::Profile RobotSimulator::planMove(double t0, double p0, double v0, double target,
                                                 double max_speed, double max_acceleration) {
  Profile profile;
  profile.start_time = t0;
  profile.start_position = p0;
  profile.start_velocity = v0;
  profile.end_position = target;
  profile.end_velocity = 0.0;
  const double a = max_acceleration;
  auto add = [&profile](double duration, double acceleration) {
    if (duration > 0.0) profile.segments[profile.segment_count++] = {duration, acceleration};
  };
  double p = p0, v = v0;
  double d = target - p;
  const double braking = v * std::abs(v) / (2.0 * a);  // signed distance to stop [unit]
  if (v != 0.0 && (v * d < 0.0 || std::abs(braking) > std::abs(d))) {
    // Moving away from the target or unable to stop before it: brake to rest first.
    add(std::abs(v) / a, v > 0.0 ? -a : a);
    p += braking;
    v = 0.0;
    d = target - p;
  }
  if (d == 0.0) return profile;
  const double sign = d > 0.0 ? 1.0 : -1.0;
  const double u = std::abs(d);  // distance to go [unit]
  const double w0 = sign * v;    // speed towards the target, >= 0 [unit/s]
  // Peak speed: change from w0 to vp and brake from vp to 0 within u (the triangle's peak
  // sqrt(a u + w0^2 / 2) >= w0 since w0^2 / (2 a) <= u); below w0 only for a lower cruise speed.
  const double vp = std::min(max_speed, std::sqrt(a * u + 0.5 * w0 * w0));
  const double d1 = std::abs(vp * vp - w0 * w0) / (2.0 * a);
  const double d3 = vp * vp / (2.0 * a);
  const double cruise = std::max(0.0, u - d1 - d3);
  add(std::abs(vp - w0) / a, vp >= w0 ? sign * a : -sign * a);
  add(vp > 0.0 ? cruise / vp : 0.0, 0.0);
  add(vp / a, -sign * a);
  return profile;
}

RobotSimulator::Profile RobotSimulator::planRamp(double t0, double p0, double v0, double v_target,
                                                 double max_acceleration) {
  Profile profile;
  profile.start_time = t0;
  profile.start_position = p0;
  profile.start_velocity = v0;
  profile.end_velocity = v_target;
  const double dv = v_target - v0;
  const double duration = std::abs(dv) / max_acceleration;
  const double acceleration = dv > 0.0 ? max_acceleration : -max_acceleration;
  if (duration > 0.0) profile.segments[profile.segment_count++] = {duration, acceleration};
  profile.end_position = p0 + v0 * duration + 0.5 * acceleration * duration * duration;
  return profile;
}

// ---- the simulator ----

RobotSimulator::RobotSimulator(const RobotSimulatorConfig& config) : config_(config) {
  validateSimulatorConfig(config_);
  const SimStringConfig& s = config_.string;
  fixed_position_ = s.initial_disc * s.pitch;
  moving_position_ = fixed_position_ + s.home_gap;
  for (int c = 0; c < 2; ++c) {
    clamps_[c].contact = true;
    clamps_[c].angle = clampConfig(c).contact_angle;
    snapshot_.joints[c].position = clamps_[c].angle;
  }
  charge_ = config_.battery.initial_charge * config_.battery.capacity * kSecondsPerHour;
  snapshot_.battery_current = 0.0;
  snapshot_.link_up = true;
  refreshSensors();
}

const SimClampConfig& RobotSimulator::clampConfig(int clamp) const {
  return clamp == 0 ? config_.fixed_clamp : config_.moving_clamp;
}

const SimAxisConfig& RobotSimulator::axisConfig(int axis) const {
  return axis == 0 ? config_.j3 : (axis == 1 ? config_.j4 : config_.j5);
}

std::optional<int> RobotSimulator::discAt(double position) const {
  const SimStringConfig& s = config_.string;
  if (!std::isfinite(position)) return std::nullopt;
  const double i = std::round(position / s.pitch);
  if (i < 0.0 || i > s.disc_count) return std::nullopt;
  if (std::abs(position - i * s.pitch) > s.tolerance) return std::nullopt;
  return static_cast<int>(i);
}

std::optional<std::string> RobotSimulator::refuse(const SimCommand& command) const {
  if (!validJoint(command.joint)) {
    return "unknown joint " + std::to_string(static_cast<int>(command.joint));
  }
  const char* joint = simJointName(command.joint);
  const std::string kind = commandKindName(command.kind);
  switch (command.kind) {
    case SimCommandKind::kClose:
    case SimCommandKind::kRelease:
      if (!isClamp(command.joint)) return kind + " is not a command of " + joint;
      return std::nullopt;
    case SimCommandKind::kStop:
      return std::nullopt;
    case SimCommandKind::kMoveTo: {
      if (!isAxis(command.joint)) return kind + " is not a command of " + joint;
      const char* unit = unitOf(command.joint);
      if (!std::isfinite(command.value)) {
        return std::string(joint) + " move_to target " + formatNumber(command.value) + " " + unit +
               " is not finite";
      }
      const SimAxisConfig& a = axisConfig(static_cast<int>(simJointIndex(command.joint)) - 2);
      if (command.value < a.min_position || command.value > a.max_position) {
        return std::string(joint) + " move_to target " + formatNumber(command.value) + " " + unit +
               " is outside the limits [" + formatNumber(a.min_position) + ", " +
               formatNumber(a.max_position) + "] " + unit;
      }
      if (!(command.speed >= 0.0 && command.speed <= a.max_speed)) {
        return std::string(joint) + " move_to speed " + formatNumber(command.speed) + " " + unit +
               "/s is outside [0, max_speed = " + formatNumber(a.max_speed) + "] " + unit + "/s";
      }
      return std::nullopt;
    }
    case SimCommandKind::kSpin:
      if (command.joint != SimJoint::kJ6) return kind + " is not a command of " + joint;
      if (!std::isfinite(command.value)) {
        return "J6 spin speed " + formatNumber(command.value) + " rpm is not finite";
      }
      if (std::abs(command.value) > config_.j6.max_speed) {
        return "J6 spin speed " + formatNumber(command.value) + " rpm is above the limit " +
               formatNumber(config_.j6.max_speed) + " rpm";
      }
      return std::nullopt;
  }
  return "unknown command kind " + std::to_string(static_cast<int>(command.kind));
}

void RobotSimulator::command(const SimCommand& command) {
  if (const auto reason = refuse(command)) throw Error("simulator command refused: " + *reason);
  const double now = time();
  const std::size_t j = simJointIndex(command.joint);
  SimJointState& state = snapshot_.joints[j];
  if (isClamp(command.joint)) {
    ClampState& clamp = clamps_[j];
    switch (command.kind) {
      case SimCommandKind::kClose:
        clamp.mode = JawMode::kClosing;
        if (clamp.contact) {  // pressing again: the rise restarts from the present current
          clamp.contact_time = now;
          clamp.contact_current = state.current;
        } else {
          clamp.start_time = now;
          clamp.start_angle = clamp.angle;
        }
        break;
      case SimCommandKind::kRelease:
        clamp.mode = JawMode::kReleasing;
        clamp.start_time = now;
        clamp.start_angle = clamp.angle;
        break;
      default:  // kStop: the jaw holds where it is (self-locking), the motor is off
        clamp.mode = JawMode::kIdle;
        break;
    }
    return;
  }
  if (isAxis(command.joint)) {
    const int axis_index = static_cast<int>(j) - 2;
    AxisState& axis = axes_[axis_index];
    const SimAxisConfig& a = axisConfig(axis_index);
    axis.replan = false;
    if (command.kind == SimCommandKind::kMoveTo) {
      axis.target = command.value;
      axis.speed = command.speed > 0.0 ? command.speed : a.max_speed;
      axis.profile = planMove(now, state.position, state.velocity, command.value, axis.speed,
                              a.max_acceleration);
    } else {  // kStop: brake to rest
      axis.profile = planRamp(now, state.position, state.velocity, 0.0, a.max_acceleration);
      axis.target = axis.profile.end_position;
    }
    return;
  }
  // J6: speed ramps in [deg/s] and [deg/s^2]; the brush angle is its integral.
  const double rpm = command.kind == SimCommandKind::kSpin ? command.value : 0.0;
  brush_ = planRamp(now, state.position, state.velocity * kDegPerSecondPerRpm,
                    rpm * kDegPerSecondPerRpm, config_.j6.max_acceleration * kDegPerSecondPerRpm);
}

void RobotSimulator::stepClamp(int c, double t0, double t1) {
  ClampState& s = clamps_[c];
  const SimClampConfig& cfg = clampConfig(c);
  SimJointState& j = snapshot_.joints[c];
  const double platform = c == 0 ? fixed_position_ : moving_position_;
  const bool at_disc = !falling_ && discAt(platform).has_value();
  auto contactCurrent = [&](double t) {
    return cfg.stall_current + (s.contact_current - cfg.stall_current) *
                                   std::exp(-(t - s.contact_time) / cfg.time_constant);
  };
  auto travel = [&](double angle, double velocity) {
    s.angle = angle;
    j.velocity = velocity;
    j.current = cfg.running_current;
    j.moving = true;
  };
  auto rest = [&](double angle, double current) {
    s.angle = angle;
    j.velocity = 0.0;
    j.current = current;
    j.moving = false;
  };

  switch (s.mode) {
    case JawMode::kIdle:
      rest(s.angle, 0.0);
      break;
    case JawMode::kReleasing: {
      s.contact = false;
      const double t_zero = s.start_time + s.start_angle / cfg.jaw_speed;
      if (t_zero <= t1) {
        rest(0.0, 0.0);
        s.mode = JawMode::kIdle;
      } else {
        travel(s.start_angle - cfg.jaw_speed * (t1 - s.start_time), -cfg.jaw_speed);
      }
      break;
    }
    case JawMode::kClosing:
      if (s.contact) {
        rest(s.angle, contactCurrent(t1));
      } else if (at_disc && s.angle <= cfg.contact_angle) {
        const double t_contact =
            std::max(t0, s.start_time + (cfg.contact_angle - s.start_angle) / cfg.jaw_speed);
        if (t_contact <= t1) {
          s.contact = true;
          s.contact_time = t_contact;
          s.contact_current = cfg.running_current;
          rest(cfg.contact_angle, contactCurrent(t1));
        } else {
          travel(s.start_angle + cfg.jaw_speed * (t1 - s.start_time), cfg.jaw_speed);
        }
      } else {
        const double t_end = s.start_time + (cfg.end_stop_angle - s.start_angle) / cfg.jaw_speed;
        if (t_end <= t1) {  // the end-stop limit cuts the motor
          rest(cfg.end_stop_angle, 0.0);
          s.mode = JawMode::kIdle;
        } else {
          travel(s.start_angle + cfg.jaw_speed * (t1 - s.start_time), cfg.jaw_speed);
        }
      }
      break;
  }
  j.position = s.angle;
}

const SimSnapshot& RobotSimulator::step() {
  const double dt = config_.dt;
  const double t0 = static_cast<double>(steps_) * dt;
  const double t1 = static_cast<double>(steps_ + 1) * dt;

  // Clamps first: whether each grips decides what J3 moves over this step.
  stepClamp(0, t0, t1);
  stepClamp(1, t0, t1);
  const bool fixed_grips = clamps_[0].contact;
  const bool moving_grips = clamps_[1].contact;
  if (!fixed_grips && !moving_grips) falling_ = true;

  // J3, J4, J5.
  for (int i = 0; i < 3; ++i) {
    AxisState& axis = axes_[i];
    const SimAxisConfig& a = axisConfig(i);
    SimJointState& j = snapshot_.joints[2 + i];
    const bool pending = axis.replan || t0 < axis.profile.endTime();
    if (i == 0 && pending && !falling_ && fixed_grips && moving_grips) {
      // Both clamps hold the string: J3 pushes against it and stalls.
      j3_stalled_ = true;
      axis.replan = true;
      j.velocity = 0.0;
      j.current = config_.j3_stall_current;
      j.moving = true;
      continue;
    }
    if (i == 0) j3_stalled_ = false;
    if (axis.replan) {
      const double speed = axis.speed > 0.0 ? axis.speed : a.max_speed;
      axis.profile = planMove(t0, j.position, 0.0, axis.target, speed, a.max_acceleration);
      axis.replan = false;
    }
    double position = 0.0, velocity = 0.0;
    axis.profile.evaluate(t1, position, velocity);
    j.position = position;
    j.velocity = velocity;
    j.moving = t1 < axis.profile.endTime();
    j.current = j.moving ? a.running_current : 0.0;
    if (i == 0 && !falling_) {
      // The gripping platform stays put; the other one is carried by J3.
      const double gap = config_.string.home_gap;
      if (fixed_grips && !moving_grips) moving_position_ = fixed_position_ + gap - position;
      if (moving_grips && !fixed_grips) fixed_position_ = moving_position_ - gap + position;
    }
  }

  // J6.
  {
    SimJointState& j = snapshot_.joints[5];
    double angle = 0.0, velocity = 0.0;  // [deg], [deg/s]
    brush_.evaluate(t1, angle, velocity);
    j.position = angle;
    j.velocity = velocity / kDegPerSecondPerRpm;
    j.moving = t1 < brush_.endTime();
    j.current = (j.moving || velocity != 0.0) ? config_.j6.running_current : 0.0;
  }

  // Battery: the step's end currents over dt.
  double current =
      config_.battery.idle_current + faults_[static_cast<int>(SimFault::kBatteryDrain)];
  for (const SimJointState& j : snapshot_.joints) current += j.current;
  charge_ = std::max(0.0, charge_ - current * dt);
  snapshot_.battery_current = current;

  ++steps_;
  snapshot_.step = steps_;
  snapshot_.time = t1;
  refreshSensors();
  return snapshot_;
}

void RobotSimulator::refreshSensors() {
  SimSnapshot& s = snapshot_;
  for (int c = 0; c < 2; ++c) {
    SimJointState& j = s.joints[c];
    const int never = static_cast<int>(c == 0 ? SimFault::kFixedZeroSwitchNeverPressed
                                              : SimFault::kMovingZeroSwitchNeverPressed);
    const int always = never + 1;
    j.zero_switch = clamps_[c].angle <= 0.0;
    if (faults_[never] > 0.0) j.zero_switch = false;
    if (faults_[always] > 0.0) j.zero_switch = true;
    j.gripping = clamps_[c].contact;
    j.encoder = std::llround(j.position * clampConfig(c).counts_per_deg);
  }
  for (int i = 0; i < 3; ++i) {
    SimJointState& j = s.joints[2 + i];
    j.encoder = std::llround(j.position * axisConfig(i).counts_per_unit);
  }
  s.joints[5].encoder = std::llround(s.joints[5].position / 360.0 * config_.j6.counts_per_rev);

  s.j3_stalled = j3_stalled_;
  s.falling = falling_;
  s.fixed_platform_position = fixed_position_;
  s.moving_platform_position = moving_position_;
  s.fixed_platform_disc = falling_ ? std::nullopt : discAt(fixed_position_);
  s.moving_platform_disc = falling_ ? std::nullopt : discAt(moving_position_);

  const SimBatteryConfig& b = config_.battery;
  s.battery_charge = charge_ / kSecondsPerHour;
  s.battery_voltage = b.empty_voltage +
                      (b.full_voltage - b.empty_voltage) * charge_ / (b.capacity * kSecondsPerHour);
  s.battery_low = s.battery_voltage < b.low_voltage;
}

void RobotSimulator::setLinkUp(bool up) { snapshot_.link_up = up; }

void RobotSimulator::setFault(SimFault fault, double value) {
  const auto i = static_cast<std::size_t>(fault);
  if (i >= kFaultCount) throw Error("unknown fault " + std::to_string(i));
  if (!(value >= 0.0) || !std::isfinite(value)) {
    throw Error(std::string("fault ") + faultName(fault) + " value " + formatNumber(value) +
                ", must be >= 0");
  }
  if (fault == SimFault::kBatteryDrain) {
    faults_[i] = value;
  } else {
    faults_[i] = value > 0.0 ? 1.0 : 0.0;
    // never/always pressed on one switch exclude each other: pairs (0, 1) and (2, 3).
    if (value > 0.0) faults_[i ^ 1u] = 0.0;
  }
  refreshSensors();
}

double RobotSimulator::fault(SimFault fault) const {
  const auto i = static_cast<std::size_t>(fault);
  return i < kFaultCount ? faults_[i] : 0.0;
}

}  // namespace mcws
