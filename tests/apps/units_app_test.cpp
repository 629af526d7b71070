// Every tool's results name their units (issue 16, section 1): "length_unit" is the unit of the
// lengths (the robot file's, or the one a cloud records), "units" names each dimensioned number,
// and --unit converts lengths, areas and volumes by the exact factors between m, cm and mm.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "apps/tool_paths.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;
using Json = nlohmann::json;

Json runJson(const std::string& command) {
  const test::RunResult r = test::run(command);
  EXPECT_EQ(r.exit_code, 0) << command << "\n" << r.err;
  return r.exit_code == 0 ? Json::parse(r.out) : Json::object();
}

/// Relative agreement for a value converted by an exact power of ten (one rounding each way).
void expectScaled(double shown, double data, double factor, const std::string& what) {
  EXPECT_NEAR(shown, data * factor, 1e-12 * std::abs(data * factor)) << what;
}

/// A de-icing cloud in the x-z plane (cm, theta3 fixed) and its boundary, made once.
class UnitsApp : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir;
    cloud_ = dir_->file("deicing.pcd");
    rim_ = dir_->file("rim.pcd");
    ball_ = dir_->file("ball.pcd");
    ASSERT_EQ(test::run(kSample + " --robot " + test::robotPath("deicing") +
                        " --samples 20000 --fix theta3=0 --output " + cloud_)
                  .exit_code,
              0);
    ASSERT_EQ(
        test::run(kBoundary + " --input " + cloud_ + " --plane xz --output " + rim_).exit_code, 0);
    ASSERT_EQ(test::run(kSample + " --shape ball --samples 5000 --output " + ball_).exit_code, 0);
  }
  static void TearDownTestSuite() { delete dir_; }
  static test::TempDir* dir_;
  static std::string cloud_, rim_, ball_;
};
test::TempDir* UnitsApp::dir_ = nullptr;
std::string UnitsApp::cloud_, UnitsApp::rim_, UnitsApp::ball_;

TEST_F(UnitsApp, SampleNamesTheRobotsUnitOrNoneForAShape) {
  const Json robot = runJson(kSample + " --robot " + test::robotPath("ta1400") +
                             " --samples 100 --json --output " + dir_->file("t.pcd"));
  EXPECT_EQ(robot["length_unit"], "mm");
  EXPECT_EQ(robot["units"]["bbox.min"], "mm");
  EXPECT_EQ(robot["units"]["seconds"], "s");
  const Json shape =
      runJson(kSample + " --shape disk --samples 100 --json --output " + dir_->file("d.pcd"));
  EXPECT_EQ(shape["length_unit"], "unrecorded");
  EXPECT_EQ(shape["units"]["area"], "unrecorded^2");
}

TEST_F(UnitsApp, MeasureGivesAreaInSquareUnitsAndConvertsThem) {
  const std::string args = kMeasure + " --input " + cloud_ + " --plane xz --boundary " + rim_;
  const Json cm = runJson(args + " --json");
  EXPECT_EQ(cm["length_unit"], "cm");
  EXPECT_EQ(cm["units"]["area"], "cm^2");
  EXPECT_EQ(cm["units"]["uncorrected"], "cm^2");
  EXPECT_EQ(cm["units"]["cross_check.area"], "cm^2");
  EXPECT_EQ(cm["units"]["alpha"], "local spacings");
  EXPECT_THAT(cm["cross_check"]["note"].get<std::string>(), HasSubstr("biased high"));
  // 1 cm^2 = 1e-4 m^2 = 100 mm^2.
  const Json m = runJson(args + " --json --unit m");
  EXPECT_EQ(m["length_unit"], "m");
  EXPECT_EQ(m["units"]["area"], "m^2");
  expectScaled(m["area"], cm["area"], 1e-4, "area");
  expectScaled(m["uncorrected"], cm["uncorrected"], 1e-4, "uncorrected");
  expectScaled(m["cross_check"]["area"], cm["cross_check"]["area"], 1e-4, "cross-check");
  const Json mm = runJson(kMeasure + " --input " + rim_ + " --plane xz --boundary " + rim_ +
                          " --method column --json --unit mm");
  const Json column_cm = runJson(kMeasure + " --input " + rim_ + " --plane xz --boundary " + rim_ +
                                 " --method column --json");
  expectScaled(mm["area"], column_cm["area"], 100.0, "column area");
  expectScaled(mm["column_width"], column_cm["column_width"], 10.0, "column width");
  EXPECT_EQ(mm["units"]["crossing_gap"], "mm");
  // Plain output: the number and its unit; the cross-check labelled as the paper's method.
  const test::RunResult plain = test::run(args);
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_THAT(plain.out, HasSubstr(" cm^2\ncross_check "));
  EXPECT_THAT(plain.out, HasSubstr("column method, biased high"));
}

