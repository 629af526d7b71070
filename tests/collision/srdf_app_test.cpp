// mcws_collide --srdf and --find-allowed-pairs (issue 33, item 5) on the column of boxes of
// column_urdf.h, whose allowed pairs are worked out by hand there.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "apps/tool_paths.h"
#include "collision/column_urdf.h"
#include "mcws/collision/srdf.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

TEST(SrdfApps, DisabledPairIsNoLongerReported) {
  test::TempDir dir;
  test::writeFile(dir.file("column.urdf"), test::kColumnUrdf);
  const std::string run =
      kCollide + " --robot " + dir.file("column.urdf") + " --tip link3 --q '0 0 0' --json";
  // link1 (body j1) and link3 (body j3) overlap at q = 0.
  test::RunResult r = test::run(run);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json out = nlohmann::json::parse(r.out);
  EXPECT_EQ(out["label"], 1);
  ASSERT_FALSE(out["pairs"].empty());
  EXPECT_EQ(out["pairs"][0]["a"], "j1");
  EXPECT_EQ(out["pairs"][0]["b"], "j3");
  // The bodies named by their URDF links too.
  EXPECT_EQ(out["pairs"][0]["links_a"], nlohmann::json::array({"link1"}));
  EXPECT_EQ(out["pairs"][0]["links_b"], nlohmann::json::array({"link3"}));
  // ... and only by them in the text report (the bodies' joint names mean nothing to a reader).
  const test::RunResult text = test::run(run.substr(0, run.size() - std::string(" --json").size()));
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("link1 - link3 "));
  EXPECT_THAT(text.out, ::testing::Not(HasSubstr("j1")));

  test::writeFile(dir.file("column.srdf"),
                  srdfText("column", {{"link3", "link1", "Default"}, {"marker", "post", "User"}}));
  r = test::run(run + " --srdf " + dir.file("column.srdf"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  out = nlohmann::json::parse(r.out);
  EXPECT_EQ(out["label"], 0);
  for (const auto& pair : out["pairs"]) EXPECT_FALSE(pair["a"] == "j1" && pair["b"] == "j3");
}

TEST(SrdfApps, BadSrdfIsOneLine) {
  test::TempDir dir, out;
  test::writeFile(dir.file("column.urdf"), test::kColumnUrdf);
  test::writeFile(dir.file("bad.srdf"), srdfText("column", {{"link1", "link9", "Never"}}));
  const std::string robot = "--robot " + dir.file("column.urdf") + " --tip link3 --q '0 0 0'";
  test::expectToolFailure(kCollide, robot + " --srdf " + dir.file("bad.srdf"), 1,
                          dir.file("bad.srdf") +
                              ": disable_collisions link1=\"link1\" link2=\"link9\": 'link9' is "
                              "not a link of the robot",
                          out);
  test::expectToolFailure(kCollide, robot + " --srdf " + dir.file("none.srdf"), 2,
                          "--srdf: '" + dir.file("none.srdf") + "' is not a file", out);
  test::expectToolFailure(kCollide, robot + " --find-allowed-pairs 0 --output " + out.file("a"), 2,
                          "--find-allowed-pairs", out);
  test::expectToolFailure(kCollide, robot + " --output " + out.file("a.srdf"), 2,
                          "--output and --seed need --find-allowed-pairs", out);
}

TEST(SrdfApps, FindAllowedPairsWritesTheHandWorkedSrdf) {
  test::TempDir dir;
  test::writeFile(dir.file("column.urdf"), test::kColumnUrdf);
  const std::string run = kCollide + " --robot " + dir.file("column.urdf") +
                          " --tip link3 --find-allowed-pairs 100 --seed 4 --output ";
  const test::RunResult r = test::run(run + dir.file("a.srdf"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Counts worked out in column_urdf.h.
  EXPECT_THAT(r.out, HasSubstr("15 link pairs need no check over 100 samples (7 Adjacent, "
                               "1 Default, 7 Never)"));
  const std::string text = test::readFile(dir.file("a.srdf"));
  EXPECT_THAT(text, HasSubstr("<robot name=\"column\">"));
  EXPECT_THAT(text,
              HasSubstr(R"(<disable_collisions link1="link1" link2="link3" reason="Default"/>)"));
  EXPECT_EQ(parseSrdf(text, "a.srdf").size(), 15u);
  // Read back with --srdf: every pair disabled, so nothing is checked.
  const test::RunResult check =
      test::run(kCollide + " --robot " + dir.file("column.urdf") +
                " --tip link3 --q '0 0 0' --json --srdf " + dir.file("a.srdf"));
  ASSERT_EQ(check.exit_code, 0) << check.err;
  EXPECT_EQ(nlohmann::json::parse(check.out)["pairs_checked"], 0);
  // Same seed, same file.
  ASSERT_EQ(test::run(run + dir.file("b.srdf")).exit_code, 0);
  EXPECT_EQ(test::readFile(dir.file("b.srdf")), text);
}

}  // namespace
}  // namespace mcws
