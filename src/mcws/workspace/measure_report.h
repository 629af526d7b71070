#pragma once
/// \file
/// \brief The area or volume of a region as a report (mcws_measure --json) gives it: each number
/// with its unit.

#include <cstdint>
#include <nlohmann/json.hpp>

#include "mcws/core/length_unit.h"
#include "mcws/workspace/measure.h"

namespace mcws {

/// \brief delaunayMeasure()'s result as JSON, measures converted to `units`: "area" (2
/// dimensions) or "volume" (3), "uncorrected", "correction" (efron or none, from `options`),
/// "alpha" (its factor [local spacings]), "points", "triangulated", "boundary_vertices",
/// "outside", with their "units".
nlohmann::json regionMeasureJson(const RegionMeasure& measured, const MeasureOptions& options,
                                 int dimensions, const ResultUnits& units);

/// \brief delaunayMeasureSubset()'s result as JSON for the points labelled `label`: the subset's
/// "area" or "volume", "uncorrected", "points" and "outside" (its weighted share of the whole
/// cloud's Efron count), "label", "correction", "alpha", "triangulated" and "boundary_vertices" (of
/// the whole cloud's triangulation), and "all": the whole cloud's area or volume, "uncorrected",
/// "points" and "outside", measured the same way; with their "units".
nlohmann::json subsetMeasureJson(const SubsetMeasure& measured, std::uint32_t label,
                                 const MeasureOptions& options, int dimensions,
                                 const ResultUnits& units);

/// \brief columnArea()'s result as JSON, converted to `units`: "area", "column_width",
/// "crossing_gap", "columns", "odd_columns", with their "units".
nlohmann::json columnAreaJson(const ColumnArea& column, const ResultUnits& units);

/// \brief What a cross-check by the column method says of an area measured by delaunayMeasure().
constexpr char kColumnCrossCheckNote[] =
    "Yin, Wang & Yu 2010's column method, biased high: for comparison, not the result";

/// \brief Adds the column method's area to regionMeasureJson()'s of the same plane region:
/// "cross_check" {"method": "column", "area" (in `units`), "note" (kColumnCrossCheckNote)} and
/// its unit, "cross_check.area" in "units".
void addColumnCrossCheck(nlohmann::json& out, const ColumnArea& column, const ResultUnits& units);

}  // namespace mcws
