// The collision: section of robot files: shapes, frames, meshes (STL and OBJ), and every bad input
// of the issue with its one-line message naming the item.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mcws/collision/collision_model.h"
#include "mcws/core/error.h"
#include "mcws/kinematics/robot_yaml.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

/// Two revolute joints in metres and degrees; `collision` is appended as the collision: section.
std::string robotText(const std::string& collision) {
  return "name: two\nunits: {length: m, angle: deg}\nconvention: standard\njoints:\n"
         "  - {name: j1, type: revolute, a: 1, alpha: 0, d: 0, limits: [-90, 90]}\n"
         "  - {name: j2, type: revolute, a: 1, alpha: 0, d: 0, limits: [-90, 90]}\n" +
         collision;
}

CollisionModel parse(const std::string& collision, const std::string& source = "two.yaml") {
  const std::string text = robotText(collision);
  return parseCollisionYaml(parseRobotYaml(text, source), text, source);
}

/// The message of the mcws::Error that parse() throws, or "" when it does not throw.
std::string parseError(const std::string& collision, const std::string& source = "two.yaml") {
  try {
    parse(collision, source);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

const char* kCube = R"(v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
)";

TEST(CollisionModel, RobotParserAcceptsTheCollisionSection) {
  EXPECT_NO_THROW(parseRobotYaml(robotText("collision: {}\n"), "two.yaml"));
}

TEST(CollisionModel, NoSectionGivesBodiesWithoutShapes) {
  const CollisionModel model = parse("");
  ASSERT_EQ(model.links.size(), 3u);
  EXPECT_EQ(model.links[0].name, "base");
  EXPECT_EQ(model.links[2].name, "j2");
  EXPECT_EQ(model.tool.name, "tool");
  EXPECT_FALSE(hasGeometry(model));
}

TEST(CollisionModel, ReadsEveryPrimitiveWithItsPlacement) {
  const CollisionModel model = parse(
      "collision:\n"
      "  links:\n"
      "    j1: [{type: capsule, from: [0, 0, 0], to: [1, 0, 0], radius: 0.1}]\n"
      "    j2:\n"
      "      - {type: box, size: [0.2, 0.3, 0.4], xyz: [0.5, 0, 0], rpy: [0, 0, 90]}\n"
      "      - {type: cylinder, radius: 0.05, length: 0.6, xyz: [1, 0, 0]}\n"
      "  tool: [{type: sphere, center: [0, 0, 0.1], radius: 0.02}]\n"
      "  environment:\n"
      "    - {name: wall, type: box, size: [0.1, 2, 2], xyz: [3, 0, 0]}\n"
      "  allowed: [[j1, wall]]\n");
  ASSERT_EQ(model.links[1].shapes.size(), 1u);
  const ShapeSpec& capsule = model.links[1].shapes[0];
  EXPECT_EQ(capsule.type, ShapeType::kCapsule);
  EXPECT_EQ(capsule.p_to, Eigen::Vector3d(1, 0, 0));
  EXPECT_DOUBLE_EQ(capsule.radius, 0.1);
  EXPECT_EQ(capsule.source, "two.yaml:9");
  const ShapeSpec& box = model.links[2].shapes[0];
  EXPECT_EQ(box.type, ShapeType::kBox);
  EXPECT_EQ(box.size, Eigen::Vector3d(0.2, 0.3, 0.4));
  // rpy in degrees: 90 about z turns x onto y.
  EXPECT_TRUE(
      (box.T_body_shape.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_EQ(model.links[2].shapes[1].type, ShapeType::kCylinder);
  EXPECT_DOUBLE_EQ(model.links[2].shapes[1].length, 0.6);
  EXPECT_EQ(model.tool.shapes[0].type, ShapeType::kSphere);
  EXPECT_EQ(model.tool.shapes[0].p_from, Eigen::Vector3d(0, 0, 0.1));
  ASSERT_EQ(model.environment.size(), 1u);
  EXPECT_EQ(model.environment[0].name, "wall");
  ASSERT_EQ(model.allowed.size(), 1u);
  EXPECT_EQ(model.allowed[0].second, "wall");
}

TEST(CollisionModel, LoadsObjMeshesRelativeToTheRobotFileAndFansQuads) {
  test::TempDir dir;
  test::writeFile(dir.file("cube.obj"), kCube);
  const CollisionModel model = parse(
      "collision:\n  tool: [{type: mesh, file: cube.obj, scale: 2}]\n", dir.file("robot.yaml"));
  const TriangleMesh& mesh = *model.tool.shapes[0].mesh;
  EXPECT_EQ(mesh.triangles.size(), 12u);  // six quads, two triangles each
  Eigen::Vector3d max = Eigen::Vector3d::Zero();
  for (const auto& v : mesh.vertices) max = max.cwiseMax(v);
  EXPECT_EQ(max, Eigen::Vector3d(2, 2, 2));  // scaled
}

TEST(CollisionModel, LoadsTheCommittedStlMeshes) {
  const Robot robot = loadRobot(test::robotPath("ta1400_mesh"));
  const CollisionModel model = loadCollisionModel(robot, test::robotPath("ta1400_mesh"));
  // scripts/make_capsule_mesh.py 90 560 48 12 6: 48 * 2 * (12 + 6 + 12) - 2 * 48 triangles.
  EXPECT_EQ(model.links[2].shapes[0].mesh->triangles.size(), 2784u);
}

TEST(CollisionModelBadInput, MissingMeshFile) {
  EXPECT_THAT(parseError("collision:\n  tool: [{type: mesh, file: /nonexistent/torch.stl}]\n"),
              HasSubstr("two.yaml:8: collision: tool shape 1: mesh '/nonexistent/torch.stl': "
                        "file does not exist"));
}

TEST(CollisionModelBadInput, MeshWithNoTriangles) {
  test::TempDir dir;
  test::writeFile(dir.file("empty.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  test::writeFile(dir.file("empty.stl"), "solid empty\nendsolid empty\n");
  for (const char* name : {"empty.obj", "empty.stl"}) {
    const std::string message = parseError(
        "collision:\n  links:\n    j1: [{type: mesh, file: " + std::string(name) + "}]\n",
        dir.file("robot.yaml"));
    EXPECT_THAT(message, HasSubstr("collision: link 'j1' shape 1: mesh '"));
    EXPECT_THAT(message, HasSubstr(std::string(name) + "': holds no triangles"));
  }
}

TEST(CollisionModelBadInput, NegativeRadiusOrSize) {
  EXPECT_THAT(parseError("collision:\n  links:\n    j2: [{type: capsule, from: [0, 0, 0], "
                         "to: [1, 0, 0], radius: -0.1}]\n"),
              HasSubstr("two.yaml:9: collision: link 'j2' shape 1: radius -0.1 must be > 0"));
  EXPECT_THAT(parseError("collision:\n  tool: [{type: box, size: [0.1, -0.2, 0.1]}]\n"),
              HasSubstr("collision: tool shape 1: size -0.2 must be > 0"));
  EXPECT_THAT(parseError("collision:\n  tool: [{type: cylinder, radius: 0.1, length: 0}]\n"),
              HasSubstr("collision: tool shape 1: length 0 must be > 0"));
}

TEST(CollisionModelBadInput, UnknownBodyInTheAllowedList) {
  EXPECT_THAT(parseError("collision:\n  allowed: [[j1, j7]]\n"),
              HasSubstr("two.yaml:8: collision: allowed: unknown body 'j7'"));
}

TEST(CollisionModelBadInput, GeometryOnALinkThatDoesNotExist) {
  EXPECT_THAT(parseError("collision:\n  links:\n    elbow: [{type: sphere, radius: 1}]\n"),
              HasSubstr("two.yaml:9: collision: links: 'elbow' is not a link of robot 'two' "
                        "(links: base, j1, j2)"));
}

TEST(CollisionModelBadInput, UnknownShapeTypeOrKey) {
  EXPECT_THAT(parseError("collision:\n  tool: [{type: cone, radius: 1}]\n"),
              HasSubstr("type 'cone' is not capsule, sphere, box, cylinder or mesh"));
  EXPECT_THAT(parseError("collision:\n  tool: [{type: sphere, radius: 1, colour: red}]\n"),
              HasSubstr("collision: tool shape 1: unknown key 'colour'"));
  EXPECT_THAT(parseError("collision:\n  walls: []\n"), HasSubstr("unknown key 'walls'"));
}

TEST(CollisionModelBadInput, ControlCharactersInAnEnvironmentObjectName) {
  EXPECT_EQ(parseError("collision:\n  environment:\n    - {name: \"wall\\e[2J\", type: sphere, "
                       "radius: 1}\n"),
            "two.yaml:9: collision: environment object 1: name 'wall\\x1b[2J' holds a control "
            "byte (names are printable text)");
}

}  // namespace
}  // namespace mcws
