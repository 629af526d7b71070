// --base and --tip on every tool that takes --robot (issue 33 item 1), with the UR5-shaped URDF
// of tests/kinematics/ur5_shaped_urdf.h, whose last link carries two leaves, tool0 and ee_link:
// each tool gives the numbers of the chain it was told (against the hand-composed D-H table), and
// refuses a tree with several leaves, a tip or base that is not a link and a tip not below the
// base with one line naming the flag and the value.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "apps/tool_paths.h"
#include "kinematics/ur5_shaped_urdf.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

/// A joint vector of the UR5-shaped arm away from its singularities and its base [rad].
const Eigen::VectorXd kQ = (Eigen::VectorXd(6) << 0.3, -1.1, 1.4, -0.6, 0.9, 0.5).finished();
const std::string kQText = "'0.3 -1.1 1.4 -0.6 0.9 0.5'";
/// Poses printed by a tool in JSON (17 significant digits) against the hand composition [m].
constexpr double kJsonTol = 1e-9;
/// Points of a cloud (float coordinates of about 1 m: 6e-8 m per ulp) [m].
constexpr double kCloudTol = 1e-6;
/// IK's default tolerances are 1e-6 (m and rad); the pose of its answer, composed by hand.
constexpr double kIkTol = 1e-5;

/// One tool and the flags it needs besides --robot, --base and --tip to reach the robot (`@O@`
/// the directory its outputs would go to, which a refused run must leave empty).
struct Tool {
  std::string name, exe, args;
};

/// For GoogleTest's test names and messages.
void PrintTo(const Tool& tool, std::ostream* out) { *out << "mcws_" << tool.name; }

std::string withDir(std::string args, const std::string& dir) {
  for (std::size_t at; (at = args.find("@O@")) != std::string::npos;) args.replace(at, 3, dir);
  return args;
}

const Tool kTools[] = {
    {"fk", MCWS_FK_EXE, "--q " + kQText},
    {"ik", MCWS_IK_EXE, "--pose '0.3 0.2 0.4 0 0 0'"},
    {"collide", MCWS_COLLIDE_EXE, "--q " + kQText},
    {"sample", MCWS_SAMPLE_EXE, "--samples 10 --output @O@/s.pcd"},
    {"refine", MCWS_REFINE_EXE, "--input @O@/in.pcd --samples 10 --output @O@/r.pcd"},
    {"reach", MCWS_REACH_EXE, "--resolution 20cm --samples 100 --output @O@/m.pcd"},
    {"place", MCWS_PLACE_EXE,
     "--targets @O@/t.csv --along '0 0 1' --resolution 20cm --samples 100 --output @O@/b.pcd"},
    {"traj", MCWS_TRAJ_EXE,
     "--from " + kQText + " --to " + kQText + " --duration 1 --rate 10 --output @O@/t.csv"},
};

class EveryRobotTool : public ::testing::TestWithParam<Tool> {
 protected:
  void SetUp() override { test::writeFile(urdf_, test::kUr5ShapedUrdf); }
  /// Expects the tool to refuse `chain` (--base/--tip flags) with exit 2 and `message`.
  void expectRefused(const std::string& robot, const std::string& chain,
                     const std::string& message) {
    const Tool& tool = GetParam();
    test::expectToolFailure(tool.exe,
                            "--robot " + robot + " " + chain + " " + withDir(tool.args, out_path_),
                            2, message, out_);
  }
  test::TempDir dir_, out_;
  const std::string urdf_ = dir_.file("ur5.urdf");
  const std::string out_path_ = out_.file("");
};

