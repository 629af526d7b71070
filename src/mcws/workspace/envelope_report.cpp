#include "mcws/workspace/envelope_report.h"

#include <cmath>
#include <string>

namespace mcws {

std::vector<ReportValue> envelopeValues(const Envelope& envelope, const MeasureOptions& options,
                                        const ResultUnits& units) {
  const std::string volume = units.volumeName();
  return {{"volume", units.volume(envelope.volume), volume},
          {"measure_volume", units.volume(envelope.measure.measure), volume},
          {"uncorrected", units.volume(envelope.measure.uncorrected), volume},
          {"area", units.area(envelope.area), units.areaName()},
          {"offset", units.length(envelope.offset), units.lengthName()},
          {"filled_volume", units.volume(envelope.filled), volume},
          {"alpha", options.alpha_factor, "local spacings"}};
}

std::vector<ReportValue> drawingValues(const EnvelopeDrawing& drawing, const ResultUnits& units) {
  const EnvelopeSection& side = drawing.side;
  const EnvelopeTopView& top = drawing.top;
  const auto deg = [](double radians) { return radians / (M_PI / 180.0); };
  const std::string length = units.lengthName();
  return {{"azimuth", deg(side.azimuth), "deg"},     {"section_area", side.area, units.areaName()},
          {"front_reach", side.front_reach, length}, {"back_reach", side.back_reach, length},
          {"section_highest", side.highest, length}, {"section_lowest", side.lowest, length},
          {"max_reach", top.max_reach, length},      {"min_reach", top.min_reach, length},
          {"swept_angle", deg(top.sweep), "deg"},    {"sweep_from", deg(top.sweep_from), "deg"},
          {"sweep_to", deg(top.sweep_to), "deg"},    {"highest", drawing.highest, length},
          {"lowest", drawing.lowest, length}};
}

namespace {

/// Each value under its name in `out` and its unit under `prefix` + name in `units`.
void addValues(const std::vector<ReportValue>& values, const std::string& prefix,
               nlohmann::json& out, nlohmann::json& units) {
  for (const ReportValue& value : values) {
    out[value.name] = value.value;
    units[prefix + value.name] = value.unit;
  }
}

}  // namespace

nlohmann::json envelopeSummary(const Envelope& envelope, const MeasureOptions& options,
                               const std::optional<EnvelopeDrawing>& drawing,
                               const ResultUnits& units) {
  const SurfaceTopology topology = surfaceTopology(envelope.mesh);
  nlohmann::json out{{"correction", options.edge_correction ? "efron" : "none"},
                     {"points", envelope.measure.points},
                     {"vertices", topology.vertices},
                     {"triangles", topology.triangles},
                     {"edges", topology.edges},
                     {"euler_characteristic", topology.euler_characteristic},
                     {"closed_and_oriented", topology.closedAndOriented()},
                     {"non_manifold_edges", topology.non_manifold_edges},
                     {"length_unit", units.lengthName()}};
  addValues(envelopeValues(envelope, options, units), "", out, out["units"]);
  if (drawing) addValues(drawingValues(*drawing, units), "drawing.", out["drawing"], out["units"]);
  return out;
}

}  // namespace mcws
