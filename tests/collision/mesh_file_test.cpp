// Mesh files (binary and ASCII STL, OBJ) as collision meshes: the same triangles from each
// format, and every bad file refused with one line naming the file, the vertex and the value,
// with nothing printed by a library (issue 31: NaN, Inf and 1e38 vertices were accepted and the
// link then never collided; a malformed STL printed 14 coloured VTK lines).
#include "mcws/collision/mesh_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>

#include "mcws/collision/collision_model.h"
#include "mcws/core/error.h"
#include "mcws/core/input_files.h"
#include "mcws/kinematics/robot_yaml.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

/// A tetrahedron: the origin and the unit points on the axes; its four faces, outward.
const Eigen::Vector3d kCorners[4] = {
    {0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {0, 0, 3}};  // y and z stretched, to tell the axes apart
const int kFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

/// A binary STL of triangles given by their corners (normals left 0).
std::string binaryStl(const std::vector<std::array<std::array<float, 3>, 3>>& triangles,
                      const std::string& header = "mcws test") {
  std::string bytes = header;
  bytes.resize(80, ' ');
  const auto put32 = [&](std::uint32_t value) {
    for (int k = 0; k < 4; ++k) bytes += char((value >> (8 * k)) & 0xff);
  };
  put32(std::uint32_t(triangles.size()));
  for (const auto& triangle : triangles) {
    for (int k = 0; k < 3; ++k) put32(0);  // normal
    for (const auto& corner : triangle) {
      for (float value : corner) {
        std::uint32_t bits;
        std::memcpy(&bits, &value, sizeof bits);
        put32(bits);
      }
    }
    bytes += std::string(2, '\0');  // attribute
  }
  return bytes;
}

std::vector<std::array<std::array<float, 3>, 3>> tetrahedronTriangles() {
  std::vector<std::array<std::array<float, 3>, 3>> out;
  for (const auto& face : kFaces) {
    std::array<std::array<float, 3>, 3> triangle;
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 3; ++k) triangle[c][k] = float(kCorners[face[c]][k]);
    }
    out.push_back(triangle);
  }
  return out;
}

/// The tetrahedron as an ASCII STL; `corner` replaces the text of triangle 3 corner 2 when given.
std::string asciiStl(const std::string& corner = "") {
  std::string text = "solid tetra\n";
  for (int t = 0; t < 4; ++t) {
    text += "  facet normal 0 0 0\n    outer loop\n";
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d& p = kCorners[kFaces[t][c]];
      text += "      vertex ";
      if (t == 2 && c == 1 && !corner.empty()) {
        text += corner + "\n";
      } else {
        text += std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) +
                "\n";
      }
    }
    text += "    endloop\n  endfacet\n";
  }
  return text + "endsolid tetra\n";
}

/// The tetrahedron as an OBJ; `vertex3` replaces the numbers of vertex 3 when given. Faces use
/// every corner form (i, i/t, i//n, i/t/n, negative).
std::string obj(const std::string& vertex3 = "") {
  return "# tetrahedron\no tetra\nv 0 0 0\nv 1 0 0\nv " + (vertex3.empty() ? "0 2 0" : vertex3) +
         "\nv 0 0 3\nvt 0 0\nvn 0 0 1\n"
         "f 1 3 2\nf 1/1 2/1 4/1\nf 1//1 4//1 3//1\nf -3/1/1 -2 -1\n";
}

/// Checks that `mesh` is the tetrahedron: four vertices at kCorners (in any order) and four
/// triangles whose corners are those of kFaces.
void expectTetrahedron(const TriangleMesh& mesh) {
  ASSERT_EQ(mesh.vertices.size(), 4u);
  ASSERT_EQ(mesh.triangles.size(), 4u);
  for (int t = 0; t < 4; ++t) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(mesh.vertices[mesh.triangles[t][c]], kCorners[kFaces[t][c]])
          << "triangle " << t << " corner " << c;
    }
  }
}

