#include "mcws/kinematics/robot_urdf.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/core/text_file.h"
#include "mcws/core/yaml_reader.h"
#include "mcws/kinematics/detail/urdf_guard.h"
#include "mcws/kinematics/forward_kinematics.h"

namespace mcws {
namespace {

/// The shortest text that reads back as `value` ("1e+308", "1000000000.5").
std::string shortest(double value) {
  char buffer[32];
  return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, value).ptr);
}

/// Reads a chain from a model that detail::parseUrdfModel() checked to be a tree, so its searches
/// up and down the tree end.
class ChainReader {
 public:
  ChainReader(const urdf::ModelInterface& model, std::string source)
      : model_(model), source_(std::move(source)) {}

  /// The links and joints of a chain.
  struct Chain {
    urdf::LinkConstSharedPtr base, tip;
    std::vector<urdf::JointConstSharedPtr> joints;  ///< from the base to the tip
  };

  Chain chain(const UrdfChainOptions& options) const {
    Chain chain;
    chain.base = baseLink(options.base_link);
    chain.tip =
        options.tip_link.empty() ? singleLeaf(chain.base, options) : tipLink(options, chain.base);
    for (urdf::LinkConstSharedPtr current = chain.tip; current != chain.base;) {
      if (!current->parent_joint) {
        throw chainError(UrdfChainError::Problem::kTipNotBelowBase, chain.base->name, options, {});
      }
      chain.joints.push_back(current->parent_joint);
      current = model_.getLink(current->parent_joint->parent_link_name);
      if (!current) fail("joint '" + chain.joints.back()->name + "' has no parent link");
    }
    std::reverse(chain.joints.begin(), chain.joints.end());
    return chain;
  }

  Robot robot(const Chain& chain) const {
    Robot robot;
    robot.name = model_.getName();
    robot.source = source_;
    robot.length_unit = LengthUnit::kMetre;
    robot.base_link = chain.base->name;
    robot.tip_link = chain.tip->name;
    const std::map<std::string, int> free = freeJoints(chain);
    Eigen::Isometry3d T_fixed = Eigen::Isometry3d::Identity();  // fixed joints since the last move
    for (const urdf::JointConstSharedPtr& joint : chain.joints) {
      T_fixed = T_fixed * pose(*joint);
      if (joint->type == urdf::Joint::FIXED) continue;
      const Coupling coupled = coupling(*joint, free);
      if (coupled.free < 0) {  // a mimic joint whose master is off the chain: fixed at its value
        T_fixed = T_fixed * motionAt(*joint, coupled.offset);
        continue;
      }
      const Joint moving = movingJoint(*joint, T_fixed);
      T_fixed = Eigen::Isometry3d::Identity();
      if (!joint->mimic) {
        robot.joints.push_back(moving);
      } else {
        robot.mimic_joints.push_back(
            {moving, robot.dof(), coupled.free, coupled.multiplier, coupled.offset});
      }
    }
    if (robot.joints.empty()) {
      fail("no revolute, continuous or prismatic joint between base link '" + chain.base->name +
           "' and tip link '" + chain.tip->name + "'");
    }
    robot.T_last_flange = T_fixed;
    return robot;
  }

  /// The `<collision>` elements of the links the chain carries, placed on their bodies (see
  /// loadRobotUrdfGeometry()). `robot` is robot(chain).
  std::vector<UrdfCollision> collisions(const Chain& chain, const Robot& robot) const {
    std::map<std::string, std::string> unplaced;  // link: why it cannot be placed
    const std::map<std::string, Place> places = linkPlaces(chain, robot, unplaced);
    std::vector<UrdfCollision> out;
    for (const auto& named : model_.links_) {  // by link name
      const urdf::Link& link = *named.second;
      if (link.collision_array.empty()) continue;
      const auto place = places.find(link.name);
      if (place == places.end()) {
        fail("link '" + link.name + "' has <collision> elements but is not part of the chain: " +
             notCarried(chain, link, unplaced));
      }
      for (std::size_t k = 0; k < link.collision_array.size(); ++k) {
        out.push_back(collisionElement(link, int(k) + 1, *link.collision_array[k], place->second));
      }
    }
    return out;
  }

