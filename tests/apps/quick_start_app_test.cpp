// The README's "Quick start: my own URDF" (issue 33, item 7), run as written on a robot as ROS
// packages hold them, so that the five commands cannot rot: a package folder with package.xml,
// the URDF in urdf/ and its meshes in meshes/ as COLLADA (written in millimetres), STL and OBJ,
// all named by package:// URIs, two leaf links (tool0 and ee_link, as the UR descriptions have),
// no SRDF but the one the first command writes. Only the sample counts are made small.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "collision/collada_box.h"
#include "test_support.h"

namespace mcws {
namespace {

namespace fs = std::filesystem;

/// The heading the README's section has, and the block this test runs while README.md has none.
constexpr char kQuickStartHeading[] = "## Quick start: my own URDF";
constexpr char kQuickStartCopy[] =
    R"(B=build/apps; W=~/ws/src       # the tools; the folder holding your robot's ROS package(s)
R="--robot $W/my_arm_description/urdf/my_arm.urdf --tip tool0 --package-path $W"
# 1. the link pairs a collision check may skip, found as MoveIt's setup assistant finds them
#    (or give your MoveIt config's SRDF to --srdf below instead)
$B/mcws_collide $R --find-allowed-pairs 10000 --output my_arm.srdf
# 2. the workspace: tool0 positions of random joint vectors, each labelled by collision (0 = free)
$B/mcws_sample $R --srdf my_arm.srdf --collision --samples 200000 --output ws.pcd
# 3. the collision-free samples
$B/mcws_select --input ws.pcd --label 0 --output free.pcd
# 4. their envelope (a closed mesh) and the datasheet drawing (side and top view, dimensioned)
$B/mcws_envelope --input free.pcd --output envelope.ply --drawing range.png --json
# 5. a reachability map: per 5 cm voxel, the share of approach directions reached without collision
$B/mcws_reach $R --srdf my_arm.srdf --collision --resolution 5cm --samples 10000000 \
  --output reach.pcd --map reach.bin --halfcut reach.png
)";

/// The first ```sh block after the quick start's heading in `readme`, "" when there is none.
std::string quickStartBlock(const std::string& readme) {
  const std::size_t heading = readme.find(std::string("\n") + kQuickStartHeading + "\n");
  if (heading == std::string::npos) return "";
  const std::size_t open = readme.find("\n```sh\n", heading);
  const std::size_t next_section = readme.find("\n## ", heading + 1);
  if (open == std::string::npos || (next_section != std::string::npos && open > next_section))
    return "";
  const std::size_t begin = open + 7;
  return readme.substr(begin, readme.find("\n```", begin) + 1 - begin);
}

/// `corners` as an ASCII STL of the box's 12 triangles, wound as collada_box.h winds them.
std::string quickStartStl(const test::ColladaBox& box) {
  const auto corners = test::colladaBoxCorners(box);
  const int faces[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                            {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  std::ostringstream stl;
  stl << "solid box\n";
  for (const auto& face : faces) {
    stl << "facet normal 0 0 0\nouter loop\n";
    for (int c : face) {
      stl << "vertex " << corners[c].x() << " " << corners[c].y() << " " << corners[c].z() << "\n";
    }
    stl << "endloop\nendfacet\n";
  }
  stl << "endsolid box\n";
  return stl.str();
}

/// The same box as an OBJ of six quads.
std::string quickStartObj(const test::ColladaBox& box) {
  std::ostringstream obj;
  for (const auto& p : test::colladaBoxCorners(box)) {
    obj << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
  }
  obj << "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
  return obj.str();
}

test::ColladaBox quickStartBox(Eigen::Vector3d lo, Eigen::Vector3d hi, const std::string& unit) {
  test::ColladaBox box;
  box.lo = lo;
  box.hi = hi;
  box.unit_meter = unit;
  return box;
}

/// A four-joint arm (about 1.1 m) as a ROS package under `ws`: base (a .dae in millimetres),
/// shoulder (STL), upper arm (OBJ), forearm (the .dae again, stretched by the URDF's scale), a
/// wrist box, then two fixed frames below the wrist: tool0 and ee_link.
void writeQuickStartRobot(const fs::path& ws) {
  const fs::path package = ws / "src" / "my_arm_description";
  fs::create_directories(package / "urdf");
  fs::create_directories(package / "meshes");
  test::writeFile((package / "package.xml").string(),
                  "<package format=\"2\"><name>my_arm_description</name></package>\n");
  test::writeFile((package / "meshes" / "base.dae").string(),
                  test::colladaBoxText(quickStartBox({-80, -80, 0}, {80, 80, 90}, "0.001")));
  test::writeFile((package / "meshes" / "shoulder.stl").string(),
                  quickStartStl(quickStartBox({-0.05, -0.05, 0.0}, {0.05, 0.05, 0.15}, "")));
  test::writeFile((package / "meshes" / "upper_arm.obj").string(),
                  quickStartObj(quickStartBox({-0.04, -0.04, 0.02}, {0.04, 0.04, 0.38}, "")));
  test::writeFile((package / "meshes" / "forearm.dae").string(),
                  test::colladaBoxText(quickStartBox({-30, -30, 10}, {30, 30, 160}, "0.001")));
  const auto link = [](const std::string& name, const std::string& geometry) {
    return "  <link name=\"" + name + "\"><collision><geometry>" + geometry +
           "</geometry></collision></link>\n";
  };
  const auto mesh = [](const std::string& file, const std::string& scale = "") {
    return "<mesh filename=\"package://my_arm_description/meshes/" + file + "\"" +
           (scale.empty() ? "" : " scale=\"" + scale + "\"") + "/>";
  };
  const auto joint = [](const std::string& name, const std::string& type, const std::string& parent,
                        const std::string& child, const std::string& xyz, const std::string& axis,
                        double limit) {
    std::string text = "  <joint name=\"" + name + "\" type=\"" + type + "\"><parent link=\"" +
                       parent + "\"/><child link=\"" + child + "\"/><origin xyz=\"" + xyz +
                       "\" rpy=\"0 0 0\"/>";
    if (type == "revolute") {
      text += "<axis xyz=\"" + axis + "\"/><limit lower=\"" + std::to_string(-limit) +
              "\" upper=\"" + std::to_string(limit) + "\" effort=\"100\" velocity=\"3\"/>";
    }
    return text + "</joint>\n";
  };
  test::writeFile(
      (package / "urdf" / "my_arm.urdf").string(),
      "<?xml version=\"1.0\"?>\n<!-- as xacro writes it: package:// meshes, two leaves -->\n"
      "<robot name=\"my_arm\">\n  <link name=\"world\"/>\n" +
          link("base_link", mesh("base.dae")) + link("shoulder", mesh("shoulder.stl")) +
          link("upper_arm", mesh("upper_arm.obj")) + link("forearm", mesh("forearm.dae", "1 1 2")) +
          link("wrist", "<box size=\"0.06 0.06 0.08\"/>") +
          "  <link name=\"tool0\"/>\n  <link name=\"ee_link\"/>\n" +
          joint("world_joint", "fixed", "world", "base_link", "0 0 0", "", 0) +
          joint("shoulder_pan", "revolute", "base_link", "shoulder", "0 0 0.1", "0 0 1", 3.0) +
          joint("shoulder_lift", "revolute", "shoulder", "upper_arm", "0 0 0.15", "0 1 0", 2.0) +
          joint("elbow", "revolute", "upper_arm", "forearm", "0 0 0.4", "0 1 0", 2.5) +
          joint("wrist_1", "revolute", "forearm", "wrist", "0 0 0.35", "0 0 1", 3.0) +
          joint("tool0_fixed", "fixed", "wrist", "tool0", "0 0 0.1", "", 0) +
          joint("ee_fixed", "fixed", "wrist", "ee_link", "0 0 0.05", "", 0) + "</robot>\n");
}

TEST(QuickStart, TheBlockIsReadUnderItsHeading) {
  EXPECT_EQ(quickStartBlock("# x\n## Quick start: my own URDF\nText.\n```sh\na\nb \\\n  c\n```\n"
                            "## Next\n```sh\nd\n```\n"),
            "a\nb \\\n  c\n");
  // A block of another section is not taken for it.
  EXPECT_EQ(quickStartBlock("## Quick start: my own URDF\nText.\n## Next\n```sh\nd\n```\n"), "");
  EXPECT_EQ(quickStartBlock("\n## Quick start: my own URDF\nText.\n## Next\n```sh\nd\n```\n"), "");
  EXPECT_EQ(quickStartBlock("## Other\n```sh\nd\n```\n"), "");
}

TEST(QuickStart, MyOwnUrdfInFiveCommands) {
  const std::string readme = test::readFile(std::string(MCWS_SOURCE_DIR) + "/README.md");
  std::string block = quickStartBlock(readme);
  if (block.empty()) {
    std::cout << "note: README.md has no '" << kQuickStartHeading
              << "' section with a ```sh block: running this test's copy of it\n";
    block = kQuickStartCopy;
  }
  // Small counts: the commands' flags are what is tested, not the numbers.
  block = std::regex_replace(block, std::regex("--find-allowed-pairs [0-9]+"),
                             "--find-allowed-pairs 300");
  block = std::regex_replace(block, std::regex("--samples [0-9]+"), "--samples 20000");

  // The tools where the block looks for them (build/apps from the current folder), the
  // workspace where it looks for the package (~/ws/src, with HOME here).
  test::TempDir dir;
  const fs::path home = dir.file("");
  fs::create_directories(home / "build");
  fs::create_directory_symlink(fs::path(MCWS_TOOLS_DIR), home / "build" / "apps");
  writeQuickStartRobot(home / "ws");
  test::writeFile(dir.file("quick_start.sh"), block);
  const test::RunResult r =
      test::run("cd " + home.string() + " && HOME=" + home.string() + " bash -eu quick_start.sh");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  for (const char* file : {"my_arm.srdf", "ws.pcd", "free.pcd", "envelope.ply", "range.png",
                           "reach.pcd", "reach.bin", "reach.png"}) {
    std::error_code ec;
    EXPECT_GT(fs::file_size(dir.file(file), ec), 0u) << file << " " << ec.message();
  }
  // The SRDF names the robot and skips the joints' neighbours (adjacent in the chain).
  const std::string srdf = test::readFile(dir.file("my_arm.srdf"));
  EXPECT_THAT(srdf, ::testing::HasSubstr("<robot name=\"my_arm\">"));
  EXPECT_THAT(srdf, ::testing::ContainsRegex("link1=\"(shoulder\" link2=\"upper_arm|upper_arm\" "
                                             "link2=\"shoulder)\" reason=\"Adjacent\""));
  // The envelope of the collision-free tool0 points is a closed surface, and the drawing measures
  // tool0: its largest distance from the first joint's axis is at most the arm stretched out
  // level, 0.4 + 0.35 + 0.1 = 0.85 m (ee_link's would be 0.80 m), and the fixed seed's 20000
  // samples come within 1 cm of it.
  EXPECT_THAT(r.out, ::testing::HasSubstr("\"closed_and_oriented\":true"));
  std::smatch reach;
  ASSERT_TRUE(std::regex_search(r.out, reach, std::regex("\"max_reach\":([-+.0-9e]+)")));
  EXPECT_LE(std::stod(reach[1]), 0.85 + 1e-9);
  EXPECT_GE(std::stod(reach[1]), 0.84);

  // Why --tip is there: the URDF has two leaves, and without it the tool says so.
  const test::RunResult no_tip =
      test::run(std::string(MCWS_TOOLS_DIR) + "/mcws_sample --robot " +
                (home / "ws/src/my_arm_description/urdf/my_arm.urdf").string() +
                " --package-path " + (home / "ws/src").string() + " --output " + dir.file("x.pcd"));
  EXPECT_EQ(no_tip.exit_code, 2);
  EXPECT_THAT(no_tip.err,
              ::testing::AllOf(::testing::HasSubstr("ee_link"), ::testing::HasSubstr("tool0"),
                               ::testing::HasSubstr("--tip")));
}

}  // namespace
}  // namespace mcws
