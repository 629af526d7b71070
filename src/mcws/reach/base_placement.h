#pragma once
/// \file
/// \brief Where to put the robot's base so its arm reaches a set of targets: every candidate base
/// position scored from the reachability map, the best confirmed by inverse kinematics (the
/// inverse-reachability question of Zacharias et al. 2007 and ROS Reuleaux, asked of a line or
/// grid of base positions: the power-line robot stopping along its conductor).

#include <pcl/point_types.h>
#include <pcl/register_point_struct.h>

#include <Eigen/Geometry>
#include <functional>
#include <string>
#include <vector>

#include "mcws/reach/reach_map.h"
#include "mcws/reach/reach_study.h"

namespace mcws {

/// \brief Whether the map marks a target reachable with the robot moved by `offset` (a
/// translation of the whole robot, world frame [length unit]): the voxel holding the target
/// point less the offset has the target's orientation bin. A free-roll target counts any roll bin
/// of its approach's direction region; with `approach_tolerance` > 0 [rad] also of the regions of
/// directions around the approach out to the tolerance (rings spaced, and probes along each ring
/// spaced, at most half a region's diameter apart, so no region that reaches well inside the
/// tolerance cone is missed). A full pose counts its own bin only.
bool mapReaches(const ReachMap& map, const ReachTarget& target, const Eigen::Vector3d& offset,
                double approach_tolerance, float* manipulability = nullptr);

/// \brief One candidate base position and its scores.
struct BaseCandidate {
  Eigen::Vector3d offset{Eigen::Vector3d::Zero()};  ///< the robot's move [length unit]
  double map_share{0.0};  ///< share of the targets the map marks reachable [1]
  /// Mean over the targets of the best manipulability of the target's voxel where the map marks
  /// it reachable, 0 elsewhere: an estimate of the IK score (above it at the rims of the reach,
  /// where a voxel only partly reachable counts; below it where the samples missed a bin).
  double map_score{0.0};
  bool confirmed{false};  ///< inverse kinematics was run here
  ReachSummary ik;        ///< the reach study at this position (when confirmed)
};

/// \brief Settings of placeBase().
struct PlacementOptions {
  /// Candidates confirmed by inverse kinematics whatever their map share: the best `confirm` by
  /// the map (share, then score, then order); a negative value confirms all.
  int confirm{5};
  /// Also confirmed: every candidate whose map share is at least the best map share less this
  /// margin [share of the targets, 0..1]; negative: none by margin. The map's manipulability
  /// score is not trusted to rank them (it is the best of a voxel's samples, luck of the draw).
  double confirm_margin{-1.0};
  double approach_tolerance{0.0};  ///< as ReachStudyOptions::approach_tolerance [rad]
};

/// \brief The candidates placeBase() confirms, by index, in the map's order (share, then score,
/// then index): the best `confirm` and every one within `confirm_margin` of the best share.
std::vector<std::size_t> candidatesToConfirm(const std::vector<BaseCandidate>& candidates,
                                             const PlacementOptions& options);

/// \brief The offsets of a grid of base positions [length unit]: every (x, y, z) of `xs` x `ys`
/// x `zs`, z fastest, then y, then x.
std::vector<Eigen::Vector3d> offsetGrid(const std::vector<double>& xs,
                                        const std::vector<double>& ys,
                                        const std::vector<double>& zs);

/// \brief Scores every offset from the map, confirms those candidatesToConfirm() names by the
/// study (the robot and collision model it holds, the environment staying in place).
/// \param progress called with (steps done, all steps) now and then.
std::vector<BaseCandidate> placeBase(
    const ReachMap& map, const ReachStudy& study, const std::vector<ReachTarget>& targets,
    const std::vector<Eigen::Vector3d>& offsets, const PlacementOptions& options,
    const std::function<void(std::size_t, std::size_t)>& progress = {});

/// \brief Index of the best confirmed candidate: highest IK share, then IK mean score, then the
/// first; -1 when none is confirmed.
int bestCandidate(const std::vector<BaseCandidate>& candidates);

/// \brief PNG: the map's and the confirmed IK share reached against the offset along x.
/// \throws mcws::Error when gnuplot fails.
std::string renderPlacementPng(const std::vector<BaseCandidate>& candidates,
                               const std::string& title, const std::string& unit);

/// \brief A candidate base as a PCD point: `x y z` where the robot's base frame lands [length
/// unit], `map_share`, `map_score`, `ik_share` and `ik_score` (-1 where not confirmed).
struct EIGEN_ALIGN16 BasePoint {
  PCL_ADD_POINT4D;
  float map_share;
  float map_score;
  float ik_share;
  float ik_score;
  BasePoint()
      : data{0.f, 0.f, 0.f, 1.f}, map_share(0.f), map_score(0.f), ik_share(-1.f), ik_score(-1.f) {}
  PCL_MAKE_ALIGNED_OPERATOR_NEW
};

/// \brief The candidates as points, in their order: where the base frame T_world_base lands
/// after each offset.
std::vector<BasePoint> basePoints(const std::vector<BaseCandidate>& candidates,
                                  const Eigen::Isometry3d& T_world_base);

}  // namespace mcws

// clang-format off
POINT_CLOUD_REGISTER_POINT_STRUCT(mcws::BasePoint,
    (float, x, x) (float, y, y) (float, z, z)
    (float, map_share, map_share) (float, map_score, map_score)
    (float, ik_share, ik_share) (float, ik_score, ik_score))
// clang-format on
