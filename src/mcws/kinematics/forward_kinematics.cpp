#include "mcws/kinematics/forward_kinematics.h"

namespace mcws {
Eigen::Isometry3d jointMotion(const Joint& joint, double q) {
  Eigen::Isometry3d M = Eigen::Isometry3d::Identity();
  if (joint.type == JointType::kRevolute) {
    M.linear() = Eigen::AngleAxisd(q, joint.axis).toRotationMatrix();
  } else {
    M.translation() = q * joint.axis;
  }
  return M;
}

void applyMimicJoints(const Robot& robot, int before, const double* q, Eigen::Isometry3d& T) {
  for (const MimicJoint& mimic : robot.mimic_joints) {
    if (mimic.before == before) {
      T = T * mimic.joint.T_parent_joint * jointMotion(mimic.joint, mimicValue(mimic, q));
    }
  }
}

ChainPoses chainPoses(const Robot& robot, const Eigen::VectorXd& q) {
  robot.checkSize(q);
  ChainPoses poses;
  poses.T_world_joint.reserve(robot.joints.size());
  poses.T_world_link.reserve(robot.joints.size());
  Eigen::Isometry3d T = robot.T_world_base;
  for (int i = 0; i < robot.dof(); ++i) {
    applyMimicJoints(robot, i, q.data(), T);
    T = T * robot.joints[i].T_parent_joint;
    poses.T_world_joint.push_back(T);
    T = T * jointMotion(robot.joints[i], q[i]);
    poses.T_world_link.push_back(T);
  }
  applyMimicJoints(robot, robot.dof(), q.data(), T);
  poses.T_world_flange = T * robot.T_last_flange;
  poses.T_world_tool = poses.T_world_flange * robot.T_flange_tool;
  return poses;
}

Eigen::Isometry3d flangePose(const Robot& robot, const Eigen::VectorXd& q) {
  robot.checkSize(q);
  Eigen::Isometry3d T = robot.T_world_base;
  for (int i = 0; i < robot.dof(); ++i) {
    applyMimicJoints(robot, i, q.data(), T);
    T = T * robot.joints[i].T_parent_joint * jointMotion(robot.joints[i], q[i]);
  }
  applyMimicJoints(robot, robot.dof(), q.data(), T);
  return T * robot.T_last_flange;
}

Eigen::Isometry3d toolPose(const Robot& robot, const Eigen::VectorXd& q) {
  return flangePose(robot, q) * robot.T_flange_tool;
}

}  // namespace mcws
