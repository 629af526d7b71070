#include "common/units.h"

#include "common/cloud_io.h"
#include "common/flags.h"
#include "mcws/core/error.h"

namespace mcws::app {
namespace {

LengthUnit unitNamed(const std::string& name) {
  if (name == "m") return LengthUnit::kMetre;
  if (name == "cm") return LengthUnit::kCentimetre;
  return LengthUnit::kMillimetre;  // "mm": the only other name parseChoice() and provenance allow
}

}  // namespace

ResultUnits::ResultUnits(std::optional<LengthUnit> data, std::optional<LengthUnit> shown)
    : name_(kUnrecordedUnit) {
  if (data && shown) scale_ = unitInMetres(*data) / unitInMetres(*shown);
  if (shown || data) name_ = unitName(shown ? *shown : *data);
}

void declareUnitFlag(CommandLine& cli) {
  cli.addValue("unit", "give lengths, areas and volumes in m, cm or mm (default: the data's unit)");
}

ResultUnits readResultUnits(const CommandLine& cli, std::optional<LengthUnit> data,
                            const std::string& what) {
  if (!cli.has("unit")) return {data, std::nullopt};
  const LengthUnit shown = unitNamed(parseChoice(cli.required("unit"), "unit", {"m", "cm", "mm"}));
  if (!data) {
    throw Error("--unit " + cli.required("unit") + ": " + what +
                " records no length unit to convert from (a cloud of mcws_sample --shape, or one "
                "written before clouds recorded their robot)");
  }
  return {data, shown};
}

std::vector<std::string> jointUnits(const Robot& robot, const std::string& per) {
  std::vector<std::string> units;
  for (const Joint& joint : robot.joints) {
    units.push_back((joint.type == JointType::kRevolute ? "rad" : unitName(robot.length_unit)) +
                    per);
  }
  return units;
}

std::optional<LengthUnit> recordedUnit(const std::string& cloud_path) {
  const std::optional<io::CloudProvenance> recorded = readProvenance(cloud_path);
  if (!recorded) return std::nullopt;
  return unitNamed(recorded->length_unit);
}

}  // namespace mcws::app
