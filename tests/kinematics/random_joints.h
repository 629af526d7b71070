#pragma once
// Random joint vectors for the kinematics tests.

#include <Eigen/Core>
#include <random>

#include "mcws/kinematics/robot.h"

namespace mcws::test {

/// Joint values drawn uniformly within each joint's limits [rad | length unit].
inline Eigen::VectorXd randomJoints(const Robot& robot, std::mt19937_64& rng) {
  Eigen::VectorXd q(robot.dof());
  for (int i = 0; i < robot.dof(); ++i) {
    q[i] =
        std::uniform_real_distribution<double>(robot.joints[i].lower, robot.joints[i].upper)(rng);
  }
  return q;
}

}  // namespace mcws::test
