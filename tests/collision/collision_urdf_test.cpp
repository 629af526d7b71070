// Collision geometry from URDF <collision> elements: the inspection arm's URDF against its YAML
// (the same shapes, the same label on every sample), each primitive's body and pose against a
// hand-worked tiny URDF, and the one-line messages for what is not supported.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>

#include "kinematics/ur5_shaped_urdf.h"
#include "mcws/collision/collision_checker.h"
#include "mcws/collision/collision_model.h"
#include "mcws/core/error.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/robot_urdf.h"
#include "mcws/kinematics/robot_yaml.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

/// Millimetres per metre: inspection6.yaml is in mm, its URDF in m.
constexpr double kMmPerM = 1000.0;
/// Agreement of a URDF length (m, read from decimal text, times 1000) with the YAML's [mm]: a few
/// ulps of numbers below 4000 mm.
constexpr double kMmTolerance = 1e-9;
/// Agreement of hand-worked poses with the reader's [m]: rounding of a few products of sin(pi/2).
constexpr double kPoseTolerance = 1e-12;
/// A pair whose distance is within this of 0 [mm] touches exactly up to rounding. inspection6.yaml
/// has such configurations: j1's capsule (radius 60) lies on joint 1's axis and j3's (radius 40)
/// in the arm plane, d2 + 50 = 100 mm from that axis, so the two touch exactly whenever the
/// forearm passes over the shoulder; there the label rests on the last bit of the distance, and
/// metres and millimetres round differently.
constexpr double kTouchMm = 1e-9;

const double kHalfPi = M_PI / 2.0;

std::string inspectionUrdf() { return std::string(MCWS_ROBOTS_DIR) + "/inspection6.urdf"; }

/// The inspection arm read both ways, with checkers for the two models.
class Inspection6Urdf : public ::testing::Test {
 protected:
  const Robot yaml_robot_ = loadRobot(test::robotPath("inspection6"));
  const CollisionModel yaml_model_ =
      loadCollisionModel(yaml_robot_, test::robotPath("inspection6"));
  const Robot urdf_robot_ = loadRobot(inspectionUrdf());
  const CollisionModel urdf_model_ = loadCollisionModel(urdf_robot_, inspectionUrdf());
  /// The URDF's shapes converted to the YAML robot's millimetres (its joints have the same names).
  const CollisionModel urdf_model_mm_ = loadCollisionUrdf(yaml_robot_, inspectionUrdf());

  /// Joint vectors uniform within the limits [rad], seeded.
  static std::vector<Eigen::VectorXd> samples(int count) {
    std::mt19937_64 random(16);
    std::uniform_real_distribution<double> angle(-M_PI, M_PI);
    std::vector<Eigen::VectorXd> qs(count, Eigen::VectorXd(6));
    for (Eigen::VectorXd& q : qs) {
      for (int j = 0; j < 6; ++j) q[j] = angle(random);
    }
    return qs;
  }
};

/// |distance| of the pair a-b in a report, or infinity when it is not there.
double pairDistance(const std::vector<PairReport>& report, const std::string& a,
                    const std::string& b) {
  for (const PairReport& pair : report) {
    if (pair.body_a == a && pair.body_b == b) return std::abs(pair.distance);
  }
  return std::numeric_limits<double>::infinity();
}

/// Expects the URDF body (m) to hold the YAML body's shapes (mm), in the same order.
void expectSameShapes(const BodySpec& urdf, const BodySpec& yaml) {
  SCOPED_TRACE("body " + yaml.name);
  EXPECT_EQ(urdf.name, yaml.name);
  ASSERT_EQ(urdf.shapes.size(), yaml.shapes.size());
  for (std::size_t i = 0; i < yaml.shapes.size(); ++i) {
    const ShapeSpec& u = urdf.shapes[i];
    const ShapeSpec& y = yaml.shapes[i];
    EXPECT_EQ(u.type, y.type) << shapeTypeName(u.type) << " vs " << shapeTypeName(y.type);
    EXPECT_NEAR(u.radius * kMmPerM, y.radius, kMmTolerance);
    EXPECT_LT((u.p_from * kMmPerM - y.p_from).norm(), kMmTolerance);
    EXPECT_LT((u.p_to * kMmPerM - y.p_to).norm(), kMmTolerance);
    EXPECT_LT((u.size * kMmPerM - y.size).norm(), kMmTolerance);
    EXPECT_LT((u.T_body_shape.translation() * kMmPerM - y.T_body_shape.translation()).norm(),
              kMmTolerance);
    EXPECT_TRUE(u.T_body_shape.linear().isApprox(y.T_body_shape.linear(), kPoseTolerance));
  }
}

