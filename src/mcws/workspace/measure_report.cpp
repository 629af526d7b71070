#include "mcws/workspace/measure_report.h"

#include <string>

namespace mcws {

nlohmann::json regionMeasureJson(const RegionMeasure& measured, const MeasureOptions& options,
                                 int dimensions, const ResultUnits& units) {
  auto measure = [&](double v) { return dimensions == 2 ? units.area(v) : units.volume(v); };
  const char* key = dimensions == 2 ? "area" : "volume";
  const std::string unit = units.measureName(dimensions);
  return {{key, measure(measured.measure)},
          {"correction", options.edge_correction ? "efron" : "none"},
          {"alpha", options.alpha_factor},
          {"points", measured.points},
          {"triangulated", measured.triangulated},
          {"uncorrected", measure(measured.uncorrected)},
          {"boundary_vertices", measured.boundary_vertices},
          {"outside", measured.outside},
          {"units", {{key, unit}, {"uncorrected", unit}, {"alpha", "local spacings"}}}};
}

nlohmann::json subsetMeasureJson(const SubsetMeasure& measured, std::uint32_t label,
                                 const MeasureOptions& options, int dimensions,
                                 const ResultUnits& units) {
  auto measure = [&](double v) { return dimensions == 2 ? units.area(v) : units.volume(v); };
  const std::string key = dimensions == 2 ? "area" : "volume";
  const std::string unit = units.measureName(dimensions);
  return {{key, measure(measured.measure)},
          {"label", label},
          {"correction", options.edge_correction ? "efron" : "none"},
          {"alpha", options.alpha_factor},
          {"points", measured.points},
          {"uncorrected", measure(measured.uncorrected)},
          {"outside", measured.outside},
          {"triangulated", measured.all.triangulated},
          {"boundary_vertices", measured.all.boundary_vertices},
          {"all",
           {{key, measure(measured.all.measure)},
            {"uncorrected", measure(measured.all.uncorrected)},
            {"points", measured.all.points},
            {"outside", measured.all.outside}}},
          {"units",
           {{key, unit},
            {"uncorrected", unit},
            {"all." + key, unit},
            {"all.uncorrected", unit},
            {"alpha", "local spacings"}}}};
}

nlohmann::json columnAreaJson(const ColumnArea& column, const ResultUnits& units) {
  return {{"area", units.area(column.area)},
          {"column_width", units.length(column.width)},
          {"crossing_gap", units.length(column.gap)},
          {"columns", column.columns},
          {"odd_columns", column.odd_columns},
          {"units",
           {{"area", units.areaName()},
            {"column_width", units.lengthName()},
            {"crossing_gap", units.lengthName()}}}};
}

void addColumnCrossCheck(nlohmann::json& out, const ColumnArea& column, const ResultUnits& units) {
  out["cross_check"] = {
      {"method", "column"}, {"area", units.area(column.area)}, {"note", kColumnCrossCheckNote}};
  out["units"]["cross_check.area"] = units.areaName();
}

}  // namespace mcws
