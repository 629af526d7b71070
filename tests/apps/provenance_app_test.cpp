// The robot recorded in the clouds the tools write (issue 17 section 3, issue 16 section 1):
// written by mcws_sample, mcws_refine and mcws_reach, read by PCL and its tools, carried through
// mcws_boundary and mcws_select, and a cloud of another robot refused by mcws_refine.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <filesystem>

#include "apps/tool_paths.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

/// What `sha256sum` says of a file (an oracle independent of the tools' OpenSSL).
std::string sha256sum(const std::string& path) {
  const test::RunResult r = test::run("sha256sum " + path);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.out.substr(0, r.out.find(' '));
}

/// Line `number` (from 1) of a file.
std::string line(const std::string& path, int number) {
  std::istringstream text(test::readFile(path));
  std::string out;
  for (int k = 0; k < number; ++k) std::getline(text, out);
  return out;
}

/// The file's bytes with line `number` (from 1) replaced by `replacement` (removed when empty).
std::string replaceLine(const std::string& path, int number, const std::string& replacement) {
  const std::string text = test::readFile(path);
  std::size_t begin = 0;
  for (int k = 1; k < number; ++k) begin = text.find('\n', begin) + 1;
  const std::size_t end = text.find('\n', begin) + 1;
  return text.substr(0, begin) + (replacement.empty() ? "" : replacement + "\n") + text.substr(end);
}

class ProvenanceApp : public ::testing::Test {
 protected:
  void SetUp() override {
    // A copy of the de-icing robot, so that the test can edit it.
    robot_ = dir_.file("deicing.yaml");
    std::filesystem::copy_file(test::robotPath("deicing"), robot_);
    cloud_ = dir_.file("ws.pcd");
    ASSERT_EQ(sample(robot_, cloud_).exit_code, 0);
  }
  test::RunResult sample(const std::string& robot, const std::string& output) const {
    return test::run(kSample + " --robot " + robot + " --fix theta3=0 --samples 2000 --output " +
                     output);
  }
  /// The line mcws_sample should write for the robot file `path` (name deicing, unit cm) and
  /// --fix theta3=0.
  std::string expectedLine(const std::string& path) const {
    return "# mcws robot=deicing file=" + std::filesystem::path(path).filename().string() +
           " sha256=" + sha256sum(path) + " length_unit=cm point=tool collision=0 fix=theta3:0";
  }
  std::string refineArgs(const std::string& robot, const std::string& input,
                         const std::string& output) const {
    return "--robot " + robot + " --input " + input + " --samples 100 --output " + output;
  }
  test::TempDir dir_, nothing_written_;
  std::string robot_, cloud_;
};

TEST_F(ProvenanceApp, SampleRecordsTheRobotNameFileHashAndUnitAfterPclsFirstLine) {
  EXPECT_EQ(line(cloud_, 1), "# .PCD v0.7 - Point Cloud Data file format");
  EXPECT_EQ(line(cloud_, 2), expectedLine(robot_));
  EXPECT_EQ(line(cloud_, 3), "VERSION 0.7");
  // A URDF robot's lengths are in metres; its chain is recorded.
  const std::string urdf = std::string(MCWS_ROBOTS_DIR) + "/inspection6.urdf";
  ASSERT_EQ(
      test::run(kSample + " --robot " + urdf + " --samples 10 --output " + dir_.file("urdf.pcd"))
          .exit_code,
      0);
  EXPECT_EQ(
      line(dir_.file("urdf.pcd"), 2),
      "# mcws robot=inspection6 file=inspection6.urdf sha256=" + sha256sum(urdf) +
          " length_unit=m base_link=base_link tip_link=flange point=tool collision=0 fix=none");
  // A --shape has no robot: no line.
  ASSERT_EQ(
      test::run(kSample + " --shape disk --samples 10 --output " + dir_.file("disk.pcd")).exit_code,
      0);
  EXPECT_THAT(test::readFile(dir_.file("disk.pcd")), ::testing::Not(HasSubstr("# mcws")));
}