TEST_F(Inspection6Urdf, ReadsTheSameShapesAsTheYaml) {
  ASSERT_EQ(urdf_model_.links.size(), yaml_model_.links.size());
  for (std::size_t i = 0; i < yaml_model_.links.size(); ++i) {
    expectSameShapes(urdf_model_.links[i], yaml_model_.links[i]);
  }
  // Each URDF cylinder with its two end spheres is read back as the YAML's capsule.
  EXPECT_EQ(urdf_model_.links[2].shapes[0].type, ShapeType::kCapsule);
  expectSameShapes(urdf_model_.tool, yaml_model_.tool);
  // Environment objects come in the order of their link names (urdfdom keeps no file order).
  ASSERT_EQ(urdf_model_.environment.size(), yaml_model_.environment.size());
  for (const BodySpec& object : yaml_model_.environment) {
    const auto found = std::find_if(urdf_model_.environment.begin(), urdf_model_.environment.end(),
                                    [&](const BodySpec& b) { return b.name == object.name; });
    ASSERT_NE(found, urdf_model_.environment.end()) << object.name;
    expectSameShapes(*found, object);
  }
  EXPECT_TRUE(urdf_model_.allowed.empty());
  EXPECT_TRUE(yaml_model_.allowed.empty());
}

TEST_F(Inspection6Urdf, UrdfShapesInMillimetresAreTheYamlsExactly) {
  // Converted to mm the URDF's decimal metres land on the YAML's numbers to the last bit.
  for (std::size_t i = 0; i < yaml_model_.links.size(); ++i) {
    const std::vector<ShapeSpec>& u = urdf_model_mm_.links[i].shapes;
    const std::vector<ShapeSpec>& y = yaml_model_.links[i].shapes;
    ASSERT_EQ(u.size(), y.size()) << yaml_model_.links[i].name;
    for (std::size_t k = 0; k < y.size(); ++k) {
      EXPECT_EQ(u[k].p_from, y[k].p_from) << yaml_model_.links[i].name;
      EXPECT_EQ(u[k].p_to, y[k].p_to) << yaml_model_.links[i].name;
      EXPECT_EQ(u[k].radius, y[k].radius) << yaml_model_.links[i].name;
    }
  }
}

TEST_F(Inspection6Urdf, UrdfShapesGiveTheYamlsLabelOnEverySample) {
  // The URDF's shapes on the YAML robot (both in mm): the same label, bit for bit, everywhere.
  const CollisionChecker yaml_checker(yaml_robot_, yaml_model_);
  const CollisionChecker urdf_checker(yaml_robot_, urdf_model_mm_);
  ASSERT_EQ(urdf_checker.pairs().size(), yaml_checker.pairs().size());
  std::array<int, 4> counts{};  // per label
  const std::vector<Eigen::VectorXd> qs = samples(5000);
  for (std::size_t s = 0; s < qs.size(); ++s) {
    const std::uint32_t label = yaml_checker.label(qs[s]);
    ASSERT_EQ(urdf_checker.label(qs[s]), label) << "sample " << s << ", q = " << qs[s].transpose();
    ASSERT_LT(label, counts.size());
    ++counts[label];
  }
  // Every label occurs, so the comparison covers links, the tool and the environment.
  for (std::uint32_t label = 0; label < counts.size(); ++label) {
    EXPECT_GT(counts[label], 0) << labelName(label);
  }
}

