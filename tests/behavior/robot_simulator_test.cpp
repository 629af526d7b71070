// Wang et al. 2018: the time-stepped simulator of the insulator-cleaning robot (clamps, J3..J6,
// string, battery, faults). Expected values are closed forms of the documented model or
// hand-worked.
#include "mcws/behavior/robot_simulator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mcws/core/error.h"

namespace mcws {
namespace {

constexpr double kExact = 1e-9;  // closed forms evaluated the same way up to rounding
using J = SimJoint;

/// Steps until `done` holds (checked after each step) or `timeout` [s] passes; true if it held.
/// `every_step` sees every snapshot (the place for invariants).
bool runUntil(RobotSimulator& sim, const std::function<bool(const SimSnapshot&)>& done,
              double timeout, const std::function<void(const SimSnapshot&)>& every_step = {}) {
  const double end = sim.time() + timeout;
  while (sim.time() < end) {
    const SimSnapshot& s = sim.step();
    if (every_step) every_step(s);
    if (done(s)) return true;
  }
  return false;
}

/// The paper's "current at the set value for the set time": true once `clamp`'s current has been at
/// least `current` [A] for `hold` [s].
std::function<bool(const SimSnapshot&)> currentHeld(J clamp, double current, double hold) {
  auto since = std::make_shared<double>(-1.0);
  return [=](const SimSnapshot& s) {
    if (s.joint(clamp).current < current) {
      *since = -1.0;
      return false;
    }
    if (*since < 0.0) *since = s.time;
    return s.time - *since >= hold - kExact;
  };
}

TEST(RobotSimulator, StartsGrippingAtTheTowerEndFitting) {
  const RobotSimulator sim;
  const SimSnapshot& s = sim.snapshot();
  EXPECT_EQ(s.time, 0.0);
  EXPECT_EQ(s.step, 0u);
  EXPECT_TRUE(s.joint(kFixedClamp).gripping);
  EXPECT_TRUE(s.joint(kMovingClamp).gripping);
  EXPECT_FALSE(s.joint(kFixedClamp).zero_switch);
  EXPECT_EQ(s.joint(kFixedClamp).position, 25.0);  // contact angle
  EXPECT_EQ(s.fixed_platform_position, 0.0);
  EXPECT_EQ(s.moving_platform_position, 310.0);  // home_gap below, as the robot file
  EXPECT_EQ(s.fixed_platform_disc, 0);
  EXPECT_EQ(s.moving_platform_disc, 2);
  for (J j : {J::kJ3, J::kJ4, J::kJ5, J::kJ6}) {
    EXPECT_EQ(s.joint(j).position, 0.0) << simJointName(j);
    EXPECT_EQ(s.joint(j).encoder, 0) << simJointName(j);
  }
  EXPECT_FALSE(s.falling);
  EXPECT_FALSE(s.j3_stalled);
  EXPECT_EQ(s.battery_voltage, 25.2);
  EXPECT_FALSE(s.battery_low);
  EXPECT_TRUE(s.link_up);
}

TEST(Clamp, ReleaseReachesTheZeroSwitchAfterAngleOverSpeed) {
  RobotSimulator sim;
  const SimClampConfig& c = sim.config().fixed_clamp;
  sim.command(SimCommand::release(kFixedClamp));
  const double expected = c.contact_angle / c.jaw_speed;  // 25 deg / 10 deg/s = 2.5 s
  int checked = 0;
  ASSERT_TRUE(runUntil(
      sim,
      [&checked](const SimSnapshot& s) {
        if (s.step == 100) {  // t = 1 s, hand-worked: 25 - 10 * 1 = 15 deg, moving
          ++checked;
          EXPECT_NEAR(s.joint(kFixedClamp).position, 15.0, kExact);
          EXPECT_EQ(s.joint(kFixedClamp).velocity, -10.0);
          EXPECT_EQ(s.joint(kFixedClamp).current, 0.4);
        }
        return s.joint(kFixedClamp).zero_switch;
      },
      10.0));
  EXPECT_EQ(checked, 1);
  EXPECT_GE(sim.time(), expected - kExact);
  EXPECT_LT(sim.time(), expected + sim.config().dt);
  EXPECT_EQ(sim.snapshot().joint(kFixedClamp).position, 0.0);
  EXPECT_EQ(sim.snapshot().joint(kFixedClamp).current, 0.0);
  EXPECT_FALSE(sim.snapshot().joint(kFixedClamp).gripping);
  EXPECT_TRUE(sim.snapshot().joint(kMovingClamp).gripping);
  EXPECT_FALSE(sim.snapshot().falling);
}

TEST(Clamp, CloseOnADiscRaisesTheCurrentAsTheFirstOrderClosedForm) {
  RobotSimulator sim;
  const SimClampConfig& c = sim.config().fixed_clamp;
  sim.command(SimCommand::release(kFixedClamp));
  ASSERT_TRUE(runUntil(
      sim, [](const SimSnapshot& s) { return s.joint(kFixedClamp).zero_switch; }, 10.0));
  const double t_command = sim.time();
  sim.command(SimCommand::close(kFixedClamp));
  const double t_contact = t_command + c.contact_angle / c.jaw_speed;  // + 2.5 s
  const double hold = 2.0;  // [A], the behaviour's set current
  const double t_hold =
      t_contact + c.time_constant * std::log((c.stall_current - c.running_current) /
                                             (c.stall_current - hold));  // + 0.215 s
  double first_at_hold = -1.0;
  int checked = 0;
  runUntil(
      sim, [](const SimSnapshot&) { return false; }, 4.0,
      [&](const SimSnapshot& s) {
        const SimJointState& jaw = s.joint(kFixedClamp);
        if (s.time < t_contact - kExact) {
          EXPECT_EQ(jaw.current, c.running_current) << s.time;
          EXPECT_FALSE(jaw.gripping) << s.time;
        } else if (s.time > t_contact + kExact) {
          const double expected =
              c.stall_current + (c.running_current - c.stall_current) *
                                    std::exp(-(s.time - t_contact) / c.time_constant);
          EXPECT_NEAR(jaw.current, expected, kExact) << s.time;
          EXPECT_TRUE(jaw.gripping) << s.time;
          EXPECT_EQ(jaw.position, c.contact_angle);
          ++checked;
        }
        if (first_at_hold < 0.0 && jaw.current >= hold) first_at_hold = s.time;
      });
  EXPECT_GT(checked, 100);
  EXPECT_GE(first_at_hold, t_hold - kExact);
  EXPECT_LT(first_at_hold, t_hold + sim.config().dt);
}

TEST(Clamp, CloseOffADiscNeverRaisesTheCurrent) {
  RobotSimulator sim;
  // The body goes 50 mm down the string, between two grip positions (155 mm apart).
  sim.command(SimCommand::release(kFixedClamp));
  ASSERT_TRUE(runUntil(
      sim, [](const SimSnapshot& s) { return s.joint(kFixedClamp).zero_switch; }, 10.0));
  sim.command(SimCommand::moveTo(J::kJ3, 50.0));
  ASSERT_TRUE(runUntil(
      sim, [](const SimSnapshot& s) { return !s.joint(J::kJ3).moving; }, 10.0));
  EXPECT_EQ(sim.snapshot().fixed_platform_position, 50.0);
  EXPECT_FALSE(sim.snapshot().fixed_platform_disc.has_value());

  const double t_command = sim.time();
  sim.command(SimCommand::close(kFixedClamp));
  double max_current = 0.0;
  runUntil(
      sim, [](const SimSnapshot&) { return false; }, 10.0,
      [&](const SimSnapshot& s) {
        max_current = std::max(max_current, s.joint(kFixedClamp).current);
        EXPECT_FALSE(s.joint(kFixedClamp).gripping) << s.time;
      });
  const SimClampConfig& c = sim.config().fixed_clamp;
  EXPECT_EQ(max_current, c.running_current);
  EXPECT_EQ(sim.snapshot().joint(kFixedClamp).position, c.end_stop_angle);
  EXPECT_EQ(sim.snapshot().joint(kFixedClamp).current, 0.0);  // end stop: motor cut
  EXPECT_GT(sim.time() - t_command, c.end_stop_angle / c.jaw_speed);
}

/// The CB1 of Wang et al. 2018, section 3.2 (with the corrected last step: the moving clamp
/// closes), driven by hand with the behaviours' ending conditions. Returns false if a step timed
/// out.
bool runCb1(RobotSimulator& sim, std::int64_t* max_j3_count) {
  const auto invariant = [&](const SimSnapshot& s) {
    EXPECT_FALSE(s.falling) << s.time;
    EXPECT_TRUE(s.joint(kFixedClamp).gripping || s.joint(kMovingClamp).gripping) << s.time;
    *max_j3_count = std::max(*max_j3_count, s.joint(J::kJ3).encoder);
    // The platforms stay home_gap - J3 apart, whichever of them J3 carries.
    EXPECT_NEAR(s.moving_platform_position - s.fixed_platform_position,
                sim.config().string.home_gap - s.joint(J::kJ3).position, kExact)
        << s.time;
  };
  const std::int64_t pitch_counts = std::llround(155.0 * sim.config().j3.counts_per_unit);
  const auto zero = [](J clamp) {
    return [clamp](const SimSnapshot& s) { return s.joint(clamp).zero_switch; };
  };
  // q1 -> q2: fixed clamp releases until its zero switch.
  sim.command(SimCommand::release(kFixedClamp));
  if (!runUntil(sim, zero(kFixedClamp), 10.0, invariant)) return false;
  // q2 -> q3: moving platform to the set position until the count is reached.
  sim.command(SimCommand::moveTo(J::kJ3, 155.0));
  if (!runUntil(
          sim, [&](const SimSnapshot& s) { return s.joint(J::kJ3).encoder >= pitch_counts; }, 20.0,
          invariant)) {
    return false;
  }
  // q3 -> q4: fixed clamp closes until the current is held.
  sim.command(SimCommand::close(kFixedClamp));
  if (!runUntil(sim, currentHeld(kFixedClamp, 2.0, 0.5), 10.0, invariant)) return false;
  // q4 -> q5: moving clamp releases.
  sim.command(SimCommand::release(kMovingClamp));
  if (!runUntil(sim, zero(kMovingClamp), 10.0, invariant)) return false;
  // q5 -> q6: moving platform home until the count is zero.
  sim.command(SimCommand::moveTo(J::kJ3, 0.0));
  if (!runUntil(
          sim, [](const SimSnapshot& s) { return s.joint(J::kJ3).encoder == 0; }, 20.0,
          invariant)) {
    return false;
  }
  // q6 -> q1: moving clamp closes until the current is held.
  sim.command(SimCommand::close(kMovingClamp));
  return runUntil(sim, currentHeld(kMovingClamp, 2.0, 0.5), 10.0, invariant);
}

TEST(RobotSimulator, Cb1ByHandMovesTheRobotOnePitchDownTheString) {
  RobotSimulator sim;
  std::int64_t max_j3_count = 0;
  ASSERT_TRUE(runCb1(sim, &max_j3_count));
  const SimSnapshot& s = sim.snapshot();
  EXPECT_EQ(max_j3_count, 15500);  // 155 mm * 100 counts/mm, and no further
  EXPECT_EQ(s.joint(J::kJ3).encoder, 0);
  EXPECT_EQ(s.joint(J::kJ3).position, 0.0);
  EXPECT_EQ(s.fixed_platform_position, 155.0);   // exactly one pitch towards the conductor
  EXPECT_EQ(s.moving_platform_position, 465.0);  // the next disc
  EXPECT_EQ(s.fixed_platform_disc, 1);
  EXPECT_EQ(s.moving_platform_disc, 3);
  EXPECT_TRUE(s.joint(kFixedClamp).gripping);
  EXPECT_TRUE(s.joint(kMovingClamp).gripping);

  ASSERT_TRUE(runCb1(sim, &max_j3_count));  // and again: disc 2
  EXPECT_EQ(sim.snapshot().fixed_platform_position, 310.0);
  EXPECT_EQ(sim.snapshot().moving_platform_position, 620.0);
  EXPECT_EQ(sim.snapshot().moving_platform_disc, 4);
}

TEST(RobotSimulator, J3StallsWhileBothClampsGrip) {
  RobotSimulator sim;
  sim.command(SimCommand::moveTo(J::kJ3, 100.0));
  runUntil(
      sim, [](const SimSnapshot&) { return false; }, 1.0,
      [](const SimSnapshot& s) {
        EXPECT_TRUE(s.j3_stalled) << s.time;
        EXPECT_TRUE(s.joint(J::kJ3).moving);
        EXPECT_EQ(s.joint(J::kJ3).position, 0.0);
        EXPECT_EQ(s.joint(J::kJ3).encoder, 0);
        EXPECT_EQ(s.joint(J::kJ3).current, 3.0);  // j3_stall_current
        EXPECT_EQ(s.fixed_platform_position, 0.0);
      });
  // Releasing the fixed clamp frees J3, which then carries the body down.
  sim.command(SimCommand::release(kFixedClamp));
  sim.step();
  EXPECT_FALSE(sim.snapshot().j3_stalled);
  ASSERT_TRUE(runUntil(
      sim, [](const SimSnapshot& s) { return !s.joint(J::kJ3).moving; }, 20.0));
  EXPECT_EQ(sim.snapshot().joint(J::kJ3).position, 100.0);
  EXPECT_EQ(sim.snapshot().fixed_platform_position, 100.0);
  EXPECT_EQ(sim.snapshot().moving_platform_position, 310.0);
}

TEST(RobotSimulator, ReleasingBothClampsSetsTheFallingFlag) {
  RobotSimulator sim;
  sim.command(SimCommand::release(kFixedClamp));
  sim.step();
  EXPECT_FALSE(sim.snapshot().falling);  // the moving clamp still holds
  sim.command(SimCommand::release(kMovingClamp));
  sim.step();
  EXPECT_TRUE(sim.snapshot().falling);
  EXPECT_FALSE(sim.snapshot().fixed_platform_disc.has_value());
  // Latched: closing again does not put the robot back on the string.
  sim.command(SimCommand::close(kFixedClamp));
  sim.command(SimCommand::close(kMovingClamp));
  runUntil(
      sim, [](const SimSnapshot&) { return false; }, 6.0);
  EXPECT_TRUE(sim.snapshot().falling);
  EXPECT_FALSE(sim.snapshot().joint(kFixedClamp).gripping);
}

/// dV/dt [V/s] for a steady battery current [A] under the default battery.
double voltageRate(const SimBatteryConfig& b, double current) {
  return (b.full_voltage - b.empty_voltage) * current / (b.capacity * 3600.0);
}

TEST(Battery, VoltageFallsByTheClosedFormAmount) {
  const SimBatteryConfig b;
  const double seconds = 10.0;
  {  // idle: only the electronics draw
    RobotSimulator sim;
    const double v0 = sim.snapshot().battery_voltage;
    runUntil(
        sim, [](const SimSnapshot&) { return false; }, seconds);
    EXPECT_NEAR(v0 - sim.snapshot().battery_voltage, voltageRate(b, b.idle_current) * seconds,
                kExact);
    EXPECT_EQ(sim.snapshot().battery_current, b.idle_current);
  }
  {  // the brush turning at a steady speed adds its running current
    RobotSimulator sim;
    sim.command(SimCommand::spin(300.0));
    runUntil(
        sim, [](const SimSnapshot&) { return false; }, 2.0);
    const double v0 = sim.snapshot().battery_voltage;
    runUntil(
        sim, [](const SimSnapshot&) { return false; }, seconds);
    const double current = b.idle_current + sim.config().j6.running_current;  // 1.5 A
    EXPECT_NEAR(v0 - sim.snapshot().battery_voltage, voltageRate(b, current) * seconds, kExact);
  }
  {  // an extra drain adds linearly
    for (double drain : {1.0, 2.0}) {
      RobotSimulator sim;
      sim.setFault(SimFault::kBatteryDrain, drain);
      const double v0 = sim.snapshot().battery_voltage;
      runUntil(
          sim, [](const SimSnapshot&) { return false; }, seconds);
      EXPECT_NEAR(v0 - sim.snapshot().battery_voltage,
                  voltageRate(b, b.idle_current + drain) * seconds, kExact)
          << drain;
    }
  }
}

TEST(Battery, LowFlagComesBelowTheThresholdAtTheClosedFormTime) {
  RobotSimulatorConfig config;
  const SimBatteryConfig& b = config.battery;
  const double v_start = 22.3;  // [V], 0.1 V above low_voltage
  config.battery.initial_charge = (v_start - b.empty_voltage) / (b.full_voltage - b.empty_voltage);
  RobotSimulator sim(config);
  EXPECT_NEAR(sim.snapshot().battery_voltage, v_start, kExact);
  EXPECT_FALSE(sim.snapshot().battery_low);
  const double drain = 10.0;  // [A]
  sim.setFault(SimFault::kBatteryDrain, drain);
  const double t_low = (v_start - b.low_voltage) / voltageRate(b, b.idle_current + drain);
  ASSERT_TRUE(runUntil(
      sim, [](const SimSnapshot& s) { return s.battery_low; }, 100.0));
  EXPECT_GE(sim.time(), t_low - kExact);
  EXPECT_LT(sim.time(), t_low + config.dt);
}

TEST(Axis, J5FullTurnAtItsSpeedLimitTakesTheClosedFormTime) {
  RobotSimulator sim;
  const SimAxisConfig& a = sim.config().j5;  // 30 deg/s, 60 deg/s^2
  sim.command(SimCommand::moveTo(J::kJ5, 360.0));
  const double duration = 360.0 / a.max_speed + a.max_speed / a.max_acceleration;  // 12.5 s
  int checked = 0;
  ASSERT_TRUE(runUntil(
      sim,
      [&](const SimSnapshot& s) {
        if (s.step == 600) {  // t = 6 s: cruising
          ++checked;
          EXPECT_NEAR(s.joint(J::kJ5).velocity, a.max_speed, kExact);
        }
        return !s.joint(J::kJ5).moving;
      },
      20.0));
  EXPECT_EQ(checked, 1);
  EXPECT_GE(sim.time(), duration - kExact);
  EXPECT_LT(sim.time(), duration + sim.config().dt);
  EXPECT_EQ(sim.snapshot().joint(J::kJ5).position, 360.0);
  EXPECT_EQ(sim.snapshot().joint(J::kJ5).velocity, 0.0);
  EXPECT_EQ(sim.snapshot().joint(J::kJ5).encoder, 18000);  // 360 deg * 50 counts/deg
}

TEST(Axis, ShortMoveIsTriangular) {
  RobotSimulator sim;
  const SimAxisConfig& a = sim.config().j4;  // 20 mm/s, 40 mm/s^2: v^2/a = 10 mm > 5 mm
  sim.command(SimCommand::moveTo(J::kJ4, 5.0));
  const double duration = 2.0 * std::sqrt(5.0 / a.max_acceleration);  // 0.707 s
  double peak = 0.0;
  ASSERT_TRUE(runUntil(
      sim,
      [&](const SimSnapshot& s) {
        peak = std::max(peak, s.joint(J::kJ4).velocity);
        return !s.joint(J::kJ4).moving;
      },
      5.0));
  EXPECT_GE(sim.time(), duration - kExact);
  EXPECT_LT(sim.time(), duration + sim.config().dt);
  EXPECT_LE(peak, std::sqrt(5.0 * a.max_acceleration) + kExact);  // sqrt(d a) = 14.1 mm/s
  EXPECT_EQ(sim.snapshot().joint(J::kJ4).position, 5.0);
}

TEST(Axis, MovesAtTheCommandedSpeedAndSlowsDownToANewOne) {
  RobotSimulator sim;
  const SimAxisConfig& a = sim.config().j4;  // 20 mm/s, 40 mm/s^2
  sim.command(SimCommand::moveTo(J::kJ4, 100.0, 10.0));
  const double duration = 100.0 / 10.0 + 10.0 / a.max_acceleration;  // 10.25 s
  double peak = 0.0;
  ASSERT_TRUE(runUntil(
      sim,
      [&](const SimSnapshot& s) {
        peak = std::max(peak, s.joint(J::kJ4).velocity);
        return !s.joint(J::kJ4).moving;
      },
      20.0));
  EXPECT_NEAR(peak, 10.0, kExact);
  EXPECT_GE(sim.time(), duration - kExact);
  EXPECT_LT(sim.time(), duration + sim.config().dt);
  EXPECT_EQ(sim.snapshot().joint(J::kJ4).position, 100.0);

  // Back to 0 at full speed; at 2 s (cruising at 20 mm/s, 35 mm travelled) slow to 5 mm/s:
  // 0.375 s of braking at 40 mm/s^2, then cruise at 5 mm/s.
  sim.command(SimCommand::moveTo(J::kJ4, 0.0));
  const std::uint64_t from = sim.snapshot().step;
  runUntil(
      sim, [&](const SimSnapshot& s) { return s.step == from + 200; }, 5.0);
  ASSERT_NEAR(sim.snapshot().joint(J::kJ4).velocity, -20.0, kExact);
  ASSERT_NEAR(sim.snapshot().joint(J::kJ4).position, 65.0, kExact);
  sim.command(SimCommand::moveTo(J::kJ4, 0.0, 5.0));
  runUntil(
      sim, [&](const SimSnapshot& s) { return s.step == from + 300; }, 5.0);
  EXPECT_NEAR(sim.snapshot().joint(J::kJ4).velocity, -5.0, kExact);
  // Remaining after the slow-down: 65 - (20^2 - 5^2) / 80 = 60.3125 mm, less 5^2 / 80 to brake.
  const double end = 2.0 + 0.375 + (60.3125 - 0.3125) / 5.0 + 5.0 / a.max_acceleration;
  ASSERT_TRUE(runUntil(
      sim, [](const SimSnapshot& s) { return !s.joint(J::kJ4).moving; }, 20.0));
  EXPECT_NEAR(sim.time() - from * sim.config().dt, end, sim.config().dt);
  EXPECT_EQ(sim.snapshot().joint(J::kJ4).position, 0.0);
}

TEST(Axis, NewTargetWithinTheBrakingDistanceBrakesThenComesBack) {
  RobotSimulator sim;
  const SimAxisConfig& a = sim.config().j5;  // 30 deg/s, 60 deg/s^2
  sim.command(SimCommand::moveTo(J::kJ5, 90.0));
  // Hand-worked: at 1.5 s J5 has accelerated 0.5 s (7.5 deg) and cruised 1 s (30 deg).
  runUntil(
      sim, [](const SimSnapshot& s) { return s.step == 150; }, 5.0);
  ASSERT_NEAR(sim.snapshot().joint(J::kJ5).position, 37.5, kExact);
  ASSERT_NEAR(sim.snapshot().joint(J::kJ5).velocity, 30.0, kExact);
  // 40 deg lies within the 7.5 deg braking distance: brake 0.5 s to 45 deg, then a triangular
  // 5 deg move back, 2 sqrt(5 / 60) s.
  sim.command(SimCommand::moveTo(J::kJ5, 40.0));
  const double end = 1.5 + 0.5 + 2.0 * std::sqrt(5.0 / a.max_acceleration);  // 2.577 s
  double highest = 0.0, previous_velocity = 30.0;
  ASSERT_TRUE(runUntil(
      sim, [](const SimSnapshot& s) { return !s.joint(J::kJ5).moving; }, 5.0,
      [&](const SimSnapshot& s) {
        highest = std::max(highest, s.joint(J::kJ5).position);
        EXPECT_LE(std::abs(s.joint(J::kJ5).velocity - previous_velocity),
                  a.max_acceleration * sim.config().dt + kExact)
            << s.time;
        previous_velocity = s.joint(J::kJ5).velocity;
      }));
  EXPECT_NEAR(highest, 45.0, kExact);  // the braking step lands on t = 2.0 s exactly
  EXPECT_GE(sim.time(), end - kExact);
  EXPECT_LT(sim.time(), end + sim.config().dt);
  EXPECT_EQ(sim.snapshot().joint(J::kJ5).position, 40.0);
}

TEST(Brush, SpinsUpAndDownWithItsAccelerationLimit) {
  RobotSimulator sim;
  const double accel = sim.config().j6.max_acceleration;  // 300 rpm/s
  sim.command(SimCommand::spin(300.0));
  runUntil(
      sim, [](const SimSnapshot&) { return false; }, 2.0,
      [&](const SimSnapshot& s) {
        EXPECT_NEAR(s.joint(J::kJ6).velocity, std::min(accel * s.time, 300.0), kExact) << s.time;
        EXPECT_EQ(s.joint(J::kJ6).moving, s.time < 1.0 - kExact) << s.time;
      });
  // Angle after 2 s: 1 s ramp to 1800 deg/s (900 deg) + 1 s at 1800 deg/s = 2700 deg.
  EXPECT_NEAR(sim.snapshot().joint(J::kJ6).position, 2700.0, kExact);
  EXPECT_EQ(sim.snapshot().joint(J::kJ6).encoder, 7680);  // 7.5 rev * 1024 counts/rev
  sim.command(SimCommand::stop(J::kJ6));
  ASSERT_TRUE(runUntil(
      sim, [](const SimSnapshot& s) { return s.joint(J::kJ6).velocity == 0.0; }, 5.0));
  EXPECT_NEAR(sim.time(), 3.0, kExact);
  EXPECT_EQ(sim.snapshot().joint(J::kJ6).current, 0.0);
}

void expectSameSnapshot(const SimSnapshot& a, const SimSnapshot& b) {
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.step, b.step);
  for (std::size_t i = 0; i < kSimJointCount; ++i) {
    const SimJointState& x = a.joints[i];
    const SimJointState& y = b.joints[i];
    EXPECT_EQ(x.position, y.position) << i;
    EXPECT_EQ(x.velocity, y.velocity) << i;
    EXPECT_EQ(x.encoder, y.encoder) << i;
    EXPECT_EQ(x.current, y.current) << i;
    EXPECT_EQ(x.moving, y.moving) << i;
    EXPECT_EQ(x.zero_switch, y.zero_switch) << i;
    EXPECT_EQ(x.gripping, y.gripping) << i;
  }
  EXPECT_EQ(a.j3_stalled, b.j3_stalled);
  EXPECT_EQ(a.falling, b.falling);
  EXPECT_EQ(a.fixed_platform_position, b.fixed_platform_position);
  EXPECT_EQ(a.moving_platform_position, b.moving_platform_position);
  EXPECT_EQ(a.fixed_platform_disc, b.fixed_platform_disc);
  EXPECT_EQ(a.moving_platform_disc, b.moving_platform_disc);
  EXPECT_EQ(a.battery_voltage, b.battery_voltage);
  EXPECT_EQ(a.battery_charge, b.battery_charge);
  EXPECT_EQ(a.battery_current, b.battery_current);
  EXPECT_EQ(a.battery_low, b.battery_low);
  EXPECT_EQ(a.link_up, b.link_up);
  EXPECT_TRUE(a == b);
}

/// A scripted run touching every joint, the link and the faults; `shift` delays one command.
std::vector<SimSnapshot> scriptedRun(int shift) {
  RobotSimulator sim;
  std::vector<SimSnapshot> out{sim.snapshot()};
  for (int k = 0; k < 3000; ++k) {
    if (k == 0) sim.command(SimCommand::release(kFixedClamp));
    if (k == 300 + shift) sim.command(SimCommand::moveTo(J::kJ3, 155.0));
    if (k == 500) sim.setLinkUp(false);
    if (k == 700) sim.setFault(SimFault::kMovingZeroSwitchNeverPressed);
    if (k == 1000) sim.command(SimCommand::close(kFixedClamp));
    if (k == 1100) sim.command(SimCommand::spin(-250.0));
    if (k == 1150) sim.setFault(SimFault::kBatteryDrain, 1.5);
    if (k == 1200) sim.command(SimCommand::moveTo(J::kJ5, 90.0));
    if (k == 1250) sim.command(SimCommand::moveTo(J::kJ4, 60.0));
    if (k == 1400) sim.command(SimCommand::release(kMovingClamp));
    if (k == 1500) sim.setLinkUp(true);
    if (k == 1700) sim.command(SimCommand::moveTo(J::kJ3, 0.0));
    if (k == 1350) sim.command(SimCommand::moveTo(J::kJ5, 40.0));  // replans mid-move
    if (k == 2500) sim.command(SimCommand::close(kMovingClamp));
    out.push_back(sim.step());
  }
  return out;
}

TEST(RobotSimulator, IdenticalRunsGiveIdenticalSnapshots) {
  const std::vector<SimSnapshot> a = scriptedRun(0);
  const std::vector<SimSnapshot> b = scriptedRun(0);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    SCOPED_TRACE(k);
    expectSameSnapshot(a[k], b[k]);
    if (::testing::Test::HasFailure()) break;
  }
  // The comparison can tell runs apart: one command a step later changes the snapshots.
  const std::vector<SimSnapshot> c = scriptedRun(1);
  EXPECT_TRUE(a != c);
  EXPECT_TRUE(a.back().joint(kMovingClamp).gripping);  // the run ended on the next disc
  EXPECT_EQ(a.back().fixed_platform_position, 155.0);
}

