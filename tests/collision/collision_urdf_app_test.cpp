// mcws_collide and mcws_sample --collision with a URDF robot (robots/inspection6.urdf): they load
// its <collision> elements and answer as with the same arm's YAML (robots/inspection6.yaml), in
// metres instead of millimetres.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "apps/tool_paths.h"
#include "mcws/points/point_types.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

/// Agreement of a pair's distance from the URDF [m, times 1000] with the YAML's [mm]: the checker
/// takes 1e-6 length units off FCL distances (1e-3 mm in metres, 1e-6 mm in mm) and GJK converges
/// to about that; FCL's penetration depths (EPA) agree to about 1e-5 of the depth, so the
/// tolerance is the larger of 0.01 mm and kDepthFraction of the distance.
constexpr double kDistanceToleranceMm = 0.01;
constexpr double kDepthFraction = 1e-4;
/// A pair within this of touching [mm] touches exactly up to rounding: inspection6's j1 and j3
/// capsules do whenever the forearm passes over the shoulder (tests/collision/
/// collision_urdf_test.cpp, kTouchMm); there the label rests on the last bit, which metres and
/// millimetres round differently. Joint values read back from a PCD file are floats, so the
/// configuration is rechecked near, not at, the sample; the touch holds on an open set of them.
constexpr double kTouchMm = 1e-9;

std::string urdf() { return std::string(MCWS_ROBOTS_DIR) + "/inspection6.urdf"; }
std::string yaml() { return test::robotPath("inspection6"); }

/// mcws_collide --all --json for one joint vector, parsed.
nlohmann::json collide(const std::string& robot, const std::string& q) {
  const test::RunResult r =
      test::run(kCollide + " --robot " + robot + " --q '" + q + "' --all --ignore-limits --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.exit_code == 0 ? nlohmann::json::parse(r.out) : nlohmann::json();
}

TEST(CollisionUrdfApps, CollideAnswersAsTheYamlInMetres) {
  // Joint vectors [rad] that give each label with the YAML (checked below): free at zero and
  // folded up, the upper arm 21 mm into the mast (link-link), the camera 25 mm into the upper arm
  // (tool-link), the camera boom through the floor (environment).
  const std::vector<std::string> qs = {"0 0 0 0 0 0", "-2.5659 -2.959 1.3682 1.6508 2.4168 1.8065",
                                       "-2.1456 0.7942 -1.7997 -1.7742 1.1056 0.4015",
                                       "-2.7453 -0.7295 1.3946 2.897 -1.9249 -1.5518",
                                       "2.1569 -0.2411 1.1428 -2.964 0.9278 2.1779"};
  std::set<int> labels;
  for (const std::string& q : qs) {
    SCOPED_TRACE("q = " + q);
    const nlohmann::json from_yaml = collide(yaml(), q);
    const nlohmann::json from_urdf = collide(urdf(), q);
    ASSERT_FALSE(from_yaml.is_null());
    ASSERT_FALSE(from_urdf.is_null());
    EXPECT_EQ(from_urdf["label"], from_yaml["label"]);
    EXPECT_EQ(from_urdf["label_name"], from_yaml["label_name"]);
    EXPECT_EQ(from_urdf["pairs_checked"], from_yaml["pairs_checked"]);
    labels.insert(from_yaml["label"].get<int>());
    std::map<std::pair<std::string, std::string>, nlohmann::json> yaml_pairs;
    for (const auto& pair : from_yaml["pairs"]) yaml_pairs[{pair["a"], pair["b"]}] = pair;
    ASSERT_EQ(from_urdf["pairs"].size(), yaml_pairs.size());
    for (const auto& pair : from_urdf["pairs"]) {
      const auto found = yaml_pairs.find({pair["a"], pair["b"]});
      ASSERT_NE(found, yaml_pairs.end()) << pair;
      EXPECT_EQ(pair["kind"], found->second["kind"]) << pair;
      EXPECT_EQ(pair["colliding"], found->second["colliding"]) << pair;
      const double mm = found->second["distance"].get<double>();
      EXPECT_NEAR(pair["distance"].get<double>() * 1000.0, mm,
                  std::max(kDistanceToleranceMm, kDepthFraction * std::abs(mm)))
          << pair;
    }
  }
  EXPECT_EQ(labels, (std::set<int>{0, 1, 2, 3})) << "the vectors no longer cover every label";
}

TEST(CollisionUrdfApps, SampleLabelsEachSampleAsTheYaml) {
  test::TempDir dir;
  const std::string from_urdf = dir.file("urdf.pcd"), from_yaml = dir.file("yaml.pcd");
  for (const auto& [robot, cloud] : {std::pair{urdf(), from_urdf}, {yaml(), from_yaml}}) {
    const test::RunResult r = test::run(kSample + " --robot " + robot +
                                        " --collision --samples 4000 --seed 16 --output " + cloud);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  pcl::PointCloud<WorkspacePoint> u, y;
  ASSERT_EQ(pcl::io::loadPCDFile(from_urdf, u), 0);
  ASSERT_EQ(pcl::io::loadPCDFile(from_yaml, y), 0);
  ASSERT_EQ(u.size(), 4000u);
  ASSERT_EQ(y.size(), 4000u);
  std::set<std::uint32_t> labels;
  int touches = 0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    labels.insert(y[i].label);
    // The same configuration: the URDF's tool point in m is the YAML's in mm.
    ASSERT_NEAR(u[i].x * 1000.0, y[i].x, 0.01) << "sample " << i;
    if (u[i].label == y[i].label) continue;
    ++touches;  // allowed only where a pair touches exactly
    std::ostringstream q;
    q << std::setprecision(9);
    for (float value : {y[i].q1, y[i].q2, y[i].q3, y[i].q4, y[i].q5, y[i].q6}) q << value << " ";
    const nlohmann::json report = collide(yaml(), q.str());
    bool touching = false;
    for (const auto& pair : report["pairs"]) {
      touching = touching || std::abs(pair["distance"].get<double>()) <= kTouchMm;
    }
    EXPECT_TRUE(touching) << "sample " << i << ": labels " << u[i].label << " (URDF) and "
                          << y[i].label << " (YAML), q = " << q.str();
  }
  EXPECT_LE(touches, 5);
  EXPECT_EQ(labels.size(), 4u);
}

TEST(CollisionUrdfApps, UnsupportedGeometryIsOneLineNamingFileAndLink) {
  test::TempDir dir, out;
  std::string text = test::readFile(urdf());
  const std::string box = "<box size=\"0.06 0.15 0.05\"/>";
  ASSERT_NE(text.find(box), std::string::npos);
  text.replace(text.find(box), box.size(), "<mesh filename=\"camera.ply\"/>");
  test::writeFile(dir.file("arm.urdf"), text);
  test::expectToolFailure(kCollide, "--robot " + dir.file("arm.urdf") + " --q '0 0 0 0 0 0'", 1,
                          dir.file("arm.urdf") +
                              ": link 'flange' <collision> 1: mesh 'camera.ply': .ply meshes are "
                              "not supported (STL, OBJ or COLLADA .dae)",
                          out);
  test::expectToolFailure(
      kSample, "--robot " + dir.file("arm.urdf") + " --collision --output " + out.file("x.pcd"), 1,
      ": link 'flange' <collision> 1: mesh 'camera.ply'", out);
  // Not the YAML parser's message of before.
  const test::RunResult r =
      test::run(kCollide + " --robot " + dir.file("arm.urdf") + " --q '0 0 0 0 0 0'");
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("YAML")));
}

}  // namespace
}  // namespace mcws