TEST_F(Inspection6Urdf, UrdfChainGivesTheYamlsLabelOnEverySampleButExactTouches) {
  // The URDF robot in m with its own frames against the YAML robot in mm. A label may differ
  // only where a pair touches exactly (kTouchMm) in both models: then both labels are right.
  const CollisionChecker yaml_checker(yaml_robot_, yaml_model_);
  const CollisionChecker urdf_checker(urdf_robot_, urdf_model_);
  ASSERT_EQ(urdf_checker.pairs().size(), yaml_checker.pairs().size());
  std::array<int, 4> counts{};
  int touches = 0;
  const std::vector<Eigen::VectorXd> qs = samples(5000);
  for (std::size_t s = 0; s < qs.size(); ++s) {
    const std::uint32_t label = yaml_checker.label(qs[s]);
    ASSERT_LT(label, counts.size());
    ++counts[label];
    if (urdf_checker.label(qs[s]) == label) continue;
    ++touches;
    const std::vector<PairReport> yaml_report = yaml_checker.report(qs[s]);
    const std::vector<PairReport> urdf_report = urdf_checker.report(qs[s]);
    bool touching = false;
    for (const PairReport& pair : yaml_report) {
      touching =
          touching || (std::abs(pair.distance) <= kTouchMm &&
                       pairDistance(urdf_report, pair.body_a, pair.body_b) * kMmPerM <= kTouchMm);
    }
    EXPECT_TRUE(touching) << "sample " << s << ", q = " << qs[s].transpose();
  }
  EXPECT_LE(touches, 5) << "more exact touches than the j1-j3 contact gives";
  for (std::uint32_t label = 0; label < counts.size(); ++label) {
    EXPECT_GT(counts[label], 0) << labelName(label);
  }
}

TEST_F(Inspection6Urdf, LoadsAsARobotAndReadsTheSameChainAsBefore) {
  // The floor and the cabinet are extra leaves fixed to the base; the chain still ends at the
  // flange, and its flange pose is the YAML's (in m).
  ASSERT_EQ(urdf_robot_.dof(), 6);
  Eigen::VectorXd q(6);
  q << M_PI / 3, M_PI / 6, M_PI / 2, M_PI / 4, M_PI / 3, M_PI / 6;
  EXPECT_LT((flangePose(urdf_robot_, q).translation() * kMmPerM -
             flangePose(yaml_robot_, q).translation())
                .norm(),
            1e-9);
}

TEST(CollisionUrdf, YamlRobotsStillNeedTheirCollisionKey) {
  const Robot robot = loadRobot(test::robotPath("insulator_cleaner"));
  try {
    loadRequiredCollisionModel(robot, test::robotPath("insulator_cleaner"));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("has no collision geometry (collision: key)"));
  }
}

// ---- A tiny URDF whose shapes and poses are worked out by hand -------------------------------