TEST(Faults, StuckZeroSwitchIsNeverPressed) {
  RobotSimulator sim;
  sim.setFault(SimFault::kFixedZeroSwitchNeverPressed);
  sim.command(SimCommand::release(kFixedClamp));
  EXPECT_FALSE(runUntil(
      sim, [](const SimSnapshot& s) { return s.joint(kFixedClamp).zero_switch; }, 10.0));
  EXPECT_EQ(sim.snapshot().joint(kFixedClamp).position, 0.0);  // the jaw did open
  sim.setFault(SimFault::kFixedZeroSwitchNeverPressed, 0.0);   // cleared: reads at once
  EXPECT_TRUE(sim.snapshot().joint(kFixedClamp).zero_switch);

  sim.setFault(SimFault::kMovingZeroSwitchAlwaysPressed);
  EXPECT_TRUE(sim.snapshot().joint(kMovingClamp).zero_switch);  // though the jaw grips
  EXPECT_TRUE(sim.snapshot().joint(kMovingClamp).gripping);
  sim.setFault(SimFault::kMovingZeroSwitchNeverPressed);  // replaces "always pressed"
  EXPECT_EQ(sim.fault(SimFault::kMovingZeroSwitchAlwaysPressed), 0.0);
  EXPECT_THROW(sim.setFault(SimFault::kBatteryDrain, -1.0), Error);
}

