#include "mcws/trajectory/trajectory_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/kinematics/forward_kinematics.h"

namespace mcws {
namespace {

using ::testing::StartsWith;

// Planar arm: revolute 'shoulder' at the origin, prismatic 'slide' along the link, 10 cm flange.
Robot slideArm() {
  Robot robot;
  robot.name = "slide";
  robot.length_unit = LengthUnit::kCentimetre;
  Joint shoulder, slide;
  shoulder.name = "shoulder";
  shoulder.lower = -M_PI;
  shoulder.upper = M_PI;
  slide.name = "slide";
  slide.type = JointType::kPrismatic;
  slide.axis = Eigen::Vector3d::UnitX();
  slide.upper = 50;
  robot.joints = {shoulder, slide};
  robot.T_last_flange.translation() = Eigen::Vector3d(10, 0, 0);
  return robot;
}

std::vector<double> numbers(const std::string& line) {
  std::vector<double> out;
  std::istringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) out.push_back(std::stod(cell));
  return out;
}

TEST(TrajectoryCsv, HeaderNamesJointsAndEveryRowHoldsStateAndToolPosition) {
  const Robot robot = slideArm();
  const JointTrajectory traj = pointToPoint(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(1.0, 20.0),
                                            2.0, TimeProfile::kQuintic);
  const SampledTrajectory s = sampleTrajectory(traj, 4.0);
  const std::string csv = trajectoryCsv(robot, s);
  std::istringstream lines(csv);
  std::string line;
  std::getline(lines, line);
  // Each column's unit in its name: rad for the revolute joint, the robot's cm for the slide.
  EXPECT_EQ(line,
            "t_s,shoulder_rad,slide_cm,shoulder_rad_per_s,slide_cm_per_s,shoulder_rad_per_s2,"
            "slide_cm_per_s2,x_cm,y_cm,z_cm");
  int rows = 0;
  while (std::getline(lines, line)) {
    const std::vector<double> v = numbers(line);
    ASSERT_EQ(v.size(), 10u);
    const double t = rows / 4.0;
    EXPECT_DOUBLE_EQ(v[0], t);
    EXPECT_NEAR(v[1], traj.position(t)[0], 1e-11);
    EXPECT_NEAR(v[4], traj.velocity(t)[1], 1e-10);
    EXPECT_NEAR(v[6], traj.acceleration(t)[1], 1e-10);
    // Tool at radius (slide + 10) cm in direction shoulder.
    EXPECT_NEAR(v[7], (v[2] + 10) * std::cos(v[1]), 1e-9);
    EXPECT_NEAR(v[8], (v[2] + 10) * std::sin(v[1]), 1e-9);
    EXPECT_EQ(v[9], 0.0);
    ++rows;
  }
  EXPECT_EQ(rows, 9);
}

TEST(TrajectoryCsv, WrittenInPiecesIsTheSameText) {
  const Robot robot = slideArm();
  const SampledTrajectory s =
      sampleTrajectory(pointToPoint(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(1.0, 20.0), 2.0,
                                    TimeProfile::kQuintic),
                       4.0);  // 9 samples
  std::string joined;
  std::vector<std::size_t> done;
  std::vector<int> lines;
  writeTrajectoryCsv(
      robot, s,
      [&](const std::string& piece, std::size_t n) {
        joined += piece;
        done.push_back(n);
        lines.push_back(static_cast<int>(std::count(piece.begin(), piece.end(), '\n')));
      },
      4);
  EXPECT_EQ(joined, trajectoryCsv(robot, s));
  EXPECT_EQ(done, (std::vector<std::size_t>{4, 8, 9}));
  EXPECT_EQ(lines, (std::vector<int>{5, 4, 1}));  // the header goes with the first piece
}

TEST(TrajectoryCsv, RejectsATrajectoryOfAnotherRobot) {
  const SampledTrajectory s = sampleTrajectory(
      pointToPoint(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 1.0, TimeProfile::kCubic), 2);
  try {
    trajectoryCsv(slideArm(), s);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "trajectory of 3 joints and 3 samples does not fit robot 'slide' with 2 joints");
  }
}

TEST(TrajectoryPng, GnuplotRendersAPicture) {
  const Robot robot = slideArm();
  const SampledTrajectory s =
      sampleTrajectory(pointToPoint(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(1.0, 20.0), 2.0,
                                    TimeProfile::kQuintic),
                       50.0);
  const std::string png = renderTrajectoryPng(robot, s, "it's a test");  // quote in the title
  EXPECT_THAT(png, StartsWith("\x89PNG"));
  EXPECT_GT(png.size(), 10000u);
}

}  // namespace
}  // namespace mcws
