#pragma once
/// \file
/// \brief A time-stepped simulator of the suspension-insulator cleaning robot of Wang et al. 2018
/// (sections 1.2 and 3.1): six joints with speed and acceleration limits, clamp motor currents that
/// rise on contact, zero switches, incremental encoders, the insulator string, a battery and the
/// radio link. It knows nothing of behaviours or state machines: a caller sends joint commands,
/// calls step() and reads the sensor snapshot.
///
/// Usage:
/// \code
///   mcws::RobotSimulator sim;                                   // default configuration
///   sim.command(mcws::SimCommand::release(mcws::kFixedClamp));  // J1 opens
///   while (!sim.snapshot().joint(mcws::kFixedClamp).zero_switch) sim.step();
///   const auto move = mcws::SimCommand::moveTo(mcws::SimJoint::kJ3, 155.0);  // [mm]
///   if (const auto reason = sim.refuse(move)) { /* report *reason, do not send */ }
///   sim.command(move);
///   while (sim.snapshot().joint(mcws::SimJoint::kJ3).encoder < 15500) sim.step();
/// \endcode
///
/// Units: time [s]; J1, J2 (clamp jaws) and J5 (circular guide) [deg], [deg/s], [deg/s^2];
/// J3 (moving platform travel) and J4 (cleaning platform travel) [mm], [mm/s], [mm/s^2]; J6
/// (brush) angle [deg], speed [rpm], acceleration [rpm/s]; positions along the string [mm] from
/// the tower end towards the conductor; currents [A]; voltage [V]; charge [A h].

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace mcws {

/// \brief The robot's six joints (Wang et al. 2018, section 1.2 and Figure 2).
enum class SimJoint {
  kJ1 = 0,  ///< fixed platform's clamp (revolute jaw) [deg]
  kJ2,      ///< moving platform's clamp (revolute jaw) [deg]
  kJ3,      ///< moving platform travel relative to the fixed platform (prismatic) [mm]
  kJ4,      ///< cleaning platform travel (prismatic) [mm]
  kJ5,      ///< circular guide about the string (revolute) [deg]
  kJ6,      ///< brush spin (revolute) [deg], speed [rpm]
};
/// \brief Number of joints.
constexpr std::size_t kSimJointCount = 6;
/// \brief The fixed platform's clamp, J1.
constexpr SimJoint kFixedClamp = SimJoint::kJ1;
/// \brief The moving platform's clamp, J2.
constexpr SimJoint kMovingClamp = SimJoint::kJ2;

/// \brief Index 0..5 of a joint (J1 = 0).
constexpr std::size_t simJointIndex(SimJoint joint) { return static_cast<std::size_t>(joint); }
/// \brief "J1" .. "J6".
const char* simJointName(SimJoint joint);
/// \brief The joint called `name` ("J1" .. "J6"). \throws mcws::Error naming `name` otherwise.
SimJoint simJointFromName(const std::string& name);

/// \brief What a command asks of a joint.
enum class SimCommandKind {
  kClose,    ///< J1, J2: close the jaw (until it meets the insulator or its end stop)
  kRelease,  ///< J1, J2: open the jaw (until it presses its zero switch at 0 deg)
  kStop,     ///< any joint: J1, J2 stop at once; J3..J5 brake to rest; J6 spins down
  kMoveTo,   ///< J3, J4, J5: move to `value` [mm or deg]
  kSpin,     ///< J6: spin at `value` [rpm] (sign gives the direction)
};
/// \brief "close", "release", "stop", "move_to", "spin".
const char* commandKindName(SimCommandKind kind);
/// \brief The kind called `name`. \throws mcws::Error naming `name` otherwise.
SimCommandKind commandKindFromName(const std::string& name);

/// \brief One command to one joint.
struct SimCommand {
  SimJoint joint{SimJoint::kJ1};
  SimCommandKind kind{SimCommandKind::kStop};
  /// kMoveTo: target position [mm] (J3, J4) or [deg] (J5); kSpin: brush speed [rpm]; else unused.
  double value{0.0};
  /// kMoveTo: cruise speed [mm/s] or [deg/s], at most the joint's max_speed; 0 = max_speed.
  double speed{0.0};

  static SimCommand close(SimJoint clamp) { return {clamp, SimCommandKind::kClose, 0.0, 0.0}; }
  static SimCommand release(SimJoint clamp) { return {clamp, SimCommandKind::kRelease, 0.0, 0.0}; }
  static SimCommand stop(SimJoint joint) { return {joint, SimCommandKind::kStop, 0.0, 0.0}; }
  /// \param target [mm] for J3, J4; [deg] for J5.
  /// \param speed cruise speed [mm/s] or [deg/s]; 0 = the joint's max_speed.
  static SimCommand moveTo(SimJoint joint, double target, double speed = 0.0) {
    return {joint, SimCommandKind::kMoveTo, target, speed};
  }
  /// \param rpm brush speed [rpm].
  static SimCommand spin(double rpm) { return {SimJoint::kJ6, SimCommandKind::kSpin, rpm, 0.0}; }
};
/// \brief A command as text for logs: "J1 close", "J3 move_to 155 mm", "J3 move_to 155 mm at 10
/// mm/s", "J6 spin 300 rpm".
std::string describe(const SimCommand& command);

/// \brief Injected faults (Wang et al. 2018, section 2.4: sensor faults and a draining battery).
enum class SimFault {
  kFixedZeroSwitchNeverPressed,    ///< J1's zero switch reads "not pressed" whatever the jaw
  kFixedZeroSwitchAlwaysPressed,   ///< J1's zero switch reads "pressed" whatever the jaw
  kMovingZeroSwitchNeverPressed,   ///< J2's zero switch reads "not pressed" whatever the jaw
  kMovingZeroSwitchAlwaysPressed,  ///< J2's zero switch reads "pressed" whatever the jaw
  kBatteryDrain,                   ///< an extra current [A] drawn from the battery
};
/// \brief "fixed_zero_switch_never_pressed", ..., "battery_drain".
const char* faultName(SimFault fault);
/// \brief The fault called `name`. \throws mcws::Error naming `name` otherwise.
SimFault faultFromName(const std::string& name);

/// \brief A clamp (J1 or J2): a jaw driven at a constant angular speed.
///
/// Released, the jaw rests at 0 deg and presses its zero switch. Closing on a platform that sits
/// at a disc, the jaw meets the insulator at `contact_angle` and stops there; from the contact
/// time t_c the motor current rises as I(t) = I_s + (I_c - I_s) exp(-(t - t_c) / tau) from
/// I_c = `running_current` towards I_s = `stall_current`. With no insulator under it the jaw
/// closes to `end_stop_angle`, where its limit cuts the motor: the current never rises.
/// A jaw counts as gripping from the contact on until a release moves it (the release starts
/// from the contact angle, so it presses the zero switch contact_angle / jaw_speed later). A
/// stopped motor draws 0 A; a stopped jaw in contact still grips (the drive is self-locking);
/// a close sent again in contact restarts the rise from the present current. A jaw already
/// past `contact_angle` when its platform arrives at a disc does not grip.
struct SimClampConfig {
  double jaw_speed{10.0};       ///< jaw angular speed while moving [deg/s]
  double contact_angle{25.0};   ///< jaw angle at which it meets the insulator [deg]
  double end_stop_angle{40.0};  ///< fully closed jaw angle, > contact_angle [deg]
  double running_current{0.4};  ///< motor current while the jaw moves freely [A]
  double stall_current{2.5};    ///< current the contact rise tends to, > running_current [A]
  double time_constant{0.15};   ///< time constant tau of the contact rise [s]
  double counts_per_deg{20.0};  ///< encoder resolution [counts/deg]
};

/// \brief A positioned joint (J3, J4 or J5): time-optimal trapezoidal velocity profile.
///
/// A move_to accelerates at `max_acceleration`, cruises at its speed (`max_speed` unless the
/// command gives a lower one) and brakes to rest at the target exactly; a short move is
/// triangular. From rest a move of distance d takes d / v + v / a when d >= v^2 / a, else
/// 2 sqrt(d / a) (v = cruise speed, a = max_acceleration). A new command while moving replans
/// from the present position and velocity (braking first when the target lies behind or within
/// the braking distance; slowing down to a lower cruise speed at max_acceleration).
struct SimAxisConfig {
  double max_speed{20.0};         ///< [mm/s] (J3, J4) or [deg/s] (J5)
  double max_acceleration{40.0};  ///< [mm/s^2] or [deg/s^2]
  double min_position{0.0};       ///< lower joint limit [mm] or [deg]; <= 0 (the start pose)
  double max_position{180.0};     ///< upper joint limit [mm] or [deg]; >= 0
  double counts_per_unit{100.0};  ///< encoder resolution [counts/mm] or [counts/deg]
  double running_current{0.8};    ///< motor current while the joint moves [A]
};

/// \brief The brush (J6): its speed follows a spin command at most at `max_acceleration`.
struct SimBrushConfig {
  double max_speed{600.0};         ///< largest |spin| speed [rpm]
  double max_acceleration{300.0};  ///< spin-up and spin-down rate [rpm/s]
  double counts_per_rev{1024.0};   ///< encoder resolution [counts/rev]
  double running_current{1.2};     ///< motor current while the brush turns [A]
};

/// \brief The insulator string and where the robot is mounted on it.
///
/// Grip positions lie at i * pitch [mm] from the tower end, i = 0 .. disc_count: i = 0 is the
/// tower-end fitting, i = 1 .. disc_count are the discs (the numbering of planCleaningTask()).
/// A platform "sits at a disc" when it is within `tolerance` of a grip position; only there can
/// its clamp grip. As in robots/insulator_cleaner.yaml, the fixed platform is the upper one and
/// the moving platform hangs `home_gap` - J3 below it: J3 > 0 draws the moving platform up
/// towards the fixed platform.
struct SimStringConfig {
  double pitch{155.0};    ///< disc pitch: XWP2-160 structure height [mm]
  int disc_count{28};     ///< number of discs (grip positions 0 .. disc_count)
  double tolerance{2.0};  ///< |position - i * pitch| at which a clamp grips [mm], < pitch/2
  int initial_disc{0};    ///< grip position of the fixed platform at the start
  /// Distance along the string from the fixed clamp down (towards the conductor) to the moving
  /// clamp when J3 = 0 [mm]: two pitches, as the robot file (J3 home leaves the platforms 310 mm
  /// apart). Must put the moving clamp at a grip position too: at the start the fixed clamp grips
  /// grip position initial_disc and the moving clamp initial_disc + 2.
  double home_gap{310.0};
};

/// \brief The battery: voltage linear in the remaining charge.
///
/// V = empty_voltage + (full_voltage - empty_voltage) * Q / capacity, where Q [A h] falls by
/// (sum of the six motor currents + idle_current + the kBatteryDrain fault) * dt every step,
/// with the currents read at the end of the step; Q stops at 0.
struct SimBatteryConfig {
  double capacity{5.0};        ///< charge when full [A h]
  double initial_charge{1.0};  ///< state of charge at the start, in (0, 1]
  double full_voltage{25.2};   ///< voltage when full [V]
  double empty_voltage{21.0};  ///< voltage when empty [V]
  double low_voltage{22.2};    ///< the low-battery flag is set below this [V]
  double idle_current{0.3};    ///< electronics and radio, always drawn [A]
};

/// \brief Everything the simulator is built from; every field has a documented default.
struct RobotSimulatorConfig {
  double dt{0.01};              ///< time step [s]
  SimClampConfig fixed_clamp;   ///< J1
  SimClampConfig moving_clamp;  ///< J2
  /// J3: moving platform travel, 0..180 mm (one 155 mm pitch plus margin, as the robot file).
  SimAxisConfig j3{20.0, 40.0, 0.0, 180.0, 100.0, 0.8};
  double j3_stall_current{3.0};  ///< J3's current while it pushes against two gripping clamps [A]
  /// J4: cleaning platform travel, 0..130 mm (as the robot file).
  SimAxisConfig j4{20.0, 40.0, 0.0, 130.0, 100.0, 0.5};
  /// J5: circular guide, 0..360 deg: one full cleaning turn, then back (as the robot file).
  SimAxisConfig j5{30.0, 60.0, 0.0, 360.0, 50.0, 0.6};
  SimBrushConfig j6;  ///< J6
  SimStringConfig string;
  SimBatteryConfig battery;
};

/// \brief Checks a configuration.
/// \throws mcws::Error naming the first bad field and its value, e.g. "simulator config: dt = 0
///   s, must be > 0".
void validateSimulatorConfig(const RobotSimulatorConfig& config);

/// \brief What one joint's sensors and motor read.
struct SimJointState {
  /// J1, J2 jaw angle [deg] (0 = released); J3, J4 [mm]; J5 [deg]; J6 brush angle [deg].
  double position{0.0};
  /// J1, J2, J5 [deg/s]; J3, J4 [mm/s]; J6 [rpm].
  double velocity{0.0};
  /// Incremental encoder count: round(position * resolution) (J6: position / 360 * counts/rev).
  std::int64_t encoder{0};
  double current{0.0};  ///< motor current [A]
  /// A commanded motion has not finished: a jaw travelling, a profile running (or J3 stalled
  /// with its move pending), the brush changing speed.
  bool moving{false};
  bool zero_switch{false};  ///< J1, J2: zero switch reads pressed (faults applied); else false
  bool gripping{false};     ///< J1, J2: the jaw is in contact with the insulator; else false
};

/// \brief The sensor snapshot at one simulated time.
struct SimSnapshot {
  double time{0.0};                                    ///< simulated time: step * dt [s]
  std::uint64_t step{0};                               ///< steps taken
  std::array<SimJointState, kSimJointCount> joints{};  ///< indexed by simJointIndex()
  bool j3_stalled{false};  ///< J3 has a move pending but both clamps grip: it cannot move
  /// Neither clamp grips: the robot has fallen off the string (latched; the string positions
  /// below are frozen and meaningless from then on).
  bool falling{false};
  double fixed_platform_position{0.0};      ///< fixed platform (robot body) along the string [mm]
  double moving_platform_position{0.0};     ///< moving platform along the string [mm]
  std::optional<int> fixed_platform_disc;   ///< grip position it sits at, if any
  std::optional<int> moving_platform_disc;  ///< grip position it sits at, if any
  double battery_voltage{0.0};              ///< [V]
  double battery_charge{0.0};               ///< remaining charge [A h]
  double battery_current{0.0};              ///< total current drawn over the last step [A]
  bool battery_low{false};                  ///< battery_voltage < low_voltage
  bool link_up{true};                       ///< radio link to the ground station

  const SimJointState& joint(SimJoint j) const { return joints[simJointIndex(j)]; }
};
/// \brief Exact equality of every field (doubles compared with ==): same commands, same
/// snapshots, bit for bit.
bool operator==(const SimJointState& a, const SimJointState& b);
bool operator==(const SimSnapshot& a, const SimSnapshot& b);
inline bool operator!=(const SimSnapshot& a, const SimSnapshot& b) { return !(a == b); }

/// \brief The robot on its string, advanced in fixed time steps.
///
/// Which body moves when J3 moves: the robot hangs on the string by whichever clamps grip. The
/// moving platform sits `home_gap` - J3 below (towards the conductor) the fixed platform. With only
/// the fixed clamp gripping, J3 moves the moving platform along the string; with only the moving
/// clamp gripping, J3 moves the fixed platform (the robot body); with both gripping, J3 cannot move
/// (`j3_stalled`, its current at j3_stall_current); with neither the robot falls (`falling`,
/// latched: no clamp grips again). A stalled move resumes, planned afresh from rest, as soon as one
/// clamp lets go. So the CB1 of Wang et al. 2018 (release J1, J3 to one pitch, close J1, release
/// J2, J3 home, close J2) moves the robot one pitch down the string.
///
/// Determinism: the clock is step * dt; every motion is evaluated in closed form from the time
/// of its command, so the same commands at the same steps give the same snapshots bit for bit.
/// There is no randomness and no wall clock.
class RobotSimulator {
 public:
  /// \brief The robot at time 0: both clamps gripping (jaws at their contact angle, motors off)
  /// with the fixed platform at grip position `initial_disc`, J3..J6 at 0 and at rest, the
  /// battery at `initial_charge`, the link up, no faults.
  /// \throws mcws::Error naming the field for a bad configuration (validateSimulatorConfig()).
  explicit RobotSimulator(const RobotSimulatorConfig& config = RobotSimulatorConfig());

  const RobotSimulatorConfig& config() const { return config_; }

  /// \brief Why `command` must not be sent, or nothing when it may.
  ///
  /// Reasons: a kind the joint does not take (close on J3, spin on J1, ...), an unknown joint, a
  /// non-finite value, a move_to target outside the joint's limits, a spin above the brush's
  /// max_speed. The executor calls this before every motion (Wang et al. 2018, section 2.4,
  /// item 4).
  std::optional<std::string> refuse(const SimCommand& command) const;

  /// \brief Starts `command` at the present time(); it acts over the following steps and
  /// replaces the joint's previous command.
  /// \throws mcws::Error with refuse()'s reason when refuse() gives one.
  void command(const SimCommand& command);

  /// \brief Advances the clock by dt and returns the new snapshot.
  const SimSnapshot& step();

  /// \brief The sensors at time(). Link and fault changes show at once; commands from the next
  /// step.
  const SimSnapshot& snapshot() const { return snapshot_; }
  /// \brief Simulated time [s].
  double time() const { return snapshot_.time; }

  /// \brief Sets the radio link to the ground station up or down (any time; the simulator only
  /// reports it).
  void setLinkUp(bool up);

  /// \brief Injects (value > 0) or clears (value = 0) a fault. For the zero-switch faults the
  /// value is just on or off, and setting "never pressed" clears "always pressed" on the same
  /// switch and vice versa; for kBatteryDrain it is the extra current [A].
  /// \throws mcws::Error for a negative or non-finite value.
  void setFault(SimFault fault, double value = 1.0);
  /// \brief The fault's value (0 when not active).
  double fault(SimFault fault) const;

  /// \brief Grip position at which a platform at `position` [mm] along the string sits, if any.
  std::optional<int> discAt(double position) const;

 private:
  /// One constant-acceleration piece of a motion profile.
  struct Segment {
    double duration{0.0};      // [s]
    double acceleration{0.0};  // [unit/s^2]
  };
  /// Position and velocity in closed form from a start state: up to four constant-acceleration
  /// segments, then constant velocity `end_velocity` (0 for a positioned joint).
  struct Profile {
    double start_time{0.0}, start_position{0.0}, start_velocity{0.0};
    std::array<Segment, 4> segments{};
    int segment_count{0};
    double end_position{0.0}, end_velocity{0.0};
    double endTime() const;
    void evaluate(double t, double& position, double& velocity) const;
  };
  enum class JawMode { kIdle, kClosing, kReleasing };
  struct ClampState {
    JawMode mode{JawMode::kIdle};
    double angle{0.0};  // [deg]
    double start_time{0.0}, start_angle{0.0};
    bool contact{false};
    double contact_time{0.0}, contact_current{0.0};
  };
  struct AxisState {
    Profile profile;
    double target{0.0};
    double speed{0.0};   // cruise speed of the move [unit/s]
    bool replan{false};  // J3 was stalled: plan afresh from rest when it can move
  };

  static Profile planMove(double t0, double p0, double v0, double target, double max_speed,
                          double max_acceleration);
  static Profile planRamp(double t0, double p0, double v0, double v_target,
                          double max_acceleration);
  const SimClampConfig& clampConfig(int clamp) const;
  const SimAxisConfig& axisConfig(int axis) const;
  void stepClamp(int clamp, double t0, double t1);
  void refreshSensors();

  RobotSimulatorConfig config_;
  std::uint64_t steps_{0};
  std::array<ClampState, 2> clamps_{};
  std::array<AxisState, 3> axes_{};                    // J3, J4, J5
  Profile brush_;                                      // J6 angle [deg], velocity [deg/s]
  double fixed_position_{0.0}, moving_position_{0.0};  // along the string [mm]
  bool falling_{false};
  bool j3_stalled_{false};
  double charge_{0.0};  // [A s]
  std::array<double, 5> faults_{};
  SimSnapshot snapshot_;
};

}  // namespace mcws
