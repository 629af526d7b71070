#pragma once
/// \file
/// \brief The clouds a boundary refinement reads: their joint fields and how their samples were
/// drawn, so that the new samples are drawn the same way.

#include <pcl/point_cloud.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "mcws/io/provenance.h"
#include "mcws/points/point_types.h"

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

/// \brief The points of `points` (the cloud of `cloud`) labelled `label`: the parents of a
/// refinement of the boundary of the region of that collision label only (mcws_refine
/// --collision), so that the collision-free region's edge, where free samples meet colliding
/// ones, fills in rather than the whole cloud's.
/// \param sampling how the cloud was sampled (recordRefineSampling()): it must record collision
///   labels (mcws_sample --collision), or every label reads 0.
/// \param label_name the label's name, for messages ("free").
/// \throws mcws::Error naming the flag and the file: a cloud with no field `label` (PCL would
///   read every label as 0), one sampled without collision labels, or one with no point labelled
///   `label`.
pcl::PointCloud<WorkspacePoint> labelledParents(const RefineCloud& cloud,
                                                const pcl::PointCloud<WorkspacePoint>& points,
                                                const io::SamplingRecord& sampling,
                                                std::uint32_t label, const std::string& label_name);

}  // namespace mcws