 private:
  /// Where a link's frame sits on the chain.
  struct Place {
    UrdfBody body{UrdfBody::kBase};
    int joint{-1};  ///< kLink: the joint whose link carries it
    /// The link's frame in the body's frame [m]; for kTool in the last link's frame until the
    /// end of linkPlaces(), which turns it into the flange frame.
    Eigen::Isometry3d T_body_link{Eigen::Isometry3d::Identity()};
  };

  /// The place of every link the chain carries: the chain's own links, then the branches that
  /// hang off them, their joints at their default values (defaultValue()). `unplaced` receives,
  /// for the first link of each part that cannot be placed, why.
  std::map<std::string, Place> linkPlaces(const Chain& chain, const Robot& robot,
                                          std::map<std::string, std::string>& unplaced) const {
    std::map<std::string, Place> places;
    std::set<std::string> chain_joints;
    const std::map<std::string, int> free = freeJoints(chain);
    // The tool is what follows the last free joint's link rigidly: not so past a mimic joint.
    const bool mimic_at_end =
        !robot.mimic_joints.empty() && robot.mimic_joints.back().before == robot.dof();
    Place place;
    places[chain.base->name] = place;
    int moving = -1;
    std::string mimic;  // the mimic joint of the chain that the current link moves with
    for (const urdf::JointConstSharedPtr& joint : chain.joints) {
      chain_joints.insert(joint->name);
      const bool fixed = joint->type == urdf::Joint::FIXED || coupling(*joint, free).free < 0;
      if (!fixed) {
        mimic = joint->mimic ? joint->name : "";
        place = Place{UrdfBody::kLink, mimic.empty() ? ++moving : moving,
                      Eigen::Isometry3d::Identity()};
      } else {
        if (place.body == UrdfBody::kLink && place.joint == robot.dof() - 1 && !mimic_at_end) {
          place.body = UrdfBody::kTool;
        }
        place.T_body_link = place.T_body_link * pose(*joint) * fixedMotion(*joint, free);
      }
      if (mimic.empty()) {
        places[joint->child_link_name] = place;
      } else {
        unplaced[joint->child_link_name] =
            "it moves with joint '" + mimic + "', a mimic joint of the chain (not supported yet)";
      }
    }
    placeBranches(places, chain_joints, free, unplaced);
    const Eigen::Isometry3d T_flange_last = robot.T_last_flange.inverse();
    for (auto& named : places) {
      if (named.second.body != UrdfBody::kTool) continue;
      named.second.joint = -1;
      named.second.T_body_link = T_flange_last * named.second.T_body_link;
    }
    return places;
  }

  /// Places the links below the placed ones that joints off the chain lead to, those joints at
  /// their default values, rigidly on the body of the chain link they hang from.
  void placeBranches(std::map<std::string, Place>& places,
                     const std::set<std::string>& chain_joints,
                     const std::map<std::string, int>& free,
                     std::map<std::string, std::string>& unplaced) const {
    std::vector<std::string> stack;
    for (const auto& named : places) stack.push_back(named.first);
    while (!stack.empty()) {
      const urdf::LinkConstSharedPtr link = model_.getLink(stack.back());
      const Place parent = places.at(stack.back());
      stack.pop_back();
      for (const urdf::JointSharedPtr& joint : link->child_joints) {
        if (chain_joints.count(joint->name)) continue;
        const std::string why = branchProblem(*joint, free);
        if (!why.empty()) {
          unplaced[joint->child_link_name] = why;
          continue;
        }
        Place child = parent;
        if (child.body == UrdfBody::kBase) child.body = UrdfBody::kEnvironment;
        child.T_body_link = child.T_body_link * pose(*joint) * fixedMotion(*joint, free);
        places[joint->child_link_name] = child;
        stack.push_back(joint->child_link_name);
      }
    }
  }

