#pragma once
/// \file
/// \brief Collision geometry of a robot, its tool and its surroundings, read from the `collision:`
/// section of a robot YAML file or from the `<collision>` elements of a URDF file.

#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "mcws/collision/mesh_file.h"
#include "mcws/kinematics/robot.h"
#include "mcws/kinematics/robot_urdf.h"

namespace mcws {

/// \brief Kind of a collision shape.
enum class ShapeType { kCapsule, kSphere, kBox, kCylinder, kMesh };

/// \brief Name of a shape type ("capsule", "sphere", "box", "cylinder", "mesh").
const char* shapeTypeName(ShapeType type);

/// \brief One collision shape, placed in the frame of the body that carries it. Lengths are in
/// the robot's length unit.
///
/// - capsule: the points within `radius` of the segment [p_from, p_to] (the line-swept sphere, LSS,
///   of Fu, Hu, Chen & Pan 2016);
/// - sphere: the points within `radius` of p_from;
/// - box: edges `size`, centred at the origin of T_body_shape;
/// - cylinder: `radius`, `length` along z of T_body_shape, centred at its origin;
/// - mesh: the triangles of `mesh` (vertices already scaled) placed by T_body_shape.
struct ShapeSpec {
  ShapeType type{ShapeType::kSphere};
  Eigen::Isometry3d T_body_shape{Eigen::Isometry3d::Identity()};
  Eigen::Vector3d p_from{Eigen::Vector3d::Zero()};
  Eigen::Vector3d p_to{Eigen::Vector3d::Zero()};
  double radius{0.0};
  Eigen::Vector3d size{Eigen::Vector3d::Zero()};
  double length{0.0};
  std::shared_ptr<const TriangleMesh> mesh;
  std::string source;  ///< "file:line" of the shape, for messages
};

/// \brief A rigid body made of shapes.
struct BodySpec {
  std::string name;
  std::vector<ShapeSpec> shapes;
};

/// \brief Collision geometry of a robot.
///
/// Frames: `links[0]` is the base, placed in the robot's base frame (T_world_base);
/// `links[i]` (i = 1 .. dof) moves with joint i and is placed in that joint's frame after its
/// motion (ChainPoses::T_world_link[i-1]); for a standard D-H row the link's segment runs from
/// that frame's origin to (a cos(theta), a sin(theta), d). The tool is placed in the flange frame
/// and is mounted on the last link. Environment objects are placed in the world frame.
struct CollisionModel {
  std::vector<BodySpec> links;  ///< dof + 1 bodies: "base", then the joint names
  BodySpec tool;                ///< name "tool"
  std::vector<BodySpec> environment;
  /// Body pairs never checked, by name (adjacent links are never checked anyway).
  std::vector<std::pair<std::string, std::string>> allowed;
  /// A URDF model's links that carry geometry, each with the name of the body that carries it
  /// (a link fixed to another shares its body); empty for a YAML model, whose bodies are its links.
  std::vector<std::pair<std::string, std::string>> link_bodies;
  /// A URDF model's link names, with or without geometry (what an SRDF may name); empty for YAML.
  std::vector<std::string> link_names;
};

/// \brief Links of `model` that carry geometry, each with the body that carries it:
/// CollisionModel::link_bodies, or for a YAML model each body with shapes as its own link.
std::vector<std::pair<std::string, std::string>> linkBodies(const CollisionModel& model);

/// \brief Parses the `collision:` section of a robot YAML document.
///
/// \code{.yaml}
/// collision:
///   links:                    # base, or a joint name: the link that joint moves
///     base: [{type: capsule, from: [0, 0, -420], to: [0, 0, -330], radius: 180}]
///     j2:   [{type: capsule, from: [0, 0, 0], to: [560, 0, 0], radius: 90}]
///   tool:                     # in the flange frame
///     - {type: mesh, file: meshes/torch.stl, scale: 1, xyz: [0, 0, 0], rpy: [0, 0, 0]}
///   environment:              # in the world frame, each a named object of one shape
///     - {name: conductor, type: cylinder, radius: 1.5, length: 3000, xyz: [0, 0, 40],
///        rpy: [0, 90, 0]}
///   allowed: [[j1, j3]]       # pairs never checked
/// \endcode
/// Shapes: capsule (from, to, radius), sphere (center, radius), box (size, xyz, rpy), cylinder
/// (radius, length, xyz, rpy), mesh (file relative to the YAML file, STL, OBJ or COLLADA, scale,
/// xyz, rpy). Angles in the file's angle unit, lengths in its length unit.
/// \param robot the robot the same file describes (link names, length unit).
/// \param text the whole YAML document; \param source its file name, for messages and for mesh
///   paths.
/// \return an empty model (no shapes) when the document has no `collision:` key.
/// \throws mcws::Error "file:line: ..." naming the item for an unknown link or key, a
///   non-positive radius or size, a missing or empty mesh, an unknown body in `allowed`.
CollisionModel parseCollisionYaml(const Robot& robot, const std::string& text,
                                  const std::string& source);

/// \brief The collision model of a robot read from a URDF: the `<collision>` elements of the links
/// its chain carries.
///
/// Each element goes to the body that carries its link (loadRobotUrdfGeometry()): the base (the
/// base link and the links up to the first moving joint), link i (the child link of moving joint
/// i and the links fixed below it), the tool (links fixed after the last moving joint's child on
/// the way to the tip link, e.g. a flange or tool link, placed in the flange frame), or an
/// environment object named by its link (a link fixed to the base off the chain, in the world
/// frame; objects in the order of their link names, as urdfdom keeps no file order). Geometry:
/// `<sphere>`, `<box>`, `<cylinder>` (along z, centred on its origin, as ShapeType::kCylinder),
/// `<mesh filename scale>` of an STL, OBJ or COLLADA file (loadMesh(); a path relative to the
/// URDF file's directory, an absolute path, a `file://` URI, or a `package://` URI resolved as
/// ROS does through Robot::package_path and the `ROS_PACKAGE_PATH` variable, then upward from the
/// URDF's folder: resolvePackageUri(), collision/package_uri.h; other URIs are errors). URDF has
/// no capsule: a
/// `<cylinder>` and two `<sphere>`s of its radius centred on its end faces, in one body, are read
/// as one capsule, which is the same set of points, so that it is tested by the exact segment
/// distance as a YAML capsule is. Adjacent links are not checked (as for YAML); URDF gives no other
/// allowed pairs (loadCollisionModel() adds an SRDF's). Lengths are converted from metres to the
/// robot's length unit. \param robot the chain read from the same text (joint names must match).
/// \param text the URDF text; \param source its file name, for messages and mesh paths. \param
/// chain base and tip links, as given to loadRobotUrdf() for `robot`. \throws mcws::Error, one line
/// naming the file and the link: as loadRobotUrdfGeometry(); a
///   chain whose joints are not the robot's; an unsupported mesh URI or format; a package not
///   found (naming the URI and every place looked); a missing or
///   unreadable mesh; an environment link named as the base, the tool or a joint.
CollisionModel parseCollisionUrdf(const Robot& robot, const std::string& text,
                                  const std::string& source, const UrdfChainOptions& chain = {});

/// \brief parseCollisionUrdf() of a file. \throws mcws::Error when the file cannot be read.
CollisionModel loadCollisionUrdf(const Robot& robot, const std::string& path,
                                 const UrdfChainOptions& chain = {});

/// \brief The collision model of a robot file: loadCollisionUrdf() of the chain `robot` was read
/// as (Robot::base_link to Robot::tip_link, so a robot read with --base/--tip gets the geometry of
/// that chain) for a `.urdf` file, else parseCollisionYaml() of the file; with Robot::srdf, less
/// the pairs that SRDF disables (applySrdf(), collision/srdf.h).
/// \throws mcws::Error when a file cannot be read, and as those three and loadSrdf().
CollisionModel loadCollisionModel(const Robot& robot, const std::string& path);

/// \brief True when the model has at least one shape.
bool hasGeometry(const CollisionModel& model);

/// \brief loadCollisionModel() for a run that needs collision geometry (labelled sampling,
/// collision checks). \throws mcws::Error "<path>: has no collision geometry (collision: key)",
/// or "(no <collision> element on a link of its chain)" for a URDF, when the model has no shape.
CollisionModel loadRequiredCollisionModel(const Robot& robot, const std::string& path);

/// \brief Reads a triangle mesh (STL, OBJ or COLLADA, by extension; see mcws::readMeshFile(); a
/// COLLADA file's vertices in metres) and scales it; polygons with more than three corners are
/// fanned into triangles.
/// \param scale factor applied to the vertices (e.g. 1000 for a file in metres and a robot in mm).
/// \throws mcws::Error naming the file when it is missing, not a regular file, malformed, holds
///   no triangles, or a coordinate that is not a finite number or, as written or scaled, larger
///   than kLargestMeshCoordinate in size.
TriangleMesh loadMesh(const std::string& path, double scale);

/// \brief Scales the vertices of `mesh` read from `path` by `factor`, per axis.
/// \throws mcws::Error "'path': coordinate c times scale f is out of range (at most 1e9 in size)"
///   when a scaled coordinate is larger than kLargestMeshCoordinate in size (or not finite).
void scaleMesh(TriangleMesh& mesh, const Eigen::Vector3d& factor, const std::string& path);

}  // namespace mcws
