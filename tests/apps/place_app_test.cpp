// mcws_reach --targets and mcws_place through their command lines: the planar 2R arm's reachable
// annulus (closed form) decides which targets are reached and from which interval of the line
// the base reaches them all; bad input gets one line and writes nothing.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <pcl/io/pcd_io.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "apps/tool_paths.h"
#include "mcws/io/cloud_io.h"
#include "mcws/io/sha256.h"
#include "mcws/reach/base_placement.h"
#include "mcws/reach/reach_study.h"
#include "png_image.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

/// planar2: links 40 and 30 cm, q2 within +-160 deg: the tool point reaches the annulus
/// r_min <= r <= 70 cm of the plane z = 0, its z axis always world +z.
const double kRMin =
    std::sqrt(40.0 * 40.0 + 30.0 * 30.0 + 2 * 40.0 * 30.0 * std::cos(160 * M_PI / 180));

class StudyApp : public ::testing::Test {
 protected:
  std::string file(const std::string& name) const { return dir_.file(name); }
  /// A CSV of point-and-normal targets in the plane z = 0, approaching along +z.
  std::string planarTargets(const std::vector<std::pair<double, double>>& points) const {
    std::ostringstream csv;
    csv.precision(17);
    csv << "x,y,z,normal_x,normal_y,normal_z\n";
    for (const auto& [x, y] : points) csv << x << ',' << y << ",0,0,0,-1\n";
    const std::string path = file("targets.csv");
    test::writeFile(path, csv.str());
    return path;
  }
  /// Where failing runs would write (must stay empty).
  std::string output(const std::string& name) const { return out_.file(name); }
  test::TempDir dir_, out_;
};

