#pragma once
// Chains and references shared by the kinematics and reach tests: a chain unlike the shipped
// robots, and the Jacobian by central differences of forward kinematics.

#include <Eigen/Geometry>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/jacobian.h"
#include "mcws/kinematics/robot.h"

namespace mcws::test {

/// Every robots/*.yaml, so a newly shipped robot is covered without editing a test (behaviour
/// models, *_behaviors.yaml, are not robots).
inline std::vector<std::string> shippedRobotFiles() {
  std::set<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(MCWS_ROBOTS_DIR)) {
    const std::string name = entry.path().filename().string();
    const bool behaviors =
        name.size() > 15 && name.compare(name.size() - 15, 15, "_behaviors.yaml") == 0;
    if (entry.path().extension() == ".yaml" && !behaviors) files.insert(entry.path().string());
  }
  return {files.begin(), files.end()};
}

/// Step of differenceJacobian() [rad | length unit].
constexpr double kDifferenceStep = 1e-5;

/// A chain with tilted joint axes, a base and a tool offset, one prismatic joint: the shipped
/// robots all move about or along z in D-H frames, URDF chains need not.
inline Robot tiltedAxesRobot() {
  Robot robot;
  robot.name = "tilted";
  robot.T_world_base = poseFromXyzRpy({0.1, -0.2, 0.3}, {0.2, -0.1, 0.5});
  const Eigen::Vector3d axes[] = {{0, 0, 1}, {0, 1, 0}, {1, 1, 0}, {0, 0, -1}, {0.3, -0.5, 0.8}};
  for (int i = 0; i < 5; ++i) {
    Joint joint;
    joint.name = "j" + std::to_string(i + 1);
    joint.type = i == 3 ? JointType::kPrismatic : JointType::kRevolute;
    joint.axis = axes[i].normalized();
    joint.T_parent_joint = poseFromXyzRpy({0.05 * i, 0.3, 0.1}, {0.3 * i, -0.2, 0.1 * i});
    joint.lower = -2.0;
    joint.upper = 2.0;
    robot.joints.push_back(joint);
  }
  robot.T_last_flange = poseFromXyzRpy({0, 0, 0.2}, {0, 0.4, 0});
  robot.T_flange_tool = poseFromXyzRpy({0.1, 0, 0.15}, {0.1, 0, 0});
  return robot;
}

/// The geometric Jacobian by central differences of toolPose() (forward_kinematics.h, not the
/// KinematicChain that builds the analytic one): linear rows from the tool point, angular rows
/// from the rotation vector of R(q + h) R(q - h)^T over 2h (the world-frame angular velocity).
inline Jacobian differenceJacobian(const Robot& robot, const Eigen::VectorXd& q) {
  Jacobian J(6, robot.dof());
  for (int i = 0; i < robot.dof(); ++i) {
    Eigen::VectorXd plus = q, minus = q;
    plus[i] += kDifferenceStep;
    minus[i] -= kDifferenceStep;
    const Eigen::Isometry3d T_plus = toolPose(robot, plus), T_minus = toolPose(robot, minus);
    J.col(i).head<3>() = (T_plus.translation() - T_minus.translation()) / (2 * kDifferenceStep);
    const Eigen::AngleAxisd turn(T_plus.linear() * T_minus.linear().transpose());
    J.col(i).tail<3>() = turn.angle() * turn.axis() / (2 * kDifferenceStep);
  }
  return J;
}

}  // namespace mcws::test
