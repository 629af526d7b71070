#pragma once
/// \file
/// \brief Serial chains read from URDF files (urdfdom) into the mcws::Robot model.

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/kinematics/robot.h"

namespace mcws {

/// \brief Largest URDF text read [bytes] (64 MiB, hundreds of times a large robot's URDF).
constexpr std::uintmax_t kMaxUrdfBytes = std::uintmax_t{64} << 20;

/// \brief Deepest element nesting handed to the XML parser. TinyXML, which urdfdom uses,
/// recurses once per nested element and overflows an 8 MB stack at some tens of thousands of
/// levels; a URDF nests about five.
constexpr int kMaxUrdfNesting = 1000;

/// \brief Which chain of a URDF tree to read (the tools' --base and --tip).
struct UrdfChainOptions {
  /// First link of the chain; its frame is the world frame. Empty: the tree's root link.
  std::string base_link;
  /// Last link of the chain, any link below base_link (a moving link, or a frame fixed to one
  /// such as `tool0` or a TCP link); its frame is the flange frame, and so the tool frame.
  /// Empty: the one leaf below base_link that a moving joint leads to (an error naming the
  /// leaves when there are several); leaves that only fixed joints lead to, objects fixed to the
  /// base, are passed over unless there is no other.
  std::string tip_link;
};

/// \brief A chain that UrdfChainOptions do not pick out: a base or tip that is not a link of the
/// robot, a tip that is not below the base, or no tip given and several leaves to choose from.
/// what() is the library's own line ("arm.urdf: tip link 'hand' is not a link of robot 'arm'");
/// describe() words it for the flags or keys the caller read the links from.
class UrdfChainError : public Error {
 public:
  enum class Problem { kUnknownBase, kUnknownTip, kTipNotBelowBase, kSeveralLeaves };

  /// \param base the base link, as given or (none given) the tree's root link.
  /// \param base_given whether the base link was chosen (UrdfChainOptions::base_link).
  /// \param tip the tip link given (kUnknownTip, kTipNotBelowBase).
  /// \param leaves the leaf links to choose from (kSeveralLeaves).
  UrdfChainError(Problem problem, std::string source, std::string robot, std::string base,
                 bool base_given, std::string tip, std::vector<std::string> leaves);

  Problem problem() const { return problem_; }

  /// \brief The message for a caller whose base and tip are named `base_option` and `tip_option`
  /// ("--base", "--tip"): "--tip: 'hand' is not a link of robot 'arm' in arm.urdf", "--tip: link
  /// 'link1' is not below --base link 'link3' in arm.urdf", "--base: 'torso' is not a link of
  /// robot 'arm' in arm.urdf", or "arm.urdf: link 'world' has 2 leaf links below it (tool0,
  /// ee_link): choose one with " + `choose_tip`.
  std::string describe(const std::string& base_option, const std::string& tip_option,
                       const std::string& choose_tip) const;

