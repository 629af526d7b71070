// The README's "Quick start: my own URDF" (issue 33, item 7), run as written on a robot as ROS
// packages hold them, so that the five commands cannot rot: a package folder with package.xml,
// the URDF in urdf/ and its meshes in meshes/ as COLLADA (written in millimetres), STL and OBJ,
// all named by package:// URIs, two leaf links (tool0 and ee_link, as the UR descriptions have),
// no SRDF but the one the first command writes. Only the sample counts are made small.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

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

/// Two fingers for the quick start's wrist: finger_joint (0 to 0.04 m, its default 0) and
/// finger_mimic, which follows it at 1 x its value + 0.01 m, in the opposite direction.
constexpr char kGripper[] =
    R"(  <link name="finger_left"><collision><geometry><box size="0.01 0.01 0.04"/></geometry></collision></link>
  <link name="finger_right"><collision><geometry><box size="0.01 0.01 0.04"/></geometry></collision></link>
  <joint name="finger_joint" type="prismatic"><parent link="wrist"/><child link="finger_left"/>
    <origin xyz="0 0.02 0.1" rpy="0 0 0"/><axis xyz="0 1 0"/>
    <limit lower="0" upper="0.04" effort="10" velocity="0.1"/></joint>
  <joint name="finger_mimic" type="prismatic"><parent link="wrist"/><child link="finger_right"/>
    <origin xyz="0 -0.02 0.1" rpy="0 0 0"/><axis xyz="0 -1 0"/>
    <limit lower="0" upper="0.05" effort="10" velocity="0.1"/>
    <mimic joint="finger_joint" multiplier="1" offset="0.01"/></joint>
)";

/// A four-joint arm (about 1.1 m) as a ROS package under `ws`: base (a .dae in millimetres),
/// shoulder (STL), upper arm (OBJ), forearm (the .dae again, stretched by the URDF's scale), a
/// wrist box, then two fixed frames below the wrist: tool0 and ee_link. With `gripper`, two
/// finger boxes on prismatic joints below the wrist as well, the second a mimic of the first
/// (multiplier 1, offset 0.01 m): two more leaves, neither on the chain.
void writeQuickStartRobot(const fs::path& ws, bool gripper = false) {
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
          joint("ee_fixed", "fixed", "wrist", "ee_link", "0 0 0.05", "", 0) +
          (gripper ? kGripper : "") + "</robot>\n");
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

/// Where the quick start's tool0 is for the joint values q [rad]: the arm moves in the plane that
/// shoulder_pan turns about z; shoulder_lift and elbow turn about y (0.15 m above the pan, the
/// upper arm 0.4 m), wrist_1 turns about the forearm, which tool0 continues (0.35 + 0.1 m).
Eigen::Vector3d quickStartTool0(const double* q) {
  const double r = 0.4 * std::sin(q[1]) + 0.45 * std::sin(q[1] + q[2]);
  return {r * std::cos(q[0]), r * std::sin(q[0]),
          0.25 + 0.4 * std::cos(q[1]) + 0.45 * std::cos(q[1] + q[2])};
}

/// Whether the planar two-link arm (0.4 m, then 0.45 m to tool0; lift within +-2, elbow within
/// +-2.5 rad, both measured from straight up) puts tool0 at (x, z) from the lift axis.
bool quickStartPlanarReach(double x, double z) {
  const double d2 = x * x + z * z;
  const double c = (d2 - 0.4 * 0.4 - 0.45 * 0.45) / (2 * 0.4 * 0.45);
  if (c < -1 || c > 1) return false;
  for (const double elbow : {std::acos(c), -std::acos(c)}) {
    const double lift =
        std::atan2(x, z) - std::atan2(0.45 * std::sin(elbow), 0.4 + 0.45 * std::cos(elbow));
    const double wrapped = std::remainder(lift, 2 * M_PI);
    if (std::abs(elbow) <= 2.5 && std::abs(wrapped) <= 2.0) return true;
  }
  return false;
}

/// The volume tool0 sweeps [m^3], by Pappus: the pan turns the planar arm's reach about z, and a
/// point at -r is reached through the pan and a lift of the other sign, so the workspace is the
/// solid of revolution of the half-plane points (r >= 0) reached at r or at -r; midpoint sums on
/// a 1 mm grid.
double quickStartVolume() {
  const double h = 0.001;
  double sum = 0;
  for (double r = h / 2; r < 0.86; r += h) {
    for (double z = -0.86 + h / 2; z < 0.86; z += h) {
      if (quickStartPlanarReach(r, z) || quickStartPlanarReach(-r, z)) sum += r;
    }
  }
  return 2 * M_PI * sum * h * h;
}

