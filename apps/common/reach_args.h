#pragma once
/// \file
/// \brief The flags of the reachability tools (mcws_reach, mcws_place): how a map is built and
/// how targets are solved, declared and read in one place.

#include <memory>
#include <string>
#include <vector>

#include "common/app.h"
#include "mcws/collision/collision_checker.h"
#include "mcws/kinematics/robot.h"
#include "mcws/reach/reach_map.h"
#include "mcws/reach/reach_study.h"

namespace mcws::app {

/// \brief --resolution, --orientations, --rolls, --samples, --no-manipulability (with
/// --quality-task and --length, --seed and --threads, which the study shares).
void declareMapFlags(CommandLine& cli, const char* resolution_help);
/// \brief --quality-task, --length (declareQualityFlags()), --seed, --threads.
void declareSharedFlags(CommandLine& cli);
/// \brief --targets, --standoff, --approach-tolerance, --ik-starts, --no-collision.
void declareStudyFlags(CommandLine& cli);

/// \brief The grid of --resolution (required), --orientations (200), --rolls (1).
ReachGrid readReachGrid(const CommandLine& cli, const Robot& robot);
/// \brief --samples (default 5e8), --seed, --threads, --no-manipulability, the quality flags.
/// The collision checker is left to the caller.
ReachSampling readReachSampling(const CommandLine& cli, const Robot& robot);
/// \brief --approach-tolerance, --ik-starts, --seed, --threads, the quality flags.
ReachStudyOptions readReachStudyOptions(const CommandLine& cli, const Robot& robot);
/// \brief --targets (loadTargets()), each moved --standoff (a length, default 0) off its surface:
/// along its normal (minus the tool's z axis for a full pose), where the tool works from.
std::vector<ReachTarget> readTargets(const CommandLine& cli, const Robot& robot);
/// \brief The robot's collision checker for a study: nullptr with --no-collision or when the
/// robot file has no collision geometry.
/// \param environment false: the links and tool only (a map meant for other base positions).
std::unique_ptr<CollisionChecker> studyChecker(const CommandLine& cli, const Robot& robot,
                                               bool environment = true);

}  // namespace mcws::app
