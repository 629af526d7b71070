#include "mcws/sampling/sample_report.h"

#include "mcws/core/length_unit.h"

namespace mcws {

nlohmann::json shapeSummary(const std::string& name, Shape shape) {
  const char* measure = shapeIsPlanar(shape) ? "area" : "volume";
  return {
      {"shape", name},
      {measure, shapeMeasure(shape)},
      {"length_unit", kUnrecordedUnit},
      {"units", {{measure, std::string(kUnrecordedUnit) + (shapeIsPlanar(shape) ? "^2" : "^3")}}}};
}

void addBoundingBox(nlohmann::json& summary, const SampleSummary& result,
                    const std::string& length_unit) {
  summary["bbox"] = {{"min", {result.min.x(), result.min.y(), result.min.z()}},
                     {"max", {result.max.x(), result.max.y(), result.max.z()}}};
  summary["units"]["bbox.min"] = length_unit;
  summary["units"]["bbox.max"] = length_unit;
}

std::string tipName(const Robot& robot, SamplePoint point) {
  if (!robot.tip_link.empty()) return robot.tip_link;
  return point == SamplePoint::kFlange ? "flange" : "tool";
}

void addRobotNames(nlohmann::json& out, const Robot& robot, SamplePoint point) {
  out["robot"] = robot.name;
  out["tip"] = tipName(robot, point);
}

void addRecordedRobotNames(nlohmann::json& out,
                           const std::optional<io::CloudProvenance>& recorded) {
  out["robot"] = recorded ? nlohmann::json(recorded->robot) : nlohmann::json();
  const std::optional<std::string> tip = recorded ? io::recordedTip(*recorded) : std::nullopt;
  out["tip"] = tip ? nlohmann::json(*tip) : nlohmann::json();
}

}  // namespace mcws