  /// Why the links below a joint off the chain cannot hang rigidly from its parent, or "".
  std::string branchProblem(const urdf::Joint& joint,
                            const std::map<std::string, int>& free) const {
    if (joint.type == urdf::Joint::FLOATING || joint.type == urdf::Joint::PLANAR) {
      return std::string("it hangs below ") +
             (joint.type == urdf::Joint::FLOATING ? "floating" : "planar") + " joint '" +
             joint.name + "' (revolute, continuous, prismatic and fixed joints are supported)";
    }
    if (joint.type == urdf::Joint::FIXED) return "";
    const Coupling coupled = coupling(joint, free);
    if (coupled.free < 0) return "";
    return "it moves with joint '" + joint.name + "', which mimics joint '" +
           joint.mimic->joint_name + "' of the chain (a joint off the chain is posed at one value)";
  }

  /// Why the chain does not carry `link` (one that linkPlaces() did not place): the reason
  /// recorded for it or a link above it, else it is not below the base.
  std::string notCarried(const Chain& chain, const urdf::Link& link,
                         const std::map<std::string, std::string>& unplaced) const {
    for (urdf::LinkConstSharedPtr current = model_.getLink(link.name); current;) {
      const auto found = unplaced.find(current->name);
      if (found != unplaced.end()) return found->second;
      if (!current->parent_joint) break;
      current = model_.getLink(current->parent_joint->parent_link_name);
    }
    return "it is not below base link '" + chain.base->name + "' of the chain from link '" +
           chain.base->name + "' to link '" + chain.tip->name + "'";
  }

  /// One `<collision>` element of a link at `place`.
  UrdfCollision collisionElement(const urdf::Link& link, int element,
                                 const urdf::Collision& collision, const Place& place) const {
    const std::string label = "link '" + link.name + "' <collision> " + std::to_string(element);
    UrdfCollision out;
    out.link = link.name;
    out.element = element;
    out.body = place.body;
    out.joint = place.joint;
    out.T_body_geometry = place.T_body_link * pose(collision.origin, label);
    if (!collision.geometry) fail(label + ": has no geometry");
    const urdf::Geometry& geometry = *collision.geometry;
    switch (geometry.type) {
      case urdf::Geometry::SPHERE:
        out.type = UrdfGeometry::kSphere;
        out.radius =
            size(static_cast<const urdf::Sphere&>(geometry).radius, label, "sphere radius");
        break;
      case urdf::Geometry::BOX: {
        out.type = UrdfGeometry::kBox;
        const urdf::Vector3& dim = static_cast<const urdf::Box&>(geometry).dim;
        out.size = {size(dim.x, label, "box size x"), size(dim.y, label, "box size y"),
                    size(dim.z, label, "box size z")};
        break;
      }
      case urdf::Geometry::CYLINDER: {
        out.type = UrdfGeometry::kCylinder;
        const auto& cylinder = static_cast<const urdf::Cylinder&>(geometry);
        out.radius = size(cylinder.radius, label, "cylinder radius");
        out.length = size(cylinder.length, label, "cylinder length");
        break;
      }
      case urdf::Geometry::MESH: {
        out.type = UrdfGeometry::kMesh;
        const auto& mesh = static_cast<const urdf::Mesh&>(geometry);
        if (mesh.filename.empty()) fail(label + ": mesh has no filename");
        out.filename = mesh.filename;
        out.scale = {size(mesh.scale.x, label, "mesh scale x"),
                     size(mesh.scale.y, label, "mesh scale y"),
                     size(mesh.scale.z, label, "mesh scale z")};
        break;
      }
      default:
        fail(label + ": unknown geometry type");
    }
    return out;
  }

