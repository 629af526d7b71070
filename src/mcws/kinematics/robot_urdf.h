#pragma once
/// \file
/// \brief Serial chains read from URDF files (urdfdom) into the mcws::Robot model.

#include <string>

#include "mcws/kinematics/robot.h"

namespace mcws {

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
///   file, malformed XML or URDF (urdfdom's message), unknown root or tip link, a tip that is not
///   below the root, several leaves and no tip, no moving joint, a floating, planar or mimic
///   joint, a moving joint without limits, limits in the wrong order, non-finite numbers, a zero
///   axis, a joint name containing '=', ',' or a space.
Robot loadRobotUrdf(const std::string& path, const UrdfChainOptions& options = {});

/// \brief As loadRobotUrdf(), from the URDF text.
/// \param text the XML text.
/// \param source name used in messages (usually the file name).
Robot parseRobotUrdf(const std::string& text, const std::string& source,
                     const UrdfChainOptions& options = {});

}  // namespace mcws