TEST(Links, LinkStateIsReportedAsSet) {
  RobotSimulator sim;
  sim.setLinkUp(false);
  EXPECT_FALSE(sim.snapshot().link_up);
  EXPECT_FALSE(sim.step().link_up);
  sim.setLinkUp(true);
  EXPECT_TRUE(sim.step().link_up);
}

TEST(RobotSimulator, RefusesCommandsOutsideTheLimits) {
  RobotSimulator sim;
  EXPECT_FALSE(sim.refuse(SimCommand::moveTo(J::kJ3, 155.0)).has_value());
  const auto reason = sim.refuse(SimCommand::moveTo(J::kJ3, 200.0));
  ASSERT_TRUE(reason.has_value());
  EXPECT_EQ(*reason, "J3 move_to target 200 mm is outside the limits [0, 180] mm");
  EXPECT_NE(sim.refuse(SimCommand::moveTo(J::kJ5, -400.0)).value_or("").find("J5"),
            std::string::npos);
  EXPECT_NE(sim.refuse(SimCommand::moveTo(J::kJ4, std::nan(""))).value_or("").find("not finite"),
            std::string::npos);
  EXPECT_EQ(sim.refuse(SimCommand::spin(900.0)).value_or(""),
            "J6 spin speed 900 rpm is above the limit 600 rpm");
  EXPECT_EQ(sim.refuse(SimCommand::close(J::kJ3)).value_or(""), "close is not a command of J3");
  EXPECT_EQ(sim.refuse(SimCommand::moveTo(J::kJ1, 10.0)).value_or(""),
            "move_to is not a command of J1");
  EXPECT_FALSE(sim.refuse(SimCommand::stop(J::kJ4)).has_value());
  EXPECT_EQ(sim.refuse(SimCommand::moveTo(J::kJ3, 100.0, 30.0)).value_or(""),
            "J3 move_to speed 30 mm/s is outside [0, max_speed = 20] mm/s");
  EXPECT_FALSE(sim.refuse(SimCommand::moveTo(J::kJ3, 100.0, 10.0)).has_value());
  try {
    sim.command(SimCommand::moveTo(J::kJ3, 200.0));
    FAIL() << "no throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("J3 move_to target 200 mm"), std::string::npos);
  }
  EXPECT_EQ(sim.snapshot().joint(J::kJ3).moving, false);  // nothing was started
}

