// scripts/view_plane.sh --print: the pcl_viewer -cam string that faces a plane cloud, checked
// against camera positions worked by hand; bad arguments.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

const std::string kView = std::string(MCWS_SCRIPTS_DIR) + "/view_plane.sh";
// The script prints 6 significant digits.
constexpr double kRelativeTolerance = 1e-5;

/// An ASCII PCD file with fields x y z.
void writeXyz(const std::string& path, const std::vector<std::vector<double>>& points) {
  std::ostringstream pcd;
  pcd << "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH "
      << points.size() << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << points.size()
      << "\nDATA ascii\n";
  for (const auto& p : points) pcd << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
  test::writeFile(path, pcd.str());
}

/// The numbers of a -cam string, in order (its separators '/' and ',' dropped).
std::vector<double> camNumbers(const std::string& cam) {
  std::vector<double> numbers;
  std::string field;
  std::istringstream in(cam);
  while (std::getline(in, field, '/')) {
    std::istringstream parts(field);
    for (std::string n; std::getline(parts, n, ',');) numbers.push_back(std::stod(n));
  }
  return numbers;
}

/// The -cam string of `view_plane.sh --print ARGS`, which must print "pcl_viewer CLOUD -cam S".
std::string camOf(const std::string& args, const std::string& cloud) {
  const test::RunResult r = test::run(kView + " --print " + args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const std::string prefix = "pcl_viewer " + cloud + " -cam ";
  EXPECT_EQ(r.out.rfind(prefix, 0), 0u) << r.out;
  if (r.out.rfind(prefix, 0) != 0) return "";
  std::string rest = r.out.substr(prefix.size());
  return rest.substr(0, rest.find_first_of(" \n"));
}

void expectCamera(const std::string& cam, const std::vector<double>& expected) {
  const std::vector<double> got = camNumbers(cam);
  ASSERT_EQ(got.size(), expected.size()) << cam;
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_NEAR(got[i], expected[i], kRelativeTolerance * (1 + std::abs(expected[i])))
        << "number " << i << " of " << cam;
  }
}

TEST(ViewPlane, FacesAnXZCloudFromMinusYWithZUp) {
  // A 4 x 2 rectangle in the X-Z plane, window 800 x 600. Worked by hand: focal point = centre
  // (2, 0, 1); the window's half height must show 1.1 max(2 * 600 / 800, 1) = 1.65; pcl_viewer's
  // field of view is 30 deg, so the distance is 1.65 / tan(15 deg) = 6.15788 (plus half the
  // thickness, 0); the camera at (2, -6.15788, 1) looks along +y (x to the right) with z up;
  // clipping range [d / 100, 10 d].
  test::TempDir dir;
  const std::string cloud = dir.file("rect.pcd");
  writeXyz(cloud, {{0, 0, 0}, {4, 0, 0}, {0, 0, 2}, {4, 0, 2}});
  const std::string expected_text =
      "0.0615788,61.5788/2,0,1/2,-6.15788,1/0,0,1/0.523599/800,600/0,0";
  const std::string cam = camOf("--size 800,600 " + cloud + " xz", cloud);
  EXPECT_EQ(cam, expected_text);
  // Without a plane, the thinnest axis (y) is the one looked along.
  EXPECT_EQ(camOf("--size 800,600 " + cloud, cloud), cam);
}

TEST(ViewPlane, FacesTheYZPlaneOfAThickCloudFromPlusX) {
  // Box x in [-1, 1], y in [0, 6], z in [0, 3], window 1000 x 500: half height
  // 1.1 max(1.5, 3 * 500 / 1000) = 1.65, distance 1.65 / tan(15 deg) + 1 (half of x's extent,
  // so that the near face fits) = 7.15788; camera at (7.15788, 3, 1.5) looking along -x
  // (y to the right), z up.
  test::TempDir dir;
  const std::string cloud = dir.file("box.pcd");
  writeXyz(cloud, {{-1, 0, 0}, {1, 6, 3}, {0, 3, 1}});
  expectCamera(
      camOf("--size 1000,500 " + cloud + " yz", cloud),
      {0.0715788, 71.5788, 0, 3, 1.5, 7.15788, 3, 1.5, 0, 0, 1, 0.523599, 1000, 500, 0, 0});
}

TEST(ViewPlane, FacesAnXYCloudFromAboveWithYUp) {
  // A unit-radius square in z = 5 (default window 1024 x 768): half height
  // 1.1 max(1, 1 * 768 / 1024) = 1.1, distance 1.1 / tan(15 deg) = 4.10526, camera at
  // (0, 0, 9.10526) looking down, y up.
  test::TempDir dir;
  const std::string cloud = dir.file("square.pcd");
  writeXyz(cloud, {{-1, -1, 5}, {1, 1, 5}});
  expectCamera(camOf(cloud, cloud),
               {0.0410526, 41.0526, 0, 0, 5, 0, 0, 9.10526, 0, 1, 0, 0.523599, 1024, 768, 0, 0});
}

TEST(ViewPlane, PassesTheArgumentsAfterDoubleDashToPclViewer) {
  test::TempDir dir;
  const std::string cloud = dir.file("rect.pcd");
  writeXyz(cloud, {{0, 0, 0}, {4, 0, 2}});
  const test::RunResult r = test::run(kView + " --print " + cloud + " xz -- -ps 3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("/0,0 -ps 3\n"));
}

TEST(ViewPlane, BadArgumentsAreUsageErrorsAndAMissingCloudFails) {
  test::TempDir dir;
  const std::string cloud = dir.file("rect.pcd");
  writeXyz(cloud, {{0, 0, 0}, {4, 0, 2}});
  struct Case {
    std::string args;
    int exit_code;
    std::string message;
  };
  for (const Case& c : std::vector<Case>{
           {cloud + " xq", 2, "the plane must be xz, xy or yz, not 'xq'"},
           {"", 2, "a cloud is required"},
           {"--size 800 " + cloud, 2, "--size must be W,H in pixels, not '800'"},
           {"--zoom 2 " + cloud, 2, "unknown option: --zoom"},
           {dir.file("missing.pcd"), 1, "cannot read input file: " + dir.file("missing.pcd")},
       }) {
    SCOPED_TRACE(c.args);
    const test::RunResult r = test::run(kView + " --print " + c.args);
    EXPECT_EQ(r.exit_code, c.exit_code) << r.err;
    EXPECT_EQ(r.err.rfind("view_plane: ", 0), 0u) << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.message));
    EXPECT_EQ(test::lineCount(r.err), 1) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

}  // namespace
}  // namespace mcws
