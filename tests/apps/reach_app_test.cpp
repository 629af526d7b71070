// mcws_reach and mcws_sample --quality through their command lines: bad input (one line, exit
// code, nothing written), closed forms (a planar arm's annulus and single approach direction, a
// spherical wrist reaching every orientation, a 2R arm's manipulability), and the same bytes for
// any thread count.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "apps/tool_paths.h"
#include "mcws/points/point_types.h"
#include "mcws/reach/reach_map.h"
#include "png_image.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

/// A three-axis spherical wrist (standard D-H z-y-z, every axis through one point) whose tool
/// point is the wrist centre, placed at (5, 5, 5) cm: the tool point never moves and every
/// orientation is reachable.
constexpr char kWrist[] = R"(name: wrist
units: {length: cm, angle: deg}
convention: standard
base: {xyz: [5, 5, 5]}
joints:
  - {name: a, type: revolute, a: 0, alpha: -90, d: 0, limits: [-180, 180]}
  - {name: b, type: revolute, a: 0, alpha: 90, d: 0, limits: [-180, 180]}
  - {name: c, type: revolute, a: 0, alpha: 0, d: 0, limits: [-180, 180]}
)";

class ReachApp : public ::testing::Test {
 protected:
  std::string out(const std::string& name = "map.pcd") const { return dir_.file(name); }
  void expectFailure(const std::string& args, int exit_code, const std::string& message) {
    test::expectToolFailure(kReach, args, exit_code, message, dir_);
  }
  test::TempDir dir_;
};

TEST_F(ReachApp, HelpDescribesTheFlags) {
  const test::RunResult r = test::run(kReach + " --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* flag : {"--robot", "--resolution", "--orientations", "--rolls", "--samples",
                           "--map", "--halfcut", "--histogram", "--collision", "--json"}) {
    EXPECT_THAT(r.out, HasSubstr(flag));
  }
}

TEST_F(ReachApp, BadInputIsOneLineAndWritesNothing) {
  const std::string planar = " --robot " + test::robotPath("planar2") + " --output " + out();
  expectFailure(planar + " --resolution 0", 2, "--resolution: 0 is not a positive number");
  expectFailure(planar + " --resolution 2furlong", 2, "--resolution");
  expectFailure(planar + " --resolution 2cm --orientations 0", 2, "--orientations");
  expectFailure(planar + " --resolution 2cm --rolls 0", 2, "--rolls");
  expectFailure(planar + " --resolution 2cm --orientations 1000 --rolls 1000", 2,
                "more than 65536");
  expectFailure(planar + " --resolution 2cm --quality-task twist", 2, "--quality-task");
  expectFailure(planar + " --resolution 2cm --samples 0", 2, "--samples");
  expectFailure("--robot /nonexistent.yaml --resolution 2cm --output " + out(), 1,
                "/nonexistent.yaml");
  test::TempDir robots;
  const std::string wrist = robots.file("wrist.yaml");
  test::writeFile(wrist, kWrist);
  expectFailure("--robot " + wrist + " --resolution 2 --collision --output " + out(), 1,
                "has no collision geometry");
  expectFailure("--robot " + test::robotPath("planar2") + " --resolution 2", 2, "--output");
}