/// The message of the mcws::Error that loadMesh(path) throws ("" and a failure when none).
std::string meshError(const std::string& path, double scale = 1.0) {
  try {
    loadMesh(path, scale);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for " << path;
  return "";
}

TEST(MeshFile, ReadsTheSameTetrahedronFromBinaryStlAsciiStlAndObj) {
  test::TempDir dir;
  test::writeFile(dir.file("b.stl"), binaryStl(tetrahedronTriangles()));
  test::writeFile(dir.file("a.STL"), asciiStl());
  test::writeFile(dir.file("t.obj"), obj());
  for (const char* name : {"b.stl", "a.STL", "t.obj"}) {
    SCOPED_TRACE(name);
    expectTetrahedron(loadMesh(dir.file(name), 1.0));
  }
}

TEST(MeshFile, ReadsABinaryStlWhoseHeaderStartsWithSolid) {
  // Many exporters write "solid" into a binary header; the size decides.
  test::TempDir dir;
  test::writeFile(dir.file("b.stl"), binaryStl(tetrahedronTriangles(), "solid exported"));
  expectTetrahedron(loadMesh(dir.file("b.stl"), 1.0));
}

TEST(MeshFile, ScalesAndFansPolygons) {
  test::TempDir dir;
  test::writeFile(dir.file("quad.obj"), "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  const TriangleMesh mesh = loadMesh(dir.file("quad.obj"), 1000.0);
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.triangles[0], (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(mesh.triangles[1], (std::array<int, 3>{0, 2, 3}));
  EXPECT_EQ(mesh.vertices[2], Eigen::Vector3d(1000, 1000, 0));
}

TEST(MeshFile, RefusesNonFiniteVerticesInEveryFormatNamingFileVertexAndValue) {
  test::TempDir dir;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const std::string stl = dir.file("bad.stl"), obj_path = dir.file("bad.obj");
  for (int axis = 0; axis < 3; ++axis) {
    const std::string name(1, "xyz"[axis]);
    for (const auto& [bad, text] : {std::pair{nan, "nan"}, {inf, "inf"}, {-inf, "-inf"}}) {
      SCOPED_TRACE(name + " " + text);
      // Binary STL: triangle 2, corner 3.
      auto triangles = tetrahedronTriangles();
      triangles[1][2][axis] = bad;
      test::writeFile(stl, binaryStl(triangles));
      EXPECT_EQ(meshError(stl), "'" + stl + "': triangle 2 corner 3: " + name + " coordinate " +
                                    text + " is not a finite number");
      // ASCII STL: triangle 3, corner 2, on line 1 + 7 * 2 + 4 = 19 (7 lines a triangle).
      std::string numbers[3] = {"0", "0", "3"};
      numbers[axis] = text;
      test::writeFile(stl, asciiStl(numbers[0] + " " + numbers[1] + " " + numbers[2]));
      EXPECT_EQ(meshError(stl), "'" + stl + "': line 19: triangle 3 corner 2: " + name +
                                    " coordinate " + text + " is not a finite number");
      // OBJ: vertex 3 on line 5, written as C's printf would ("NaN" and "Infinity" too).
      numbers[axis] = axis == 1 ? (bad > 0 ? "Infinity" : bad < 0 ? "-Infinity" : "NaN") : text;
      test::writeFile(obj_path, obj(numbers[0] + " " + numbers[1] + " " + numbers[2]));
      EXPECT_EQ(meshError(obj_path), "'" + obj_path + "': line 5: vertex 3: " + name +
                                         " coordinate " + numbers[axis] +
                                         " is not a finite number");
    }
  }
}

TEST(MeshFile, RefusesCoordinatesLargerThan1e9AsWrittenOrScaled) {
  test::TempDir dir;
  const std::string stl = dir.file("big.stl"), obj_path = dir.file("big.obj");
  auto triangles = tetrahedronTriangles();
  triangles[0][1][2] = 1e38f;  // the issue's mesh
  test::writeFile(stl, binaryStl(triangles));
  EXPECT_EQ(meshError(stl), "'" + stl +
                                "': triangle 1 corner 2: z coordinate 9.99999968e+37 is out of "
                                "range (at most 1e9 in size)");  // 1e38 as a float
  test::writeFile(stl, asciiStl("0 -1e400 3"));                  // too large for a double
  EXPECT_EQ(meshError(stl), "'" + stl +
                                "': line 19: triangle 3 corner 2: y coordinate -1e400 is out of "
                                "range (at most 1e9 in size)");
  test::writeFile(obj_path, obj("1000000000.5 0 0"));
  EXPECT_EQ(meshError(obj_path), "'" + obj_path +
                                     "': line 5: vertex 3: x coordinate 1000000000.5 is out of "
                                     "range (at most 1e9 in size)");
  // 1e9 itself is accepted, and refused once scaled past it.
  test::writeFile(obj_path, obj("1e9 2 -1e9"));
  EXPECT_EQ(loadMesh(obj_path, 1.0).vertices[2], Eigen::Vector3d(1e9, 2, -1e9));
  EXPECT_EQ(meshError(obj_path, 1.5), "'" + obj_path +
                                          "': coordinate 1e+09 times scale 1.5 is out of "
                                          "range (at most 1e9 in size)");
}

TEST(MeshFile, RefusesAMeshWithABadVertexInARobotFileAndInAUrdf) {
  test::TempDir dir;
  test::writeFile(dir.file("nan.obj"), obj("0 nan 0"));
  const std::string yaml =
      "name: two\nunits: {length: m, angle: deg}\nconvention: standard\njoints:\n"
      "  - {name: j1, type: revolute, a: 1, alpha: 0, d: 0, limits: [-90, 90]}\n"
      "collision:\n  links:\n    j1: [{type: mesh, file: nan.obj}]\n";
  const std::string path = dir.file("two.yaml");
  try {
    parseCollisionYaml(parseRobotYaml(yaml, path), yaml, path);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), path + ":8: collision: link 'j1' shape 1: mesh '" +
                                         dir.file("nan.obj") +
                                         "': line 5: vertex 3: y coordinate nan is not a finite "
                                         "number");
  }
  // A URDF mesh is scaled by <mesh scale>: 6e8 m is 1.2e9 m at scale 2.
  test::writeFile(dir.file("far.obj"), obj("0 6e8 0"));
  const std::string urdf = R"(<robot name="one"><link name="base"/>
<link name="l1"><collision><geometry><mesh filename="far.obj" scale="1 2 1"/></geometry>
</collision></link>
<joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>)";
  const std::string urdf_path = dir.file("one.urdf");
  test::writeFile(urdf_path, urdf);
  try {
    loadCollisionUrdf(loadRobot(urdf_path), urdf_path);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), urdf_path + ": link 'l1' <collision> 1: mesh '" +
                                         dir.file("far.obj") +
                                         "': coordinate 600000000 times scale 2 is out of range "
                                         "(at most 1e9 in size)");
  }
}

