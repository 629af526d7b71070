// package:// mesh URIs (issue 33, item 3), resolved as ROS does: the --package-path folders, then
// ROS_PACKAGE_PATH (package folders holding package.xml, at any depth), then a folder of the
// package's name in or above the URDF's folder; package://file relative to the URDF. A package not
// found is one line naming the URI and every place looked.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "mcws/collision/collision_model.h"
#include "mcws/collision/package_uri.h"
#include "mcws/core/error.h"
#include "mcws/kinematics/robot_urdf.h"
#include "test_support.h"

namespace mcws {
namespace {

namespace fs = std::filesystem;

/// A tetrahedron with corners 0, x, y, z [m], as an ASCII STL.
const std::string kTetraStl = R"(solid t
facet normal 0 0 0
outer loop
vertex 0 0 0
vertex 0 1 0
vertex 1 0 0
endloop
endfacet
facet normal 0 0 0
outer loop
vertex 0 0 0
vertex 1 0 0
vertex 0 0 1
endloop
endfacet
facet normal 0 0 0
outer loop
vertex 0 0 0
vertex 0 0 1
vertex 0 1 0
endloop
endfacet
facet normal 0 0 0
outer loop
vertex 1 0 0
vertex 0 1 0
vertex 0 0 1
endloop
endfacet
endsolid t
)";

/// An arm of one joint whose tool link carries `uri` as its mesh.
std::string armWithMesh(const std::string& uri) {
  return "<robot name='arm'><link name='base'/><link name='tool'><collision><geometry>"
         "<mesh filename='" +
         uri +
         "'/></geometry></collision></link><joint name='j1' type='revolute'>"
         "<parent link='base'/><child link='tool'/><axis xyz='0 0 1'/>"
         "<limit lower='-1' upper='1' effort='1' velocity='1'/></joint></robot>";
}

/// A workspace as ROS users have them: ws/src/my_robot/{package.xml, meshes/tetra.stl,
/// urdf/arm.urdf}, and an overlay package of the same name elsewhere.
class PackageTree : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* folder : {"ws/src/my_robot/meshes", "ws/src/my_robot/urdf",
                               "overlay/my_robot/meshes", "lone/urdf", "empty"}) {
      fs::create_directories(dir_.file(folder));
    }
    test::writeFile(dir_.file("ws/src/my_robot/package.xml"), "<package/>");
    test::writeFile(dir_.file("overlay/my_robot/package.xml"), "<package/>");
    test::writeFile(dir_.file("ws/src/my_robot/meshes/tetra.stl"), kTetraStl);
    test::writeFile(dir_.file("overlay/my_robot/meshes/tetra.stl"), kTetraStl);
    test::writeFile(dir_.file("lone/urdf/tetra.stl"), kTetraStl);
  }
  std::string urdf() const { return dir_.file("ws/src/my_robot/urdf/arm.urdf"); }
  std::string lone() const { return dir_.file("lone/urdf/arm.urdf"); }
  std::string resolve(const std::string& uri, const std::string& robot_file,
                      const PackageSearch& search = {}) const {
    return fs::path(resolvePackageUri(uri, robot_file, search)).lexically_normal().string();
  }
  test::TempDir dir_;
  const std::string uri_ = "package://my_robot/meshes/tetra.stl";
};

TEST_F(PackageTree, FoundThroughThePackagePathAtAnyDepth) {
  // ws holds the package two levels down (ws/src/my_robot), as a catkin workspace does.
  EXPECT_EQ(resolve(uri_, lone(), {{dir_.file("empty"), dir_.file("ws")}, ""}),
            dir_.file("ws/src/my_robot/meshes/tetra.stl"));
  // The package folder itself as an entry.
  EXPECT_EQ(resolve(uri_, lone(), {{dir_.file("overlay/my_robot")}, ""}),
            dir_.file("overlay/my_robot/meshes/tetra.stl"));
  // The package path comes before the upward search from the URDF (which finds ws/src/my_robot).
  EXPECT_EQ(resolve(uri_, urdf(), {{dir_.file("overlay")}, ""}),
            dir_.file("overlay/my_robot/meshes/tetra.stl"));
}

TEST_F(PackageTree, FoundThroughRosPackagePathAfterThePackagePath) {
  const std::string ros = "/nonexistent/mcws:" + dir_.file("overlay") + "::";
  EXPECT_EQ(resolve(uri_, lone(), {{}, ros}), dir_.file("overlay/my_robot/meshes/tetra.stl"));
  EXPECT_EQ(resolve(uri_, lone(), {{dir_.file("ws")}, ros}),
            dir_.file("ws/src/my_robot/meshes/tetra.stl"));
}

TEST_F(PackageTree, FoundUpwardFromTheUrdfAndRelativeWithoutAPackage) {
  EXPECT_EQ(resolve(uri_, urdf()), dir_.file("ws/src/my_robot/meshes/tetra.stl"));
  // package://file with no package folder: next to the URDF.
  EXPECT_EQ(resolve("package://tetra.stl", lone()), dir_.file("lone/urdf/tetra.stl"));
}

TEST_F(PackageTree, NotFoundNamesTheUriAndEveryPlaceLooked) {
  try {
    resolvePackageUri(uri_, lone(), {{dir_.file("empty")}, "/opt/ros/none"});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "mesh 'package://my_robot/meshes/tetra.stl': package 'my_robot' not found; looked "
              "in --package-path " +
                  dir_.file("empty") +
                  "; ROS_PACKAGE_PATH /opt/ros/none; and for a folder 'my_robot' in " +
                  dir_.file("lone/urdf") + " and each folder above it");
  }
  try {
    resolvePackageUri(uri_, lone(), {});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("--package-path (none); ROS_PACKAGE_PATH (unset)"));
  }
}

/// The collision model of the one-joint arm whose mesh is `uri`, read from `path`.
CollisionModel modelOf(const std::string& path, const std::string& uri,
                       const std::vector<std::string>& package_path = {}) {
  test::writeFile(path, armWithMesh(uri));
  Robot robot = loadRobotUrdf(path);
  robot.package_path = package_path;
  return loadCollisionModel(robot, path);
}

TEST_F(PackageTree, TheCollisionModelReadsThePackageMesh) {
  // Before issue 33 item 3: "package:// URIs are not resolved (that needs ROS)".
  const std::string path = dir_.file("lone/urdf/arm.urdf");
  ::unsetenv("ROS_PACKAGE_PATH");
  CollisionModel model = modelOf(path, uri_, {dir_.file("ws")});
  ASSERT_EQ(model.links[1].shapes.size(), 1u);
  ASSERT_TRUE(model.links[1].shapes[0].mesh);
  EXPECT_EQ(model.links[1].shapes[0].mesh->triangles.size(), 4u);
  // Through the ROS_PACKAGE_PATH variable.
  ::setenv("ROS_PACKAGE_PATH", dir_.file("overlay").c_str(), 1);
  model = modelOf(path, uri_);
  ::unsetenv("ROS_PACKAGE_PATH");
  ASSERT_EQ(model.links[1].shapes.size(), 1u);
  // Not found: one line, after the file and the link.
  try {
    modelOf(path, "package://nowhere/m.stl");
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_THAT(message, ::testing::StartsWith(path + ": link 'tool' <collision> 1: mesh "
                                                      "'package://nowhere/m.stl': package "
                                                      "'nowhere' not found; looked in"));
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
}

}  // namespace
}  // namespace mcws
