#pragma once
/// \file
/// \brief The summary of a refinement that a report (mcws_refine --json) gives.

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mcws/io/provenance.h"
#include "mcws/kinematics/robot.h"
#include "mcws/workspace/refine.h"

namespace mcws {

/// \brief What a refinement did, as JSON: "robot", "tip" (tipName() of the point refined),
/// "length_unit", "boundary_points" (the parents),
/// "samples" (new), "copied" (points of the copied cloud), "points" (copied + new), "spread"
/// [joint ranges], "seed", "pinned" (the pinned joints' names, RefineSampler::pinnedJoints()),
/// and the sampling the cloud records, "point" and "collision"; with "units".
nlohmann::json refineSummary(const Robot& robot, std::size_t boundary_points, std::size_t samples,
                             std::size_t copied, const RefineOptions& options,
                             const std::vector<std::string>& pinned,
                             const io::SamplingRecord& sampling);

}  // namespace mcws