/// The planar 2R arm (l1 = 40, l2 = 30 cm, q2 within +-160 deg): every voxel centre lies within
/// half a voxel diagonal of the annulus 10 <= r <= 70 cm in z = 0's voxel layer, and its tool z
/// axis is always world z, so every voxel reaches exactly one of the orientation bins.
TEST_F(ReachApp, PlanarArmFillsTheAnnulusWithOneApproachDirection) {
  const test::RunResult r =
      test::run(kReach + " --robot " + test::robotPath("planar2") +
                " --resolution 2cm --samples 200000 --json --output " + out());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto summary = nlohmann::json::parse(r.out);
  EXPECT_EQ(summary["length_unit"], "cm");
  EXPECT_EQ(summary["occupied_volume_unit"], "cm^3");
  EXPECT_EQ(summary["manipulability"]["task"], "position");
  pcl::PointCloud<ReachPoint> cloud;
  ASSERT_EQ(pcl::io::loadPCDFile(out(), cloud), 0);
  ASSERT_EQ(cloud.size(), summary["voxels"].get<std::size_t>());
  const double half_diagonal = std::sqrt(2.0);  // of a 2 cm square, in the plane
  const double l1 = 40.0, l2 = 30.0;
  const double r_min = std::sqrt(l1 * l1 + l2 * l2 + 2 * l1 * l2 * std::cos(160.0 * M_PI / 180));
  std::uint64_t counted = 0;
  for (const ReachPoint& p : cloud) {
    const double radius = std::hypot(p.x, p.y);
    EXPECT_LE(radius, l1 + l2 + half_diagonal);
    EXPECT_GE(radius, r_min - half_diagonal);
    EXPECT_FLOAT_EQ(p.z, 1.0f);  // the layer [0, 2) cm
    EXPECT_FLOAT_EQ(p.reachability, 1.0f / 200.0f);
    counted += p.count;
  }
  EXPECT_EQ(counted, 200000u);
  // The annulus' area over the voxel area bounds the voxel count from below (partial voxels at
  // both rims add to it): pi (70^2 - r_min^2) / 4.
  EXPECT_GT(cloud.size(), M_PI * (70.0 * 70.0 - r_min * r_min) / 4.0);
}

TEST_F(ReachApp, SphericalWristReachesEveryOrientationInItsVoxel) {
  const std::string robot = dir_.file("wrist.yaml");
  test::writeFile(robot, kWrist);
  const test::RunResult r = test::run(
      kReach + " --robot " + robot + " --resolution 10cm --samples 20000 --json --output " + out());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  pcl::PointCloud<ReachPoint> cloud;
  ASSERT_EQ(pcl::io::loadPCDFile(out(), cloud), 0);
  ASSERT_EQ(cloud.size(), 1u);
  EXPECT_FLOAT_EQ(cloud[0].x, 5.0f);
  EXPECT_FLOAT_EQ(cloud[0].reachability, 1.0f);
  EXPECT_EQ(cloud[0].count, 20000u);
  // With 4 roll bins too: every (direction, roll) of the 800 bins, 25 samples each on average.
  const test::RunResult rolls =
      test::run(kReach + " --robot " + robot +
                " --resolution 10cm --rolls 4 --samples 40000 --output " + out("rolls.pcd"));
  ASSERT_EQ(rolls.exit_code, 0) << rolls.err;
  ASSERT_EQ(pcl::io::loadPCDFile(out("rolls.pcd"), cloud), 0);
  EXPECT_FLOAT_EQ(cloud[0].reachability, 1.0f);
}