TEST_P(EveryRobotTool, ListsBaseAndTipInItsHelp) {
  const test::RunResult r = test::run(GetParam().exe + " --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, HasSubstr("--base arg"));
  EXPECT_THAT(r.out, HasSubstr("--tip arg"));
  EXPECT_THAT(r.out, HasSubstr("--package-path arg"));
}

TEST_P(EveryRobotTool, RefusesAPackagePathThatIsNoFolderOrForADhRobot) {
  expectRefused(urdf_, "--tip tool0 --package-path " + out_path_ + "none",
                "--package-path: '" + out_path_ + "none' is not a folder");
  expectRefused(test::robotPath("inspection6"), "--package-path " + out_path_,
                "--package-path needs a .urdf robot");
}

TEST_P(EveryRobotTool, NamesTheLeavesAndTheFlagWhenTheTreeHasSeveral) {
  expectRefused(urdf_, "",
                "--robot: " + urdf_ +
                    ": link 'world' has 2 leaf links below it (tool0, ee_link): choose one with "
                    "--tip");
  expectRefused(urdf_, "--base base_link",
                "--robot: " + urdf_ +
                    ": link 'base_link' has 2 leaf links below it (tool0, ee_link): choose one "
                    "with --tip");
}

TEST_P(EveryRobotTool, RefusesATipOrBaseThatIsNoLinkOrATipNotBelowTheBase) {
  expectRefused(urdf_, "--tip hand",
                "--tip: 'hand' is not a link of robot 'ur5_shaped' in " + urdf_);
  expectRefused(urdf_, "--base torso --tip tool0",
                "--base: 'torso' is not a link of robot 'ur5_shaped' in " + urdf_);
  expectRefused(urdf_, "--base wrist_1_link --tip upper_arm_link",
                "--tip: link 'upper_arm_link' is not below --base link 'wrist_1_link' in " + urdf_);
  expectRefused(urdf_, "--base tool0 --tip ee_link",
                "--tip: link 'ee_link' is not below --base link 'tool0' in " + urdf_);
}

TEST_P(EveryRobotTool, RefusesBaseAndTipForADhRobot) {
  expectRefused(test::robotPath("inspection6"), "--tip tool0",
                "--base and --tip need a .urdf robot");
  expectRefused(test::robotPath("inspection6"), "--base base",
                "--base and --tip need a .urdf robot");
}

INSTANTIATE_TEST_SUITE_P(Tools, EveryRobotTool, ::testing::ValuesIn(kTools),
                         [](const ::testing::TestParamInfo<Tool>& info) {
                           return info.param.name;
                         });

// ---- each tool's numbers for the chain it was given ----

class RobotChainApp : public ::testing::Test {
 protected:
  void SetUp() override { test::writeFile(urdf_, test::kUr5ShapedUrdf); }
  std::string robot(const std::string& chain) const { return " --robot " + urdf_ + " " + chain; }
  std::string file(const std::string& name) const { return dir_.file(name); }
  test::TempDir dir_;
  const std::string urdf_ = dir_.file("ur5.urdf");
};

/// The 4x4 "pose" of a tool's JSON as a pose.
Eigen::Isometry3d jsonPose(const nlohmann::json& rows) {
  Eigen::Isometry3d T;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) T.matrix()(r, c) = rows[r][c].get<double>();
  }
  return T;
}

double gap(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.matrix() - b.matrix()).cwiseAbs().maxCoeff();
}

TEST_F(RobotChainApp, FkGivesTheFrameOfTheTipAndBaseChosen) {
  struct Case {
    std::string chain;
    Eigen::Isometry3d expected;
  };
  const Case cases[] = {
      {"--tip tool0", test::ur5FromWorld(test::ur5BaseToTool0(kQ))},
      {"--tip ee_link", test::ur5FromWorld(test::ur5BaseToEeLink(kQ))},
      {"--base base_link --tip tool0", test::ur5BaseToTool0(kQ)},
  };
  for (const Case& c : cases) {
    const test::RunResult r =
        test::run(kTools[0].exe + robot(c.chain) + " --q " + kQText + " --json");
    ASSERT_EQ(r.exit_code, 0) << c.chain << "\n" << r.err;
    EXPECT_LT(gap(jsonPose(nlohmann::json::parse(r.out)["pose"]), c.expected), kJsonTol) << c.chain;
  }
}

