#pragma once
/// \file
/// \brief The JSON summaries of the reach tools: how manipulability is measured, a reachability
/// map, a reach study and a base placement, each number with its unit.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mcws/kinematics/robot.h"
#include "mcws/reach/base_placement.h"
#include "mcws/reach/quality.h"
#include "mcws/reach/reach_map.h"
#include "mcws/reach/reach_study.h"

namespace mcws {

/// \brief How manipulability is measured: "task", "characteristic_length" (with its unit) and
/// "manipulability_unit": 1 for the full task; for the position task length^k, k = min(n, 3),
/// or, when a joint is prismatic, a mixture said in words.
nlohmann::json qualitySummary(const QualityOptions& quality, const Robot& robot);

/// \brief The summary of a map of `samples` samples (mcws_reach): the grid, the counts, the
/// occupied volume (voxels times the voxel's volume) [length unit^3], the mean reachability
/// index [1], how manipulability was measured (null without it) and whether only
/// collision-free samples counted.
nlohmann::json mapSummary(const Robot& robot, const ReachGrid& grid, const ReachSampling& sampling,
                          std::uint64_t samples, const ReachMap& map, bool collision);

/// \brief The summary of a reach study (mcws_reach --targets): the counts and means of
/// summarize(), the smallest clearance of a reached target [length unit] (null when none),
/// the approach tolerance [deg] and, per target not reached, whether IK solved it, its collision
/// label, its position error [length unit] and orientation error [deg].
nlohmann::json studySummary(const Robot& robot, const ReachStudyOptions& options,
                            const std::vector<TargetReach>& results, bool collision);

/// \brief One candidate of a placement: its offset [length unit], the map's share and score and,
/// where IK confirmed it, IK's (else null).
nlohmann::json candidateJson(const BaseCandidate& candidate);

/// \brief How a placement chose the positions it confirmed by IK: "margin_share" (every position
/// whose map share is at least the best less it, a fraction of the targets; null: none by
/// margin), "best_by_map" (that many best by the map in any case; -1: all), "confirmed" (how many
/// were) and "rule" (the rule in words).
nlohmann::json confirmationJson(const PlacementOptions& options,
                                const std::vector<BaseCandidate>& candidates);

/// \brief The summary of a base placement (mcws_place) over `targets` targets: the map's grid
/// and `map_about` (where it came from), every candidate and the best (index `best`, -1: none)
/// with its base position in the world [length unit].
nlohmann::json placementSummary(const Robot& robot, std::size_t targets, const ReachMap& map,
                                const nlohmann::json& map_about, const ReachStudyOptions& options,
                                bool collision, const std::vector<BaseCandidate>& candidates,
                                int best);

/// \brief The header a map file records (ReachMap::write()): the robot, the base name and
/// SHA-256 of its file, the length unit, and of `summary` (mapSummary()) the samples, seed,
/// collision and manipulability, so that a reader (mcws_place --map) can check them; for a URDF
/// robot also its chain's `base_link` and `tip_link` (Robot::base_link, tip_link).
std::string mapFileHeader(const Robot& robot, const std::string& robot_file,
                          const std::string& robot_sha256, const nlohmann::json& summary);

/// \brief The identity of one process's part of a map run that its checkpoint records
/// (ReachCheckpoint::run): the robot, its file's SHA-256, the grid, the samples of the whole run,
/// the seed, whether only collision-free samples count, how manipulability is measured, the
/// process count and rank, and a URDF robot's chain (`base_link`, `tip_link`), so that a
/// checkpoint of another run is refused.
std::string checkpointRun(const Robot& robot, const std::string& robot_sha256,
                          const ReachGrid& grid, const ReachSampling& sampling,
                          std::uint64_t samples, bool collision, int processes, int rank);

}  // namespace mcws