/// base -j1 (revolute z, at z = 1 turned 90 deg about z)- l1 -j2 (revolute y, x = 1)- l2
/// -fixed (z = 0.3, roll 90 deg)- flange -fixed (z = 0.2)- tool0; off the chain: l1_cover fixed
/// to l1, sensor fixed to l2, post fixed to the base. `extra` is appended inside <robot>.
std::string tinyUrdf(const std::string& extra = "") {
  return R"(<?xml version="1.0"?>
<robot name="tiny">
  <link name="base">
    <collision><origin xyz="0 0 -0.5"/><geometry><box size="0.4 0.3 0.2"/></geometry></collision>
  </link>
  <link name="l1">
    <collision><origin xyz="0.5 0 0" rpy="0 1.5707963267948966 0"/>
      <geometry><cylinder radius="0.1" length="1"/></geometry></collision>
    <collision><origin xyz="1 0 0"/><geometry><sphere radius="0.2"/></geometry></collision>
  </link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <origin xyz="0 0 1" rpy="0 0 1.5707963267948966"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <link name="l1_cover">
    <collision><origin xyz="0 0.1 0"/><geometry><sphere radius="0.05"/></geometry></collision>
  </link>
  <joint name="cover" type="fixed"><parent link="l1"/><child link="l1_cover"/>
    <origin xyz="0.2 0 0"/></joint>
  <link name="l2">
    <collision><origin xyz="0 0.25 0" rpy="-1.5707963267948966 0 0"/>
      <geometry><cylinder radius="0.04" length="0.5"/></geometry></collision>
    <collision><origin xyz="0 0.5 0"/><geometry><sphere radius="0.04"/></geometry></collision>
    <collision><origin xyz="0 0 0"/><geometry><sphere radius="0.04"/></geometry></collision>
  </link>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/>
    <origin xyz="1 0 0"/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
  <link name="sensor">
    <collision><geometry><cylinder radius="0.02" length="0.06"/></geometry></collision>
  </link>
  <joint name="sensor_mount" type="fixed"><parent link="l2"/><child link="sensor"/>
    <origin xyz="0.1 0 0"/></joint>
  <link name="flange">
    <collision><origin xyz="0 0 0.1"/><geometry><box size="0.1 0.1 0.2"/></geometry></collision>
  </link>
  <joint name="flange_mount" type="fixed"><parent link="l2"/><child link="flange"/>
    <origin xyz="0 0 0.3" rpy="1.5707963267948966 0 0"/></joint>
  <link name="tool0">
    <collision><geometry><sphere radius="0.03"/></geometry></collision>
  </link>
  <joint name="tool_mount" type="fixed"><parent link="flange"/><child link="tool0"/>
    <origin xyz="0 0 0.2"/></joint>
  <link name="post">
    <collision><geometry><cylinder radius="0.05" length="1"/></geometry></collision>
  </link>
  <joint name="post_mount" type="fixed"><parent link="base"/><child link="post"/>
    <origin xyz="2 0 0"/></joint>
)" + extra +
         "</robot>\n";
}

CollisionModel parseTiny(const std::string& text, const std::string& source = "tiny.urdf",
                         const UrdfChainOptions& chain = test::kUr5ToTool0) {
  return parseCollisionUrdf(parseRobotUrdf(text, source, chain), text, source, chain);
}

