// mcws_sample through its command line: --help, every bad input of the foundation issue (one-line
// message, exit code, no output left behind), and real runs.
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
using ::testing::StartsWith;

class SampleApp : public ::testing::Test {
 protected:
  std::string out() const { return dir_.file("ws.pcd"); }
  std::string deicing() const { return test::robotPath("deicing"); }

  void expectFailure(const std::string& args, int exit_code, const std::string& message) {
    test::expectToolFailure(kSample, args, exit_code, message, dir_);
  }

  test::TempDir dir_;
};

TEST_F(SampleApp, HelpExitsZeroAndDescribesTheFlags) {
  const test::RunResult r = test::run(kSample + " --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* flag : {"--robot", "--shape", "--samples", "--seed", "--fix", "--point",
                           "--threads", "--ascii", "--json"}) {
    EXPECT_THAT(r.out, HasSubstr(flag));
  }
}

TEST_F(SampleApp, MissingOrUnreadableRobotFile) {
  expectFailure("--robot /nonexistent.yaml --output " + out(), 1,
                "--robot: /nonexistent.yaml: robot file does not exist");
  expectFailure("--robot " + dir_.file("") + " --output " + out(), 1, "is not a regular file");
}

TEST_F(SampleApp, UnknownYamlKeyAndReversedLimits) {
  test::TempDir robots;
  std::string text = test::readFile(deicing());
  const std::string bad_key = robots.file("bad_key.yaml");
  test::writeFile(bad_key, text + "colour: red\n");
  expectFailure("--robot " + bad_key + " --output " + out(), 1, "unknown key 'colour'");
  const std::string reversed = robots.file("reversed.yaml");
  text.replace(text.find("limits: [-45, 45]"), 17, "limits: [45, -45]");
  test::writeFile(reversed, text);
  expectFailure("--robot " + reversed + " --output " + out(), 1,
                "joint 2 'theta1': limits min 45 is greater than max -45");
}

TEST_F(SampleApp, RobotWithMoreJointsThanAPointRecordsIsTheRobotFilesFault) {
  // Nine revolute joints: exit 1 naming the file (it was exit 2 about a --fix never given).
  test::TempDir robots;
  std::string text = "name: nine\nunits: {length: cm, angle: deg}\nconvention: standard\njoints:\n";
  for (int k = 1; k <= 9; ++k) {
    text += "  - {name: j" + std::to_string(k) +
            ", type: revolute, a: 10, alpha: 0, d: 0, theta: 0, limits: [-90, 90]}\n";
  }
  const std::string nine = robots.file("nine.yaml");
  test::writeFile(nine, text);
  expectFailure("--robot " + nine + " --output " + out(), 1,
                nine + ": robot 'nine' has 9 joints; a workspace point records at most 8");
}

TEST_F(SampleApp, BadSampleCounts) {
  const std::string base = "--robot " + deicing() + " --output " + out();
  expectFailure(base + " --samples 0", 2, "--samples: 0 is less than 1");
  expectFailure(base + " --samples=-5", 2, "--samples: -5 is less than 1");
  expectFailure(base + " --samples 10x", 2, "--samples: '10x' is not a whole number");
  expectFailure(base + " --samples 1e3", 2, "--samples: '1e3' is not a whole number");
  expectFailure(base + " --threads two", 2, "--threads: 'two' is not a whole number");
  expectFailure(base + " --threads 100000", 2, "--threads: 100000 is more than 256");
  expectFailure(base + " --threads=-1", 2, "--threads: -1 is less than 0");
  expectFailure(base + " --seed=-1", 2, "--seed: -1 is less than 0");
  expectFailure(base + " --seed 1x", 2, "--seed: '1x' is not a whole number");
  expectFailure(base + " --samples 3000000000", 2, "--samples: 3000000000 is more than 2147483647");
}

TEST_F(SampleApp, BadFixedJoints) {
  const std::string base = "--robot " + deicing() + " --output " + out();
  expectFailure(base + " --fix theta9=0", 2, "--fix: robot 'deicing' has no joint 'theta9'");
  expectFailure(base + " --fix a2=80", 2,
                "--fix: fixed value 80 of joint 'a2' is outside its limits [25, 70] cm");
  expectFailure(base + " --fix theta3=0 --fix theta3=0.5", 2,
                "--fix: joint 'theta3' is fixed twice");
  expectFailure(base + " --fix theta3=0.5x", 2, "--fix: '0.5x' is not a finite number");
  expectFailure(base + " --fix theta3", 2, "--fix: 'theta3' is not name=value");
}