TEST(QuickStart, AnUneditedUrdfGoesThroughEveryStage) {
  // Issue 33's acceptance: package:// meshes in .dae, .stl and .obj, several leaves, a gripper
  // with a mimic finger; only --tip, --package-path and --srdf.
  test::TempDir dir;
  const fs::path ws = fs::path(dir.file("")) / "ws";
  writeQuickStartRobot(ws, true);
  const std::string tools = std::string(MCWS_TOOLS_DIR) + "/";
  const std::string robot = "--robot " + (ws / "src/my_arm_description/urdf/my_arm.urdf").string() +
                            " --tip tool0 --package-path " + (ws / "src").string();
  const auto json = [&](const std::string& tool, const std::string& args) {
    const test::RunResult r = test::run(tools + tool + " " + args + " --json");
    EXPECT_EQ(r.exit_code, 0) << tool << " " << args << "\n" << r.err;
    return r.exit_code == 0 ? nlohmann::json::parse(r.out) : nlohmann::json::object();
  };
  const test::RunResult srdf = test::run(
      tools + "mcws_collide " + robot + " --find-allowed-pairs 300 --output " + dir.file("a.srdf"));
  ASSERT_EQ(srdf.exit_code, 0) << srdf.err;
  const std::string args = robot + " --srdf " + dir.file("a.srdf");

  // FK: four free joints (the fingers are off the chain, the mimic finger no degree of freedom),
  // tool0 where the closed form puts it.
  const double q[4] = {0.3, -0.5, 0.7, 1.0};
  const nlohmann::json fk = json("mcws_fk", args + " --q '0.3 -0.5 0.7 1.0'");
  ASSERT_EQ(fk["q"].size(), 4u);
  EXPECT_EQ(fk["tip"], "tool0");
  const Eigen::Vector3d p = quickStartTool0(q);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(fk["position"][i].get<double>(), p[i], 1e-12) << i;

  // IK back to that point: the solution's tool0, by the closed form, is on it.
  const nlohmann::json ik =
      json("mcws_ik", args + " --position-only --pose '" + std::to_string(p.x()) + " " +
                          std::to_string(p.y()) + " " + std::to_string(p.z()) + " 0 0 0'");
  ASSERT_EQ(ik["q"].size(), 4u);
  const std::vector<double> solved = ik["q"].get<std::vector<double>>();
  EXPECT_LT((quickStartTool0(solved.data()) - p).norm(), 1e-5);

  // The fingers are in the collision model, carried by the wrist's body.
  const nlohmann::json collide = json("mcws_collide", args + " --q '0 0 0 0' --all");
  std::string links = collide.dump();
  EXPECT_NE(links.find("finger_left"), std::string::npos) << links;
  EXPECT_NE(links.find("finger_right"), std::string::npos) << links;

  // Sampling, boundary and volume without collision: the solid of revolution's volume.
  const std::string cloud = dir.file("ws.pcd");
  json("mcws_sample", args + " --samples 100000 --output " + cloud);
  json("mcws_sample", args + " --collision --samples 20000 --output " + dir.file("labelled.pcd"));
  const nlohmann::json boundary =
      json("mcws_boundary", "--input " + cloud + " --output " + dir.file("rim.pcd"));
  EXPECT_GT(boundary["boundary"].get<double>(), 1000) << boundary.dump();
  // Without the edge correction: Efron's assumes samples of uniform density, while samples
  // uniform in the joints crowd on the outer sphere (the stretched arm is a singular pose), so
  // there it adds the outside points' share again (4 % too much with these 1e5 samples).
  const nlohmann::json volume = json("mcws_measure", "--input " + cloud + " --correction none");
  EXPECT_EQ(volume["tip"], "tool0");
  EXPECT_NEAR(volume["volume"].get<double>() / quickStartVolume(), 1.0, 0.02) << volume.dump();

  // The envelope and the drawing: tool0 stretched out level, 0.85 m from the pan axis at most.
  const nlohmann::json envelope =
      json("mcws_envelope", "--input " + cloud + " --output " + dir.file("env.ply") +
                                " --drawing " + dir.file("range.png"));
  EXPECT_LE(envelope["drawing"]["max_reach"].get<double>(), 0.85 + 1e-9) << envelope.dump();
  EXPECT_GE(envelope["drawing"]["max_reach"].get<double>(), 0.83);

  // Where to stop the base along x so that tool0 reaches a point on the lift axis' height: the
  // distance from the lift axis must lie between the folded arm's (elbow at 2.5 rad: 0.272 m) and
  // the stretched arm's 0.85 m, so the offsets 0.3 to 0.8 (either side) and no other.
  test::writeFile(dir.file("targets.csv"), "x,y,z,normal_x,normal_y,normal_z\n0,0,0.25,0,0,1\n");
  const nlohmann::json place =
      json("mcws_place",
           args + " --targets " + dir.file("targets.csv") +
               " --along '-1 1 0.1' --resolution 5cm --samples 200000 --confirm all --map-cache off"
               " --approach-tolerance 180deg --ik-starts 16 --output " +
               dir.file("bases.pcd"));
  ASSERT_EQ(place["candidates"].size(), 21u) << place.dump();
  for (const auto& c : place["candidates"]) {
    const double d = std::abs(c["offset"][0].get<double>());
    EXPECT_EQ(c["ik_share"].get<double>(), d > 0.25 && d < 0.85 ? 1.0 : 0.0) << c.dump();
  }
}

}  // namespace
}  // namespace mcws