TEST(RobotSimulator, NamesRoundTrip) {
  for (std::size_t i = 0; i < kSimJointCount; ++i) {
    const auto joint = static_cast<J>(i);
    EXPECT_EQ(simJointFromName(simJointName(joint)), joint);
  }
  EXPECT_EQ(commandKindFromName("move_to"), SimCommandKind::kMoveTo);
  EXPECT_EQ(faultFromName("battery_drain"), SimFault::kBatteryDrain);
  EXPECT_EQ(faultFromName(faultName(SimFault::kFixedZeroSwitchNeverPressed)),
            SimFault::kFixedZeroSwitchNeverPressed);
  EXPECT_THROW(simJointFromName("J7"), Error);
  EXPECT_THROW(commandKindFromName("grip"), Error);
  EXPECT_THROW(faultFromName("x"), Error);
  EXPECT_EQ(describe(SimCommand::moveTo(J::kJ3, 155.0)), "J3 move_to 155 mm");
  EXPECT_EQ(describe(SimCommand::spin(300.0)), "J6 spin 300 rpm");
  EXPECT_EQ(describe(SimCommand::moveTo(J::kJ3, 155.0, 10.0)), "J3 move_to 155 mm at 10 mm/s");
  EXPECT_EQ(describe(SimCommand::close(kMovingClamp)), "J2 close");
}

