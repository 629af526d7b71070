// mcws_traj through its command line (closed-form peaks of the blends, via points, CSV layout,
// PNG, bad input), and URDF robots through the existing mcws_fk.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/tool_paths.h"
#include "png_image.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

const std::string kInspectionUrdf = std::string(MCWS_ROBOTS_DIR) + "/inspection6.urdf";
// Liu, Han, Xu & Li 2021, section 1.4: the end joint vector of its 10 s move (the start is not
// legible in the paper; the arm's zero pose here).
const std::string kSeedMove =
    " --from '0 0 0 0 0 0' --to '-0.267 0.268 -0.769 -0.151 0.329 0.594' --duration 10 --rate 100";
const double kSeedGoal[6] = {-0.267, 0.268, -0.769, -0.151, 0.329, 0.594};
// CSV numbers have 12 significant digits.
constexpr double kCsvTol = 1e-10;

test::Csv readCsv(const std::string& path) { return test::parseCsv(test::readFile(path)); }

TEST(TrajApp, HelpExitsZero) {
  const test::RunResult r = test::run(kTraj + " --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* flag : {"--robot", "--from", "--to", "--via", "--duration", "--rate",
                           "--profile", "--output", "--plot", "--json"}) {
    EXPECT_THAT(r.out, HasSubstr(flag));
  }
}

TEST(TrajApp, ThePapersQuinticMoveHasClosedFormEndsAndPeaks) {
  test::TempDir dir;
  const std::string out = dir.file("traj.csv");
  const test::RunResult r = test::run(kTraj + kInspection + kSeedMove + " --output " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("1001 samples"));
  const test::Csv csv = readCsv(out);
  ASSERT_EQ(csv.header.size(), 1u + 18u + 3u);
  EXPECT_EQ(csv.header[0], "t_s");
  EXPECT_EQ(csv.header[1], "j1_rad");
  EXPECT_EQ(csv.header[7], "j1_rad_per_s");
  EXPECT_EQ(csv.header[13], "j1_rad_per_s2");
  EXPECT_EQ(csv.header[19], "x_mm");
  ASSERT_EQ(csv.rows.size(), 1001u);
  EXPECT_DOUBLE_EQ(csv.last()[0], 10.0);
  for (int j = 0; j < 6; ++j) {
    const std::string name = "j" + std::to_string(j + 1) + "_rad";
    EXPECT_NEAR(csv.rows.front()[1 + j], 0.0, kCsvTol);
    EXPECT_NEAR(csv.last()[1 + j], kSeedGoal[j], kCsvTol);
    EXPECT_NEAR(csv.last()[7 + j], 0.0, kCsvTol);   // at rest
    EXPECT_NEAR(csv.last()[13 + j], 0.0, kCsvTol);  // no jerk at the stop
    // Peak velocity 1.875 D / T at t = 5 s (row 500).
    EXPECT_NEAR(csv.max(name + "_per_s", true), 1.875 * std::abs(kSeedGoal[j]) / 10, kCsvTol);
    EXPECT_NEAR(std::abs(csv.rows[500][7 + j]), 1.875 * std::abs(kSeedGoal[j]) / 10, kCsvTol);
  }
  // Tool position: the last row is mcws_fk's pose at the goal.
  const test::RunResult fk =
      test::run(kFk + kInspection + " --q '-0.267 0.268 -0.769 -0.151 0.329 0.594' --json");
  ASSERT_EQ(fk.exit_code, 0) << fk.err;
  const auto position = nlohmann::json::parse(fk.out)["position"];
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(csv.last()[19 + k], position[k].get<double>(), 1e-8);
  }
}

TEST(TrajApp, CubicProfilePeaksAtOnePointFiveDOverT) {
  test::TempDir dir;
  const std::string out = dir.file("traj.csv");
  const test::RunResult r =
      test::run(kTraj + kInspection + kSeedMove + " --profile cubic --json --output " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["profile"], "cubic");
  EXPECT_EQ(json["samples"], 1001);
  for (int j = 0; j < 6; ++j) {
    EXPECT_NEAR(json["peak_velocity"][j].get<double>(), 1.5 * std::abs(kSeedGoal[j]) / 10, 1e-12);
    // The cubic starts with acceleration 6 D / T^2.
    EXPECT_NEAR(json["peak_acceleration"][j].get<double>(), 6 * std::abs(kSeedGoal[j]) / 100,
                1e-12);
  }
  EXPECT_EQ(readCsv(out).rows.size(), 1001u);
}

