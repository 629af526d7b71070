// mcws_refine through its command line.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

const std::string kRefine = MCWS_REFINE_EXE;

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
  // A cloud without joint values (a shape): a2 = 0 lies outside its limits [25, 70] cm.
  const std::string disk = dir_.file("disk.pcd");
  ASSERT_EQ(test::run(std::string(MCWS_SAMPLE_EXE) + " --shape disk --samples 100 --output " + disk)
                .exit_code,
            0);
  expectFailure("--robot " + test::robotPath("deicing") + " --input " + disk +
                    " --samples 10 --output " + out,
                1, "outside joint 'a2' limits");
  expectFailure(
      "--robot " + test::robotPath("nosuch") + " --input " + rim_ + " --samples 10 --output " + out,
      1, "--robot: " + test::robotPath("nosuch") + ": robot file does not exist");
  expectFailure("--robot " + test::robotPath("deicing") + " --input " + dir_.file("missing.pcd") +
                    " --samples 10 --output " + out,
                1, "missing.pcd");
}

}  // namespace
}  // namespace mcws
