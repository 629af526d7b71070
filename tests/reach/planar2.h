#pragma once
// robots/planar2.yaml, the two-link arm the reach tests work by hand.

#include <cmath>

#include "mcws/kinematics/robot.h"
#include "test_support.h"

namespace mcws::test {

constexpr double kDeg = M_PI / 180.0;
/// Upper arm and forearm [cm].
constexpr double kL1 = 40.0, kL2 = 30.0;
/// The elbow's joint limit, either way [rad].
constexpr double kElbowLimit = 160.0 * kDeg;

inline Robot planar2() { return loadRobot(robotPath("planar2")); }

}  // namespace mcws::test