TEST_F(RobotChainApp, IkReachesThePoseOfTheTipChosen) {
  const Eigen::Isometry3d target = test::ur5FromWorld(test::ur5BaseToEeLink(kQ));
  std::ostringstream matrix, q0;
  matrix.precision(17);
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) matrix << target.matrix()(r, c) << ' ';
  }
  for (int j = 0; j < 6; ++j) q0 << kQ[j] + 0.05 << ' ';
  const test::RunResult r = test::run(kTools[1].exe + robot("--tip ee_link") + " --matrix '" +
                                      matrix.str() + "' --q0 '" + q0.str() + "' --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto q = nlohmann::json::parse(r.out)["q"].get<std::vector<double>>();
  ASSERT_EQ(q.size(), 6u);
  const Eigen::VectorXd solved = Eigen::Map<const Eigen::VectorXd>(q.data(), 6);
  EXPECT_LT(gap(test::ur5FromWorld(test::ur5BaseToEeLink(solved)), target), kIkTol);
}

TEST_F(RobotChainApp, CollideFindsPackageMeshesThroughThePackagePath) {
  // base_link's sphere as a package:// mesh (a 1 cm tetrahedron) of a package in a workspace that
  // neither the URDF's folder nor those above it hold.
  std::string text = test::kUr5ShapedUrdf;
  const std::string sphere = "<sphere radius=\"0.1\"/>";
  text.replace(text.find(sphere), sphere.size(),
               "<mesh filename=\"package://ur5_pkg/meshes/base.stl\" scale=\"0.01 0.01 0.01\"/>");
  std::filesystem::create_directories(file("ws/src/ur5_pkg/meshes"));
  test::writeFile(file("ws/src/ur5_pkg/package.xml"), "<package/>");
  test::writeFile(file("ws/src/ur5_pkg/meshes/base.stl"),
                  "solid t\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                  "vertex 0 1 0\nendloop\nendfacet\nfacet normal 0 0 0\nouter loop\n"
                  "vertex 0 0 0\nvertex 0 0 1\nvertex 1 0 0\nendloop\nendfacet\nendsolid t\n");
  test::writeFile(urdf_, text);
  const std::string args = robot("--tip tool0") + " --q " + kQText;
  const test::RunResult found = test::run("env -u ROS_PACKAGE_PATH " + kTools[2].exe + args +
                                          " --package-path " + file("ws"));
  EXPECT_EQ(found.exit_code, 0) << found.err;
  const test::RunResult lost = test::run("env -u ROS_PACKAGE_PATH " + kTools[2].exe + args);
  EXPECT_EQ(lost.exit_code, 1);
  EXPECT_THAT(
      lost.err,
      HasSubstr("link 'base_link' <collision> 1: mesh "
                "'package://ur5_pkg/meshes/base.stl': package 'ur5_pkg' not found; "
                "looked in --package-path (none); ROS_PACKAGE_PATH (unset); and for a "
                "folder 'ur5_pkg' in " +
                std::filesystem::path(urdf_).parent_path().string() + " and each folder above it"));
  EXPECT_EQ(test::lineCount(lost.err), 1) << lost.err;
}

