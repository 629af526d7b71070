// mcws_sample --collision, mcws_select and mcws_collide through their command lines: labels and
// their counts, the split into clouds, one configuration's pairs, and bad input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>

#include <nlohmann/json.hpp>

#include "apps/tool_paths.h"
#include "mcws/points/point_types.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

class CollisionApps : public ::testing::Test {
 protected:
  std::string ta1400() const { return test::robotPath("ta1400"); }
  test::TempDir dir_;
};

TEST_F(CollisionApps, HelpStatesTheLabelRule) {
  const test::RunResult sample = test::run(kSample + " --help");
  EXPECT_EQ(sample.exit_code, 0);
  EXPECT_THAT(sample.out, HasSubstr("--collision"));
  EXPECT_THAT(sample.out, HasSubstr("the lowest non-zero code"));
  for (const std::string& tool : {kSelect, kCollide}) {
    const test::RunResult r = test::run(tool + " --help");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_THAT(r.out, HasSubstr("--json"));
  }
}

TEST_F(CollisionApps, LabelledSamplingCountsAndSplitsIntoClouds) {
  const std::string cloud = dir_.file("c.pcd");
  const test::RunResult r = test::run(kSample + " --robot " + ta1400() +
                                      " --collision --samples 20000 --json --output " + cloud);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto summary = nlohmann::json::parse(r.out);
  std::size_t total = 0;
  for (const char* name : {"free", "link-link", "tool-link", "environment"}) {
    const std::size_t count = summary["labels"][name]["count"];
    EXPECT_DOUBLE_EQ(summary["labels"][name]["fraction"].get<double>(), count / 20000.0);
    total += count;
  }
  EXPECT_EQ(total, 20000u);
  EXPECT_GT(summary["labels"]["link-link"]["count"].get<std::size_t>(), 0u);
  EXPECT_GT(summary["labels"]["tool-link"]["count"].get<std::size_t>(), 0u);
  EXPECT_EQ(summary["labels"]["environment"]["count"].get<std::size_t>(), 0u);  // no scene

  // The file's labels are the counts; mcws_select keeps exactly the asked-for labels.
  pcl::PointCloud<WorkspacePoint> points;
  ASSERT_EQ(pcl::io::loadPCDFile(cloud, points), 0);
  std::size_t collided = 0;
  for (const auto& p : points) collided += p.label == kLabelLinkLink || p.label == kLabelToolLink;
  const std::string out = dir_.file("collided.pcd");
  const test::RunResult select =
      test::run(kSelect + " --input " + cloud + " --label 1,2 --json --output " + out);
  ASSERT_EQ(select.exit_code, 0) << select.err;
  EXPECT_EQ(nlohmann::json::parse(select.out)["points_out"].get<std::size_t>(), collided);
  EXPECT_EQ(collided, summary["labels"]["link-link"]["count"].get<std::size_t>() +
                          summary["labels"]["tool-link"]["count"].get<std::size_t>());
  pcl::PointCloud<WorkspacePoint> kept;
  ASSERT_EQ(pcl::io::loadPCDFile(out, kept), 0);
  ASSERT_EQ(kept.size(), collided);
  for (const auto& p : kept) EXPECT_TRUE(p.label == 1u || p.label == 2u);
}

TEST_F(CollisionApps, LabelledFileIsTheSameForOneAndTwoThreads) {
  const std::string one = dir_.file("one.pcd"), two = dir_.file("two.pcd");
  ASSERT_EQ(test::run(kSample + " --robot " + ta1400() +
                      " --collision --samples 30000 --threads 1 --output " + one)
                .exit_code,
            0);
  ASSERT_EQ(test::run(kSample + " --robot " + ta1400() +
                      " --collision --samples 30000 --threads 2 --output " + two)
                .exit_code,
            0);
  EXPECT_TRUE(test::readFile(one) == test::readFile(two));
}

TEST_F(CollisionApps, CollideNamesThePairsAndTheirPenetration) {
  // The folded elbow of tests/collision: link j4 250 mm deep in the base.
  const test::RunResult r =
      test::run(kCollide + " --robot " + ta1400() + " --q '0 0.8726646 1.0471976 0 0 0' --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto out = nlohmann::json::parse(r.out);
  EXPECT_EQ(out["label"], 1);
  EXPECT_EQ(out["label_name"], "link-link");
  bool found = false;
  for (const auto& pair : out["pairs"]) {
    if (pair["a"] == "base" && pair["b"] == "j4") {
      found = true;
      EXPECT_NEAR(pair["distance"].get<double>(), -250.0, 1e-6);
    }
  }
  EXPECT_TRUE(found) << r.out;
  const test::RunResult free = test::run(kCollide + " --robot " + ta1400() + " --q '0 0 0 0 0 0'");
  EXPECT_EQ(free.exit_code, 0);
  EXPECT_THAT(free.out, HasSubstr("label 0 (free)"));
  EXPECT_THAT(free.out, HasSubstr("j5 - tool"));
  EXPECT_THAT(free.out, HasSubstr("clearance 25 mm"));
}

TEST_F(CollisionApps, BadInput) {
  // A robot without collision geometry.
  test::expectToolFailure(kSample,
                          "--robot " + test::robotPath("insulator_cleaner") +
                              " --collision --output " + dir_.file("x.pcd"),
                          1, "has no collision geometry (collision: key)", dir_);
  test::expectToolFailure(kSample, "--shape disk --collision --output " + dir_.file("x.pcd"), 2,
                          "--fix, --point, --collision and --quality need --robot", dir_);
  // A missing mesh: one line naming the file and the shape.
  test::TempDir robots;
  const std::string broken = robots.file("broken.yaml");
  std::string text = test::readFile(test::robotPath("ta1400_mesh"));
  for (std::size_t at; (at = text.find("file: meshes/")) != std::string::npos;)
    text.replace(at, 13, "file: " + std::string(MCWS_ROBOTS_DIR) + "/meshes/");
  text.replace(text.find("torch_body.stl"), 14, "no_torch.stl");
  test::writeFile(broken, text);
  test::expectToolFailure(kCollide, "--robot " + broken + " --q '0 0 0 0 0 0'", 1,
                          "collision: tool shape 1: mesh '", dir_);
  test::expectToolFailure(kCollide, "--robot " + broken + " --q '0 0 0 0 0 0'", 1,
                          "no_torch.stl': file does not exist", dir_);
  test::expectToolFailure(kCollide, "--robot " + ta1400() + " --q '0 0 0'", 2, "--q:", dir_);
  // mcws_select: a bad label list, a cloud without labels.
  const std::string plain = robots.file("plain.pcd");
  pcl::PointCloud<pcl::PointXYZ> xyz;
  xyz.push_back({1, 2, 3});
  pcl::io::savePCDFileBinary(plain, xyz);
  test::expectToolFailure(kSelect, "--input " + plain + " --label x --output " + dir_.file("o.pcd"),
                          2, "--label", dir_);
  test::expectToolFailure(kSelect, "--input " + plain + " --label 0 --output " + dir_.file("o.pcd"),
                          1, "has no field 'label'", dir_);
  test::expectToolFailure(kSelect,
                          "--input " + plain + " --label 1.5 --output " + dir_.file("o.pcd"), 2,
                          "is not a list of whole numbers", dir_);
}

}  // namespace
}  // namespace mcws