 private:
  Problem problem_;
  std::string source_, robot_, base_;
  bool base_given_;
  std::string tip_;
  std::vector<std::string> leaves_;
};

/// \brief Reads the serial chain from `base_link` to `tip_link` of a URDF file.
///
/// Mapping onto mcws::Robot (robot.h): each moving joint's `<origin>`, preceded by the origins of
/// the fixed joints since the previous moving joint, becomes `T_parent_joint`; its normalised
/// `<axis>` becomes `axis`. Fixed joints after the last moving joint form `T_last_flange`, so the
/// flange is the tip link's frame; `T_flange_tool` and `T_world_base` are the identity.
/// `revolute` and `prismatic` joints keep their `<limit lower upper>`; a `continuous` joint becomes
/// a revolute joint with its `<limit lower upper>` when it has one with lower < upper, else
/// [-pi, pi] (one full turn). Lengths are in metres (`length_unit` = kMetre), angles in [rad].
/// A `<mimic>` joint of the chain follows its master (value = multiplier x master + offset,
/// through mimics of mimics): when the master is a free joint of the chain it becomes a
/// Robot::mimic_joints entry, no degree of freedom of its own; when the master is off the chain
/// it is fixed at its value, the master posed at its default value (see
/// loadRobotUrdfGeometry()). Joints off the chain are not read, except as masters. Robot::base_link
/// and Robot::tip_link name the chain's two links (the tree's root and the leaf when not given).
/// \param path a `.urdf` file.
/// \param options base and tip links (default: the whole tree's root to its single leaf).
/// \throws mcws::Error, one line naming the file and the link or joint: missing or unreadable
///   file, a file larger than kMaxUrdfBytes, XML nested deeper than kMaxUrdfNesting elements,
///   text that is not UTF-8 or an XML declaration other than `<?xml name="value" ...?>` (the
///   nesting check needs both), malformed XML or URDF (urdfdom's message), joints that close a
///   loop or give a link a second parent, no moving joint, a floating or planar joint on the chain,
///   a `<mimic>` of a missing, fixed, floating or planar joint or mimics that follow one another
///   round, a moving joint without limits, limits in the wrong order, non-finite numbers, limits or
///   origin coordinates larger than 1e9 in size (as robot YAML files), a zero axis, a joint name
///   containing '=', ',' or a space; UrdfChainError (an mcws::Error) for an unknown base or tip
///   link, a tip that is not below the base, several leaves and no tip.
Robot loadRobotUrdf(const std::string& path, const UrdfChainOptions& options = {});

/// \brief As loadRobotUrdf(), from the URDF text.
/// \param text the XML text.
/// \param source name used in messages (usually the file name).
Robot parseRobotUrdf(const std::string& text, const std::string& source,
                     const UrdfChainOptions& options = {});

/// \brief The body of a chain that carries a URDF link (see UrdfCollision).
enum class UrdfBody {
  kBase,         ///< the base link, and the links fixed to it on the way to the first moving joint
  kLink,         ///< a link that moves with one joint of the chain
  kTool,         ///< fixed below the last moving joint, on the way to the tip link or below it
  kEnvironment,  ///< fixed to the base off the chain: an object that stays in the world frame
};

/// \brief Kind of a URDF collision geometry.
enum class UrdfGeometry { kSphere, kBox, kCylinder, kMesh };

/// \brief One `<collision>` element of a URDF link, placed on the body of the chain that carries
/// it. Lengths in metres, as in the file.
struct UrdfCollision {
  std::string link;  ///< the URDF link that holds the element
  int element{1};    ///< 1-based among that link's `<collision>` elements
  UrdfBody body{UrdfBody::kBase};
  int joint{-1};  ///< kLink: index (0-based) of the joint whose link carries the element
  /// Frame of the geometry (the link frame moved by the element's `<origin>`) in its body's frame
  /// [m]: the base link's frame (the robot's base frame) for kBase and kEnvironment, link `joint`'s
  /// frame (ChainPoses::T_world_link[joint]) for kLink, the flange frame (the tip link's frame) for
  /// kTool.
  Eigen::Isometry3d T_body_geometry{Eigen::Isometry3d::Identity()};
  UrdfGeometry type{UrdfGeometry::kSphere};
  double radius{0.0};                              ///< sphere, cylinder [m]
  double length{0.0};                              ///< cylinder, along z of its frame [m]
  Eigen::Vector3d size{Eigen::Vector3d::Zero()};   ///< box edges [m]
  std::string filename;                            ///< mesh, as written in the file
  Eigen::Vector3d scale{Eigen::Vector3d::Ones()};  ///< mesh, per axis
};

/// \brief A chain of a URDF file and the `<collision>` elements of the links it carries.
struct UrdfRobotGeometry {
  Robot robot;  ///< as loadRobotUrdf()
  std::vector<UrdfCollision> collisions;
  std::vector<std::string> links;  ///< every link name of the file, sorted (for SRDF pair names)
};

/// \brief Reads the chain of a URDF file (as loadRobotUrdf()) and places each `<collision>`
/// element of its links on the body of the chain that carries it.
///
/// A link is carried by the body that its path of fixed joints leads to: the links on the chain
/// from the base link to the first moving joint belong to the base; the child link of moving
/// joint i, and the links fixed below it, to link i; the links after the last moving joint's child
/// on the way to the tip link, and the links fixed below them, to the tool (so a flange or tool
/// link's geometry is the tool, placed in the flange frame); the other links fixed to the base
/// are environment objects. A branch off the chain (gripper fingers, a sensor, a second arm)
/// hangs rigidly from the chain link it starts at, each of its joints at its default value: zero,
/// or the value within its limits nearest zero (a continuous joint without limits: zero); a
/// mimic joint at multiplier x its master's value + offset. So fingers below the tool link are
/// tool geometry, and a second arm on the base is environment.
/// \param path a `.urdf` file.
/// \param options base and tip links, as loadRobotUrdf().
/// \throws mcws::Error as loadRobotUrdf(), and one line naming the file and the link for: an
///   error urdfdom logs and would skip (an unknown geometry such as `<capsule>`, a malformed
///   `scale`), a `<collision>` on a link the chain does not carry (moved by a joint outside the
///   chain, or not below the base link), a radius, length, box edge or mesh scale that is not a
///   finite number > 0, an origin that is not finite or larger than 1e9 in size.
UrdfRobotGeometry loadRobotUrdfGeometry(const std::string& path,
                                        const UrdfChainOptions& options = {});

/// \brief As loadRobotUrdfGeometry(), from the URDF text.
/// \param text the XML text.
/// \param source name used in messages (usually the file name).
UrdfRobotGeometry parseRobotUrdfGeometry(const std::string& text, const std::string& source,
                                         const UrdfChainOptions& options = {});

}  // namespace mcws