  /// How a joint's value depends on the free joints: multiplier * q[free] + offset, or just
  /// offset when `free` is -1 (a joint posed at one value).
  struct Coupling {
    int free{-1};
    double multiplier{0.0};
    double offset{0.0};  ///< [rad] or [m]
  };

  /// The free joints of the chain by name: its moving joints that mimic none, numbered in order.
  std::map<std::string, int> freeJoints(const Chain& chain) const {
    std::map<std::string, int> free;
    for (const urdf::JointConstSharedPtr& joint : chain.joints) {
      if (joint->type == urdf::Joint::FIXED) continue;
      movingType(*joint);  // refuses a floating or planar joint
      if (!joint->mimic) free.emplace(joint->name, static_cast<int>(free.size()));
    }
    return free;
  }

  /// How the value of moving joint `joint` follows the free joints: a free joint itself, a mimic
  /// joint through its master (value = multiplier * master + offset, masters followed to the
  /// end), any other joint at its default value. \throws mcws::Error for a mimic of a joint that
  /// is missing, fixed, floating or planar, non-finite mimic numbers, mimics that form a loop.
  Coupling coupling(const urdf::Joint& joint, const std::map<std::string, int>& free,
                    std::size_t depth = 0) const {
    if (!joint.mimic) {
      const auto found = free.find(joint.name);
      if (found != free.end()) return {found->second, 1.0, 0.0};
      return {-1, 0.0, defaultValue(joint)};
    }
    const std::string label = "joint '" + joint.name + "'";
    const std::string& name = joint.mimic->joint_name;
    if (depth > model_.joints_.size())
      fail(label + ": its <mimic> joints follow one another round");
    const urdf::JointConstSharedPtr master = model_.getJoint(name);
    if (!master) fail(label + ": <mimic> joint '" + name + "' is not a joint of the robot");
    if (master->type == urdf::Joint::FIXED) {
      fail(label + ": <mimic> joint '" + name + "' is a fixed joint");
    }
    movingType(*master);
    const double multiplier = joint.mimic->multiplier, offset = joint.mimic->offset;
    if (!std::isfinite(multiplier) || !std::isfinite(offset) ||
        std::abs(offset) > YamlReader::kLargestNumber ||
        std::abs(multiplier) > YamlReader::kLargestNumber) {
      fail(label + ": <mimic> multiplier and offset must be finite numbers (at most 1e9 in size)");
    }
    const Coupling master_coupling = coupling(*master, free, depth + 1);
    return {master_coupling.free, multiplier * master_coupling.multiplier,
            multiplier * master_coupling.offset + offset};
  }

  /// The value a joint off the chain is posed at [rad | m]: zero, or the value within its
  /// limits nearest zero (a continuous joint without limits: zero).
  static double defaultValue(const urdf::Joint& joint) {
    if (!joint.limits || !(joint.limits->lower <= joint.limits->upper)) return 0.0;
    if (joint.type == urdf::Joint::CONTINUOUS && !hasContinuousLimits(joint)) return 0.0;
    return joint.limits->lower > 0.0 ? joint.limits->lower : std::min(0.0, joint.limits->upper);
  }

  /// Whether a continuous joint states its range: a <limit> with lower < upper (urdfdom reads
  /// lower = upper = 0 when the attributes are missing).
  static bool hasContinuousLimits(const urdf::Joint& joint) {
    return joint.limits && joint.limits->lower < joint.limits->upper;
  }

  /// The motion of a moving joint at `value` [rad | m] (its type and axis only).
  Eigen::Isometry3d motionAt(const urdf::Joint& joint, double value) const {
    Joint moving;
    moving.type = movingType(joint);
    moving.axis = axisOf(joint);
    return jointMotion(moving, value);
  }

  /// The motion of a joint posed at one value (the identity for a fixed joint).
  Eigen::Isometry3d fixedMotion(const urdf::Joint& joint,
                                const std::map<std::string, int>& free) const {
    if (joint.type == urdf::Joint::FIXED) return Eigen::Isometry3d::Identity();
    return motionAt(joint, coupling(joint, free).offset);
  }