TEST_F(ReachApp, SameBytesForAnyThreadCountAndTheMapReadsBack) {
  const std::string common =
      kReach + " --robot " + test::robotPath("inspection6") + " --resolution 20cm --samples 300000";
  for (int threads : {1, 3}) {
    const std::string t = std::to_string(threads);
    const test::RunResult r = test::run(common + " --threads " + t + " --output " +
                                        out("m" + t + ".pcd") + " --map " + out("m" + t + ".bin"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  EXPECT_EQ(test::readFile(out("m1.pcd")), test::readFile(out("m3.pcd")));
  EXPECT_EQ(test::readFile(out("m1.bin")), test::readFile(out("m3.bin")));
  std::ifstream in(out("m1.bin"), std::ios::binary);
  std::string header;
  const ReachMap map = ReachMap::read(in, "m1.bin", &header);
  EXPECT_THAT(header, HasSubstr("\"robot\":\"inspection6\""));
  EXPECT_EQ(map.samples(), 300000u);
  pcl::PointCloud<ReachPoint> cloud;
  ASSERT_EQ(pcl::io::loadPCDFile(out("m1.pcd"), cloud), 0);
  ASSERT_EQ(cloud.size(), map.size());
  for (std::size_t v = 0; v < map.size(); ++v) {
    EXPECT_EQ(cloud[v].count, map.count(v));
    EXPECT_FLOAT_EQ(cloud[v].reachability, static_cast<float>(map.reachability(v)));
    EXPECT_FLOAT_EQ(cloud[v].manipulability, map.bestManipulability(v));
  }
}

/// The inspection arm from its URDF (metres) and its YAML (millimetres), resolution given with a
/// unit: the same voxels, counts and reachability, the centres 1000 times apart.
TEST_F(ReachApp, UrdfInMetresAndYamlInMillimetresGiveTheSameMap) {
  for (const char* format : {"urdf", "yaml"}) {
    const test::RunResult r = test::run(
        kReach + " --robot " + std::string(MCWS_ROBOTS_DIR) + "/inspection6." + format +
        " --resolution 20cm --samples 200000 --output " + out(std::string(format) + ".pcd"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  pcl::PointCloud<ReachPoint> urdf, yaml;
  ASSERT_EQ(pcl::io::loadPCDFile(out("urdf.pcd"), urdf), 0);
  ASSERT_EQ(pcl::io::loadPCDFile(out("yaml.pcd"), yaml), 0);
  ASSERT_EQ(urdf.size(), yaml.size());
  for (std::size_t v = 0; v < urdf.size(); ++v) {
    EXPECT_EQ(urdf[v].count, yaml[v].count);
    EXPECT_EQ(urdf[v].reachability, yaml[v].reachability);
    EXPECT_NEAR(urdf[v].x * 1000.0, yaml[v].x, 1e-3);
    EXPECT_NEAR(urdf[v].z * 1000.0, yaml[v].z, 1e-3);
  }
}

TEST_F(ReachApp, PicturesShowTheMap) {
  const test::RunResult r =
      test::run(kReach + " --robot " + test::robotPath("inspection6") +
                " --resolution 20cm --samples 100000 --output " + out() + " --halfcut " +
                out("cut.png") + " --histogram " + out("hist.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  pcl::PointCloud<ReachPoint> map;
  ASSERT_EQ(pcl::io::loadPCDFile(out(), map), 0);
  float max_d = 0.0f;
  for (const ReachPoint& p : map) max_d = std::max(max_d, p.reachability);
  // The slab is the layer of 20 cm voxels whose y range [c - 100, c + 100) holds y = 0.
  Eigen::Array2f lo(1e9f, 1e9f), hi(-1e9f, -1e9f);  // x, z of its voxel centres
  for (const ReachPoint& p : map) {
    if (p.y - 100.0f <= 0.0f && 0.0f < p.y + 100.0f) {
      lo = lo.min(Eigen::Array2f(p.x, p.z));
      hi = hi.max(Eigen::Array2f(p.x, p.z));
    }
  }
  ASSERT_LT(lo.x(), hi.x());

  // Histogram of D over [0, 1] (its x range), bins of 0.05 drawn in #6b9efc: the bars end at the
  // bin holding the largest D of the map, within two pixels.
  const test::PngImage hist(out("hist.png"));
  ASSERT_EQ(hist.width(), 1000);
  ASSERT_EQ(hist.height(), 650);
  const test::PixelBox frame = hist.frame();
  ASSERT_FALSE(frame.empty());
  test::PixelBox bars = frame;
  bars.y0 += 40;  // below the legend's sample
  const test::PixelBox drawn = hist.box(0x6b9efc, 8, bars);
  ASSERT_FALSE(drawn.empty());
  const double pixels_per_d = frame.x1 - frame.x0;
  EXPECT_NEAR(drawn.x0, frame.x0, 2.0);
  EXPECT_NEAR(drawn.x1, frame.x0 + std::ceil(max_d / 0.05) * 0.05 * pixels_per_d, 2.0)
      << "largest D " << max_d;
  EXPECT_NEAR(drawn.y1, frame.y1, 2.0);  // bars stand on the axis

  // Half-cut: the slab's voxels as squares, equal scales on both axes (size ratio -1): the drawn
  // cells span the centres' extent plus one voxel in x and in z, in the same proportion.
  const test::PngImage cut(out("cut.png"));
  ASSERT_EQ(cut.width(), 1100);
  ASSERT_EQ(cut.height(), 900);
  const test::PixelBox plot = cut.frame();
  ASSERT_FALSE(plot.empty());
  const test::PixelBox cells = cut.box([](test::Rgb c) { return !test::isGrey(c); }, plot);
  ASSERT_FALSE(cells.empty());
  const double ratio = (hi.x() - lo.x() + 200.0) / (hi.y() - lo.y() + 200.0);
  EXPECT_NEAR(static_cast<double>(cells.width()) / cells.height(), ratio, 0.02);
  // inspection6 turns about its base's z axis: the cells are centred in x as the data are.
  const double centre = 0.5 * (cells.x0 + cells.x1), data_centre = 0.5 * (lo.x() + hi.x());
  EXPECT_NEAR((centre - 0.5 * (plot.x0 + plot.x1)) / cells.width(),
              data_centre / (hi.x() - lo.x() + 200.0), 0.01);
}

/// mcws_sample --quality on the planar 2R arm: manipulability l1 l2 |sin q2| (closed form) and
/// the inverse condition number of its 2 x 2 Jacobian, from the singular values of a 2 x 2
/// matrix in closed form.
TEST(SampleQuality, PlanarArmMatchesTheClosedForm) {
  test::TempDir dir;
  const std::string cloud_path = dir.file("q.pcd");
  const test::RunResult r = test::run(kSample + " --robot " + test::robotPath("planar2") +
                                      " --samples 2000 --quality --json --output " + cloud_path);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["quality"]["manipulability_unit"], "cm^2");
  pcl::PointCloud<QualityPoint> cloud;
  ASSERT_EQ(pcl::io::loadPCDFile(cloud_path, cloud), 0);
  ASSERT_EQ(cloud.size(), 2000u);
  const double l1 = 40.0, l2 = 30.0;
  for (const QualityPoint& p : cloud) {
    const double q1 = p.q1, q2 = p.q2;
    EXPECT_NEAR(p.manipulability, l1 * l2 * std::abs(std::sin(q2)), 2e-3);
    const double a = -l1 * std::sin(q1) - l2 * std::sin(q1 + q2), b = -l2 * std::sin(q1 + q2);
    const double c = l1 * std::cos(q1) + l2 * std::cos(q1 + q2), d = l2 * std::cos(q1 + q2);
    // Singular values of [[a, b], [c, d]]: sqrt((S +- sqrt(S^2 - 4 det^2)) / 2), S = |J|_F^2.
    const double S = a * a + b * b + c * c + d * d, det = a * d - b * c;
    const double root = std::sqrt(std::max(0.0, S * S - 4 * det * det));
    const double sigma_max = std::sqrt((S + root) / 2), sigma_min = std::sqrt((S - root) / 2);
    EXPECT_NEAR(p.inverse_condition, sigma_min / sigma_max, 1e-4);
  }
  // An arm with a prismatic joint (the de-icing arm's telescope) says its unit is mixed.
  const test::RunResult deicing =
      test::run(kSample + " --robot " + test::robotPath("deicing") +
                " --samples 10 --quality --json --output " + dir.file("d.pcd"));
  ASSERT_EQ(deicing.exit_code, 0) << deicing.err;
  EXPECT_THAT(
      nlohmann::json::parse(deicing.out)["quality"]["manipulability_unit"].get<std::string>(),
      ::testing::StartsWith("mixed"));
  // Other tools read the file as plain workspace points.
  pcl::PointCloud<WorkspacePoint> plain;
  ASSERT_EQ(pcl::io::loadPCDFile(cloud_path, plain), 0);
  EXPECT_FLOAT_EQ(plain[7].x, cloud[7].x);
}

TEST(SampleQuality, QualityFlagsNeedQualityAndARobot) {
  test::TempDir dir;
  test::expectToolFailure(kSample, "--shape disk --quality --output " + dir.file("q.pcd"), 2,
                          "--quality need --robot", dir);
  test::expectToolFailure(
      kSample,
      "--robot " + test::robotPath("planar2") + " --length 3 --output " + dir.file("q.pcd"), 2,
      "--quality-task and --length need --quality", dir);
  test::expectToolFailure(kSample,
                          "--robot " + test::robotPath("planar2") +
                              " --quality --quality-task spin --output " + dir.file("q.pcd"),
                          2, "--quality-task", dir);
}

}  // namespace
}  // namespace mcws