TEST(TrajApp, SplinePassesTheViasAtEqualIntervals) {
  test::TempDir dir;
  const std::string out = dir.file("traj.csv");
  const test::RunResult r = test::run(
      kTraj + kInspection +
      " --from '0 0 0 0 0 0' --via '0.5 0.2 -0.3 0.1 0 0' --via '0.8 -0.1 -0.6 0.2 0.3 0.1'"
      " --to '1 0 -0.2 0 0.5 0.4' --duration 6 --rate 50 --output " +
      out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const test::Csv csv = readCsv(out);
  ASSERT_EQ(csv.rows.size(), 301u);
  // Vias at t = 2 s and 4 s (rows 100 and 200).
  const double via1[6] = {0.5, 0.2, -0.3, 0.1, 0, 0}, via2[6] = {0.8, -0.1, -0.6, 0.2, 0.3, 0.1};
  for (int j = 0; j < 6; ++j) {
    EXPECT_NEAR(csv.rows[100][1 + j], via1[j], kCsvTol);
    EXPECT_NEAR(csv.rows[200][1 + j], via2[j], kCsvTol);
    EXPECT_NEAR(csv.rows.front()[7 + j], 0.0, kCsvTol);
    EXPECT_NEAR(csv.last()[7 + j], 0.0, kCsvTol);
    // Velocity and acceleration continuous across the vias: neighbouring samples close.
    for (int row : {100, 200}) {
      EXPECT_LT(std::abs(csv.rows[row + 1][13 + j] - csv.rows[row - 1][13 + j]), 0.05);
    }
  }
}

TEST(TrajApp, PlotShowsTheMoveBesideTheCsv) {
  test::TempDir dir;
  const test::RunResult r = test::run(kTraj + kInspection + kSeedMove + " --output " +
                                      dir.file("t.csv") + " --plot " + dir.file("t.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(dir.fileCount(), 2u);
  const test::PngImage png(dir.file("t.png"));
  ASSERT_EQ(png.width(), 1400);
  ASSERT_EQ(png.height(), 1000);
  // Joint positions, top left: gnuplot's colours for j1 .. j6. Where each curve ends (its
  // rightmost pixels, left of the legend), the curves lie in the order of the goal values.
  const test::Rgb colour[6] = {0x9400d3, 0x009e73, 0x56b4e9, 0xe69f00, 0xf0e442, 0x0072b2};
  const test::PixelBox positions{0, static_cast<int>(0.43 * png.width()), 0,
                                 static_cast<int>(0.47 * png.height())};
  std::vector<std::pair<double, double>> end_y_and_goal;
  for (int j = 0; j < 6; ++j) {
    const test::PixelBox curve = png.box(colour[j], 0, positions);
    ASSERT_FALSE(curve.empty()) << "j" << j + 1;
    const test::PixelBox end = png.box(colour[j], 0, {curve.x1, curve.x1, curve.y0, curve.y1});
    end_y_and_goal.emplace_back(0.5 * (end.y0 + end.y1), kSeedGoal[j]);
  }
  std::sort(end_y_and_goal.begin(), end_y_and_goal.end());  // top of the picture first
  for (std::size_t k = 1; k < end_y_and_goal.size(); ++k) {
    EXPECT_GT(end_y_and_goal[k - 1].second, end_y_and_goal[k].second)
        << "curves end at y " << end_y_and_goal[k - 1].first << " and " << end_y_and_goal[k].first;
  }
  // The tool path, bottom right, with its start (green) and end (red) marks.
  const test::PixelBox tool_panel{png.width() / 2, png.width() - 1, png.height() / 2,
                                  png.height() - 1};
  for (const test::Rgb mark : {0x1f77b4u, 0x2ca02cu, 0xd62728u}) {
    EXPECT_FALSE(png.box(mark, 0, tool_panel).empty()) << std::hex << mark;
  }
}

TEST(TrajApp, UrdfRobotGivesTheYamlMoveInMetres) {
  test::TempDir dir;
  const test::RunResult yaml =
      test::run(kTraj + kInspection + kSeedMove + " --json --output " + dir.file("y.csv"));
  const test::RunResult urdf = test::run(kTraj + " --robot " + kInspectionUrdf + kSeedMove +
                                         " --json --output " + dir.file("u.csv"));
  ASSERT_EQ(yaml.exit_code, 0) << yaml.err;
  ASSERT_EQ(urdf.exit_code, 0) << urdf.err;
  const auto y = nlohmann::json::parse(yaml.out), u = nlohmann::json::parse(urdf.out);
  EXPECT_EQ(u["length_unit"], "m");
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(u["tool_end"][k].get<double>() * 1000, y["tool_end"][k].get<double>(), 1e-9);
  }
  EXPECT_NEAR(u["tool_path_length"].get<double>() * 1000, y["tool_path_length"].get<double>(),
              1e-9);
}

TEST(TrajApp, BaseAndTipPickAUrdfSubChain) {
  test::TempDir dir;
  const test::RunResult r =
      test::run(kTraj + " --robot " + kInspectionUrdf +
                " --base link1 --tip link3 --from '0 0' --to '0.5 -0.5' --duration 1 --rate 10"
                " --json --output " +
                dir.file("t.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["joints"], nlohmann::json({"j2", "j3"}));
}

TEST(FkApp, UrdfRobotReproducesThePapersMatrixInMetres) {
  // Liu, Han, Xu & Li 2021, section 1.1: the pose at q = [pi/3, pi/6, pi/2, pi/4, pi/3, pi/6],
  // printed in mm.
  const test::RunResult r =
      test::run(kFk + " --robot " + kInspectionUrdf +
                " --q '1.0471975511965976 0.5235987755982988 1.5707963267948966 0.7853981633974483 "
                "1.0471975511965976 0.5235987755982988' --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["length_unit"], "m");
  EXPECT_NEAR(json["position"][0].get<double>(), -0.0393043, 0.5e-7);
  EXPECT_NEAR(json["position"][1].get<double>(), 0.7319230, 0.5e-7);
  EXPECT_NEAR(json["position"][2].get<double>(), -0.5692371, 0.5e-7);
  EXPECT_NEAR(json["pose"][2][1].get<double>(), 0.9012, 0.5e-4);
}

TEST(FkApp, MalformedUrdfIsOneLineNamingTheFile) {
  test::TempDir robots, out;
  const std::string bad = robots.file("bad.urdf");
  test::writeFile(bad, "<robot name='x'><link name='a'></robot>");
  test::expectToolFailure(kFk, "--robot " + bad + " --q 0", 1, bad + ": malformed URDF: ", out);
}

TEST(TrajApp, StraightLineToAPoseThroughIk) {
  // The goal is the tool pose at q1 (roll-pitch-yaw worked out from mcws_fk's matrix): the move
  // must end at q1 (the IK is seeded along the way), and the tool path must be the straight
  // segment, whose length is the distance between the two positions (closed form).
  const double q1[6] = {0.35, 0.45, 0.55, 0.25, 0.35, 0.15};
  const Eigen::Vector3d p0(529.9365176804231, 820.9413151411586, -382.00792828505695);
  const Eigen::Vector3d p1(457.999699196655, 826.8639683380666, -409.74976869681166);
  test::TempDir dir;
  const std::string out = dir.file("line.csv");
  const test::RunResult r =
      test::run(kTraj + kInspection +
                " --from '0.3 0.4 0.5 0.2 0.3 0.1' --to-pose '457.999699196655 826.8639683380666 "
                "-409.74976869681166 -0.5018809252268998 1.190518143712866 1.501644052136167' "
                "--duration 2 --rate 50 --json --output " +
                out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto summary = nlohmann::json::parse(r.out);
  EXPECT_EQ(summary["samples"], 101);
  EXPECT_NEAR(summary["tool_path_length"].get<double>(), (p1 - p0).norm(), 1e-6);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(summary["tool_start"][k].get<double>(), p0[k], 1e-6);
    EXPECT_NEAR(summary["tool_end"][k].get<double>(), p1[k], 1e-4);
  }
  const test::Csv csv = readCsv(out);
  for (int j = 0; j < 6; ++j) EXPECT_NEAR(csv.last()[1 + j], q1[j], 1e-6) << j;
}

TEST(TrajApp, BadInput) {
  struct Case {
    std::string args;
    int exit_code;
    std::string message;
  };
  const std::string move = " --from '0 0 0 0 0 0' --to '0.1 0.2 0.3 0.4 0.5 0.6'";
  const std::string timing = " --duration 10 --rate 100";
  const Case cases[] = {
      {kInspection + move + " --duration 0 --rate 100", 2,
       "--duration: 0 s is not a positive number"},
      {kInspection + move + " --to-pose '0 0 0 0 0 0'" + timing, 2,
       "give one of --to and --to-pose"},
      {kInspection + " --from '0 0 0 0 0 0' --to-pose '1 2 3 0 0 0' --via '0 0 0 0 0 0'" + timing,
       2, "--via does not apply to --to-pose"},
      {kInspection + " --from '0 0 0 0 0 0' --to-pose '1 2 nan 0 0 0'" + timing, 2, "--to-pose"},
      {kInspection + " --from '0 0 0 0 0 0' --to-pose '100000 0 0 0 0 0'" + timing, 1, "t = "},
      {kInspection + move + " --duration -2 --rate 100", 2,
       "--duration: -2 s is not a positive number"},
      {kInspection + move + " --duration nan --rate 100", 2,
       "--duration: 'nan' is not a finite number"},
      {kInspection + move + " --duration 10 --rate 0", 2, "--rate: 0 Hz is not a positive number"},
      {kInspection + move + " --duration 10 --rate -5", 2,
       "--rate: -5 Hz is not a positive number"},
      {kInspection + move + " --duration 10 --rate 1e9", 2,
       "--rate: 1e9 is not in (0, 1000000] Hz"},
      // Issue 17: the huge count is refused at once naming both flags (it held 67 GB before),
      // and the durations that reached the profile's arithmetic name --duration.
      {kInspection + move + " --duration 100 --rate 100000", 2,
       "--duration 100 s at --rate 100000 Hz: 10000001 samples, more than the 1000000 mcws_traj "
       "writes"},
      {kInspection + move + " --duration 1e12 --rate 1", 2,
       "--duration: 1e12 is not in [0.001, 1000000] s"},
      {kInspection + move + " --duration 1e-300 --rate 100", 2,
       "--duration: 1e-300 is not in [0.001, 1000000] s"},
      {kInspection + " --from '0 0 0' --to '0 0 0 0 0 0'" + timing, 2,
       "--from: robot 'inspection6' has 6 joints but 3 joint values were given"},
      {kInspection + " --from '0 0 0 0 0 0' --to '0 0 0 0 0 nan'" + timing, 2,
       "--to: 'nan' is not a finite number"},
      {kInspection + move + " --via '0 4 0 0 0 0'" + timing, 2,
       "--via 1: joint 'j2' value 4 is outside its limits [-3.141592654, 3.141592654] rad"},
      {kInspection + move + " --via '0 0 0 0 0 0' --via '0 0 0 0 0'" + timing, 2,
       "--via 2: robot 'inspection6' has 6 joints but 5 joint values were given"},
      // Vias inside the limits, but the spline between them is not: 0, 3.1, 3.1, 0 at t = 0,
      // 1, 2, 3 peaks at 1.25 * 3.1 at t = 1.5 s.
      {kInspection +
           " --from '0 0 0 0 0 0' --via '3.1 0 0 0 0 0' --via '3.1 0 0 0 0 0' --to '0 0 0 0 0 0'"
           " --duration 3 --rate 100",
       1, "joint 'j1' reaches 3.875 rad at t = 1.5 s, above its upper limit 3.141592654 rad"},
      {kInspection + move + timing + " --max-velocity 0.05", 1,
       "velocity of joint 'j3' reaches 0.05625 rad/s at t = 5 s, above its upper limit 0.05 rad/s"},
      {kInspection + move + timing + " --max-velocity '1 2'", 2,
       "--max-velocity: give one positive value or 6 (one per joint)"},
      {kInspection + move + timing + " --profile linear", 2,
       "--profile: 'linear' is not quintic or cubic"},
      {kInspection + move + " --via '0 0 0 0 0 0' --profile quintic" + timing, 2,
       "--profile: quintic blends one move"},
      {kInspection + " --to '0 0 0 0 0 0'" + timing, 2, "missing --from"},
      {kInspection + move + " --duration 10", 2, "missing --rate"},
      {" --robot /nonexistent.yaml" + move + timing, 1,
       "--robot: /nonexistent.yaml: robot file does not exist"},
      {kInspection + move + timing + " --base link1", 2, "--base and --tip need a .urdf robot"},
      {" --robot " + kInspectionUrdf + " --base link3 --tip link1 --from 0 --to 0" + timing, 2,
       "--tip: link 'link1' is not below --base link 'link3' in " + kInspectionUrdf},
      {" --robot " + kInspectionUrdf + " --tip hand" + move + timing, 2,
       "--tip: 'hand' is not a link of robot 'inspection6' in " + kInspectionUrdf},
  };
  for (const Case& c : cases) {
    test::TempDir dir;
    test::expectToolFailure(kTraj, c.args + " --output " + dir.file("t.csv"), c.exit_code,
                            c.message, dir);
  }
}

TEST(TrajApp, OutputErrorsLeaveNothing) {
  test::TempDir dir;
  const std::string base = kInspection + kSeedMove;
  test::expectToolFailure(kTraj, base + " --output /nonexistent/dir/t.csv", 1,
                          "cannot write '/nonexistent/dir/t.csv': directory '/nonexistent/dir' "
                          "does not exist",
                          dir);
  test::expectToolFailure(kTraj,
                          base + " --output " + dir.file("t.csv") + " --plot " + dir.file("t.csv"),
                          2, "--plot: must differ from --output", dir);
  test::expectToolFailure(kTraj,
                          base + " --output " + dir.file("t.csv") + " --plot /nonexistent/p.png", 1,
                          "cannot write '/nonexistent/p.png'", dir);
}

}  // namespace
}  // namespace mcws