  /// The unit axis of a moving joint. \throws mcws::Error when it is zero or not finite.
  Eigen::Vector3d axisOf(const urdf::Joint& joint) const {
    const Eigen::Vector3d axis(joint.axis.x, joint.axis.y, joint.axis.z);
    if (!axis.allFinite() || axis.norm() < 1e-12) {
      fail("joint '" + joint.name + "': axis must be a finite non-zero vector");
    }
    return axis.normalized();
  }

  /// The type of a revolute, continuous or prismatic joint. \throws mcws::Error for others.
  JointType movingType(const urdf::Joint& joint) const {
    const std::string label = "joint '" + joint.name + "'";
    switch (joint.type) {
      case urdf::Joint::REVOLUTE:
      case urdf::Joint::CONTINUOUS:
        return JointType::kRevolute;
      case urdf::Joint::PRISMATIC:
        return JointType::kPrismatic;
      case urdf::Joint::FLOATING:
        fail(label +
             ": floating joints are not supported (revolute, continuous, prismatic, fixed)");
      case urdf::Joint::PLANAR:
        fail(label + ": planar joints are not supported (revolute, continuous, prismatic, fixed)");
      default:
        fail(label + ": unknown joint type");
    }
  }

  /// `value` when it is a finite number in (0, 1e9]. \throws mcws::Error naming `what`.
  double size(double value, const std::string& label, const std::string& what) const {
    if (!std::isfinite(value) || value <= 0.0 || value > YamlReader::kLargestNumber) {
      fail(label + ": " + what + " " + shortest(value) + " must be a number > 0 (at most 1e9)");
    }
    return value;
  }

  [[noreturn]] void fail(const std::string& what) const { throw Error(source_ + ": " + what); }

  UrdfChainError chainError(UrdfChainError::Problem problem, const std::string& base,
                            const UrdfChainOptions& options,
                            std::vector<std::string> leaves) const {
    return UrdfChainError(problem, source_, model_.getName(), base, !options.base_link.empty(),
                          options.tip_link, std::move(leaves));
  }

  urdf::LinkConstSharedPtr baseLink(const std::string& name) const {
    if (!name.empty()) {
      urdf::LinkConstSharedPtr found = model_.getLink(name);
      if (!found) throw chainError(UrdfChainError::Problem::kUnknownBase, name, {name, ""}, {});
      return found;
    }
    if (!model_.getRoot()) fail("the URDF has no root link");
    return model_.getRoot();
  }

  urdf::LinkConstSharedPtr tipLink(const UrdfChainOptions& options,
                                   const urdf::LinkConstSharedPtr& base) const {
    urdf::LinkConstSharedPtr found = model_.getLink(options.tip_link);
    if (!found) throw chainError(UrdfChainError::Problem::kUnknownTip, base->name, options, {});
    return found;
  }

  urdf::LinkConstSharedPtr singleLeaf(const urdf::LinkConstSharedPtr& root,
                                      const UrdfChainOptions& options) const {
    // Leaves that only fixed joints lead to (objects fixed to the base) end no chain: they count
    // only when there is no other leaf, so that the message is then the missing moving joint.
    std::vector<urdf::LinkConstSharedPtr> leaves, fixed_leaves;
    std::vector<std::pair<urdf::LinkConstSharedPtr, bool>> stack{{root, false}};  // link, moved
    while (!stack.empty()) {
      const auto [current, moved] = stack.back();
      stack.pop_back();
      if (current->child_links.empty()) (moved ? leaves : fixed_leaves).push_back(current);
      for (const auto& child : current->child_links) {
        stack.emplace_back(child, moved || child->parent_joint->type != urdf::Joint::FIXED);
      }
    }
    if (leaves.empty()) leaves = fixed_leaves;
    if (leaves.size() != 1) {
      std::vector<std::string> names;
      for (const auto& leaf : leaves) names.push_back(leaf->name);
      throw chainError(UrdfChainError::Problem::kSeveralLeaves, root->name, options, names);
    }
    return leaves.front();
  }

