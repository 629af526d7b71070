#pragma once
/// \file
/// \brief The numbers of an envelope and of its datasheet drawing, each with its unit, as
/// mcws_envelope reports them.

#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "mcws/core/length_unit.h"
#include "mcws/core/report_value.h"
#include "mcws/workspace/drawing.h"
#include "mcws/workspace/envelope.h"

namespace mcws {

/// \brief The volumes, area and offset of `envelope` (in the cloud's length unit) converted to
/// `units`: volume, measure_volume, uncorrected, area, offset, filled_volume; and alpha, the
/// alpha factor of `options` [local spacings].
std::vector<ReportValue> envelopeValues(const Envelope& envelope, const MeasureOptions& options,
                                        const ResultUnits& units);

/// \brief The numbers of `drawing`, whose lengths are already in `units` (it was drawn from the
/// converted mesh): the side view's azimuth, section_area, front_reach, back_reach,
/// section_highest and section_lowest, the top view's max_reach, min_reach, swept_angle,
/// sweep_from and sweep_to, and the envelope's highest and lowest; angles in degrees.
std::vector<ReportValue> drawingValues(const EnvelopeDrawing& drawing, const ResultUnits& units);

/// \brief The report of `envelope` as JSON: "correction" (efron or none, from `options`),
/// "points", the mesh's surfaceTopology() ("vertices", "triangles", "edges",
/// "euler_characteristic", "closed_and_oriented", "non_manifold_edges"), every envelopeValues()
/// under its name and, with a drawing, its drawingValues() in "drawing"; "length_unit" and a
/// "units" entry for each number ("drawing.<name>" for the drawing's).
nlohmann::json envelopeSummary(const Envelope& envelope, const MeasureOptions& options,
                               const std::optional<EnvelopeDrawing>& drawing,
                               const ResultUnits& units);

}  // namespace mcws
