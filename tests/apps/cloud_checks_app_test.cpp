// What mcws_boundary and mcws_measure check of a cloud before they work on it (issue 17 section
// 3): a --boundary that is not a subset of --input, a --plane the cloud is flat in, clouds with no
// region (one point, copies of one point, all NaN) treated alike in 2-D and 3-D, and numeric
// flags outside the range that makes sense for the cloud. Each was exit 0 with a meaningless
// number before.
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "apps/tool_paths.h"
#include "mcws/points/point_types.h"
#include "test_support.h"

namespace mcws {
namespace {

/// An n x n grid of spacing 1 in the x-z plane (y = 0) shifted by `offset` along x.
pcl::PointCloud<pcl::PointXYZ> xzGrid(int n, float offset = 0.0f) {
  pcl::PointCloud<pcl::PointXYZ> cloud;
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < n; ++k) cloud.push_back({offset + static_cast<float>(i), 0.0f, float(k)});
  }
  return cloud;
}

class CloudChecksApp : public ::testing::Test {
 protected:
  std::string save(const std::string& name, const pcl::PointCloud<pcl::PointXYZ>& cloud) {
    const std::string path = inputs_.file(name);
    EXPECT_EQ(pcl::io::savePCDFileBinary(path, cloud), 0);
    return path;
  }
  /// `tool args` fails with `code` and `message`, writing nothing.
  void expectFailure(const std::string& tool, const std::string& args, int code,
                     const std::string& message) {
    test::expectToolFailure(tool, args, code, message, outputs_);
  }
  std::string out() const { return outputs_.file("out.pcd"); }

  test::TempDir inputs_, outputs_;
};

TEST_F(CloudChecksApp, MeasureRefusesABoundaryOfAnotherCloud) {
  const std::string cloud = save("a.pcd", xzGrid(30));
  const std::string other = save("b.pcd", xzGrid(30, 0.5f));  // every point off the grid
  const std::string boundary = inputs_.file("a_boundary.pcd");
  ASSERT_EQ(
      test::run(kBoundary + " --input " + cloud + " --plane xz --output " + boundary).exit_code, 0);
  // Its own boundary: the column cross-check is there, and the 30 x 30 grid's area is 29^2
  // whichever method (the cross-check's rectangles are a column wide: 29 + 1 columns of 29).
  const test::RunResult ok =
      test::run(kMeasure + " --input " + cloud + " --plane xz --boundary " + boundary + " --json");
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_TRUE(nlohmann::json::parse(ok.out).contains("cross_check")) << ok.out;
  // Another cloud's points as the boundary: point 0 of b.pcd is (0.5, 0, 0), not on the grid.
  expectFailure(kMeasure, "--input " + cloud + " --plane xz --boundary " + other, 1,
                "--boundary " + other + ": point 0 (0.5, 0, 0) is not a point of --input " + cloud);
}

TEST_F(CloudChecksApp, APlaneTheCloudIsFlatInIsAUsageErrorNamingTheRightPlane) {
  const std::string cloud = save("xz.pcd", xzGrid(20));
  const std::string message = cloud +
                              ": the cloud is flat in y (extent 0, its largest 19), so in the xy "
                              "plane every point is on its boundary and the area is 0; it lies "
                              "in the xz plane";
  expectFailure(kMeasure, "--input " + cloud + " --plane xy", 2, message);
  expectFailure(kBoundary, "--input " + cloud + " --plane xy --output " + out(), 2, message);
  // The right plane works: the triangles of the 20 x 20 grid of spacing 1 cover 19^2 (the edge
  // correction, made for random samples, is not what this checks).
  const test::RunResult ok = test::run(kMeasure + " --input " + cloud + " --plane xz --json");
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(ok.out).at("uncorrected").get<double>(), 361.0) << ok.out;
}

TEST_F(CloudChecksApp, CloudsWithoutARegionFailAlikeIn2DAnd3D) {
  pcl::PointCloud<pcl::PointXYZ> one, copies, nan;
  one.push_back({1.0f, 2.0f, 3.0f});
  for (int k = 0; k < 50; ++k) copies.push_back({1.0f, 2.0f, 3.0f});
  const float q = std::numeric_limits<float>::quiet_NaN();
  for (int k = 0; k < 50; ++k) nan.push_back({q, q, q});
  struct Case {
    std::string file, of;
  };
  for (const Case& c : {Case{save("one.pcd", one), "(of 1 point)"},
                        Case{save("copies.pcd", copies), "(of 50 points)"},
                        Case{save("nan.pcd", nan), "(of 50 points, 50 not finite)"}}) {
    const std::size_t distinct = c.file.find("nan") != std::string::npos ? 0 : 1;
    const std::string points =
        std::to_string(distinct) + " distinct finite point" + (distinct == 1 ? "" : "s");
    const std::string in_plane =
        c.file + ": " + points + " in the xz plane " + c.of + "; a region there needs at least 3";
    const std::string in_3d =
        c.file + ": " + points + " in 3-D " + c.of + "; a region there needs at least 4";
    expectFailure(kBoundary, "--input " + c.file + " --plane xz --output " + out(), 1, in_plane);
    expectFailure(kMeasure, "--input " + c.file + " --plane xz", 1, in_plane);
    expectFailure(kBoundary, "--input " + c.file + " --output " + out(), 1, in_3d);
    expectFailure(kMeasure, "--input " + c.file, 1, in_3d);
  }
  // Points on a line have distinct positions but no region in any plane.
  pcl::PointCloud<pcl::PointXYZ> line;
  for (int k = 0; k < 10; ++k) line.push_back({static_cast<float>(k), 0.0f, 0.0f});
  const std::string path = save("line.pcd", line);
  expectFailure(kMeasure, "--input " + path + " --plane xz", 1,
                path + ": the points extend along x only (a line): no region in the xz plane");
}

