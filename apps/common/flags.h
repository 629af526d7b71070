#pragma once
/// \file
/// \brief The flags several stage tools share, read and checked in one place with one message
/// style: "--flag: <the bad value> is not <what was wanted>", a UsageError (exit code 2).

#include <Eigen/Core>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <utility>

#include "common/app.h"
#include "mcws/filters/boundary_geometry.h"
#include "mcws/kinematics/robot.h"
#include "mcws/reach/quality.h"
#include "mcws/sampling/sampler.h"
#include "mcws/workspace/measure.h"

namespace mcws::app {

/// \brief Most worker threads a --threads flag accepts: more is a typing mistake, not a machine.
constexpr int kMaxThreads = 256;

/// \brief Runs `parse`, turning an mcws::Error it throws (a bad value found by a library
/// function: an unknown shape or joint, a count it cannot sample) into a UsageError
/// "--flag: message". A UsageError passes unchanged.
template <typename Parse>
auto asUsageError(const std::string& flag, Parse&& parse) -> decltype(parse()) {
  return mcws::asUsageError("--" + flag, std::forward<Parse>(parse));
}

/// \brief A real number > 0. \param unit appended to the value in the message ("0 s is not a
/// positive number"); may be empty.
/// \throws UsageError naming the flag and the text.
double parsePositive(const std::string& text, const std::string& flag,
                     const std::string& unit = "");

/// \brief A real number >= 0 (0 usually meaning "off" or "automatic").
/// \throws UsageError naming the flag and the text.
double parseNonNegative(const std::string& text, const std::string& flag);

/// \brief One of `choices`. \throws UsageError "--flag: 'x' is not a, b or c".
std::string parseChoice(const std::string& text, const std::string& flag,
                        std::initializer_list<const char*> choices);

/// \brief --seed: a whole number >= 0, or `fallback` when the flag is absent.
std::uint64_t readSeed(const CommandLine& cli, std::uint64_t fallback = 1);

/// \brief --threads: a whole number in [minimum, kMaxThreads], 0 (the default) meaning all
/// cores; tools that cannot take 0 pass minimum 1 and read the flag only when given.
int readThreads(const CommandLine& cli, int minimum = 0);

/// \brief --point: tool (default) | flange, the point a sample records.
SamplePoint readPoint(const CommandLine& cli);

/// \brief A length flag: a number with an optional unit suffix (m, cm, mm: "2cm", "0.02m"),
/// converted to `unit`; a bare number is already in `unit`.
/// \param allow_zero accept 0 (a distance that may be none) as well as positive lengths.
/// \throws UsageError naming the flag for a value that is not a positive (or, with allow_zero,
///   non-negative) finite length.
double parseLength(const std::string& text, const std::string& flag, LengthUnit unit,
                   bool allow_zero = false);

/// \brief An angle flag >= 0 with its unit: "5deg", "0.087rad"; a bare 0 is accepted.
/// \returns [rad]. \throws UsageError naming the flag for a negative or non-numeric value or a
///   non-zero value without a unit.
double parseAngle(const std::string& text, const std::string& flag);

/// \brief Declares --alpha, --correction and --threads of the Delaunay region (mcws_measure,
/// mcws_envelope), each help text prefixed by `prefix` (e.g. "delaunay: ").
void declareRegionFlags(CommandLine& cli, const std::string& prefix = "");

/// \brief --correction (efron | none; default efron), --alpha [local spacings] in [1, 1000]
/// (default 3 with the correction, 5 without) and --threads, as MeasureOptions.
/// \throws UsageError naming the flag.
MeasureOptions readRegionOptions(const CommandLine& cli);

/// \brief Declares --quality-task and --length (read by readQualityOptions()).
void declareQualityFlags(CommandLine& cli);

/// \brief --quality-task (position | full) and --length (parseLength()) over the robot's
/// defaults (defaultQualityOptions()).
QualityOptions readQualityOptions(const CommandLine& cli, const Robot& robot);

/// \brief --plane: xy | xz | yz, or k3D when the flag is absent.
BoundaryPlane readPlane(const CommandLine& cli);

/// \brief Declares --robot (described by `help`, e.g. "robot description (.yaml or .urdf)") and,
/// for URDF robots, --base and --tip, the links the chain runs between, and --package-path
/// (repeatable), where package:// mesh URIs are looked for, and --srdf, an SRDF file whose
/// `<disable_collisions>` pairs every collision check skips (read by readRobot()).
void declareRobotFlags(CommandLine& cli, const char* help);

/// \brief Loads --robot (.yaml or .urdf); for a URDF, the chain from --base (default the tree's
/// root link) to --tip (default its one leaf), which any collision model read for it follows
/// (loadCollisionModel() reads Robot::base_link and Robot::tip_link), its meshes' package://
/// URIs looked for in the --package-path folders first (Robot::package_path), --srdf as
/// Robot::srdf (loadCollisionModel() applies it).
/// \throws UsageError for a missing --robot, --base/--tip or --package-path with a robot that is
///   not .urdf, a --package-path that is not a folder, an --srdf that is not a file, a
///   --base or --tip that is not a link of the robot, a --tip not below --base ("--tip: link
///   'link1' is not below --base link 'link3' in arm.urdf"), or several leaves and no --tip
///   ("--robot: arm.urdf: link 'world' has 2 leaf links below it (tool0, ee_link): choose one
///   with --tip"); mcws::Error "--robot: <the loader's message, naming the file>" (exit code 1)
///   for a file that cannot be loaded.
Robot readRobot(const CommandLine& cli);

/// \brief Whether a joint vector flag must lie within the joint limits.
enum class JointLimits { kCheck, kIgnore };

/// \brief Checks a joint vector given by `flag` (already parsed with parseNumberList()): one value
/// per joint and, with JointLimits::kCheck, each finite and within its joint's limits.
/// \throws UsageError "--flag: <the robot's message naming the joint and value>".
void checkJointValues(const Robot& robot, const Eigen::VectorXd& q, const std::string& flag,
                      JointLimits limits = JointLimits::kCheck);

/// \brief parseNumberList() then checkJointValues().
Eigen::VectorXd parseJointValues(const Robot& robot, const std::string& text,
                                 const std::string& flag, JointLimits limits = JointLimits::kCheck);

}  // namespace mcws::app
