#pragma once
/// \file
/// \brief The moving joints of a chain in chain order, free and mimic, for the kinematics kernels
/// that turn each joint's axis onto z (KinematicChain, PointKinematics).

#include <vector>

#include "mcws/kinematics/robot.h"

namespace mcws::detail {

/// \brief The moving joints of a chain: each free joint, preceded by the mimic joints that sit
/// before it (Robot::mimic_joints), and last the mimic joints before the flange.
struct ChainMotions {
  std::vector<const Joint*> joints;  ///< type, axis and T_parent_joint of each
  std::vector<int> source;           ///< per joint: its free joint's index, or -1 - k: mimics[k]
  std::vector<const MimicJoint*> mimics;
};

inline ChainMotions chainMotions(const Robot& robot) {
  ChainMotions motions;
  for (int i = 0; i <= robot.dof(); ++i) {
    for (const MimicJoint& mimic : robot.mimic_joints) {
      if (mimic.before != i) continue;
      motions.joints.push_back(&mimic.joint);
      motions.source.push_back(-1 - static_cast<int>(motions.mimics.size()));
      motions.mimics.push_back(&mimic);
    }
    if (i == robot.dof()) break;
    motions.joints.push_back(&robot.joints[i]);
    motions.source.push_back(i);
  }
  return motions;
}

}  // namespace mcws::detail