TEST(MeshFile, MalformedFilesGetOneLineAndNothingOnStderr) {
  test::TempDir dir;
  const std::string stl = dir.file("m.stl"), obj_path = dir.file("m.obj");
  const std::string good = binaryStl(tetrahedronTriangles());
  struct Case {
    std::string path, bytes, message;
  };
  const std::vector<Case> cases = {
      {stl, good.substr(0, good.size() - 7),
       "not an STL file: not starting with 'solid' (ASCII STL), and its size (277 bytes) is not "
       "that of a binary STL of the 4 triangles its header counts (284 bytes)"},
      {stl, "solid" + good.substr(5, 200),
       "not an STL file: starting with 'solid' (ASCII STL) but holding a NUL byte, and its size "
       "(205 bytes) is not that of a binary STL of the 4 triangles its header counts (284 bytes)"},
      {stl, "12 bytes of x",
       "not an STL file: 13 bytes, too short for a binary STL (84-byte header), and not starting "
       "with 'solid' (ASCII STL)"},
      {stl, std::string("solid\0", 6),
       "not an STL file: 6 bytes, too short for a binary STL (84-byte header), and starting with "
       "'solid' (ASCII STL) but holding a NUL byte"},
      {stl, "",
       "not an STL file: 0 bytes, too short for a binary STL (84-byte header), and not starting "
       "with 'solid' (ASCII STL)"},
      {stl, asciiStl("0 0"), "line 20: triangle 3 corner 2: 'vertex' is not a number"},
      {stl, test::replaceOnce(asciiStl(), "outer loop", "outer lop"),
       "line 3: expected 'loop', found 'lop'"},
      {stl, asciiStl().substr(0, 100), "line 5: triangle 1 corner 2: the file ends"},
      {stl, asciiStl().substr(0, 88), "line 4: expected 'vertex', found the end of the file"},
      {stl, asciiStl() + "\x1b[31m",
       "line 31: expected 'solid' or the end of the file after 'endsolid', found '\\x1b[31m'"},
      {obj_path, obj("0 0"),
       "line 5: vertex 3: 'v' takes x y z (and an optional w, or r g b), not 2 values"},
      {obj_path, obj("0 0 zero"), "line 5: vertex 3: 'zero' is not a number"},
      {obj_path, obj() + "f 1 2 9\n",
       "line 13: a face refers to a missing vertex (number 9; the file has 4)"},
      {obj_path, obj() + "f -1 -2 -5\n",
       "line 13: a face refers to a missing vertex (before the first; the file has 4)"},
      {obj_path, obj() + "f 1 2\n", "line 13: a face needs at least 3 corners, this one has 2"},
      {obj_path, obj() + "f 1 x 3\n",
       "line 13: face corner 'x' does not start with a vertex number (1, 2, ... or -1, -2, ... "
       "from the last vertex)"},
      {obj_path, obj() + "vv 1 2 3\n",
       "line 13: unknown keyword 'vv' (v and f are read; vt, vn, vp, l, p, g, o, s, usemtl and "
       "mtllib skipped)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.message);
    test::writeFile(c.path, c.bytes);
    testing::internal::CaptureStderr();
    const std::string message = meshError(c.path);
    const std::string printed = testing::internal::GetCapturedStderr();
    EXPECT_EQ(message, "'" + c.path + "': " + c.message);
    EXPECT_EQ(printed, "");
  }
}

TEST(MeshFile, RefusesAFifoAndNotesTheMeshAsAnInputOfTheRun) {
  test::TempDir dir;
  const std::string fifo = dir.file("pipe.stl");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(meshError(fifo), fifo + ": collision mesh is not a regular file (a FIFO)");

  // Noted while a run (RunInputs) lives, forgotten when it ends.
  const std::string path = std::string(MCWS_ROBOTS_DIR) + "/meshes/ta1400/torch_body.stl";
  const RunInputs run;
  loadMesh(path, 1.0);
  struct stat status {};
  ASSERT_EQ(::stat(path.c_str(), &status), 0);
  const auto input = inputFileOf(status);
  ASSERT_TRUE(input.has_value());
  EXPECT_TRUE(std::filesystem::equivalent(input->first, path)) << input->first;
  EXPECT_EQ(input->second, "collision mesh");
}

}  // namespace
}  // namespace mcws
