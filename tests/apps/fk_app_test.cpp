// mcws_fk through its command line, checked against the pose matrix Liu, Han, Xu & Li 2021 print.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "apps/tool_paths.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

// pi/3 pi/6 pi/2 pi/4 pi/3 pi/6, Liu, Han, Xu & Li 2021, section 1.1
const std::string kSeedQ =
    " --q '1.0471975511965976 0.5235987755982988 1.5707963267948966 "
    "0.7853981633974483 1.0471975511965976 0.5235987755982988'";

TEST(FkApp, HelpExitsZero) {
  const test::RunResult r = test::run(kFk + " --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, HasSubstr("--robot"));
  EXPECT_THAT(r.out, HasSubstr("--q"));
}

TEST(FkApp, JsonPoseMatchesThePapersMatrix) {
  const test::RunResult r = test::run(kFk + kInspection + kSeedQ + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_NEAR(json["pose"][0][3].get<double>(), -39.3043, 0.5e-4);
  EXPECT_NEAR(json["pose"][1][3].get<double>(), 731.9230, 0.5e-4);
  EXPECT_NEAR(json["pose"][2][3].get<double>(), -569.2371, 0.5e-4);
  EXPECT_NEAR(json["pose"][2][1].get<double>(), 0.9012, 0.5e-4);
  EXPECT_EQ(json["q"].size(), 6u);
}

TEST(FkApp, NegativeValuesAndCommasParse) {
  const test::RunResult r =
      test::run(kFk + " --robot " + test::robotPath("deicing") + " --q '-0.5,0.2,-1,30' --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  // eq. (1) of Yin, Wang & Yu 2010 with t3 = -0.5, t1 = 0.2, t2 = -1, a2 = 30
  const double radial = 50 * std::cos(0.2) + 30 * std::cos(-0.8);
  EXPECT_NEAR(json["position"][0].get<double>(), std::cos(-0.5) * radial, 1e-9);
  EXPECT_NEAR(json["position"][2].get<double>(), 50 * std::sin(0.2) + 30 * std::sin(-0.8), 1e-9);
}

TEST(FkApp, BadJointVectors) {
  struct Case {
    std::string args;
    int exit_code;
    std::string message;
  };
  const Case cases[] = {
      {kInspection + " --q '1 2 3'", 2,
       "--q: robot 'inspection6' has 6 joints but 3 joint values were given"},
      {kInspection + " --q '1 2 3 4 5 nan'", 2, "--q: 'nan' is not a finite number"},
      {kInspection + " --q '1 2 3 4 5 6x'", 2, "--q: '6x' is not a finite number"},
      {kInspection + " --q '0 0 0 0 0 4'", 2,
       "--q: joint 'j6' value 4 is outside its limits [-3.141592654, 3.141592654] rad ([-180, "
       "180] deg)"},
      {kInspection + " --q 0 0 0 0 0 0", 2, "too many positional options"},
      {kInspection, 2, "missing --q"},
      {" --robot /nonexistent.yaml --q 0", 1,
       "--robot: /nonexistent.yaml: robot file does not exist"},
      {kInspection + " --q '0 0 0 0 0 0' --frame elbow", 2,
       "--frame: 'elbow' is not tool or flange"},
  };
  for (const Case& c : cases) {
    const test::RunResult r = test::run(kFk + c.args);
    EXPECT_EQ(r.exit_code, c.exit_code) << c.args << "\n" << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.message)) << c.args;
    EXPECT_EQ(test::lineCount(r.err), 1) << r.err;
    EXPECT_TRUE(r.out.empty());
  }
}

TEST(FkApp, IgnoreLimitsAcceptsValuesOutsideThem) {
  // q6 = 4 rad is beyond its 180 degree limit. The last joint (a = 0, alpha = 0, d = 500 mm)
  // turns the flange about its own z axis: the same point, and R(4) = R(0) Rz(4) by hand, not
  // the pose at the limit (R(0) Rz(pi)).
  const test::RunResult zero = test::run(kFk + kInspection + " --q '0 0 0 0 0 0' --json");
  const test::RunResult four =
      test::run(kFk + kInspection + " --q '0 0 0 0 0 4' --ignore-limits --json");
  ASSERT_EQ(zero.exit_code, 0) << zero.err;
  ASSERT_EQ(four.exit_code, 0) << four.err;
  const auto p0 = nlohmann::json::parse(zero.out)["pose"],
             p4 = nlohmann::json::parse(four.out)["pose"];
  const double c = std::cos(4.0), s = std::sin(4.0);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(p4[i][3].get<double>(), p0[i][3].get<double>(), 1e-9) << i;
    const double r0 = p0[i][0].get<double>(), r1 = p0[i][1].get<double>();
    EXPECT_NEAR(p4[i][0].get<double>(), c * r0 + s * r1, 1e-12) << i;
    EXPECT_NEAR(p4[i][1].get<double>(), -s * r0 + c * r1, 1e-12) << i;
    EXPECT_NEAR(p4[i][2].get<double>(), p0[i][2].get<double>(), 1e-12) << i;
  }
}

}  // namespace
}  // namespace mcws