TEST_F(SampleApp, BadShapeAndFlagCombinations) {
  expectFailure("--shape torus --output " + out(), 2,
                "--shape: unknown shape 'torus' (known: disk, annulus, ball, box)");
  expectFailure("--output " + out(), 2, "give one of --robot and --shape");
  expectFailure("--shape disk --robot " + deicing() + " --output " + out(), 2,
                "give one of --robot and --shape");
  expectFailure("--shape disk", 2, "missing --output");
  expectFailure("--shape disk --output " + out() + " --point elbow", 2,
                "--point: 'elbow' is not tool or flange");
  expectFailure("--robot " + deicing() + " --output " + out() + " --point Tool", 2,
                "--point: 'Tool' is not tool or flange");
  expectFailure("--shape disk --output " + out() + " --colour red", 2, "unrecognised option");
  expectFailure("--shape disk stray --output " + out(), 2, "too many positional options");
  expectFailure("--shape disk --output --json", 2, "--output has no value (next comes '--json')");
}

TEST_F(SampleApp, OutputDirectoryMissingOrNotADirectory) {
  expectFailure("--shape disk --output " + dir_.file("no/such/dir/ws.pcd"), 1,
                "/no/such/dir' does not exist");
  test::writeFile(dir_.file("plain"), "x");
  const test::RunResult r =
      test::run(kSample + " --shape disk --output " + dir_.file("plain/ws.pcd"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("/plain' is not a directory"));
  std::filesystem::remove(dir_.file("plain"));
  expectFailure("--shape disk --output /proc/mcws_ws.pcd", 1, "cannot write '/proc/mcws_ws.pcd'");
}

/// Root may read and write anywhere, so as root a permission test runs the tool as user nobody
/// (setpriv, from util-linux). Empty when not root.
std::string unprivileged() {
  if (::geteuid() != 0) return "";
  return test::run("command -v setpriv").exit_code == 0
             ? "setpriv --reuid=65534 --regid=65534 --clear-groups "
             : "";
}

TEST_F(SampleApp, UnreadableRobotFile) {
  const std::string runner = unprivileged();
  if (::geteuid() == 0 && runner.empty()) GTEST_SKIP() << "root without setpriv";
  test::TempDir robots;
  std::filesystem::permissions(robots.file(""), std::filesystem::perms::all);
  const std::string secret = robots.file("secret.yaml");
  test::writeFile(secret, test::readFile(deicing()));
  std::filesystem::permissions(secret, std::filesystem::perms::owner_write);
  std::filesystem::permissions(dir_.file(""), std::filesystem::perms::all);
  const test::RunResult r =
      test::run(runner + kSample + " --robot " + secret + " --output " + out());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr(secret + ": cannot open robot file: Permission denied"));
  EXPECT_EQ(dir_.fileCount(), 0u);
}

TEST_F(SampleApp, RunStoppedBySignalLeavesNoFile) {
  // SIGTERM once the run has shown progress (its first line comes after about a second), so it
  // lands mid-run however fast the machine: 10^7 collision-checked samples of the ta1400 take
  // about 4.5 s here (a 40-million-sample ball, killed after a fixed 0.5 s, took only 1.1 s).
  test::TempDir logs;
  const std::string err = logs.file("err.txt");
  const test::RunResult r =
      test::run("(" + kSample + " --robot " + test::robotPath("ta1400") +
                " --collision --samples 10000000 --output " + out() + " 2>" + err +
                " & pid=$!; for i in $(seq 600); do grep -q '%' " + err +
                " && break; sleep 0.05; done; kill -TERM $pid; wait $pid; echo \"status $?\")");
  EXPECT_THAT(r.out, HasSubstr("status 143"));  // 128 + SIGTERM: ended by the signal
  EXPECT_EQ(dir_.fileCount(), 0u);
  EXPECT_THAT(test::readFile(err), HasSubstr("% ("));  // killed after progress, not before
}