TEST_F(CloudChecksApp, AFlatCloudIsNamedByItsFlattestAxisAndItsRealExtents) {
  // 2e6 x 2 x 2e-3: flat in z (1e-9 of the largest extent), not in y (the old message said
  // "y extent 0" for a y extent of 2).
  pcl::PointCloud<pcl::PointXYZ> slab;
  for (float x : {0.0f, 2e6f}) {
    for (float y : {0.0f, 2.0f}) {
      for (float z : {0.0f, 2e-3f}) slab.push_back({x, y, z});
    }
  }
  const std::string path = save("slab.pcd", slab);
  const std::string message = path + ": the cloud is flat in z (extent 0.002, its largest 2e+06)";
  expectFailure(kBoundary, "--input " + path + " --output " + out(), 1, message);
  expectFailure(kMeasure, "--input " + path, 1, message);
}

TEST_F(CloudChecksApp, TheMeasuresOwnFailuresNameTheCloud) {
  // A tilted plane extends along every axis (so it is not flat along one), but holds no volume:
  // the triangulation's "lie in a plane" named no file.
  pcl::PointCloud<pcl::PointXYZ> tilted;
  for (int i = 0; i < 20; ++i) {
    for (int k = 0; k < 20; ++k) {
      const float u = static_cast<float>(i), v = static_cast<float>(k);
      tilted.push_back({u, v, 0.5f * u + 0.25f * v});  // exact in float: one plane
    }
  }
  const std::string path = save("tilted.pcd", tilted);
  expectFailure(kMeasure, "--input " + path, 1, path + ": the points lie in a plane: no volume");
}

TEST_F(CloudChecksApp, NumericFlagsOutsideTheCloudsRangeAreUsageErrors) {
  // 40 x 40 grid of spacing 1: extent 39 in the plane; meanSpacing() estimates the spacing from
  // the cells the points occupy as 1.02375, so lengths run from 0.102375.
  const std::string cloud = save("grid.pcd", xzGrid(40));
  const std::string boundary = inputs_.file("boundary.pcd");
  ASSERT_EQ(
      test::run(kBoundary + " --input " + cloud + " --plane xz --output " + boundary).exit_code, 0);
  const std::string measure = "--input " + cloud + " --plane xz --boundary " + boundary;
  expectFailure(kMeasure, measure + " --column-width 1e-9", 2,
                "--column-width: 1e-9 is not 0 or in [0.102375, 39] [length unit]");
  expectFailure(kMeasure, measure + " --column-width 1e30", 2,
                "--column-width: 1e30 is not 0 or in [0.102375, 39] [length unit]");
  expectFailure(kMeasure, "--input " + cloud + " --plane xz --alpha 0.5", 2,
                "--alpha: 0.5 is not in [1, 1000] local spacings");
  const std::string boundary_args = "--input " + cloud + " --plane xz --output " + out();
  expectFailure(kBoundary, boundary_args + " --method grid --cell 1e-9", 2,
                "--cell: 1e-9 is not in [0.102375, 39] [length unit]");
  expectFailure(kBoundary, boundary_args + " --radius 100", 2,
                "--radius: 100 is not in [0.102375, 39] [length unit]");
  expectFailure(kBoundary, boundary_args + " --radius 2 --outer-radius 1", 2,
                "--outer-radius: 1 is not in (2, 39] [length unit]");
  expectFailure(kBoundary, boundary_args + " --adaptive 5000", 2,
                "--adaptive: 5000 is more than 1000");
  expectFailure(kBoundary, boundary_args + " --hull-depth 50", 2,
                "--hull-depth: 50 is not 0 (off) or in [0.1, 10] local spacings");
  // Values inside the ranges run.
  EXPECT_EQ(test::run(kMeasure + " " + measure + " --column-width 2").exit_code, 0);
  EXPECT_EQ(test::run(kBoundary + " " + boundary_args + " --radius 2 --outer-radius 3").exit_code,
            0);
}

}  // namespace
}  // namespace mcws
