#pragma once
/// \file
/// \brief Serial chains read from URDF files (urdfdom) into the mcws::Robot model.

#include <cstdint>
#include <string>

#include "mcws/kinematics/robot.h"

namespace mcws {

/// \brief Largest URDF text read [bytes] (64 MiB, hundreds of times a large robot's URDF).
constexpr std::uintmax_t kMaxUrdfBytes = std::uintmax_t{64} << 20;

/// \brief Deepest element nesting handed to the XML parser. TinyXML, which urdfdom uses,
/// recurses once per nested element and overflows an 8 MB stack at some tens of thousands of
/// levels; a URDF nests about five.
constexpr int kMaxUrdfNesting = 1000;

/// \brief Which chain of a URDF tree to read.
struct UrdfChainOptions {
  /// First link of the chain; its frame is the world frame. Empty: the tree's root link.
  std::string root_link;
  /// Last link of the chain; its frame is the tool frame. Empty: the one leaf below root_link
  /// (an error naming the leaves when there are several).
  std::string tip_link;
};

/// \brief Reads the serial chain from `root_link` to `tip_link` of a URDF file.
///
/// Mapping onto mcws::Robot (robot.h): each moving joint's `<origin>`, preceded by the origins of
/// the fixed joints since the previous moving joint, becomes `T_parent_joint`; its normalised
/// `<axis>` becomes `axis`. Fixed joints after the last moving joint form `T_last_flange`, so the
/// flange is the tip link's frame; `T_flange_tool` and `T_world_base` are the identity.
/// `revolute` and `prismatic` joints keep their `<limit lower upper>`; a `continuous` joint becomes
/// a revolute joint with limits [-pi, pi] (one full turn). Lengths are in metres
/// (`length_unit` = kMetre), angles in [rad]. `<mimic>` is not supported.
/// \param path a `.urdf` file.
/// \param options root and tip links (default: the whole tree's root to its single leaf).
/// \throws mcws::Error, one line naming the file and the link or joint: missing or unreadable
///   file, a file larger than kMaxUrdfBytes, XML nested deeper than kMaxUrdfNesting elements,
///   text that is not UTF-8 or an XML declaration other than `<?xml name="value" ...?>` (the
///   nesting check needs both), malformed XML or URDF (urdfdom's message), joints that close a
///   loop or give a link a second parent, unknown root or tip link, a tip that is not below the
///   root, several leaves and no tip, no moving joint, a floating, planar or mimic joint, a moving
///   joint without limits, limits in the wrong order, non-finite numbers, limits or origin
///   coordinates larger than 1e9 in size (as robot YAML files), a zero axis, a joint name
///   containing '=', ',' or a space.
Robot loadRobotUrdf(const std::string& path, const UrdfChainOptions& options = {});

/// \brief As loadRobotUrdf(), from the URDF text.
/// \param text the XML text.
/// \param source name used in messages (usually the file name).
Robot parseRobotUrdf(const std::string& text, const std::string& source,
                     const UrdfChainOptions& options = {});

}  // namespace mcws