  Eigen::Isometry3d pose(const urdf::Joint& joint) const {
    return pose(joint.parent_to_joint_origin_transform, "joint '" + joint.name + "'");
  }

  /// The transform of an `<origin>`; `label` names its element in messages.
  Eigen::Isometry3d pose(const urdf::Pose& p, const std::string& label) const {
    const double numbers[] = {p.position.x, p.position.y, p.position.z, p.rotation.x,
                              p.rotation.y, p.rotation.z, p.rotation.w};
    for (double value : numbers) {
      if (!std::isfinite(value)) fail(label + ": origin is not finite");
    }
    for (double value : {p.position.x, p.position.y, p.position.z}) {
      if (std::abs(value) > YamlReader::kLargestNumber) {
        fail(label + ": origin coordinate " + shortest(value) +
             " is out of range (at most 1e9 in size)");
      }
    }
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
    T.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z)
                     .normalized()
                     .toRotationMatrix();
    return T;
  }

  Joint movingJoint(const urdf::Joint& joint, const Eigen::Isometry3d& T_parent_joint) const {
    const std::string label = "joint '" + joint.name + "'";
    Joint out;
    out.name = joint.name;
    if (out.name.find_first_of("=, \t") != std::string::npos) {
      fail(label + ": name contains '=', ',' or a space");
    }
    out.type = movingType(joint);
    out.T_parent_joint = T_parent_joint;
    out.axis = axisOf(joint);
    if (joint.type == urdf::Joint::CONTINUOUS && !hasContinuousLimits(joint)) {
      out.lower = -M_PI;
      out.upper = M_PI;
      return out;
    }
    if (!joint.limits) fail(label + ": a " + jointTypeName(out.type) + " joint needs <limit>");
    out.lower = joint.limits->lower;
    out.upper = joint.limits->upper;
    if (!std::isfinite(out.lower) || !std::isfinite(out.upper)) {
      fail(label + ": limits are not finite");
    }
    for (const auto& [bound, value] : {std::pair{"lower", out.lower}, {"upper", out.upper}}) {
      if (std::abs(value) > YamlReader::kLargestNumber) {
        fail(label + ": " + bound + " limit " + shortest(value) +
             " is out of range (at most 1e9 in size)");
      }
    }
    if (out.lower > out.upper) {
      std::ostringstream msg;
      msg.precision(10);
      msg << label << ": lower limit " << out.lower << " is greater than upper limit " << out.upper;
      fail(msg.str());
    }
    return out;
  }

  const urdf::ModelInterface& model_;
  std::string source_;
};

/// Throws when a URDF of `bytes` bytes is larger than kMaxUrdfBytes.
void checkUrdfSize(std::uintmax_t bytes, const std::string& source) {
  if (bytes > kMaxUrdfBytes) {
    throw Error(source + ": URDF of " + std::to_string(bytes) + " bytes is larger than " +
                std::to_string(kMaxUrdfBytes >> 20) + " MiB");
  }
}

/// "link 'world' has 2 leaf links below it (tool0, ee_link)".
std::string leavesText(const std::string& base, const std::vector<std::string>& leaves) {
  std::string list;
  for (const std::string& leaf : leaves) list += (list.empty() ? "" : ", ") + leaf;
  return "link '" + base + "' has " + std::to_string(leaves.size()) + " leaf links below it (" +
         list + ")";
}

