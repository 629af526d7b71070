// The paths of the tools under test, as the build made them (tests/CMakeLists.txt defines
// MCWS_<TOOL>_EXE for test_apps). One definition for every test file of test_apps.
#pragma once

#include <string>

#include "test_support.h"

namespace mcws {

inline const std::string kBehave = MCWS_BEHAVE_EXE;
inline const std::string kBoundary = MCWS_BOUNDARY_EXE;
inline const std::string kCollide = MCWS_COLLIDE_EXE;
inline const std::string kEnvelope = MCWS_ENVELOPE_EXE;
inline const std::string kFk = MCWS_FK_EXE;
inline const std::string kIk = MCWS_IK_EXE;
inline const std::string kMeasure = MCWS_MEASURE_EXE;
inline const std::string kPlace = MCWS_PLACE_EXE;
inline const std::string kPlan = MCWS_PLAN_EXE;
inline const std::string kReach = MCWS_REACH_EXE;
inline const std::string kRefine = MCWS_REFINE_EXE;
inline const std::string kSample = MCWS_SAMPLE_EXE;
inline const std::string kSelect = MCWS_SELECT_EXE;
inline const std::string kTraj = MCWS_TRAJ_EXE;

// The robot most tool tests run on, as the flag that names it.
inline const std::string kInspection = " --robot " + test::robotPath("inspection6");

}  // namespace mcws