/// The message of the mcws::Error that parseTiny() throws, or "" when it does not throw.
std::string tinyError(const std::string& text, const std::string& source = "tiny.urdf",
                      const UrdfChainOptions& chain = test::kUr5ToTool0) {
  try {
    parseTiny(text, source, chain);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

Eigen::Matrix3d rotation(double angle, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle, axis).toRotationMatrix();
}

void expectPose(const Eigen::Isometry3d& T, const Eigen::Vector3d& p, const Eigen::Matrix3d& R) {
  EXPECT_LT((T.translation() - p).norm(), kPoseTolerance) << T.translation().transpose();
  EXPECT_LT((T.linear() - R).norm(), kPoseTolerance) << T.linear();
}

TEST(CollisionUrdf, PlacesEachPrimitiveOnItsBodyByHand) {
  const CollisionModel model = parseTiny(tinyUrdf());
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  ASSERT_EQ(model.links.size(), 3u);

  // Base: the box 0.5 below the root link's origin.
  ASSERT_EQ(model.links[0].shapes.size(), 1u);
  const ShapeSpec& box = model.links[0].shapes[0];
  EXPECT_EQ(box.type, ShapeType::kBox);
  EXPECT_EQ(box.size, Eigen::Vector3d(0.4, 0.3, 0.2));
  expectPose(box.T_body_shape, {0, 0, -0.5}, I);
  EXPECT_EQ(box.source, "tiny.urdf: link 'base' <collision> 1");

  // Link 1 (the frame after j1's motion, not j1's parent frame): l1's cylinder along x turned by
  // pitch 90 deg, its sphere of another radius (so no capsule), and l1_cover's sphere at
  // (0.2, 0, 0) + (0, 0.1, 0).
  const std::vector<ShapeSpec>& l1 = model.links[1].shapes;
  ASSERT_EQ(l1.size(), 3u);
  EXPECT_EQ(model.links[1].name, "j1");
  EXPECT_EQ(l1[0].type, ShapeType::kCylinder);
  EXPECT_EQ(l1[0].radius, 0.1);
  EXPECT_EQ(l1[0].length, 1.0);
  expectPose(l1[0].T_body_shape, {0.5, 0, 0}, rotation(kHalfPi, Eigen::Vector3d::UnitY()));
  EXPECT_EQ(l1[1].type, ShapeType::kSphere);
  EXPECT_EQ(l1[1].radius, 0.2);
  EXPECT_LT((l1[1].p_from - Eigen::Vector3d(1, 0, 0)).norm(), kPoseTolerance);
  EXPECT_EQ(l1[2].type, ShapeType::kSphere);  // l1_cover's
  EXPECT_EQ(l1[2].radius, 0.05);
  EXPECT_LT((l1[2].p_from - Eigen::Vector3d(0.2, 0.1, 0)).norm(), kPoseTolerance);
  EXPECT_EQ(l1[2].p_from, l1[2].p_to);

  // Link 2: the cylinder along y closed by two spheres of its radius is one capsule from (0,0,0)
  // to (0,0.5,0); the sensor's cylinder 0.1 along x.
  const std::vector<ShapeSpec>& l2 = model.links[2].shapes;
  ASSERT_EQ(l2.size(), 2u);
  EXPECT_EQ(l2[0].type, ShapeType::kCapsule);
  EXPECT_EQ(l2[0].radius, 0.04);
  EXPECT_LT(l2[0].p_from.norm(), kPoseTolerance);
  EXPECT_LT((l2[0].p_to - Eigen::Vector3d(0, 0.5, 0)).norm(), kPoseTolerance);
  EXPECT_EQ(l2[1].type, ShapeType::kCylinder);
  EXPECT_EQ(l2[1].radius, 0.02);
  expectPose(l2[1].T_body_shape, {0.1, 0, 0}, I);

  // Tool, in the flange frame = the tip tool0, 0.2 along z of the flange link: the flange link's
  // box 0.1 along z of the flange link is 0.1 below the tip; tool0's sphere at the tip.
  ASSERT_EQ(model.tool.shapes.size(), 2u);
  const ShapeSpec& flange_box = model.tool.shapes[0];
  EXPECT_EQ(flange_box.type, ShapeType::kBox);
  expectPose(flange_box.T_body_shape, {0, 0, -0.1}, I);
  EXPECT_EQ(model.tool.shapes[1].type, ShapeType::kSphere);
  EXPECT_LT(model.tool.shapes[1].p_from.norm(), kPoseTolerance);

  // The post, fixed to the base off the chain, is an environment object in the world frame.
  ASSERT_EQ(model.environment.size(), 1u);
  EXPECT_EQ(model.environment[0].name, "post");
  ASSERT_EQ(model.environment[0].shapes.size(), 1u);
  expectPose(model.environment[0].shapes[0].T_body_shape, {2, 0, 0}, I);
}

TEST(CollisionUrdf, LinkFramesAreTheChainsWorldPosesWorkedByHand) {
  const Robot robot = parseRobotUrdf(tinyUrdf(), "tiny.urdf", test::kUr5ToTool0);
  const CollisionModel model = parseTiny(tinyUrdf());
  Eigen::VectorXd q(2);
  q << 0.3, -0.7;
  const ChainPoses poses = chainPoses(robot, q);
  // l1_cover's sphere: Tz(1) Rz(90 deg + 0.3) applied to (0.2, 0.1, 0).
  const Eigen::Vector3d cover =
      Eigen::Vector3d(0, 0, 1) +
      rotation(kHalfPi + 0.3, Eigen::Vector3d::UnitZ()) * Eigen::Vector3d(0.2, 0.1, 0);
  EXPECT_LT((poses.T_world_link[0] * model.links[1].shapes[2].p_from - cover).norm(),
            kPoseTolerance);
  // The sensor's centre: link 2 is link 1 moved 1 along x and turned by q2 about y.
  const Eigen::Vector3d sensor =
      Eigen::Vector3d(0, 0, 1) +
      rotation(kHalfPi + 0.3, Eigen::Vector3d::UnitZ()) *
          (Eigen::Vector3d(1, 0, 0) +
           rotation(-0.7, Eigen::Vector3d::UnitY()) * Eigen::Vector3d(0.1, 0, 0));
  EXPECT_LT(((poses.T_world_link[1] * model.links[2].shapes[1].T_body_shape).translation() - sensor)
                .norm(),
            kPoseTolerance);
  // The flange link's box centre: 0.3 along z of link 2, then 0.1 along z of the rolled flange
  // (roll 90 deg turns z into -y).
  const Eigen::Vector3d flange_box_in_l2 = Eigen::Vector3d(0, 0, 0.3) + Eigen::Vector3d(0, -0.1, 0);
  const Eigen::Vector3d expected = poses.T_world_link[1] * flange_box_in_l2;
  EXPECT_LT(
      ((poses.T_world_flange * model.tool.shapes[0].T_body_shape).translation() - expected).norm(),
      kPoseTolerance);
}

TEST(CollisionUrdf, MeshesRelativeToTheUrdfWithAPerAxisScale) {
  test::TempDir dir;
  test::writeFile(dir.file("cube.obj"),
                  "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                  "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n");
  const std::string mesh_here =
      R"(<collision><geometry><mesh filename="cube.obj" scale="0.5 1 2"/></geometry></collision>)";
  const std::string mesh_uri = R"(<collision><geometry><mesh filename="file://)" +
                               dir.file("cube.obj") + R"("/></geometry></collision>)";
  const std::string text =
      tinyUrdf("<link name='grip'>" + mesh_here + mesh_uri +
               "</link><joint name='grip_mount' type='fixed'><parent link='tool0'/>"
               "<child link='grip'/></joint>");
  const CollisionModel model = parseTiny(text, dir.file("tiny.urdf"));
  // Tool shapes by link name: the flange's box, grip's two meshes, tool0's sphere.
  ASSERT_EQ(model.tool.shapes.size(), 4u);
  for (int k : {1, 2}) {
    const ShapeSpec& mesh = model.tool.shapes[k];
    ASSERT_EQ(mesh.type, ShapeType::kMesh);
    EXPECT_EQ(mesh.mesh->triangles.size(), 12u);
    Eigen::Vector3d max = Eigen::Vector3d::Zero();
    for (const auto& v : mesh.mesh->vertices) max = max.cwiseMax(v);
    EXPECT_EQ(max, k == 1 ? Eigen::Vector3d(0.5, 1, 2) : Eigen::Vector3d(1, 1, 1));
  }
}

// ---- What is not supported: one line naming the file and the link ---------------------------

/// tinyUrdf() with `element` as a <collision> of a new link 'grip' fixed to the tip.
std::string withGrip(const std::string& element) {
  return tinyUrdf("<link name='grip'><collision><geometry>" + element +
                  "</geometry></collision></link><joint name='grip_mount' type='fixed'>"
                  "<parent link='tool0'/><child link='grip'/></joint>");
}

void expectOneLine(const std::string& message) {
  EXPECT_FALSE(message.empty());
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(CollisionUrdfBadInput, GeometryUrdfHasNoWordFor) {
  // urdfdom logs and skips an element it cannot read; here that is an error, not a lost shape.
  const std::string message = tinyError(withGrip("<capsule radius='0.1' length='0.2'/>"));
  EXPECT_EQ(message,
            "tiny.urdf: unsupported or malformed element: Unknown geometry type 'capsule'; Could "
            "not parse collision element for Link [grip]");
  expectOneLine(message);
  // The robot itself still loads (urdfdom skipped the element), as before.
  EXPECT_EQ(parseRobotUrdf(withGrip("<capsule radius='0.1' length='0.2'/>"), "tiny.urdf",
                           test::kUr5ToTool0)
                .dof(),
            2);
}

TEST(CollisionUrdfBadInput, MeshFormatsAndUrisThatAreNotRead) {
  // .dae is read since issue 33 item 4 (tests/collision/collada_mesh_test.cpp).
  std::string message = tinyError(withGrip("<mesh filename='meshes/grip.ply'/>"));
  EXPECT_EQ(message,
            "tiny.urdf: link 'grip' <collision> 1: mesh 'meshes/grip.ply': .ply meshes are not "
            "supported (STL, OBJ or COLLADA .dae)");
  expectOneLine(message);
  // package:// URIs are resolved (issue 33 item 3; tests/collision/package_uri_test.cpp): a
  // package found nowhere is named with the places looked.
  message = tinyError(withGrip("<mesh filename='package://mcws_no_such_package/grip.stl'/>"));
  EXPECT_THAT(message, HasSubstr("tiny.urdf: link 'grip' <collision> 1: mesh "
                                 "'package://mcws_no_such_package/grip.stl': package "
                                 "'mcws_no_such_package' not found; looked in --package-path "
                                 "(none); ROS_PACKAGE_PATH "));
  expectOneLine(message);
  EXPECT_THAT(tinyError(withGrip("<mesh filename='http://example.com/grip.stl'/>")),
              HasSubstr("link 'grip' <collision> 1: mesh 'http://example.com/grip.stl': URI "
                        "scheme not supported"));
}

TEST(CollisionUrdfBadInput, MissingMeshFile) {
  test::TempDir dir;
  const std::string message =
      tinyError(withGrip("<mesh filename='grip.stl'/>"), dir.file("tiny.urdf"));
  EXPECT_EQ(message, dir.file("tiny.urdf") + ": link 'grip' <collision> 1: mesh '" +
                         dir.file("grip.stl") + "': file does not exist");
  expectOneLine(message);
}

TEST(CollisionUrdfBadInput, SizesThatAreNotPositive) {
  EXPECT_EQ(tinyError(withGrip("<sphere radius='0'/>")),
            "tiny.urdf: link 'grip' <collision> 1: sphere radius 0 must be a number > 0 (at most "
            "1e9)");
  EXPECT_EQ(tinyError(withGrip("<box size='1 -2 1'/>")),
            "tiny.urdf: link 'grip' <collision> 1: box size y -2 must be a number > 0 (at most "
            "1e9)");
  EXPECT_EQ(tinyError(withGrip("<cylinder radius='0.1' length='2e9'/>")),
            "tiny.urdf: link 'grip' <collision> 1: cylinder length 2e+09 must be a number > 0 "
            "(at most 1e9)");
}

TEST(CollisionUrdfBadInput, CollisionOnALinkTheChainDoesNotCarry) {
  // A finger moved by a joint outside the chain was refused before issue 33 ("it moves with joint
  // 'finger_joint', which is not in the chain"); it is now tool geometry at the joint's default
  // value, its lower limit 0 (tests/collision/urdf_branches_test.cpp).
  const std::string finger = tinyUrdf(
      "<link name='finger'><collision><geometry><sphere radius='0.01'/></geometry></collision>"
      "</link><joint name='finger_joint' type='prismatic'><parent link='tool0'/>"
      "<child link='finger'/><axis xyz='1 0 0'/>"
      "<limit lower='0' upper='0.02' effort='1' velocity='1'/></joint>");
  EXPECT_NO_THROW(parseTiny(finger));
  std::string message;
  // The base above a chain that starts at l1.
  message = tinyError(tinyUrdf(), "tiny.urdf", {"l1", "tool0"});
  EXPECT_EQ(message,
            "tiny.urdf: link 'base' has <collision> elements but is not part of the chain: it is "
            "not below base link 'l1' of the chain from link 'l1' to link 'tool0'");
}

TEST(CollisionUrdfBadInput, RobotOfAnotherChainAndEnvironmentNameClash) {
  const std::string text = tinyUrdf();
  const Robot other = parseRobotUrdf(text, "tiny.urdf", {"l1", "tool0"});
  try {
    parseCollisionUrdf(other, text, "tiny.urdf", test::kUr5ToTool0);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "tiny.urdf: the URDF chain's joints (j1, j2) are not those of robot 'tiny' (j2)");
  }
  const std::string clash = tinyUrdf(
      "<link name='tool'><collision><geometry><sphere radius='0.1'/></geometry></collision>"
      "</link><joint name='tool_stand' type='fixed'><parent link='base'/><child link='tool'/>"
      "</joint>");
  EXPECT_EQ(tinyError(clash),
            "tiny.urdf: link 'tool' is fixed to the base off the chain, so it is an environment "
            "object, but its name is already a body's (base, tool or a joint)");
}

TEST(CollisionUrdfBadInput, UrdfWithoutCollisionElements) {
  test::TempDir dir;
  std::string text = tinyUrdf();
  for (std::size_t at; (at = text.find("<collision>")) != std::string::npos;) {
    text.erase(at, text.find("</collision>", at) + 12 - at);
  }
  test::writeFile(dir.file("bare.urdf"), text);
  const Robot robot = loadRobotUrdf(dir.file("bare.urdf"), test::kUr5ToTool0);
  EXPECT_FALSE(hasGeometry(loadCollisionUrdf(robot, dir.file("bare.urdf"), test::kUr5ToTool0)));
  // Through the robot file loader, as the tools load it.
  test::writeFile(dir.file("single.urdf"),
                  "<robot name='bare'><link name='a'/><link name='b'/><joint name='j' "
                  "type='continuous'><parent link='a'/><child link='b'/><axis xyz='0 0 1'/>"
                  "</joint></robot>");
  try {
    loadRequiredCollisionModel(loadRobot(dir.file("single.urdf")), dir.file("single.urdf"));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              dir.file("single.urdf") +
                  ": has no collision geometry (no <collision> element on a link of its chain)");
  }
}