TEST_F(StudyApp, PlanarTargetsAreReachedExactlyInsideTheAnnulus) {
  // Radii inside and outside the annulus, at several angles.
  const std::vector<double> radii = {kRMin - 2, kRMin + 2, 40, 55, 69, 71, 5};
  std::vector<std::pair<double, double>> points;
  for (std::size_t i = 0; i < radii.size(); ++i) {
    const double t = 0.7 * static_cast<double>(i) - 2.0;
    points.emplace_back(radii[i] * std::cos(t), radii[i] * std::sin(t));
  }
  const std::string targets = planarTargets(points);
  const test::RunResult r =
      test::run(kReach + " --robot " + test::robotPath("planar2") + " --targets " + targets +
                " --no-collision --quality-task position --json --output " + file("heat.pcd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto summary = nlohmann::json::parse(r.out);
  pcl::PointCloud<ReachTargetPoint> heat;
  ASSERT_EQ(pcl::io::loadPCDFile(file("heat.pcd"), heat), 0);
  ASSERT_EQ(heat.size(), radii.size());
  std::size_t inside = 0;
  for (std::size_t i = 0; i < radii.size(); ++i) {
    const bool reachable = radii[i] >= kRMin && radii[i] <= 70.0;
    inside += reachable ? 1 : 0;
    EXPECT_EQ(heat[i].reached, reachable ? 1.f : 0.f) << "r = " << radii[i];
    EXPECT_FLOAT_EQ(heat[i].normal_z, -1.f);
    if (!reachable) continue;
    // Manipulability of the position task: l1 l2 |sin q2|, q2 by the law of cosines.
    const double c2 = (radii[i] * radii[i] - 40.0 * 40.0 - 30.0 * 30.0) / (2 * 40.0 * 30.0);
    EXPECT_NEAR(heat[i].manipulability, 40.0 * 30.0 * std::sqrt(1 - c2 * c2), 1e-3);
    EXPECT_NEAR(std::abs(heat[i].q2), std::acos(c2), 1e-5);
    EXPECT_FLOAT_EQ(heat[i].score, heat[i].manipulability);
    EXPECT_FLOAT_EQ(heat[i].clearance, -1.f);  // no collision model used
  }
  EXPECT_EQ(summary["reached"].get<std::size_t>(), inside);
  EXPECT_DOUBLE_EQ(summary["share_reached"].get<double>(),
                   static_cast<double>(inside) / static_cast<double>(radii.size()));
  EXPECT_EQ(summary["length_unit"], "cm");
  EXPECT_EQ(summary["manipulability"]["manipulability_unit"], "cm^2");
  EXPECT_EQ(summary["unreached"].size(), radii.size() - inside);
}

/// The robot file's posts count: a target inside post_a (centre (30, 38, 0)) is solved by IK but
/// not reached, and reached once collisions are ignored.
TEST_F(StudyApp, CollisionModelDecidesWhatCounts) {
  const std::string targets = planarTargets({{30, 38}, {0, -30}});
  const std::string common = kReach + " --robot " + test::robotPath("planar2") + " --targets " +
                             targets + " --json --output " + file("heat.pcd");
  const test::RunResult with = test::run(common);
  ASSERT_EQ(with.exit_code, 0) << with.err;
  const auto a = nlohmann::json::parse(with.out);
  EXPECT_EQ(a["collision"], true);
  EXPECT_EQ(a["reached"], 1);
  EXPECT_EQ(a["solved"], 2);
  EXPECT_EQ(a["unreached"][0]["label"], "environment");
  EXPECT_GT(a["min_clearance_reached"].get<double>(), 0.0);
  const test::RunResult without = test::run(common + " --no-collision");
  ASSERT_EQ(without.exit_code, 0) << without.err;
  EXPECT_EQ(nlohmann::json::parse(without.out)["reached"], 2);
}

TEST_F(StudyApp, BadTargetsAreOneLineAndWriteNothing) {
  const std::string robot = " --robot " + test::robotPath("planar2");
  const std::string out = " --output " + output("heat.pcd");
  // A PCD without normals.
  pcl::PointCloud<pcl::PointXYZ> xyz;
  xyz.push_back(pcl::PointXYZ(1, 2, 3));
  pcl::io::savePCDFileASCII(file("xyz.pcd"), xyz);
  test::expectToolFailure(kReach, robot + " --targets " + file("xyz.pcd") + out, 1,
                          "has no field 'normal_x'", out_);
  test::writeFile(file("bad_header.csv"), "x,y,z\n1,2,3\n");
  test::expectToolFailure(kReach, robot + " --targets " + file("bad_header.csv") + out, 1,
                          "bad_header.csv:1: header", out_);
  test::writeFile(file("bad_value.csv"), "x,y,z,roll,pitch,yaw\n1,2,3,0,0,0\n1,2,nan,0,0,0\n");
  test::expectToolFailure(kReach, robot + " --targets " + file("bad_value.csv") + out, 1,
                          "bad_value.csv:3: value 3 'nan' is not a finite number", out_);
  test::writeFile(file("zero.csv"), "x,y,z,normal_x,normal_y,normal_z\n1,2,3,0,0,0\n");
  test::expectToolFailure(kReach, robot + " --targets " + file("zero.csv") + out, 1,
                          "zero.csv:2: target normal", out_);
  const std::string good = planarTargets({{50, 0}});
  test::expectToolFailure(kReach, robot + " --targets " + good + " --resolution 2cm" + out, 2,
                          "--resolution is for maps", out_);
  test::expectToolFailure(kReach, robot + " --targets " + good + " --approach-tolerance 5" + out, 2,
                          "--approach-tolerance: 5 has no unit", out_);
  test::expectToolFailure(kReach, robot + " --resolution 2cm --ik-starts 3" + out, 2,
                          "--ik-starts needs --targets", out_);
  test::expectToolFailure(kReach, " --robot /nonexistent.yaml --targets " + good + out, 1,
                          "/nonexistent.yaml", out_);
  test::writeFile(file("comma.csv"), "x,y,z,normal_x,normal_y,normal_z\n50,0,0,0,0,-1,\n");
  test::expectToolFailure(kReach, robot + " --targets " + file("comma.csv") + out, 1,
                          "comma.csv:2: ends with a comma", out_);
  test::expectToolFailure(kReach,
                          robot + " --targets " + good + " --approach-tolerance 181deg" + out, 2,
                          "--approach-tolerance: 181deg is more than 180deg", out_);
  test::expectToolFailure(kReach, robot + " --targets " + good + " --rolls 2" + out, 2,
                          "--rolls is for maps", out_);
  // The output may not replace an input.
  test::expectToolFailure(kReach, robot + " --targets " + good + " --output " + good, 2, "--output",
                          out_);
  // Coordinates stored as doubles would be read as zeros by PCL: refused.
  test::writeFile(file("double.pcd"),
                  "VERSION 0.7\nFIELDS x y z normal_x normal_y normal_z\nSIZE 8 8 8 4 4 4\n"
                  "TYPE F F F F F F\nCOUNT 1 1 1 1 1 1\nWIDTH 1\nHEIGHT 1\n"
                  "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 1\nDATA ascii\n50 0 0 0 0 -1\n");
  test::expectToolFailure(kReach, robot + " --targets " + file("double.pcd") + out, 1,
                          "field 'x' is not one 4-byte float", out_);
}

/// The approach tolerance: a target approached along -x is out of the planar arm's reach (its
/// tool points along +z) unless the tolerance passes 90 deg.
TEST_F(StudyApp, ApproachToleranceAdmitsTiltedTargets) {
  test::writeFile(file("tilted.csv"), "x,y,z,normal_x,normal_y,normal_z\n50,0,0,1,0,0\n");
  const std::string common = kReach + " --robot " + test::robotPath("planar2") + " --targets " +
                             file("tilted.csv") + " --no-collision --json --output " +
                             file("heat.pcd");
  const test::RunResult exact = test::run(common);
  ASSERT_EQ(exact.exit_code, 0) << exact.err;
  EXPECT_EQ(nlohmann::json::parse(exact.out)["reached"], 0);
  const test::RunResult loose = test::run(common + " --approach-tolerance 91deg --standoff 0cm");
  ASSERT_EQ(loose.exit_code, 0) << loose.err;
  EXPECT_EQ(nlohmann::json::parse(loose.out)["reached"], 1);
  pcl::PointCloud<ReachTargetPoint> heat;
  ASSERT_EQ(pcl::io::loadPCDFile(file("heat.pcd"), heat), 0);
  EXPECT_NEAR(heat[0].orientation_error, M_PI / 2, 1e-6);
}

/// Targets (0, 50) and (40, 50) with the planar arm's base moved by d along x: both are within
/// 70 cm of the base for d in [40 - sqrt(70^2 - 50^2), sqrt(70^2 - 50^2)] = [-8.99, 48.99] and
/// never closer than r_min; IK confirms every position, the map agrees within a voxel.
TEST_F(StudyApp, PlacementFindsTheOneIntervalOfTheLine) {
  const std::string targets = planarTargets({{0, 50}, {40, 50}});
  const std::string common =
      kPlace + " --robot " + test::robotPath("planar2") + " --targets " + targets +
      " --along \"-30 70 2\" --resolution 2cm --orientations 16 "
      "--samples 2000000 --confirm all --no-collision --map-cache off --json";
  const test::RunResult r =
      test::run(common + " --output " + file("bases.pcd") + " --plot " + file("placement.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto summary = nlohmann::json::parse(r.out);
  const double half = std::sqrt(70.0 * 70.0 - 50.0 * 50.0);
  const auto& candidates = summary["candidates"];
  ASSERT_EQ(candidates.size(), 51u);
  for (const auto& c : candidates) {
    const double d = c["offset"][0].get<double>();
    const bool inside = d >= 40.0 - half && d <= half;
    EXPECT_EQ(c["ik_share"].get<double>() == 1.0, inside) << "d = " << d;
    if (inside) {
      EXPECT_EQ(c["map_share"].get<double>(), 1.0) << "d = " << d;
    }
    // Beyond the interval by more than a voxel diagonal the map cannot mark both targets.
    if (d < 40.0 - half - 4.0 || d > half + 4.0) {
      EXPECT_LT(c["map_share"].get<double>(), 1.0) << "d = " << d;
    }
  }
  const double best = summary["best"]["offset"][0].get<double>();
  EXPECT_GE(best, 40.0 - half);
  EXPECT_LE(best, half);
  pcl::PointCloud<BasePoint> bases;
  ASSERT_EQ(pcl::io::loadPCDFile(file("bases.pcd"), bases), 0);
  ASSERT_EQ(bases.size(), 51u);
  EXPECT_FLOAT_EQ(bases[0].x, -30.f);  // planar2's base is at the origin
  // The positions' robot and length unit are recorded in the file, as mcws_reach's clouds.
  const std::optional<io::CloudProvenance> recorded = io::readProvenance(file("bases.pcd"));
  ASSERT_TRUE(recorded);
  EXPECT_EQ(recorded->robot, "planar2");
  EXPECT_EQ(recorded->length_unit, "cm");
  EXPECT_EQ(recorded->sha256, io::sha256OfFile(test::robotPath("planar2")));
  // The picture: IK's confirmations (dark red triangles) at 100 % span the confirmed interval,
  // [-8, 48] of the positions [-30, 70]: 56 % of the span of all triangles, whatever the axes.
  const test::PngImage png(file("placement.png"));
  ASSERT_EQ(png.width(), 1000);
  ASSERT_EQ(png.height(), 600);
  const test::PixelBox frame = png.frame();
  ASSERT_FALSE(frame.empty());
  test::PixelBox plot = frame;
  plot.y1 -= 60;  // above the legend's samples
  const test::PixelBox all = png.box(0x7a0403, 0, plot);
  ASSERT_FALSE(all.empty());
  const test::PixelBox top = png.box(0x7a0403, 0, {plot.x0, plot.x1, all.y0, all.y0 + 6});
  EXPECT_NEAR(static_cast<double>(top.x1 - top.x0) / (all.x1 - all.x0), 56.0 / 100.0, 0.01);
  EXPECT_FALSE(png.box(0x4686fb, 0, plot).empty());  // the map's estimate is drawn too

  // The same from a map file written by mcws_reach, and for another thread count.
  const test::RunResult map = test::run(kReach + " --robot " + test::robotPath("planar2") +
                                        " --resolution 2cm --orientations 16 --samples 2000000 "
                                        "--output " +
                                        file("m.pcd") + " --map " + file("m.bin"));
  ASSERT_EQ(map.exit_code, 0) << map.err;
  const test::RunResult from_file =
      test::run(kPlace + " --robot " + test::robotPath("planar2") + " --targets " + targets +
                " --along \"-30 70 2\" --map " + file("m.bin") +
                " --confirm all --no-collision --threads 1 --json --output " + file("b2.pcd"));
  ASSERT_EQ(from_file.exit_code, 0) << from_file.err;
  EXPECT_EQ(nlohmann::json::parse(from_file.out)["candidates"], candidates);
}

// Without --map the tool says it builds a map and how long that will take (from the first
// samples' rate), and confirms by IK every position whose map share is within --confirm-margin
// of the best, saying how many (JSON "confirmation", and the text after the table).
TEST_F(StudyApp, PlacementBuildingItsOwnMapSaysSoAndConfirmsTheMargin) {
  const std::string targets = planarTargets({{0, 50}, {40, 50}});
  const std::string common =
      kPlace + " --robot " + test::robotPath("planar2") + " --targets " + targets +
      " --along \"-30 70 5\" --resolution 10cm --orientations 16 "
      "--samples 100000 --threads 2 --confirm-margin 0.5 --map-cache off --output " +
      file("bases.pcd");
  const test::RunResult r = test::run(common + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("mcws_place: no --map: building a reachability map here from "
                               "100000 samples, each checked for self-collision"));
  EXPECT_THAT(r.err, HasSubstr("mcws_place: the map will take about "));
  EXPECT_THAT(r.err, HasSubstr(" s in all ("));
  EXPECT_THAT(r.err, HasSubstr(" samples a second)\n"));
  const auto summary = nlohmann::json::parse(r.out);
  const auto& confirmation = summary["confirmation"];
  EXPECT_EQ(confirmation["margin_share"].get<double>(), 0.5);
  EXPECT_EQ(confirmation["best_by_map"].get<int>(), 0);
  double best = 0.0;
  for (const auto& c : summary["candidates"]) best = std::max(best, c["map_share"].get<double>());
  std::size_t within = 0;
  for (const auto& c : summary["candidates"]) {
    const bool in = c["map_share"].get<double>() >= best - 0.5;
    within += in;
    EXPECT_EQ(!c["ik_share"].is_null(), in) << c.dump();
  }
  EXPECT_EQ(confirmation["confirmed"].get<std::size_t>(), within);
  EXPECT_GT(within, 5u);  // more than the old fixed five

  const test::RunResult text = test::run(common + " --no-collision");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_THAT(text.err,
              HasSubstr("building a reachability map here from 100000 samples (mcws_reach"));
  EXPECT_THAT(text.err, HasSubstr(" of 21 positions confirmed by IK: those within a map share of "
                                  "0.5 (fraction of the targets) of the best\n"));
  const std::string flags = " --robot " + test::robotPath("planar2") + " --targets " + targets +
                            " --along \"0 10 5\" --resolution 10cm --output " + output("b.pcd");
  test::expectToolFailure(kPlace, flags + " --confirm-margin 1.5", 2,
                          "--confirm-margin: 1.5 is above 1 (a fraction of the targets)", out_);
  test::expectToolFailure(kPlace, flags + " --confirm-margin -0.1", 2, "--confirm-margin: -0.1",
                          out_);
}

TEST_F(StudyApp, PlacementRefusesTheMapOfAnEditedRobotFileOrOneThatPredatesItsRecord) {
  // The robot file, copied so that it can be edited.
  const std::string robot = file("planar2.yaml"), map = file("m.bin");
  std::filesystem::copy_file(test::robotPath("planar2"), robot);
  const test::RunResult made =
      test::run(kReach + " --robot " + robot + " --resolution 5cm --samples 20000 --output " +
                file("m.pcd") + " --map " + map);
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const std::string targets = planarTargets({{0, 50}});
  const std::string args = "--robot " + robot + " --targets " + targets +
                           " --along \"0 10 5\" --no-collision --map " + map + " --output ";
  // The map of this very file is accepted.
  const test::RunResult same = test::run(kPlace + " " + args + file("b.pcd"));
  ASSERT_EQ(same.exit_code, 0) << same.err;
  // The elbow's limits narrowed: the same name, unit and lengths (so the same manipulability
  // scale), another reach.
  std::string text = test::readFile(robot);
  const std::string elbow = "limits: [-160, 160]";
  ASSERT_NE(text.find(elbow), std::string::npos);
  text.replace(text.find(elbow), elbow.size(), "limits: [-120, 120]");
  test::writeFile(robot, text);
  test::expectToolFailure(kPlace, args + output("b.pcd"), 1,
                          map + ": the map was made from robot file planar2.yaml (sha256 ", out_);
  test::expectToolFailure(kPlace, args + output("b.pcd"), 1,
                          "not from --robot " + robot + " (sha256 ", out_);
  // A map written before its header recorded the robot file.
  std::string bytes = test::readFile(map);
  const std::size_t from = bytes.find(",\"robot_file\":");  // then robot_sha256, samples
  const std::size_t to = bytes.find(",\"samples\":", from);
  ASSERT_NE(from, std::string::npos);
  ASSERT_NE(to, std::string::npos);
  bytes.erase(from, to - from);
  test::writeFile(map, bytes);
  test::expectToolFailure(kPlace, args + output("b.pcd"), 1,
                          map + ": the map predates the record of its robot file's SHA-256", out_);
}

TEST_F(StudyApp, PlacementHelpDescribesTheFlags) {
  const test::RunResult r = test::run(kPlace + " --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* flag :
       {"--robot", "--targets", "--along", "--across", "--up", "--map", "--resolution", "--confirm",
        "--confirm-margin", "--standoff", "--approach-tolerance", "--output", "--plot", "--json"}) {
    EXPECT_THAT(r.out, HasSubstr(flag));
  }
}

TEST_F(StudyApp, PlacementBadInput) {
  const std::string targets = planarTargets({{0, 50}});
  const std::string common = " --robot " + test::robotPath("planar2") + " --targets " + targets +
                             " --output " + output("b.pcd");
  test::expectToolFailure(kPlace, common + " --resolution 2cm", 2, "missing --along", out_);
  test::expectToolFailure(kPlace, common + " --along \"0 10\" --resolution 2cm", 2,
                          "--along: 2 values given, 3 wanted", out_);
  test::expectToolFailure(kPlace, common + " --along \"10 0 1\" --resolution 2cm", 2,
                          "--along: step 1 is not positive or last 0 is below first 10", out_);
  test::expectToolFailure(kPlace, common + " --along \"0 10 1\"", 2,
                          "missing --map or --resolution", out_);
  test::expectToolFailure(kPlace, common + " --along \"0 10 1\" --resolution 0", 2,
                          "--resolution: 0 is not a positive number", out_);
  // A map of another robot.
  const test::RunResult map = test::run(kReach + " --robot " + test::robotPath("inspection6") +
                                        " --resolution 50cm --samples 10000 --output " +
                                        file("m.pcd") + " --map " + file("m.bin"));
  ASSERT_EQ(map.exit_code, 0) << map.err;
  test::expectToolFailure(kPlace, common + " --along \"0 10 1\" --map " + file("m.bin"), 1,
                          "the map is of robot 'inspection6'", out_);
  // A map counting only samples free of the environment at the robot's own base.
  const test::RunResult collision_map =
      test::run(kReach + " --robot " + test::robotPath("planar2") +
                " --resolution 5cm --samples 10000 --collision --output " + file("c.pcd") +
                " --map " + file("c.bin"));
  ASSERT_EQ(collision_map.exit_code, 0) << collision_map.err;
  test::expectToolFailure(kPlace, common + " --along \"0 10 1\" --map " + file("c.bin"), 1,
                          "placement needs a map without it", out_);
  test::expectToolFailure(kPlace, common + " --along \"0 1 1e-300\" --resolution 2cm", 2,
                          "positions, at most 100000", out_);
  test::expectToolFailure(kPlace,
                          " --robot " + test::robotPath("planar2") + " --targets " + targets +
                              " --along \"0 10 1\" --resolution 2cm --output " + output("b.pcd") +
                              " --plot " + output("b.pcd"),
                          2, "--plot", out_);
}

}  // namespace
}  // namespace mcws
