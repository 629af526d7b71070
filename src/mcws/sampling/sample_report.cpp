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

}  // namespace mcws