TEST_F(RobotChainApp, CollideModelsTheChainChosen) {
  // tool0's sphere (r 0.02) and base_link's (r 0.1, 0.5 m up): their clearance is the distance of
  // the centres less 0.12 m, on the tool when tool0 is the tip, on the last link when ee_link is.
  const double clearance =
      (test::ur5FromWorld(test::ur5BaseToTool0(kQ)).translation() - Eigen::Vector3d(0, 0, 0.5))
          .norm() -
      0.12;
  ASSERT_GT(clearance, 0.05);
  for (const auto& [tip, body] :
       {std::pair<std::string, std::string>{"tool0", "tool"}, {"ee_link", "wrist_3_joint"}}) {
    const test::RunResult r =
        test::run(kTools[2].exe + robot("--tip " + tip) + " --q " + kQText + " --all --json");
    ASSERT_EQ(r.exit_code, 0) << tip << "\n" << r.err;
    const auto out = nlohmann::json::parse(r.out);
    EXPECT_EQ(out["label"], 0) << r.out;
    int found = 0;
    for (const auto& pair : out["pairs"]) {
      // The sphere is on one body only: the other of tool and wrist_3_joint has no shape.
      EXPECT_NE(pair["b"], body == "tool" ? "wrist_3_joint" : "tool") << r.out;
      if (pair["a"] != "base" || pair["b"] != body) continue;
      ++found;
      EXPECT_NEAR(pair["distance"].get<double>(), clearance, 1e-9) << tip;
    }
    EXPECT_EQ(found, 1) << r.out;
  }
}

/// Joints 1 to 5 pinned at kQ: only wrist_3_joint turns, about the axis tool0 lies on.
const std::string kFixAllButTheLast =
    " --fix shoulder_pan_joint=0.3,shoulder_lift_joint=-1.1,elbow_joint=1.4,wrist_1_joint=-0.6,"
    "wrist_2_joint=0.9";

std::vector<Eigen::Vector3d> cloudPoints(const std::string& path) {
  pcl::PointCloud<pcl::PointXYZ> cloud;
  EXPECT_EQ(pcl::io::loadPCDFile(path, cloud), 0) << path;
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : cloud) points.emplace_back(p.x, p.y, p.z);
  return points;
}

TEST_F(RobotChainApp, SampleAndRefineRecordThePointOfTheTipChosen) {
  // tool0 is on the last joint's axis: turning that joint leaves it where it is. ee_link is 5 cm
  // off the axis: it draws a circle of radius 0.05 m about tool0.
  const Eigen::Vector3d p_tool0 = test::ur5FromWorld(test::ur5BaseToTool0(kQ)).translation();
  const std::string tool0 = file("tool0.pcd"), ee = file("ee.pcd"), refined = file("r.pcd");
  const std::string sample = kTools[3].exe + kFixAllButTheLast + " --samples 50 --seed 3";
  ASSERT_EQ(test::run(sample + robot("--tip tool0") + " --output " + tool0).exit_code, 0);
  ASSERT_EQ(test::run(sample + robot("--tip ee_link") + " --output " + ee).exit_code, 0);
  const test::RunResult r = test::run(kTools[4].exe + robot("--tip tool0") + " --input " + tool0 +
                                      " --samples 20 --output " + refined);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(cloudPoints(tool0).size(), 50u);
  for (const Eigen::Vector3d& p : cloudPoints(tool0)) EXPECT_LT((p - p_tool0).norm(), kCloudTol);
  ASSERT_EQ(cloudPoints(refined).size(), 20u);
  for (const Eigen::Vector3d& p : cloudPoints(refined)) EXPECT_LT((p - p_tool0).norm(), kCloudTol);
  ASSERT_EQ(cloudPoints(ee).size(), 50u);
  for (const Eigen::Vector3d& p : cloudPoints(ee))
    EXPECT_NEAR((p - p_tool0).norm(), 0.05, kCloudTol);
}

