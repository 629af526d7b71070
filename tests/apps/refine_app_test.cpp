// mcws_refine through its command line.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <pcl/io/pcd_io.h>

#include <cstdio>
#include <nlohmann/json.hpp>

#include "apps/tool_paths.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/robot_yaml.h"
#include "mcws/points/point_types.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

pcl::PointCloud<WorkspacePoint> readCloud(const std::string& path) {
  pcl::PointCloud<WorkspacePoint> cloud;
  EXPECT_EQ(pcl::io::loadPCDFile(path, cloud), 0) << path;
  return cloud;
}

/// The joint values of a point, as doubles.
Eigen::VectorXd jointsOf(const WorkspacePoint& p, int dof) {
  Eigen::VectorXd q(dof);
  for (int j = 0; j < dof; ++j) q[j] = p.q[j];
  return q;
}

class RefineApp : public ::testing::Test {
 protected:
  void SetUp() override {
    cloud_ = dir_.file("ws.pcd");
    rim_ = dir_.file("rim.pcd");
    ASSERT_EQ(test::run(std::string(MCWS_SAMPLE_EXE) + " --robot " + test::robotPath("deicing") +
                        " --fix theta3=0 --samples 20000 --output " + cloud_)
                  .exit_code,
              0);
    ASSERT_EQ(test::run(std::string(MCWS_BOUNDARY_EXE) + " --input " + cloud_ +
                        " --plane xz --output " + rim_)
                  .exit_code,
              0);
  }
  std::string args(const std::string& output, const std::string& extra = "") const {
    return "--robot " + test::robotPath("deicing") + " --input " + rim_ + " --output " + output +
           " " + extra;
  }
  void expectFailure(const std::string& a, int exit_code, const std::string& message) {
    test::expectToolFailure(kRefine, a, exit_code, message, nothing_written_);
  }
  test::TempDir dir_, nothing_written_;
  std::string cloud_, rim_;
};

