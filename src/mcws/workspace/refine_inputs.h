#pragma once
/// \file
/// \brief The clouds a boundary refinement reads: their joint fields and how their samples were
/// drawn, so that the new samples are drawn the same way.

#include <string>
#include <utility>
#include <vector>

#include "mcws/io/provenance.h"

namespace mcws {

/// \brief A cloud a refinement reads, named by the flag that gave it: {"input", "b.pcd"}.
using RefineCloud = std::pair<std::string, std::string>;

/// \brief Checks the clouds a refinement reads and records in `provenance` how their samples
/// were drawn: each cloud must come from the robot of `provenance` (io::requireSameRobot), have
/// the joint fields q1..q`dof` (a mcws_reach map or a PCL cloud would load with every joint at
/// 0) and record how it was sampled (point=, collision=, fix=), the same for every cloud.
/// \param provenance the robot's (robotProvenance()); its `sampling` is set to the clouds'.
/// \throws mcws::Error naming the flag and the file: an unreadable PCD header, a missing joint
///   field, no record or one older than the sampling record, another robot, or two clouds
///   sampled differently.
void recordRefineSampling(const std::vector<RefineCloud>& clouds, int dof,
                          io::CloudProvenance& provenance);

}  // namespace mcws
