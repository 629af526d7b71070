#pragma once
/// \file
/// \brief The units a tool's results are given in: the length unit of the data (the robot file's,
/// or the one a cloud records), the unit the user asks for (--unit m|cm|mm), and the JSON that
/// names them, so that every number a tool prints says what it measures.
///
/// Convention of every tool's --json: "length_unit" is the unit of every length in the object
/// ("m", "cm", "mm", or "unrecorded" for a cloud that names none, such as the validation shapes
/// of mcws_sample --shape); "units" maps each key holding a dimensioned number to its unit
/// ("volume": "cm^3", "seconds": "s", nested keys joined by '.'). Counts (points, samples,
/// labels) are plain counts and not listed.

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

#include "common/app.h"
#include "mcws/kinematics/robot.h"

namespace mcws::app {

/// \brief What "length_unit" says of data whose unit is not recorded.
inline constexpr const char* kUnrecordedUnit = "unrecorded";

/// \brief The length unit of results: the data's (none when not recorded) and the one shown.
class ResultUnits {
 public:
  /// \param data the unit of the input's lengths, none when the input does not record one.
  /// \param shown the unit to give results in (--unit); none: the data's.
  ResultUnits(std::optional<LengthUnit> data, std::optional<LengthUnit> shown);

  /// \brief A length, area or volume of the data in the unit shown.
  double length(double value) const { return value * scale_; }
  double area(double value) const { return value * scale_ * scale_; }
  double volume(double value) const { return value * scale_ * scale_ * scale_; }

  /// \brief "cm", "cm^2", "cm^3" (or "unrecorded", "unrecorded^2", ...).
  std::string lengthName() const { return name_; }
  std::string areaName() const { return name_ + "^2"; }
  std::string volumeName() const { return name_ + "^3"; }
  /// \brief The unit of a region's measure in `dimensions` (2: area, 3: volume).
  std::string measureName(int dimensions) const {
    return dimensions == 2 ? areaName() : volumeName();
  }

 private:
  double scale_{1.0};
  std::string name_;
};

/// \brief Declares --unit (read by readResultUnits()).
void declareUnitFlag(CommandLine& cli);

/// \brief The units of a tool's results: `data` and --unit if given.
/// \param what names the input in the message when --unit is given but `data` is none.
/// \throws UsageError for a --unit other than m, cm, mm; Error for a --unit with data that records
///   no unit ("--unit m: ball.pcd records no length unit to convert from").
ResultUnits readResultUnits(const CommandLine& cli, std::optional<LengthUnit> data,
                            const std::string& what);

/// \brief The unit of each joint's value: "rad" (revolute) or the robot's length unit (prismatic),
/// followed by `per` (e.g. "/s" for velocities).
std::vector<std::string> jointUnits(const Robot& robot, const std::string& per = "");

/// \brief The length unit a cloud records (its mcws comment line), if any.
std::optional<LengthUnit> recordedUnit(const std::string& cloud_path);

}  // namespace mcws::app