TEST_F(RefineApp, HelpExitsZero) {
  const test::RunResult r = test::run(kRefine + " --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, HasSubstr("--spread"));
}

TEST_F(RefineApp, WritesTheCloudThenTheNewSamplesTheSameForAnyThreadCount) {
  const std::string one = dir_.file("one.pcd"), two = dir_.file("two.pcd");
  const test::RunResult r = test::run(
      kRefine + " " + args(one, "--cloud " + cloud_ + " --samples 7000 --threads 1 --json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto summary = nlohmann::json::parse(r.out);
  EXPECT_EQ(summary["copied"], 20000);
  EXPECT_EQ(summary["samples"], 7000);
  EXPECT_EQ(summary["points"], 27000);
  EXPECT_EQ(summary["pinned"], nlohmann::json::array({"theta3"}));
  ASSERT_EQ(
      test::run(kRefine + " " + args(two, "--cloud " + cloud_ + " --samples 7000 --threads 2"))
          .exit_code,
      0);
  EXPECT_EQ(test::run("cmp " + one + " " + two).exit_code, 0);
  // The measure of the refined cloud, through the next stage of the pipeline.
  const test::RunResult m = test::run(std::string(MCWS_MEASURE_EXE) + " --input " + one +
                                      " --plane xz --correction none --json");
  ASSERT_EQ(m.exit_code, 0) << m.err;
  EXPECT_EQ(nlohmann::json::parse(m.out)["correction"], "none");
  EXPECT_EQ(nlohmann::json::parse(m.out)["alpha"], 5.0);  // the default for refined clouds
}

TEST_F(RefineApp, RejectsBadInput) {
  const std::string out = nothing_written_.file("out.pcd");
  expectFailure(args(out), 2, "--samples");
  expectFailure(args(out, "--samples 0"), 2, "--samples");
  expectFailure(args(out, "--samples 10 --spread 0"), 2, "--spread");
  expectFailure(args(out, "--samples 10 --spread 1.5"), 2, "--spread");
  expectFailure(args(out, "--samples 10 --spread x"), 2, "--spread");
  expectFailure(args(out, "--samples 10 --point elbow"), 2,
                "--point: 'elbow' is not tool or flange");
  expectFailure(args(out, "--samples 10 --spread 2"), 2, "--spread: 2 is not in (0, 1]");
  expectFailure(args(out, "--samples 10 --seed=-3"), 2, "--seed: -3 is less than 0");
  expectFailure(args(out, "--samples 10 --threads 300"), 2, "--threads: 300 is more than 256");
  // A cloud of no robot (a shape): it does not record how it was sampled.
  const std::string disk = dir_.file("disk.pcd");
  ASSERT_EQ(test::run(std::string(MCWS_SAMPLE_EXE) + " --shape disk --samples 100 --output " + disk)
                .exit_code,
            0);
  expectFailure("--robot " + test::robotPath("deicing") + " --input " + disk +
                    " --samples 10 --output " + out,
                1, "--input '" + disk + "' does not record how it was sampled");
  expectFailure(
      "--robot " + test::robotPath("nosuch") + " --input " + rim_ + " --samples 10 --output " + out,
      1, "--robot: " + test::robotPath("nosuch") + ": robot file does not exist");
  expectFailure("--robot " + test::robotPath("deicing") + " --input " + dir_.file("missing.pcd") +
                    " --samples 10 --output " + out,
                1, "missing.pcd");
}

/// Refinement draws its samples as the cloud's were (issue 31, section 3): at the recorded point,
/// with the recorded joints pinned, labelled by collision for a --collision cloud; a cloud that
/// cannot say how it was sampled, or has no joint values, is refused.
class RefineReproducesTheSampling : public ::testing::Test {
 protected:
  std::string sample(const std::string& name, const std::string& flags,
                     const std::string& robot = "deicing") {
    const std::string path = dir_.file(name);
    const test::RunResult r = test::run(kSample + " --robot " + test::robotPath(robot) + " " +
                                        flags + " --output " + path);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return path;
  }
  test::RunResult refine(const std::string& input, const std::string& output,
                         const std::string& extra = "", const std::string& robot = "deicing") {
    return test::run(kRefine + " --robot " + test::robotPath(robot) + " --input " + input +
                     " --samples 300 --output " + output + " " + extra);
  }
  test::TempDir dir_, nothing_written_;
};

// Position agreement of the float cloud with the FK in double [mm]: the TA1400's points are
// floats of up to about 2000 mm (ulp 1.2e-4 mm) from float joint values (ulp 6e-8 rad, 1.2e-4 mm
// at 2000 mm).
constexpr double kPositionTolerance = 1e-2;

TEST_F(RefineReproducesTheSampling, AFlangeCloudIsRefinedAtTheFlange) {
  // The TA1400 carries a torch 340 mm past its flange (the de-icing arm has no tool offset).
  const std::string cloud = sample("flange.pcd", "--point flange --samples 500", "ta1400");
  const std::string out = dir_.file("refined.pcd");
  const test::RunResult r = refine(cloud, out, "--json", "ta1400");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["point"], "flange");
  const Robot robot = loadRobot(test::robotPath("ta1400"));
  const auto refined = readCloud(out);
  ASSERT_EQ(refined.size(), 300u);
  for (std::size_t i = 0; i < refined.size(); ++i) {
    const Eigen::VectorXd q = jointsOf(refined[i], robot.dof());
    const Eigen::Vector3d p = flangePose(robot, q).translation();
    // A tool point would not pass.
    ASSERT_GT((toolPose(robot, q).translation() - p).norm(), 100 * kPositionTolerance);
    ASSERT_NEAR(refined[i].x, p.x(), kPositionTolerance) << "point " << i;
    ASSERT_NEAR(refined[i].y, p.y(), kPositionTolerance) << "point " << i;
    ASSERT_NEAR(refined[i].z, p.z(), kPositionTolerance) << "point " << i;
  }
  EXPECT_THAT(test::readFile(out), HasSubstr(" point=flange collision=0 fix=none\n"));
  // Asking for the other point is refused, saying why; asking for the same one is fine.
  test::expectToolFailure(
      kRefine,
      "--robot " + test::robotPath("ta1400") + " --input " + cloud +
          " --samples 10 --point tool --output " + nothing_written_.file("o.pcd"),
      2, "--point tool: --input '" + cloud + "' was sampled at the flange", nothing_written_);
  EXPECT_EQ(refine(cloud, dir_.file("same.pcd"), "--point flange", "ta1400").exit_code, 0);
}

TEST_F(RefineReproducesTheSampling, ACollisionCloudsNewSamplesAreLabelledByTheChecker) {
  // Refined near the colliding samples (2 % of the arm's), the new ones collide or not.
  const std::string cloud = sample("labelled.pcd", "--collision --samples 2000");
  const std::string colliding_parents = dir_.file("colliding.pcd");
  ASSERT_EQ(test::run(std::string(MCWS_SELECT_EXE) + " --input " + cloud +
                      " --label 1,2,3 --output " + colliding_parents)
                .exit_code,
            0);
  const std::string out = dir_.file("refined.pcd");
  const test::RunResult r =
      test::run(kRefine + " --robot " + test::robotPath("deicing") + " --input " +
                colliding_parents + " --cloud " + cloud + " --samples 16 --output " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(test::readFile(out), HasSubstr(" point=tool collision=1 fix=none\n"));
  auto refined = readCloud(out);
  ASSERT_EQ(refined.size(), 2016u);
  refined.erase(refined.begin(), refined.begin() + 2000);  // the new samples
  // The oracle: mcws_collide on each sample's joint values (floats, printed exactly; a value
  // clamped to a limit may round a float step past it).
  const int dof = loadRobot(test::robotPath("deicing")).dof();
  int colliding = 0;
  for (std::size_t i = 0; i < refined.size(); ++i) {
    std::string q;
    for (int j = 0; j < dof; ++j) {
      char value[32];
      std::snprintf(value, sizeof value, "%.9g ", static_cast<double>(refined[i].q[j]));
      q += value;
    }
    const test::RunResult c =
        test::run(std::string(MCWS_COLLIDE_EXE) + " --robot " + test::robotPath("deicing") +
                  " --ignore-limits --json --q \"" + q + "\"");
    ASSERT_EQ(c.exit_code, 0) << c.err;
    const std::uint32_t label = nlohmann::json::parse(c.out)["label"];
    EXPECT_EQ(refined[i].label, label) << "point " << i << ", q " << q;
    colliding += label != 0;
  }
  // Labels all 0 (every sample free), or all the parents' label, would not pass.
  EXPECT_GT(colliding, 0);
  EXPECT_LT(colliding, 16);
}

TEST_F(RefineReproducesTheSampling, TheRecordedJointsStayPinnedEvenForOneBoundaryPoint) {
  // One point: no "same value in every point" to tell a pinned joint by.
  const std::string cloud = sample("one.pcd", "--fix theta3=0.3,a2=40 --samples 1");
  const std::string out = dir_.file("refined.pcd");
  const test::RunResult r = refine(cloud, out, "--json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["pinned"], nlohmann::json::array({"theta3", "a2"}));
  const Robot robot = loadRobot(test::robotPath("deicing"));
  const int theta3 = robot.jointIndex("theta3"), a2 = robot.jointIndex("a2");
  const auto refined = readCloud(out);
  ASSERT_EQ(refined.size(), 300u);
  const float parent_theta1 = readCloud(cloud)[0].q[robot.jointIndex("theta1")];
  int moved = 0;  // the other joints do move
  for (std::size_t i = 0; i < refined.size(); ++i) {
    ASSERT_EQ(refined[i].q[theta3], 0.3f) << "point " << i;
    ASSERT_EQ(refined[i].q[a2], 40.0f) << "point " << i;
    moved += refined[i].q[robot.jointIndex("theta1")] != parent_theta1;
  }
  EXPECT_GT(moved, 0);
  EXPECT_THAT(test::readFile(out), HasSubstr(" fix=theta3:0.29999999999999999,a2:40\n"));
}

TEST_F(RefineReproducesTheSampling, RefusesCloudsThatCannotSayHowTheyWereSampled) {
  const std::string out = nothing_written_.file("out.pcd");
  const std::string robot = test::robotPath("deicing");
  const auto expectRefused = [&](const std::string& input, const std::string& message,
                                 const std::string& extra = "") {
    test::expectToolFailure(
        kRefine,
        "--robot " + robot + " --input " + input + " --samples 10 --output " + out + " " + extra, 1,
        message, nothing_written_);
  };
  // A mcws_reach map cloud: the robot's, but no joint values (they would all read 0, inside the
  // planar arm's limits).
  const std::string map = dir_.file("map.pcd"), planar = test::robotPath("planar2");
  ASSERT_EQ(test::run(std::string(MCWS_REACH_EXE) + " --robot " + planar +
                      " --resolution 10cm --samples 2000 --output " + map)
                .exit_code,
            0);
  test::expectToolFailure(
      kRefine, "--robot " + planar + " --input " + map + " --samples 10 --output " + out, 1,
      "--input '" + map +
          "' has no field q1: refinement needs the joint "
          "values",
      nothing_written_);
  // A cloud of mcws before the record: its line has no point=, collision=, fix=.
  const std::string cloud = sample("ws.pcd", "--samples 200");
  std::string text = test::readFile(cloud);
  const std::size_t keys = text.find(" point=tool collision=0 fix=none");
  ASSERT_NE(keys, std::string::npos);
  text.erase(keys, std::string(" point=tool collision=0 fix=none").size());
  const std::string old = dir_.file("old.pcd");
  test::writeFile(old, text);
  expectRefused(old, "--input '" + old + "' predates the record of how it was sampled");
  // --cloud sampled otherwise than --input.
  const std::string flange = sample("flange.pcd", "--point flange --samples 200");
  expectRefused(cloud,
                "--cloud '" + flange +
                    "' was sampled with point=flange collision=0 "
                    "fix=none but --input '" +
                    cloud + "' with point=tool",
                "--cloud " + flange);
}

}  // namespace
}  // namespace mcws
