#pragma once
/// \file
/// \brief A reachability map file (mcws_reach --map) read for a base placement, its header
/// checked against the robot the placement moves.

#include <cstdint>
#include <string>

#include "mcws/kinematics/robot.h"
#include "mcws/reach/reach_map.h"

namespace mcws {

/// \brief Reads the map file `path` (docs/reach_map.md) for placing the base of `robot`: its
/// header must name the robot and its length unit, record the SHA-256 of the same robot file (the
/// same name and unit are not the same robot: the file may have been edited since), not count only
/// samples free of the environment (moved with the base, the environment's shadow would move
/// too), measure manipulability as `manipulability` says, and, when it records a URDF chain
/// (`base_link`, `tip_link`), be of the chain `robot` was read as.
/// \param robot_file the robot file as the user named it (--robot), for the messages.
/// \param manipulability how the placement measures manipulability, as the compact JSON text of
///   mcws_reach's "manipulability" member; a map whose header has none or null passes.
/// \param samples receives the header's sample count (0 when it records none).
/// \throws mcws::Error naming the file: missing or unreadable, another robot or unit, no or
///   another SHA-256, another chain, collision-filtered, another manipulability, or a header
///   member of the wrong type.
ReachMap readPlacementMap(const std::string& path, const Robot& robot,
                          const std::string& robot_file, const std::string& manipulability,
                          std::uint64_t& samples);

/// \brief The checks of readPlacementMap() on a map's header (the JSON text ReachMap::read()
/// gives, or mapFileHeader()'s): `path` names the map in the messages.
/// \throws mcws::Error as readPlacementMap() does for the header.
void checkPlacementMap(const std::string& header, const std::string& path, const Robot& robot,
                       const std::string& robot_file, const std::string& manipulability,
                       std::uint64_t& samples);

}  // namespace mcws