TEST_F(UnitsApp, MeasureOfAnUnrecordedCloudSaysSoAndCannotConvert) {
  const Json json = runJson(kMeasure + " --input " + ball_ + " --json");
  EXPECT_EQ(json["length_unit"], "unrecorded");
  EXPECT_EQ(json["units"]["volume"], "unrecorded^3");
  test::TempDir nothing;
  test::expectToolFailure(kMeasure, "--input " + ball_ + " --unit m", 1,
                          ball_ + " records no length unit to convert from", nothing);
  test::expectToolFailure(kMeasure, "--input " + cloud_ + " --plane xz --unit km", 2, "--unit",
                          nothing);
}

TEST_F(UnitsApp, BoundaryGivesItsRadiusAndSpacingInTheUnitAsked) {
  const std::string args =
      kBoundary + " --input " + cloud_ + " --plane xz --json --output " + dir_->file("b.pcd");
  const Json cm = runJson(args);
  const Json mm = runJson(args + " --unit mm");
  EXPECT_EQ(cm["length_unit"], "cm");
  EXPECT_EQ(cm["units"]["radius"], "cm");
  EXPECT_EQ(mm["units"]["spacing"], "mm");
  EXPECT_EQ(mm["boundary"], cm["boundary"]);  // the same points
  expectScaled(mm["radius"], cm["radius"], 10.0, "radius");
  expectScaled(mm["spacing"], cm["spacing"], 10.0, "spacing");
  for (const char* method : {"grid", "extremum"}) {
    const Json json = runJson(args + " --method " + method);
    EXPECT_EQ(json["units"]["cell"], "cm") << method;
  }
}

TEST_F(UnitsApp, RefineAndSelectNameTheCloudsUnit) {
  const Json refined = runJson(kRefine + " --robot " + test::robotPath("deicing") + " --input " +
                               rim_ + " --samples 1000 --json --output " + dir_->file("r.pcd"));
  EXPECT_EQ(refined["length_unit"], "cm");
  EXPECT_EQ(refined["units"]["spread"], "joint ranges");
  const std::string labelled = dir_->file("l.pcd");
  ASSERT_EQ(test::run(kSample + " --robot " + test::robotPath("ta1400") +
                      " --collision --samples 500 --output " + labelled)
                .exit_code,
            0);
  const Json selected = runJson(kSelect + " --input " + labelled + " --label 0 --json --output " +
                                dir_->file("s.pcd"));
  EXPECT_EQ(selected["length_unit"], "mm");
}

TEST_F(UnitsApp, FkNamesItsUnitAndGivesThePapersPoseInMetres) {
  // Liu, Han, Xu & Li 2021, section 1.1: at q = [pi/3, pi/6, pi/2, pi/4, pi/3, pi/6] the tool is
  // at (-39.3043, 731.9230, -569.2371) mm.
  const std::string args = kFk + " --robot " + test::robotPath("inspection6") +
                           " --q '1.0471975511965976 0.5235987755982988 1.5707963267948966 "
                           "0.7853981633974483 1.0471975511965976 0.5235987755982988'";
  const Json m = runJson(args + " --json --unit m");
  EXPECT_EQ(m["length_unit"], "m");
  EXPECT_EQ(m["units"]["position"], "m");
  EXPECT_EQ(m["units"]["q"], Json({"rad", "rad", "rad", "rad", "rad", "rad"}));
  EXPECT_NEAR(m["position"][0].get<double>(), -0.0393043, 0.5e-7);
  EXPECT_NEAR(m["position"][1].get<double>(), 0.7319230, 0.5e-7);
  EXPECT_NEAR(m["pose"][2][3].get<double>(), -0.5692371, 0.5e-7);
  EXPECT_NEAR(m["pose"][2][1].get<double>(), 0.9012, 0.5e-4);  // rotation: no unit, unchanged
  const test::RunResult plain = test::run(args);
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_EQ(
      plain.out.rfind("# tool frame in the world frame; translation (last column) in mm\n", 0), 0u)
      << plain.out;
}

TEST_F(UnitsApp, IkCollideTrajAndPlanNameTheirUnits) {
  const std::string inspection = " --robot " + test::robotPath("inspection6");
  const Json ik =
      runJson(kIk + inspection +
              " --pose '-39.3043 731.9230 -569.2371 0.5 0.5 0.5' --position-only --json");
  EXPECT_EQ(ik["length_unit"], "mm");
  EXPECT_EQ(ik["units"]["position_error"], "mm");
  EXPECT_EQ(ik["units"]["orientation_error"], "rad");
  const Json collide = runJson(kCollide + " --robot " + test::robotPath("ta1400") +
                               " --q '0 0 0 0 0 0' --all --json");
  EXPECT_EQ(collide["length_unit"], "mm");
  EXPECT_EQ(collide["units"]["pairs.distance"], "mm");
  const Json traj = runJson(kTraj + inspection + " --from '0 0 0 0 0 0' --to '0.1 0 0 0 0 0'" +
                            " --duration 1 --rate 10 --json --output " + dir_->file("t.csv"));
  EXPECT_EQ(traj["length_unit"], "mm");
  EXPECT_EQ(traj["units"]["peak_velocity"][0], "rad/s");
  EXPECT_EQ(traj["units"]["peak_acceleration"][5], "rad/s^2");
  EXPECT_EQ(traj["units"]["tool_path_length"], "mm");
  const Json plan = runJson(kPlan + " --scenario " + std::string(MCWS_SCENARIOS_DIR) +
                            "/../tests/apps/data/planar2_quick.yaml --validation-poses 200" +
                            " --json --output " + dir_->file("p.csv"));
  EXPECT_EQ(plan["length_unit"], "cm");
  EXPECT_EQ(plan["units"]["time"], "s");
}