TEST_F(ProvenanceApp, PclAndItsToolsStillReadTheCloud) {
  pcl::PointCloud<pcl::PointXYZ> xyz;
  ASSERT_EQ(pcl::io::loadPCDFile(cloud_, xyz), 0);
  EXPECT_EQ(xyz.size(), 2000u);
  if (!std::filesystem::exists("/usr/bin/pcl_pcd2ply")) GTEST_SKIP() << "no pcl_pcd2ply";
  const test::RunResult r = test::run("pcl_pcd2ply " + cloud_ + " " + dir_.file("ws.ply"));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_THAT(test::readFile(dir_.file("ws.ply")), HasSubstr("element vertex 2000"));
}

TEST_F(ProvenanceApp, RefineRefusesACloudOfAnotherRobot) {
  const std::string planar = dir_.file("planar.pcd");
  ASSERT_EQ(test::run(kSample + " --robot " + test::robotPath("planar2") +
                      " --samples 500 --output " + planar)
                .exit_code,
            0);
  const std::string out = nothing_written_.file("out.pcd");
  const std::string recorded = "robot 'planar2' (planar2.yaml, sha256 " +
                               sha256sum(test::robotPath("planar2")).substr(0, 12) + "...)";
  const std::string given =
      "--robot is 'deicing' (deicing.yaml, sha256 " + sha256sum(robot_).substr(0, 12) + "...)";
  test::expectToolFailure(kRefine, refineArgs(robot_, planar, out), 1,
                          "--input '" + planar + "' was made from " + recorded + " but " + given,
                          nothing_written_);
  // The cloud copied in front of the new samples too.
  test::expectToolFailure(kRefine, refineArgs(robot_, cloud_, out) + " --cloud " + planar, 1,
                          "--cloud '" + planar + "' was made from " + recorded + " but " + given,
                          nothing_written_);
}

TEST_F(ProvenanceApp, RefineRefusesACloudOfTheRobotFileBeforeAnEdit) {
  const std::string before = sha256sum(robot_);
  std::ofstream(robot_, std::ios::app) << "# tool changed\n";
  test::expectToolFailure(kRefine, refineArgs(robot_, cloud_, nothing_written_.file("out.pcd")), 1,
                          "--input '" + cloud_ +
                              "' was made from robot 'deicing' (deicing.yaml, sha256 " +
                              before.substr(0, 12) +
                              "...) but --robot is 'deicing' (deicing.yaml, "
                              "sha256 " +
                              sha256sum(robot_).substr(0, 12) + "...)",
                          nothing_written_);
  const test::RunResult r =
      test::run(kRefine + " " + refineArgs(robot_, cloud_, nothing_written_.file("out.pcd")));
  EXPECT_THAT(r.err, HasSubstr(": the robot file has changed since"));
}

