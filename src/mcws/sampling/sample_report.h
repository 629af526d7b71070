#pragma once
/// \file
/// \brief What a report of a sampling run (mcws_sample --json) says of its source and its points,
/// each number with its unit.

#include <nlohmann/json.hpp>
#include <string>

#include "mcws/sampling/sampler.h"

namespace mcws {

/// \brief A validation shape named `name` as JSON: "shape", its exact "area" (planar) or "volume"
/// (shapeMeasure()), "length_unit" (kUnrecordedUnit: a shape has none) and the measure's unit.
nlohmann::json shapeSummary(const std::string& name, Shape shape);

/// \brief Adds the points' bounding box to `summary`: "bbox" {"min", "max"} [x, y, z] and their
/// unit `length_unit` in "units" ("bbox.min", "bbox.max").
void addBoundingBox(nlohmann::json& summary, const SampleSummary& result,
                    const std::string& length_unit);

}  // namespace mcws