// Plain output (issue 16, section 1): every printed number names its unit, or says what it
// counts or that it is a fraction.

TEST_F(UnitsApp, IkPlainOutputNamesEachJointsUnit) {
  // The de-icing arm: three revolute joints and the telescopic forearm a2 in the robot's cm.
  const test::RunResult r = test::run(kIk + " --robot " + test::robotPath("deicing") +
                                      " --pose '60 25 20 0 0 0' --position-only");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("# joint values q in rad, rad, rad, cm (joint by joint)\nq: ", 0), 0u)
      << r.out;
  EXPECT_THAT(r.out, ::testing::ContainsRegex("\nposition error: [-+.e0-9]+ cm\n"));
}

TEST_F(UnitsApp, TrajCsvNamesTheUnitOfEveryColumn) {
  const std::string csv = dir_->file("deicing_traj.csv");
  const test::RunResult r = test::run(kTraj + " --robot " + test::robotPath("deicing") +
                                      " --from '0 0 0 30' --to '0.2 0.1 0.3 40' --duration 1" +
                                      " --rate 10 --output " + csv);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, ::testing::ContainsRegex("11 samples, tool path [.0-9]+ cm] -> "));
  const test::Csv table = test::parseCsv(test::readFile(csv));
  EXPECT_EQ(table.header,
            (std::vector<std::string>{
                "t_s", "theta3_rad", "theta1_rad", "theta2_rad", "a2_cm", "theta3_rad_per_s",
                "theta1_rad_per_s", "theta2_rad_per_s", "a2_cm_per_s", "theta3_rad_per_s2",
                "theta1_rad_per_s2", "theta2_rad_per_s2", "a2_cm_per_s2", "x_cm", "y_cm", "z_cm"}));
  ASSERT_EQ(table.rows.size(), 11u);
  EXPECT_DOUBLE_EQ(table.last()[table.column("a2_cm")], 40.0);
}

TEST_F(UnitsApp, PlanReportSaysWhatDAndPAreMeasuredIn) {
  const test::RunResult r =
      test::run(kPlan + " --scenario " + std::string(MCWS_SCENARIOS_DIR) +
                "/planar2.yaml --validation-poses 0 --output " + dir_->file("p_plain.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out,
              HasSubstr("\nunits: lengths cm, angles rad, times s; D = sqrt(sum (s_i dq_i)^2)"
                        " with s = 1/rad, 1/rad (dimensionless, as are D0, w and the "
                        "scores); P, the threshold and the free and collision rates are "
                        "fractions in [0, 1];"));
  EXPECT_THAT(r.out, ::testing::ContainsRegex("base offset [-.0-9]+ cm along the line"));
}

TEST_F(UnitsApp, ReachMapSummaryGivesTheVoxelEdgeAndWhatDIsAFractionOf) {
  const test::RunResult r =
      test::run(kReach + " --robot " + test::robotPath("inspection6") +
                " --resolution 20cm --samples 100000 --output " + dir_->file("map.pcd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The inspection arm's unit is mm: 20 cm is a 200 mm voxel; 200 directions x 1 roll bin.
  EXPECT_THAT(r.err, ::testing::ContainsRegex(
                         " ms : [0-9]+ voxels of edge 200 mm, mean D 0?\\.[0-9]+ \\(fraction "
                         "of the 200 orientation bins\\)] -> "));
}

TEST_F(UnitsApp, PlaceTableSaysTheSharesAreFractionsOfTheTargets) {
  const test::RunResult r = test::run(
      kPlace + " --robot " + test::robotPath("maintenance4") + " --standoff 2cm --targets " +
      std::string(MCWS_ROBOTS_DIR) + "/maintenance4_damper_targets.pcd" +
      " --along '-80 -40 40' --resolution 4cm --samples 100000 --confirm 1 --map-cache off "
      "--output " +
      dir_->file("bases.pcd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("offset x y z [cm]   map share   IK share   (fractions of the 15 "
                               "targets)\n"));
  EXPECT_THAT(r.err, ::testing::ContainsRegex("best: move the base by \\([- 0-9]+\\) cm: "
                                              "[0-9]+ of 15 targets reached"));
}

}  // namespace
}  // namespace mcws