/// The message of the mcws::Error a configuration throws ("" if none).
std::string configError(const std::function<void(RobotSimulatorConfig&)>& edit) {
  RobotSimulatorConfig config;
  edit(config);
  try {
    RobotSimulator sim(config);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(RobotSimulatorConfig, ErrorsNameTheField) {
  EXPECT_EQ(configError([](RobotSimulatorConfig&) {}), "");
  EXPECT_EQ(configError([](RobotSimulatorConfig& c) { c.dt = 0.0; }),
            "simulator config: dt = 0 s, must be > 0");
  EXPECT_EQ(configError([](RobotSimulatorConfig& c) { c.j3.max_speed = -5.0; }),
            "simulator config: j3.max_speed = -5 mm/s, must be > 0");
  EXPECT_EQ(configError([](RobotSimulatorConfig& c) { c.j5.max_acceleration = std::nan(""); }),
            "simulator config: j5.max_acceleration = nan deg/s^2, must be > 0");
  EXPECT_EQ(
      configError([](RobotSimulatorConfig& c) { c.fixed_clamp.end_stop_angle = 20.0; }),
      "simulator config: fixed_clamp.end_stop_angle = 20 deg, must be > contact_angle 25 deg");
  EXPECT_EQ(
      configError([](RobotSimulatorConfig& c) { c.moving_clamp.stall_current = 0.1; }),
      "simulator config: moving_clamp.stall_current = 0.1 A, must be > running_current 0.4 A");
  EXPECT_EQ(configError([](RobotSimulatorConfig& c) { c.j4.min_position = 10.0; }),
            "simulator config: j4.min_position = 10 mm, must be <= 0 (the start pose)");
  EXPECT_EQ(configError([](RobotSimulatorConfig& c) { c.j6.max_speed = 0.0; }),
            "simulator config: j6.max_speed = 0 rpm, must be > 0");
  EXPECT_EQ(configError([](RobotSimulatorConfig& c) { c.string.disc_count = 0; }),
            "simulator config: string.disc_count = 0, must be >= 1");
  EXPECT_EQ(configError([](RobotSimulatorConfig& c) { c.string.tolerance = 80.0; }),
            "simulator config: string.tolerance = 80 mm, must be in [0, pitch / 2 = 77.5 mm)");
  EXPECT_EQ(configError([](RobotSimulatorConfig& c) { c.string.home_gap = 100.0; }),
            "simulator config: string.home_gap = 100 mm, puts the moving clamp at 100 mm, at no "
            "grip position 0 .. 28");
  EXPECT_EQ(configError([](RobotSimulatorConfig& c) { c.string.initial_disc = 27; }),
            "simulator config: string.home_gap = 310 mm, puts the moving clamp at 4495 mm, at no "
            "grip position 0 .. 28");
  EXPECT_EQ(configError([](RobotSimulatorConfig& c) { c.battery.low_voltage = 30.0; }),
            "simulator config: battery.low_voltage = 30 V, must be in [empty_voltage, "
            "full_voltage] = [21, 25.2] V");
  EXPECT_EQ(configError([](RobotSimulatorConfig& c) { c.battery.initial_charge = 0.0; }),
            "simulator config: battery.initial_charge = 0, must be in (0, 1]");
  // A gap of one pitch is fine, and so is starting further down the string.
  EXPECT_EQ(configError([](RobotSimulatorConfig& c) {
              c.string.home_gap = 155.0;
              c.string.initial_disc = 27;
            }),
            "");
}

}  // namespace
}  // namespace mcws