TEST_F(RobotChainApp, TrajStartsAndEndsAtTheTipChosen) {
  const Eigen::VectorXd to = (Eigen::VectorXd(6) << 0.5, -1.0, 1.2, -0.4, 0.8, 0.1).finished();
  const test::RunResult r = test::run(
      kTools[7].exe + robot("--tip ee_link") + " --from " + kQText +
      " --to '0.5 -1.0 1.2 -0.4 0.8 0.1' --duration 1 --rate 10 --json --output " + file("t.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto out = nlohmann::json::parse(r.out);
  const auto start = out["tool_start"].get<std::vector<double>>();
  const auto end = out["tool_end"].get<std::vector<double>>();
  const Eigen::Vector3d p_start = test::ur5FromWorld(test::ur5BaseToEeLink(kQ)).translation();
  const Eigen::Vector3d p_end = test::ur5FromWorld(test::ur5BaseToEeLink(to)).translation();
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(start[k], p_start[k], kJsonTol);
    EXPECT_NEAR(end[k], p_end[k], kJsonTol);
  }
}

/// A CSV target file of one full pose (x,y,z,roll,pitch,yaw [m, rad]).
std::string writePoseTarget(const std::string& path, const Eigen::Isometry3d& T) {
  const Eigen::Vector3d ypr = T.linear().eulerAngles(2, 1, 0);  // R = Rz(yaw) Ry(pitch) Rx(roll)
  std::ostringstream csv;
  csv.precision(17);
  csv << "x,y,z,roll,pitch,yaw\n"
      << T.translation().x() << ',' << T.translation().y() << ',' << T.translation().z() << ','
      << ypr[2] << ',' << ypr[1] << ',' << ypr[0] << '\n';
  test::writeFile(path, csv.str());
  return path;
}

TEST_F(RobotChainApp, ReachAndPlaceReachThePoseOfTheTipChosen) {
  // ee_link's pose at kQ, with the collision model of that chain (the base and tool0's spheres).
  const std::string targets =
      writePoseTarget(file("t.csv"), test::ur5FromWorld(test::ur5BaseToEeLink(kQ)));
  const test::RunResult reach =
      test::run(kTools[5].exe + robot("--tip ee_link") + " --targets " + targets +
                " --ik-starts 16 --json --output " + file("heat.pcd"));
  ASSERT_EQ(reach.exit_code, 0) << reach.err;
  EXPECT_EQ(nlohmann::json::parse(reach.out)["reached"], 1) << reach.out;

  const test::RunResult place = test::run(
      kTools[6].exe + robot("--tip ee_link") + " --targets " + targets +
      " --along '0 0 1' --resolution 20cm --samples 20000 --ik-starts 16 --confirm all --json "
      "--map-cache off "
      "--output " +
      file("bases.pcd"));
  ASSERT_EQ(place.exit_code, 0) << place.err;
  const auto candidates = nlohmann::json::parse(place.out)["candidates"];
  ASSERT_EQ(candidates.size(), 1u) << place.out;
  EXPECT_EQ(candidates[0]["ik_share"].get<double>(), 1.0) << place.out;
}

TEST_F(RobotChainApp, PlaceRefusesAMapOfAnotherChainOfTheSameFile) {
  const std::string map = file("m.bin");
  const test::RunResult made =
      test::run(kTools[5].exe + robot("--tip tool0") + " --resolution 20cm --samples 2000 --map " +
                map + " --output " + file("m.pcd"));
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const std::string targets =
      writePoseTarget(file("t.csv"), test::ur5FromWorld(test::ur5BaseToTool0(kQ)));
  const std::string place = kTools[6].exe + " --targets " + targets + " --along '0 0 1' --map " +
                            map + " --no-collision --json --output ";
  const test::RunResult other = test::run(place + file("other.pcd") + robot("--tip ee_link"));
  EXPECT_EQ(other.exit_code, 1);
  EXPECT_THAT(other.err, HasSubstr(map + ": the map was made for the chain from link 'world' to "
                                         "link 'tool0', not for the chain from 'world' to "
                                         "'ee_link' (--base, --tip)"));
  EXPECT_EQ(test::lineCount(other.err), 1) << other.err;
  const test::RunResult same = test::run(place + file("same.pcd") + robot("--tip tool0"));
  EXPECT_EQ(same.exit_code, 0) << same.err;
}

}  // namespace
}  // namespace mcws
