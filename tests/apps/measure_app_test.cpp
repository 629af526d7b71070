// mcws_measure through its command line.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "apps/tool_paths.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

class MeasureApp : public ::testing::Test {
 protected:
  void SetUp() override {
    disk_ = dir_.file("disk.pcd");
    rim_ = dir_.file("rim.pcd");
    ASSERT_EQ(
        test::run(std::string(MCWS_SAMPLE_EXE) + " --shape disk --samples 50000 --output " + disk_)
            .exit_code,
        0);
    ASSERT_EQ(test::run(std::string(MCWS_BOUNDARY_EXE) + " --input " + disk_ +
                        " --plane xy --output " + rim_)
                  .exit_code,
              0);
  }
  void expectFailure(const std::string& args, int exit_code, const std::string& message) {
    test::expectToolFailure(kMeasure, args, exit_code, message, nothing_written_);
  }
  test::TempDir dir_, nothing_written_;  // inputs; a directory that must stay empty
  std::string disk_, rim_;
};

TEST_F(MeasureApp, HelpExitsZero) {
  const test::RunResult r = test::run(kMeasure + " --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, HasSubstr("--boundary"));
}

TEST_F(MeasureApp, DiskAreaWithColumnCrossCheck) {
  const test::RunResult r =
      test::run(kMeasure + " --input " + disk_ + " --plane xy --boundary " + rim_ + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["method"], "delaunay");
  EXPECT_NEAR(json["area"].get<double>() / M_PI, 1.0, 0.002);
  EXPECT_NEAR(json["cross_check"]["area"].get<double>() / M_PI, 1.0, 0.02);
  const test::RunResult column =
      test::run(kMeasure + " --input " + disk_ + " --plane xy --boundary " + rim_ +
                " --method column --json");
  ASSERT_EQ(column.exit_code, 0) << column.err;
  EXPECT_EQ(nlohmann::json::parse(column.out)["area"], json["cross_check"]["area"]);
}

TEST_F(MeasureApp, SameVolumeForAnyThreadCount) {
  // The 3-D triangulation runs on TBB's threads and lists its cells in an order that depends on
  // their number; the volume (an order-free sum) and the counts must not.
  const std::string ball = dir_.file("ball.pcd");
  ASSERT_EQ(
      test::run(std::string(MCWS_SAMPLE_EXE) + " --shape ball --samples 60000 --output " + ball)
          .exit_code,
      0);
  nlohmann::json first;
  for (const char* threads : {"1", "2", "3"}) {
    const test::RunResult r =
        test::run(kMeasure + " --input " + ball + " --threads " + threads + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto json = nlohmann::json::parse(r.out);
    EXPECT_NEAR(json["volume"].get<double>() / (4.0 / 3.0 * M_PI), 1.0, 0.002) << threads;
    json.erase("seconds");
    if (first.is_null()) first = json;
    EXPECT_EQ(json, first) << threads << " threads";  // every number to the last bit
  }
}

TEST_F(MeasureApp, TheShellMeasuresWhatEveryPointMeasures) {
  // The default triangulates the shell of points an empty ball of alpha radius may touch;
  // --triangulate all triangulates every point: the same area (to the rounding of the per-triangle
  // sum) and counts, "triangulated" telling them apart.
  nlohmann::json runs[2];
  const char* modes[2] = {"shell", "all"};
  for (int k = 0; k < 2; ++k) {
    const test::RunResult r =
        test::run(kMeasure + " --input " + disk_ + " --plane xy --json --triangulate " + modes[k]);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    runs[k] = nlohmann::json::parse(r.out);
  }
  const auto& shell = runs[0];
  const auto& all = runs[1];
  EXPECT_NEAR(shell["area"].get<double>() / all["area"].get<double>(), 1.0, 1e-11);
  EXPECT_EQ(shell["boundary_vertices"], all["boundary_vertices"]);
  EXPECT_EQ(shell["outside"], all["outside"]);
  EXPECT_EQ(all["triangulated"], all["points"]);
  // The disk of 50000 points is about 250 spacings across: its shell a small share.
  EXPECT_LT(shell["triangulated"].get<double>(), 0.25 * shell["points"].get<double>());
}

TEST_F(MeasureApp, BadInput) {
  expectFailure("--input " + disk_ + " --plane xy --threads -1", 2, "--threads");
  expectFailure("--input " + disk_ + " --plane xy --method voxels", 2, "--method: 'voxels' is not");
  expectFailure("--input " + disk_ + " --plane xy --method column", 2,
                "--method column measures an area: give --plane and --boundary");
  expectFailure("--input " + disk_ + " --plane xq", 2, "--plane: unknown plane 'xq'");
  expectFailure("--input " + disk_ + " --plane xy --alpha 0", 2,
                "--alpha: 0 is not a positive number");
  expectFailure("--input " + disk_ + " --plane xy --alpha=-1", 2,
                "--alpha: -1 is not a positive number");
  expectFailure("--input " + disk_ + " --plane xy --threads 257", 2,
                "--threads: 257 is more than 256");
  expectFailure("--input " + disk_ + " --plane xy --boundary " + rim_ + " --column-width=-1", 2,
                "--column-width: -1 is less than 0");
  expectFailure("--input " + disk_ + " --plane xy --correction some", 2,
                "--correction: 'some' is not efron or none");
  expectFailure("--input " + disk_ + " --plane xy --leave-one-out exact", 2,
                "--leave-one-out: 'exact' is not star or reinsert");
  expectFailure("--input " + disk_ + " --plane xy --triangulate some", 2,
                "--triangulate: 'some' is not shell or all");
  expectFailure(
      "--input " + disk_ + " --plane xy --boundary " + rim_ + " --method column --triangulate all",
      2, "--triangulate does not apply to --method column");
  expectFailure("--input " + disk_, 1, "the cloud is flat in z (extent 0, its largest 1.99");
  expectFailure("--input " + dir_.file("none.pcd"), 1, "cloud file does not exist");
  expectFailure(
      "--input " + dir_.file("none.pcd") + " --plane xy --method column --boundary " + rim_, 1,
      "none.pcd: cloud file does not exist");
}

/// What `sha256sum` says of a file (an oracle independent of the tools' OpenSSL).
std::string sha256sum(const std::string& path) {
  const test::RunResult r = test::run("sha256sum " + path);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.out.substr(0, r.out.find(' '));
}

/// The value of `key=` in the mcws line of a cloud.
std::string recorded(const std::string& path, const std::string& key) {
  const std::string text = test::readFile(path);
  const std::size_t at = text.find(" " + key + "=");
  if (at == std::string::npos) return "";
  const std::size_t begin = at + key.size() + 2;
  return text.substr(begin, text.find_first_of(" \n", begin) - begin);
}

/// The point count a PCD header gives.
std::string headerPoints(const std::string& path) {
  const std::string text = test::readFile(path);
  const std::size_t at = text.find("\nPOINTS ") + 8;
  return text.substr(at, text.find('\n', at) - at);
}

/// A --boundary must be the boundary of the --input cloud itself (issue 31, section 3): every
/// point of the boundary of a subset, or of an older cloud, is a point of the cloud too.
TEST(MeasureBoundaryOf, RefusesTheBoundaryOfASubsetOrOfAnOlderCloud) {
  test::TempDir dir, nothing_written;
  const std::string robot = test::robotPath("deicing");
  const std::string full = dir.file("full.pcd"), free = dir.file("free.pcd"),
                    rim = dir.file("rim.pcd"), free_rim = dir.file("free_rim.pcd"),
                    grown = dir.file("grown.pcd");
  ASSERT_EQ(test::run(std::string(MCWS_SAMPLE_EXE) + " --robot " + robot +
                      " --fix theta3=0 --collision --samples 3000 --output " + full)
                .exit_code,
            0);
  const test::RunResult selected = test::run(std::string(MCWS_SELECT_EXE) + " --input " + full +
                                             " --label 0 --json --output " + free);
  ASSERT_EQ(selected.exit_code, 0) << selected.err;
  const std::uint64_t free_points = nlohmann::json::parse(selected.out)["points_out"];
  ASSERT_LT(free_points, 3000u);  // a strict subset
  for (const auto& [in, out] : {std::pair{full, rim}, std::pair{free, free_rim}}) {
    const test::RunResult r = test::run(std::string(MCWS_BOUNDARY_EXE) + " --input " + in +
                                        " --plane xz --output " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  // mcws_boundary records its input: the count and the hash of its bytes (also with --tiles).
  EXPECT_EQ(recorded(rim, "input_points"), "3000");
  EXPECT_EQ(recorded(rim, "input_sha256"), sha256sum(full));
  EXPECT_EQ(recorded(rim, "boundary_points"), headerPoints(rim));
  EXPECT_EQ(recorded(free_rim, "input_points"), std::to_string(free_points));
  EXPECT_EQ(recorded(free_rim, "input_sha256"), sha256sum(free));
  EXPECT_EQ(recorded(free_rim, "boundary_points"), headerPoints(free_rim));
  const std::string tiled = dir.file("tiled.pcd");
  ASSERT_EQ(test::run(std::string(MCWS_BOUNDARY_EXE) + " --input " + full +
                      " --plane xz --tiles 2 --radius 8 --hull-depth 0 --output " + tiled)
                .exit_code,
            0);
  EXPECT_EQ(recorded(tiled, "input_points"), "3000");
  EXPECT_EQ(recorded(tiled, "input_sha256"), sha256sum(full));
  EXPECT_EQ(recorded(tiled, "boundary_points"), headerPoints(tiled));

  const std::string args = " --plane xz --method column --json";
  const test::RunResult own =
      test::run(kMeasure + " --input " + full + args + " --boundary " + rim);
  ASSERT_EQ(own.exit_code, 0) << own.err;
  // The free subset's boundary: every point of it is a point of the full cloud.
  test::expectToolFailure(kMeasure, "--input " + full + args + " --boundary " + free_rim, 1,
                          "--boundary " + free_rim + " is the boundary of a cloud of " +
                              std::to_string(free_points) + " points, sha256 " +
                              sha256sum(free).substr(0, 12) + "..., not of --input " + full +
                              " (3000 points, sha256 " + sha256sum(full).substr(0, 12) + "...)",
                          nothing_written);
  // The boundary of the cloud before refinement added samples to it.
  ASSERT_EQ(test::run(std::string(MCWS_REFINE_EXE) + " --robot " + robot + " --input " + rim +
                      " --cloud " + full + " --samples 500 --output " + grown)
                .exit_code,
            0);
  test::expectToolFailure(kMeasure, "--input " + grown + args + " --boundary " + rim, 1,
                          "is the boundary of a cloud of 3000 points", nothing_written);
  // A boundary that predates the record, or has no line at all, for a cloud that has one.
  std::string text = test::readFile(rim);
  // A part of the boundary: its colliding points left out (mcws_select copies the line).
  const std::string rim_part = dir.file("rim_part.pcd");
  const test::RunResult part = test::run(std::string(MCWS_SELECT_EXE) + " --input " + rim +
                                         " --label 0 --json --output " + rim_part);
  ASSERT_EQ(part.exit_code, 0) << part.err;
  const std::uint64_t part_points = nlohmann::json::parse(part.out)["points_out"];
  ASSERT_LT(part_points, std::stoull(headerPoints(rim)));  // a strict part
  test::expectToolFailure(kMeasure, "--input " + full + args + " --boundary " + rim_part, 1,
                          "--boundary " + rim_part + " has " + std::to_string(part_points) +
                              " points, but mcws_boundary found " + headerPoints(rim) +
                              " on the boundary of --input " + full,
                          nothing_written);
  const std::string keys = " input_points=3000 input_sha256=" + sha256sum(full) +
                           " boundary_points=" + headerPoints(rim);
  ASSERT_NE(text.find(keys), std::string::npos);
  text.erase(text.find(keys), keys.size());
  test::writeFile(dir.file("old_rim.pcd"), text);
  test::expectToolFailure(
      kMeasure, "--input " + full + args + " --boundary " + dir.file("old_rim.pcd"), 1,
      "its '# mcws' line predates input_points=, input_sha256=", nothing_written);
  text.erase(text.find("# mcws"), text.find('\n', text.find("# mcws")) - text.find("# mcws") + 1);
  test::writeFile(dir.file("bare_rim.pcd"), text);
  test::expectToolFailure(
      kMeasure, "--input " + full + args + " --boundary " + dir.file("bare_rim.pcd"), 1,
      "no '# mcws' header line, but --input records its robot", nothing_written);
}

}  // namespace
}  // namespace mcws