TEST_F(ProvenanceApp, RefineWithTheSameRobotFileRecordsIt) {
  const std::string out = dir_.file("refined.pcd");
  test::RunResult r =
      test::run(kRefine + " " + refineArgs(robot_, cloud_, out) + " --cloud " + cloud_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(line(out, 2), expectedLine(robot_));
  // The same bytes under another name are the same robot; the output names the file given.
  const std::string copy = dir_.file("copy.yaml");
  std::filesystem::copy_file(robot_, copy);
  r = test::run(kRefine + " " + refineArgs(copy, cloud_, dir_.file("copy.pcd")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(line(dir_.file("copy.pcd"), 2), expectedLine(copy));
}

TEST_F(ProvenanceApp, CloudsWithoutTheLineAreRefusedAndForeignCommentsAccepted) {
  // An older cloud (or another tool's): no line, so nothing says how it was sampled (issue 31).
  const std::string old = dir_.file("old.pcd");
  test::writeFile(old, replaceLine(cloud_, 2, ""));
  ASSERT_EQ(line(old, 2), "VERSION 0.7");
  test::expectToolFailure(kRefine, refineArgs(robot_, old, nothing_written_.file("a.pcd")), 1,
                          "--input '" + old + "' does not record how it was sampled",
                          nothing_written_);
  // Comments of others, also indented (PCL's reader trims a line before it looks for '#').
  const std::string noted = dir_.file("noted.pcd");
  test::writeFile(noted, replaceLine(cloud_, 1, "# .PCD v0.7\n  # measured by hand\n\t#mcwsx"));
  pcl::PointCloud<pcl::PointXYZ> xyz;
  ASSERT_EQ(pcl::io::loadPCDFile(noted, xyz), 0);
  const test::RunResult r =
      test::run(kRefine + " " + refineArgs(robot_, noted, dir_.file("b.pcd")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(line(dir_.file("b.pcd"), 2), expectedLine(robot_));
}

TEST_F(ProvenanceApp, AMalformedOrSecondLineIsRefusedNamingTheFileAndLine) {
  const std::string out = nothing_written_.file("out.pcd");
  const std::string bad = dir_.file("bad.pcd");
  const std::string good = line(cloud_, 2);
  test::writeFile(
      bad, replaceLine(cloud_, 2,
                       good.substr(0, good.find(" sha256=")) + " sha256=12ab length_unit=cm"));
  test::expectToolFailure(kRefine, refineArgs(robot_, bad, out), 1,
                          bad +
                              ": line 2: malformed mcws provenance comment: sha256=12ab is not "
                              "64 lowercase hex digits",
                          nothing_written_);
  test::expectToolFailure(std::string(MCWS_BOUNDARY_EXE),
                          "--input " + bad + " --plane xz --output " + out, 1,
                          bad + ": line 2: malformed mcws provenance comment", nothing_written_);
  test::writeFile(bad, replaceLine(cloud_, 2, good + "\n" + good));
  test::expectToolFailure(kRefine, refineArgs(robot_, bad, out), 1,
                          bad + ": line 3: a second mcws provenance comment (the first is line 2)",
                          nothing_written_);
}

TEST_F(ProvenanceApp, TheLineSurvivesBoundaryAndSelect) {
  const std::string rim = dir_.file("rim.pcd"), inside = dir_.file("inside.pcd"),
                    free = dir_.file("free.pcd");
  test::RunResult r = test::run(std::string(MCWS_BOUNDARY_EXE) + " --input " + cloud_ +
                                " --plane xz --output " + rim + " --interior " + inside);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // ... with the cloud they were found in (mcws_measure --boundary checks it).
  ASSERT_THAT(line(rim, 11), StartsWith("POINTS "));
  const std::string rim_points = line(rim, 11).substr(std::string("POINTS ").size());
  const std::string input =
      " input_points=2000 input_sha256=" + sha256sum(cloud_) + " boundary_points=" + rim_points;
  EXPECT_EQ(line(rim, 2), expectedLine(robot_) + input);
  EXPECT_EQ(line(inside, 2), expectedLine(robot_) + input);
  r = test::run(std::string(MCWS_SELECT_EXE) + " --input " + rim + " --label 0 --output " + free);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(line(free, 2), expectedLine(robot_) + input);
  // ... and so the refinement of a boundary of another robot is caught.
  test::expectToolFailure(
      kRefine, refineArgs(test::robotPath("planar2"), free, nothing_written_.file("out.pcd")), 1,
      "--input '" + free + "' was made from robot 'deicing'", nothing_written_);
}

TEST_F(ProvenanceApp, ReachRecordsTheRobotInTheMapAndTheHeatMap) {
  const std::string planar = test::robotPath("planar2");
  const std::string expected =
      "# mcws robot=planar2 file=planar2.yaml sha256=" + sha256sum(planar) + " length_unit=cm";
  test::RunResult r = test::run(kReach + " --robot " + planar +
                                " --resolution 10cm --samples 2000 --output " + dir_.file("m.pcd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(line(dir_.file("m.pcd"), 2), expected);
  test::writeFile(dir_.file("t.csv"), "x,y,z,normal_x,normal_y,normal_z\n50,0,0,1,0,0\n");
  r = test::run(kReach + " --robot " + planar + " --targets " + dir_.file("t.csv") +
                " --no-collision --output " + dir_.file("heat.pcd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(line(dir_.file("heat.pcd"), 2), expected);
}

}  // namespace
}  // namespace mcws