// loadCollisionModel() of a URDF reads the chain the robot was read as (Robot::base_link and
// tip_link, the tools' --base and --tip): tool0's sphere is the tool when tool0 is the tip, a
// shape of the last link when ee_link is; before, the file's default chain was read, which a tree
// with two leaves does not have.
TEST(CollisionUrdf, TheModelFollowsTheChainTheRobotWasReadAs) {
  const test::TempDir dir;
  const std::string path = dir.file("ur5.urdf");
  test::writeFile(path, test::kUr5ShapedUrdf);
  const Robot tool0 = loadRobot(path, {"", "tool0"});
  const CollisionModel at_tool0 = loadCollisionModel(tool0, path);
  ASSERT_EQ(at_tool0.tool.shapes.size(), 1u);
  EXPECT_EQ(at_tool0.tool.shapes[0].radius, 0.02);
  EXPECT_LT(at_tool0.tool.shapes[0].p_from.norm(), kPoseTolerance);  // tool0 is the flange
  EXPECT_TRUE(at_tool0.links[6].shapes.empty());

  const Robot ee = loadRobot(path, {"", "ee_link"});
  const CollisionModel at_ee = loadCollisionModel(ee, path);
  EXPECT_TRUE(at_ee.tool.shapes.empty());
  ASSERT_EQ(at_ee.links[6].shapes.size(), 1u);  // wrist_3_joint's link carries tool0
  EXPECT_LT((at_ee.links[6].shapes[0].p_from - Eigen::Vector3d(0, 0, 0.0823)).norm(),
            kPoseTolerance);
  // The base sphere is on the base body either way (a sphere is placed by its centre, p_from), 0.5
  // m above the chain's base link, world.
  ASSERT_EQ(at_ee.links[0].shapes.size(), 1u);
  EXPECT_LT((at_ee.links[0].shapes[0].p_from - Eigen::Vector3d(0, 0, 0.5)).norm(), kPoseTolerance);
}

}  // namespace
}  // namespace mcws
