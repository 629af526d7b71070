#include "mcws/kinematics/robot_urdf.h"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <cmath>
#include <mutex>
#include <sstream>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/core/text_file.h"

namespace mcws {
namespace {

/// Collects urdfdom's console_bridge messages instead of printing them, so that a failed parse
/// becomes one mcws::Error line.
class CapturedMessages : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR && first_error_.empty()) {
      first_error_ = text;
    }
  }
  const std::string& firstError() const { return first_error_; }

 private:
  std::string first_error_;
};

/// Message text on one line.
std::string oneLine(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

urdf::ModelInterfaceSharedPtr parseModel(const std::string& text, const std::string& source) {
  static std::mutex console_mutex;  // console_bridge's output handler is process-wide
  const std::lock_guard<std::mutex> lock(console_mutex);
  CapturedMessages messages;
  console_bridge::useOutputHandler(&messages);
  urdf::ModelInterfaceSharedPtr model;
  std::string exception_text;
  try {
    model = urdf::parseURDF(text);
  } catch (const std::exception& e) {
    exception_text = e.what();
  }
  console_bridge::restorePreviousOutputHandler();
  if (!model) {
    std::string why = !exception_text.empty() ? exception_text : messages.firstError();
    if (why.empty()) why = "not a valid URDF document";
    throw Error(source + ": malformed URDF: " + oneLine(why));
  }
  return model;
}

class ChainReader {
 public:
  ChainReader(const urdf::ModelInterface& model, std::string source)
      : model_(model), source_(std::move(source)) {}

  Robot read(const UrdfChainOptions& options) {
    const urdf::LinkConstSharedPtr root = rootLink(options.root_link);
    const urdf::LinkConstSharedPtr tip =
        options.tip_link.empty() ? singleLeaf(root) : link(options.tip_link, "tip");

    // Joints from the tip up to the root.
    std::vector<urdf::JointConstSharedPtr> joints;
    for (urdf::LinkConstSharedPtr current = tip; current != root;) {
      if (!current->parent_joint) {
        fail("tip link '" + tip->name + "' is not below root link '" + root->name + "'");
      }
      joints.push_back(current->parent_joint);
      current = model_.getLink(current->parent_joint->parent_link_name);
      if (!current) fail("joint '" + joints.back()->name + "' has no parent link");
    }

    Robot robot;
    robot.name = model_.getName();
    robot.source = source_;
    robot.length_unit = LengthUnit::kMetre;
    Eigen::Isometry3d T_fixed = Eigen::Isometry3d::Identity();  // fixed joints since the last move
    for (auto it = joints.rbegin(); it != joints.rend(); ++it) {
      const urdf::Joint& joint = **it;
      T_fixed = T_fixed * pose(joint);
      if (joint.type == urdf::Joint::FIXED) continue;
      robot.joints.push_back(movingJoint(joint, T_fixed));
      T_fixed = Eigen::Isometry3d::Identity();
    }
    if (robot.joints.empty()) {
      fail("no revolute, continuous or prismatic joint between root link '" + root->name +
           "' and tip link '" + tip->name + "'");
    }
    robot.T_last_flange = T_fixed;
    return robot;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw Error(source_ + ": " + what); }

  urdf::LinkConstSharedPtr link(const std::string& name, const std::string& role) const {
    urdf::LinkConstSharedPtr found = model_.getLink(name);
    if (!found)
      fail(role + " link '" + name + "' is not a link of robot '" + model_.getName() + "'");
    return found;
  }

  urdf::LinkConstSharedPtr rootLink(const std::string& name) const {
    if (!name.empty()) return link(name, "root");
    if (!model_.getRoot()) fail("the URDF has no root link");
    return model_.getRoot();
  }

  urdf::LinkConstSharedPtr singleLeaf(const urdf::LinkConstSharedPtr& root) const {
    std::vector<std::string> leaves;
    urdf::LinkConstSharedPtr leaf;
    std::vector<urdf::LinkConstSharedPtr> stack{root};
    while (!stack.empty()) {
      const urdf::LinkConstSharedPtr current = stack.back();
      stack.pop_back();
      if (current->child_links.empty()) {
        leaves.push_back(current->name);
        leaf = current;
      }
      for (const auto& child : current->child_links) stack.push_back(child);
    }
    if (leaves.size() != 1) {
      std::string list;
      for (const std::string& name : leaves) list += (list.empty() ? "" : ", ") + name;
      fail("link '" + root->name + "' has " + std::to_string(leaves.size()) +
           " leaf links below it (" + list + "); choose the tip link");
    }
    return leaf;
  }

  Eigen::Isometry3d pose(const urdf::Joint& joint) const {
    const urdf::Pose& p = joint.parent_to_joint_origin_transform;
    const double numbers[] = {p.position.x, p.position.y, p.position.z, p.rotation.x,
                              p.rotation.y, p.rotation.z, p.rotation.w};
    for (double value : numbers) {
      if (!std::isfinite(value)) fail("joint '" + joint.name + "': origin is not finite");
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
    if (joint.mimic) fail(label + ": mimic joints are not supported in a serial chain");
    switch (joint.type) {
      case urdf::Joint::REVOLUTE:
      case urdf::Joint::CONTINUOUS:
        out.type = JointType::kRevolute;
        break;
      case urdf::Joint::PRISMATIC:
        out.type = JointType::kPrismatic;
        break;
      case urdf::Joint::FLOATING:
        fail(label +
             ": floating joints are not supported (revolute, continuous, prismatic, fixed)");
      case urdf::Joint::PLANAR:
        fail(label + ": planar joints are not supported (revolute, continuous, prismatic, fixed)");
      default:
        fail(label + ": unknown joint type");
    }
    out.T_parent_joint = T_parent_joint;
    const Eigen::Vector3d axis(joint.axis.x, joint.axis.y, joint.axis.z);
    if (!axis.allFinite() || axis.norm() < 1e-12) {
      fail(label + ": axis must be a finite non-zero vector");
    }
    out.axis = axis.normalized();
    if (joint.type == urdf::Joint::CONTINUOUS) {
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

}  // namespace

Robot parseRobotUrdf(const std::string& text, const std::string& source,
                     const UrdfChainOptions& options) {
  const urdf::ModelInterfaceSharedPtr model = parseModel(text, source);
  return ChainReader(*model, source).read(options);
}

Robot loadRobotUrdf(const std::string& path, const UrdfChainOptions& options) {
  return parseRobotUrdf(readTextFile(path, "robot file"), path, options);
}

}  // namespace mcws
