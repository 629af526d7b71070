#pragma once
/// \file
/// \brief Length units of robots and clouds (m, cm, mm), and the units a result is shown in
/// (--unit), so that every number a tool or the library gives names what it measures.
///
/// Convention of every tool's --json: "length_unit" is the unit of every length in the object
/// ("m", "cm", "mm", or "unrecorded" for a cloud that names none, such as the validation shapes
/// of mcws_sample --shape); "units" maps each key holding a dimensioned number to its unit
/// ("volume": "cm^3", "seconds": "s", nested keys joined by '.'). Counts (points, samples,
/// labels) are plain counts and not listed.

#include <optional>
#include <string>

namespace mcws {

/// \brief Length unit of a robot description; every length of a robot is in this unit.
enum class LengthUnit { kMetre, kCentimetre, kMillimetre };

/// \brief Short name of a unit ("m", "cm", "mm").
inline const char* unitName(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kMetre:
      return "m";
    case LengthUnit::kCentimetre:
      return "cm";
    case LengthUnit::kMillimetre:
      return "mm";
  }
  return "?";
}

/// \brief Size of one unit in metres (1, 0.01, 0.001).
inline double unitInMetres(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kMetre:
      return 1.0;
    case LengthUnit::kCentimetre:
      return 0.01;
    case LengthUnit::kMillimetre:
      return 0.001;
  }
  return 1.0;
}

/// \brief The unit named "m", "cm" or "mm"; none for any other name.
inline std::optional<LengthUnit> lengthUnitNamed(const std::string& name) {
  if (name == "m") return LengthUnit::kMetre;
  if (name == "cm") return LengthUnit::kCentimetre;
  if (name == "mm") return LengthUnit::kMillimetre;
  return std::nullopt;
}

/// \brief What "length_unit" says of data whose unit is not recorded.
inline constexpr const char* kUnrecordedUnit = "unrecorded";

/// \brief The length unit of results: the data's (none when not recorded) and the one shown.
class ResultUnits {
 public:
  /// \param data the unit of the input's lengths, none when the input does not record one.
  /// \param shown the unit to give results in (--unit); none: the data's.
  ResultUnits(std::optional<LengthUnit> data, std::optional<LengthUnit> shown)
      : name_(kUnrecordedUnit) {
    if (data && shown) scale_ = unitInMetres(*data) / unitInMetres(*shown);
    if (shown || data) name_ = unitName(shown ? *shown : *data);
  }

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

}  // namespace mcws
