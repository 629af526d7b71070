#pragma once
/// \file
/// \brief Target poses of a reach study (mcws_reach --targets, mcws_place) from PCD or CSV.

#include <string>
#include <vector>

#include "mcws/reach/reach_study.h"

namespace mcws {

/// \brief Loads targets, in the robot's world frame and length unit.
///
/// - `.pcd` with fields x y z normal_x normal_y normal_z (pcl::PointNormal, as
///   `pcl_mesh_sampling` writes from a workpiece mesh): a point and its surface normal each; the
///   tool approaches against the normal, its roll free (targetFromNormal()).
/// - `.csv` whose first line names the columns, either `x,y,z,normal_x,normal_y,normal_z` (the
///   same) or `x,y,z,roll,pitch,yaw` (full poses, angles in rad, R = Rz(yaw) Ry(pitch) Rx(roll)
///   as URDF and mcws_ik --pose); blank lines and lines starting with # are skipped.
/// \throws mcws::Error naming the file (and line) for a missing file, a PCD without normals, a CSV
///   with another header, a value that is not a finite number, a zero normal, or no targets.
std::vector<ReachTarget> loadTargets(const std::string& path);

/// \brief Moves every target `standoff` [length unit] off its surface, where the tool works from:
/// along its normal (minus its z axis, the approach of the tool).
void applyStandoff(std::vector<ReachTarget>& targets, double standoff);

}  // namespace mcws