TEST_F(SampleApp, UnwritableOutputDirectory) {
  const std::string runner = unprivileged();
  if (::geteuid() == 0 && runner.empty()) GTEST_SKIP() << "root without setpriv";
  test::TempDir locked;
  std::filesystem::permissions(locked.file(""), std::filesystem::perms::owner_read |
                                                    std::filesystem::perms::owner_exec |
                                                    std::filesystem::perms::others_read |
                                                    std::filesystem::perms::others_exec);
  const test::RunResult r =
      test::run(runner + kSample + " --shape disk --output " + locked.file("ws.pcd"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("' is not writable"));
  EXPECT_EQ(test::lineCount(r.err), 1) << r.err;
  EXPECT_EQ(locked.fileCount(), 0u);
}

TEST_F(SampleApp, DeicingPlaneCloudWithJson) {
  const test::RunResult r =
      test::run(kSample + " --robot " + deicing() +
                " --samples 6000 --seed 1 --fix theta3=0 --json --output " + out());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["points"], 6000);
  EXPECT_EQ(json["robot"], "deicing");
  EXPECT_EQ(json["length_unit"], "cm");
  // In the X-Z plane the reach is at most a1 + a2max = 120 cm.
  EXPECT_LE(json["bbox"]["max"][0].get<double>(), 120.0 + 1e-3);
  EXPECT_NEAR(json["bbox"]["max"][1].get<double>(), 0.0, 1e-4);
  pcl::PointCloud<WorkspacePoint> cloud;
  ASSERT_EQ(pcl::io::loadPCDFile(out(), cloud), 0);
  ASSERT_EQ(cloud.size(), 6000u);
  EXPECT_EQ(dir_.fileCount(), 1u);
}

TEST_F(SampleApp, SameFileForOneTwoAndThreeThreadsAndThroughADescriptor) {
  const std::string robot = " --robot " + test::robotPath("ta1400") + " --samples 300001 --seed 9";
  ASSERT_EQ(test::run(kSample + robot + " --threads 1 --output " + dir_.file("a.pcd")).exit_code,
            0);
  ASSERT_EQ(test::run(kSample + robot + " --threads 2 --output " + dir_.file("b.pcd")).exit_code,
            0);
  EXPECT_EQ(test::readFile(dir_.file("a.pcd")), test::readFile(dir_.file("b.pcd")));
  // Through a descriptor the blocks are written one after the other, not at their offsets.
  ASSERT_EQ(test::run("(" + kSample + robot + " --threads 3 --output /dev/stdout > " +
                      dir_.file("c.pcd") + ")")
                .exit_code,
            0);
  EXPECT_EQ(test::readFile(dir_.file("a.pcd")), test::readFile(dir_.file("c.pcd")));
}

TEST_F(SampleApp, ReproducesTheReferenceCloudsByteForByte) {
  const std::string clouds = std::string(MCWS_CLOUDS_DIR) + "/";
  ASSERT_EQ(test::run(kSample + " --robot " + deicing() +
                      " --samples 6000 --seed 1 --fix theta3=0"
                      " --threads 2 --output " +
                      dir_.file("xz.pcd"))
                .exit_code,
            0);
  // The reference holds the points; the robot's line (name, file hash: provenance_app_test.cpp)
  // after PCL's first line is not part of it.
  std::string xz = test::readFile(dir_.file("xz.pcd"));
  const std::size_t line2 = xz.find('\n') + 1;
  ASSERT_EQ(xz.compare(line2, 21, "# mcws robot=deicing "), 0) << xz.substr(0, 200);
  xz.erase(line2, xz.find('\n', line2) + 1 - line2);
  EXPECT_EQ(xz, test::readFile(clouds + "deicing_xz_seed1.pcd"));
  ASSERT_EQ(test::run(kSample + " --shape annulus --samples 2000 --seed 1 --ascii --output " +
                      dir_.file("annulus.pcd"))
                .exit_code,
            0);
  EXPECT_EQ(test::readFile(dir_.file("annulus.pcd")),
            test::readFile(clouds + "annulus_2000_seed1.pcd"));
}

TEST_F(SampleApp, PclToolsConvertTheCloud) {
  ASSERT_EQ(
      test::run(kSample + " --robot " + deicing() + " --samples 500 --output " + out()).exit_code,
      0);
  const test::RunResult r = test::run("pcl_pcd2ply " + out() + " " + dir_.file("ws.ply"));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const std::string ply = test::readFile(dir_.file("ws.ply"));
  EXPECT_THAT(ply, HasSubstr("element vertex 500"));
  EXPECT_THAT(ply, HasSubstr("property float q4"));
  EXPECT_THAT(ply, HasSubstr("property uint label"));
}

TEST_F(SampleApp, ShapeJsonGivesTheExactMeasure) {
  const test::RunResult r =
      test::run(kSample + " --shape ball --samples 1000 --ascii --json --output " + out());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_NEAR(json["volume"].get<double>(), 4.0 * M_PI / 3.0, 1e-12);
  EXPECT_THAT(test::readFile(out()), HasSubstr("DATA ascii"));
}

}  // namespace
}  // namespace mcws