/// The library's own line for a chain error: the roles in words ("tip link 'hand' ...").
std::string chainMessage(UrdfChainError::Problem problem, const std::string& source,
                         const std::string& robot, const std::string& base, const std::string& tip,
                         const std::vector<std::string>& leaves) {
  switch (problem) {
    case UrdfChainError::Problem::kUnknownBase:
      return source + ": base link '" + base + "' is not a link of robot '" + robot + "'";
    case UrdfChainError::Problem::kUnknownTip:
      return source + ": tip link '" + tip + "' is not a link of robot '" + robot + "'";
    case UrdfChainError::Problem::kTipNotBelowBase:
      return source + ": tip link '" + tip + "' is not below base link '" + base + "'";
    case UrdfChainError::Problem::kSeveralLeaves:
      break;
  }
  return source + ": " + leavesText(base, leaves) + ": choose the tip link";
}

}  // namespace

UrdfChainError::UrdfChainError(Problem problem, std::string source, std::string robot,
                               std::string base, bool base_given, std::string tip,
                               std::vector<std::string> leaves)
    : Error(chainMessage(problem, source, robot, base, tip, leaves)),
      problem_(problem),
      source_(std::move(source)),
      robot_(std::move(robot)),
      base_(std::move(base)),
      base_given_(base_given),
      tip_(std::move(tip)),
      leaves_(std::move(leaves)) {}

std::string UrdfChainError::describe(const std::string& base_option, const std::string& tip_option,
                                     const std::string& choose_tip) const {
  const std::string in = " in " + source_;
  switch (problem_) {
    case Problem::kUnknownBase:
      return base_option + ": '" + base_ + "' is not a link of robot '" + robot_ + "'" + in;
    case Problem::kUnknownTip:
      return tip_option + ": '" + tip_ + "' is not a link of robot '" + robot_ + "'" + in;
    case Problem::kTipNotBelowBase:
      return tip_option + ": link '" + tip_ + "' is not below " +
             (base_given_ ? base_option + " link '" : "the root link '") + base_ + "'" + in;
    case Problem::kSeveralLeaves:
      break;
  }
  return source_ + ": " + leavesText(base_, leaves_) + ": choose one with " + choose_tip;
}

Robot parseRobotUrdf(const std::string& text, const std::string& source,
                     const UrdfChainOptions& options) {
  checkUrdfSize(text.size(), source);
  const urdf::ModelInterfaceSharedPtr model = detail::parseUrdfModel(text, source);
  const ChainReader reader(*model, source);
  return reader.robot(reader.chain(options));
}

UrdfRobotGeometry parseRobotUrdfGeometry(const std::string& text, const std::string& source,
                                         const UrdfChainOptions& options) {
  checkUrdfSize(text.size(), source);
  std::vector<std::string> logged;
  const urdf::ModelInterfaceSharedPtr model = detail::parseUrdfModel(text, source, &logged);
  if (!logged.empty()) {  // urdfdom skipped an element it could not read
    std::string what;
    for (const std::string& message : logged) what += (what.empty() ? "" : "; ") + message;
    throw Error(source + ": unsupported or malformed element: " + detail::oneLine(what));
  }
  const ChainReader reader(*model, source);
  const ChainReader::Chain chain = reader.chain(options);
  UrdfRobotGeometry out;
  out.robot = reader.robot(chain);
  out.collisions = reader.collisions(chain, out.robot);
  for (const auto& link : model->links_) out.links.push_back(link.first);
  return out;
}

Robot loadRobotUrdf(const std::string& path, const UrdfChainOptions& options) {
  checkPrintableName(std::filesystem::path(path).filename().string(), "robot file");
  std::error_code ec;  // a file that cannot be sized is left to readTextFile's messages
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (!ec) checkUrdfSize(bytes, path);
  return parseRobotUrdf(readTextFile(path, "robot file"), path, options);
}

UrdfRobotGeometry loadRobotUrdfGeometry(const std::string& path, const UrdfChainOptions& options) {
  checkPrintableName(std::filesystem::path(path).filename().string(), "robot file");
  std::error_code ec;
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (!ec) checkUrdfSize(bytes, path);
  return parseRobotUrdfGeometry(readTextFile(path, "robot file"), path, options);
}

}  // namespace mcws
