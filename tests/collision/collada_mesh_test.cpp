// COLLADA (.dae) collision meshes through mcws's reader (issue 33, item 4): the triangles of every
// node in metres (the file's <unit> applied), the vertices in the axes they are written in (the
// file's <up_axis> ignored, as RViz and MoveIt do), the URDF's scale on top, and each bad file one
// line naming it. The box files come from collada_box.h; every expected number is worked out from
// the box's corners.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "collision/collada_box.h"
#include "mcws/collision/collada_mesh.h"
#include "mcws/collision/collision_model.h"
#include "mcws/collision/mesh_file.h"
#include "mcws/core/error.h"
#include "mcws/kinematics/robot_urdf.h"
#include "test_support.h"

namespace mcws {
namespace {

/// A millimetre coordinate of a few hundred, times 0.001, is within 1e-7 m of the exact value
/// even when read as a float (as assimp, the reader these tests first checked, reads it; mcws's
/// reader reads doubles).
constexpr double kFloatM = 1e-7;
/// The volume of boxes of 1e-2 m^3 from such coordinates [m^3].
constexpr double kFloatM3 = 1e-9;

/// The smallest and largest coordinate of the vertices the triangles use.
std::pair<Eigen::Vector3d, Eigen::Vector3d> boundsOf(const TriangleMesh& mesh) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (const auto& triangle : mesh.triangles) {
    for (int corner : triangle) {
      lo = lo.cwiseMin(mesh.vertices[corner]);
      hi = hi.cwiseMax(mesh.vertices[corner]);
    }
  }
  return {lo, hi};
}

/// The volume a closed, outward-wound mesh encloses (divergence theorem: the sum of the signed
/// tetrahedra from the origin) [m^3].
double volumeOf(const TriangleMesh& mesh) {
  double six_volume = 0.0;
  for (const auto& t : mesh.triangles) {
    six_volume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
  }
  return six_volume / 6.0;
}

/// A box of 100 x 200 x 300 mm from (10, 20, 30) mm, in a file in millimetres.
test::ColladaBox millimetreBox() {
  test::ColladaBox box;
  box.lo = {10, 20, 30};
  box.hi = {110, 220, 330};
  box.unit_meter = "0.001";
  return box;
}

void expectBounds(const TriangleMesh& mesh, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const auto [low, high] = boundsOf(mesh);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(low[k], lo[k], kFloatM) << "axis " << k;
    EXPECT_NEAR(high[k], hi[k], kFloatM) << "axis " << k;
  }
}

TEST(ColladaMesh, MillimetreBoxIsReadInMetresInTheAxesItIsWrittenIn) {
  test::ColladaBox box = millimetreBox();
  for (const char* up : {"Z_UP", "Y_UP", "X_UP", ""}) {
    box.up_axis = up;
    const TriangleMesh mesh = parseColladaMesh(test::colladaBoxText(box), "box.dae");
    ASSERT_EQ(mesh.triangles.size(), 12u) << up;
    // The corners in metres, whatever <up_axis> says (assimp alone would turn a Z_UP file by
    // -90 degrees about x: y in [-0.33, -0.03], z in [0.02, 0.22]).
    expectBounds(mesh, {0.01, 0.02, 0.03}, {0.11, 0.22, 0.33});
    EXPECT_NEAR(volumeOf(mesh), 0.1 * 0.2 * 0.3, kFloatM3) << up;
  }
}

TEST(ColladaMesh, AFileWithoutUnitIsInMetres) {
  test::ColladaBox box;
  box.hi = {1, 2, 3};
  const TriangleMesh mesh = parseMesh(test::colladaBoxText(box), MeshFormat::kCollada, "b.dae");
  expectBounds(mesh, {0, 0, 0}, {1, 2, 3});
  EXPECT_NEAR(volumeOf(mesh), 6.0, 1e-12);
  // Inches: 0.0254 m each.
  box.unit_meter = "0.0254";
  expectBounds(parseColladaMesh(test::colladaBoxText(box), "b.dae"), {0, 0, 0},
               {0.0254, 0.0508, 0.0762});
}

TEST(ColladaMesh, QuadsAreTriangulated) {
  test::ColladaBox box = millimetreBox();
  box.quads = true;
  const TriangleMesh mesh = parseColladaMesh(test::colladaBoxText(box), "quads.dae");
  EXPECT_EQ(mesh.triangles.size(), 12u);
  expectBounds(mesh, {0.01, 0.02, 0.03}, {0.11, 0.22, 0.33});
  EXPECT_NEAR(volumeOf(mesh), 0.006, kFloatM3);
}

TEST(ColladaMesh, EachNodePlacesItsOwnInstance) {
  test::ColladaBox box = millimetreBox();
  // The box where it is, and once more 500 mm along x and turned 90 degrees about z
  // (COLLADA's <translate> then <rotate>: p -> T (R p)): (x, y) -> (500 - y, x).
  box.nodes = {"", "<translate>500 0 0</translate><rotate>0 0 1 90</rotate>"};
  const TriangleMesh mesh = parseColladaMesh(test::colladaBoxText(box), "two.dae");
  ASSERT_EQ(mesh.triangles.size(), 24u);
  EXPECT_NEAR(volumeOf(mesh), 2 * 0.006, kFloatM3);
  // The second box: x = 500 - y in [280, 480] mm, y = x in [10, 110] mm, z unchanged.
  TriangleMesh second = mesh;
  second.triangles.erase(second.triangles.begin(), second.triangles.begin() + 12);
  expectBounds(second, {0.28, 0.01, 0.03}, {0.48, 0.11, 0.33});
}

TEST(ColladaMesh, ReadThroughTheFileReaderAndAUrdfPackageUriWithScale) {
  test::TempDir dir;
  std::filesystem::create_directories(dir.file("ws/my_robot/meshes"));
  test::writeFile(dir.file("ws/my_robot/package.xml"), "<package/>");
  // An upper-case extension, as CAD exports write it.
  test::writeFile(dir.file("ws/my_robot/meshes/box.DAE"), test::colladaBoxText(millimetreBox()));
  expectBounds(readMeshFile(dir.file("ws/my_robot/meshes/box.DAE")), {0.01, 0.02, 0.03},
               {0.11, 0.22, 0.33});

  const std::string urdf = dir.file("arm.urdf");
  test::writeFile(urdf,
                  "<robot name='arm'><link name='base'/><link name='tool'><collision><geometry>"
                  "<mesh filename='package://my_robot/meshes/box.DAE' scale='2 3 0.5'/>"
                  "</geometry></collision></link><joint name='j1' type='revolute'>"
                  "<parent link='base'/><child link='tool'/><axis xyz='0 0 1'/>"
                  "<limit lower='-1' upper='1' effort='1' velocity='1'/></joint></robot>");
  Robot robot = loadRobotUrdf(urdf);
  robot.package_path = {dir.file("ws")};
  const CollisionModel model = loadCollisionModel(robot, urdf);
  ASSERT_EQ(model.links.size(), 2u);
  ASSERT_EQ(model.links[1].shapes.size(), 1u);
  const ShapeSpec& shape = model.links[1].shapes[0];
  ASSERT_EQ(shape.type, ShapeType::kMesh);
  ASSERT_TRUE(shape.mesh);
  // The URDF's scale times the file's corners in metres: x 2 * [0.01, 0.11], y 3 * [0.02, 0.22],
  // z 0.5 * [0.03, 0.33]; the volume 2 * 3 * 0.5 times 0.006 m^3.
  expectBounds(*shape.mesh, {0.02, 0.06, 0.015}, {0.22, 0.66, 0.165});
  EXPECT_NEAR(volumeOf(*shape.mesh), 3 * 0.006, 3 * kFloatM3);
}

/// The message of the error parseColladaMesh() throws for `text`, "" when none.
std::string colladaError(const std::string& text, const std::string& source = "bad.dae") {
  try {
    parseMesh(text, MeshFormat::kCollada, source);
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    return message;
  }
  return "";
}

TEST(ColladaMeshBadInput, NotANumberVertexNamesTheMeshAndVertex) {
  test::ColladaBox box = millimetreBox();
  box.first_x = "nan";
  EXPECT_EQ(colladaError(test::colladaBoxText(box)),
            "'bad.dae': mesh 'box' vertex 1: x coordinate nan is not a finite number");
  box.first_x = "inf";
  EXPECT_THAT(colladaError(test::colladaBoxText(box)),
              ::testing::EndsWith("x coordinate inf is not a finite number"));
  // Finite as written, out of range once placed: 10 mm times a node's scale of 1e13 is 1e11 m
  // (assimp, reading floats, said 9.99999983e+10).
  box.first_x = "10";
  box.nodes = {"<scale>1e13 1 1</scale>"};
  EXPECT_EQ(colladaError(test::colladaBoxText(box)),
            "'bad.dae': mesh 'box' vertex 1: x (placed, in metres) coordinate 1e+11 is out of "
            "range (at most 1e9 in size)");
  // As written: the text of the file in the message.
  box.first_x = "-2e9";
  box.nodes = {""};
  EXPECT_EQ(colladaError(test::colladaBoxText(box)),
            "'bad.dae': mesh 'box' vertex 1: x coordinate -2e9 is out of range (at most 1e9 in "
            "size)");
}

TEST(ColladaMeshBadInput, AMeshWithoutTrianglesIsEmpty) {
  test::ColladaBox box = millimetreBox();
  box.no_faces = true;
  EXPECT_EQ(colladaError(test::colladaBoxText(box)), "'bad.dae': holds no triangles");
  // No scene at all.
  std::string text = test::colladaBoxText(millimetreBox());
  text.erase(text.find("<library_visual_scenes>"),
             text.find("</COLLADA>") - text.find("<library_visual_scenes>"));
  EXPECT_EQ(colladaError(text), "'bad.dae': holds no triangles");
}

TEST(ColladaMeshBadInput, FilesThatAreNotColladaOrIndicesTheFileDoesNotHold) {
  EXPECT_EQ(colladaError("solid x\nendsolid x\n"),
            "'bad.dae': not a COLLADA file: malformed XML: Error document empty.");
  EXPECT_EQ(colladaError("<?xml version='1.0'?>\n<COLLADA><asset></COLLADA>"),
            "'bad.dae': not a COLLADA file: malformed XML at line 2: Error reading end tag.");
  EXPECT_EQ(colladaError("<?xml version='1.0'?><robot name='r'/>"),
            "'bad.dae': not a COLLADA file: its root element is <robot>, not <COLLADA>");
  std::string text = test::colladaBoxText(millimetreBox());
  text.replace(text.find("<p>0 2 1 "), 9, "<p>0 2 9 ");  // vertex 9 of 8
  EXPECT_EQ(colladaError(text),
            "'bad.dae': geometry 'box' <triangles> 1 <p> word 3: position index 9, but <accessor "
            "source='#box-array'> holds 8 positions (from 0)");
}

TEST(ColladaMeshBadInput, SizesTheFileDoesNotHoldAreRefusedBeforeAnythingIsAllocated) {
  // The mesh fuzzer's input: one byte of <p> turned to 0xA9 made assimp allocate 3 GB.
  test::ColladaBox box = millimetreBox();
  box.quads = true;
  const std::string quads = test::colladaBoxText(box);
  std::string text = quads;
  text.replace(text.find(" 6 7 0 1 "), 9,
               " 6\xA9"
               "7 0 1 ");
  EXPECT_EQ(colladaError(text),
            "'bad.dae': geometry 'box' <polylist> 1 <p> word 7 '6\xA9"
            "7' is not a whole number (an index)");
  text = quads;
  const std::string half = std::to_string(quads.size() / 2);  // each could be, six cannot
  text.replace(
      text.find("<vcount>4 4 4 4 4 4<"), 20,
      "<vcount>" + half + " " + half + " " + half + " " + half + " " + half + " " + half + "<");
  EXPECT_EQ(colladaError(text), "'bad.dae': geometry 'box' <polylist> 1 <vcount> number 1 '" +
                                    half +
                                    "': not a whole number of at most the 24 corners <p> "
                                    "has left");
  text = quads;
  text.replace(text.find("count=\"8\""), 9, "count=\"4000000000\"");
  EXPECT_EQ(colladaError(text),
            "'bad.dae': <accessor source='#box-array'>: count 4000000000 x stride 3 + offset 0 is "
            "more than the 24 numbers of <float_array id='box-array'>");
  text = quads;
  text.replace(text.find("stride=\"3\""), 10, "stride=\"300\"");
  EXPECT_EQ(colladaError(text),
            "'bad.dae': <accessor source='#box-array'>: count 8 x stride 300 + offset 0 is more "
            "than the 24 numbers of <float_array id='box-array'>");
  text = quads;
  text.replace(text.find("count=\"24\">") + 12, 1, "x");
  EXPECT_EQ(colladaError(text),
            "'bad.dae': <float_array id='box-array'> number 1 '1x.000000' is not a number");
}

TEST(ColladaMeshBadInput, AnAttributeColladaRequiresIsThere) {
  // The mesh fuzzer's input: <float_array counO="24"> crashed assimp (a null pointer).
  std::string text = test::colladaBoxText(millimetreBox());
  text.replace(text.find("count=\"24\""), 5, "counO");
  EXPECT_EQ(colladaError(text),
            "'bad.dae': <float_array id='box-array'> has no count attribute (COLLADA requires it)");
  text = test::colladaBoxText(millimetreBox());
  text.replace(text.find("semantic=\"VERTEX\""), 8, "semantiX");
  EXPECT_EQ(colladaError(text),
            "'bad.dae': <input source='#box-vertices'> has no semantic "
            "attribute (COLLADA requires it)");
}

TEST(ColladaMeshBadInput, AnAmpersandThatStartsNoEntityIsMalformedXml) {
  // The mesh fuzzer's input: "4&7" in <p> is 47 to TinyXML and 4 then garbage to assimp, which
  // allocated 2.4 GB.
  std::string text = test::colladaBoxText(millimetreBox());
  text.replace(text.find(" 3 4 7</p>"), 10, " 3 4&7</p>");
  const auto line = 1 + std::count(text.begin(), text.begin() + text.find("4&7"), '\n');
  EXPECT_EQ(colladaError(text), "'bad.dae': not a COLLADA file: malformed XML at line " +
                                    std::to_string(line) +
                                    ": a '&' that starts no entity (write &amp;)");
  // Entities, and a '&' in a comment or CDATA, are XML: the box reads as before.
  for (const char* fine : {"<!-- a & b -->", "<![CDATA[a & b]]>", "&amp;&#38;&#x26;&lt;"}) {
    text = test::colladaBoxText(millimetreBox());
    text.replace(text.find("<library_geometries>"), 0, std::string("<extra>") + fine + "</extra>");
    EXPECT_EQ(parseColladaMesh(text, "ok.dae").triangles.size(), 12u) << fine;
  }
}

/// The millimetre box's text with every `from` replaced by `to`.
std::string boxTextWith(const std::string& from, const std::string& to,
                        const test::ColladaBox& box = millimetreBox()) {
  std::string text = test::colladaBoxText(box);
  EXPECT_NE(text.find(from), std::string::npos) << from;
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at)) {
    text.replace(at, from.size(), to);
    at += to.size();
  }
  return text;
}

TEST(ColladaMeshBadInput, TheFourFuzzerFindsOfAssimpsDaysAreOneLine) {
  // count="00" with 24 numbers and a <param> without a name: assimp's SEGV.
  std::string text = boxTextWith("count=\"24\"", "count=\"00\"");
  text.replace(text.find("<param name=\"Y\""), 15, "<param naee=\"Y\"");
  EXPECT_EQ(colladaError(text),
            "'bad.dae': <float_array id='box-array'>: count='0' but it holds "
            "24 numbers");
  // The other three (a 0xA9 byte in <p>, counO, a stray '&') are the tests above; the files are
  // in fuzz/corpus/mesh/ too.
  text = boxTextWith("<param name=\"Y\"", "<param naee=\"Y\"");
  EXPECT_EQ(parseColladaMesh(text, "ok.dae").triangles.size(), 12u);  // an unnamed slot is fine
}

TEST(ColladaMeshBadInput, PositionsTheFileDoesNotHold) {
  const std::pair<std::string, std::string> cases[] = {
      {"stride=\"3\"", "stride=\"2\""},
      {"technique_common", "technique_uncommon"},
      {"source=\"#box-array\"", "source=\"#box-positions\""},
      {"vertices", "vertixes"},
      {"semantic=\"POSITION\"", "semantic=\"NORMAL\""},
      {"stride=\"3\"", "stride=\"3x\""}};
  const char* expected[] = {
      "'bad.dae': <accessor source='#box-array'>: stride 2 leaves no place for a position's 3 "
      "coordinates",
      "'bad.dae': <source id='box-positions'> has no <technique_common><accessor>",
      "'bad.dae': <accessor source='#box-positions'>: no float_array with id 'box-positions'",
      "'bad.dae': geometry 'box': its <mesh> has no <vertices>",
      "'bad.dae': <vertices id='box-vertices'> has no <input semantic='POSITION'>",
      "'bad.dae': <accessor source='#box-array'> stride='3x': not a whole number (of at most 18 "
      "digits)"};
  for (std::size_t k = 0; k < std::size(cases); ++k) {
    EXPECT_EQ(colladaError(boxTextWith(cases[k].first, cases[k].second)), expected[k]);
  }
}

TEST(ColladaMeshBadInput, PrimitivesThatDoNotMatchTheirCounts) {
  const std::string where = "'bad.dae': geometry 'box' <triangles> 1";
  EXPECT_EQ(colladaError(boxTextWith("<triangles count=\"12\"", "<triangles count=\"11\"")),
            where + ": count='11' but <p> holds 36 corners, not 33");
  // A second input at offset 1: corners of two indices each, 35 indices are not whole corners.
  EXPECT_EQ(colladaError(boxTextWith("offset=\"0\"/><p>0 2 1 ",
                                     "offset=\"0\"/><input semantic=\"NORMAL\" source=\"#n\" "
                                     "offset=\"1\"/><p>2 1 ")),
            where + " <p> holds 35 indices, not whole corners of 2 each");
  EXPECT_EQ(colladaError(boxTextWith("semantic=\"VERTEX\"", "semantic=\"NORMAL\"")),
            where + " has no <input semantic='VERTEX'>");
  EXPECT_EQ(colladaError(boxTextWith("semantic=\"VERTEX\" source=\"#box-vertices\"",
                                     "semantic=\"VERTEX\" source=\"#box-positions\"")),
            "'bad.dae': <input source='#box-positions'>: no vertices with id 'box-positions'");
  test::ColladaBox quads = millimetreBox();
  quads.quads = true;
  EXPECT_EQ(colladaError(boxTextWith("<vcount>4 4 4 4 4 4<", "<vcount>4 4 4 4 4 3<", quads)),
            "'bad.dae': geometry 'box' <polylist> 1: <vcount> adds up to 23 corners but <p> "
            "holds 24");
  EXPECT_EQ(colladaError(boxTextWith("<vcount>4 4 4 4 4 4<", "<vcount>4 4 4 4 8<", quads)),
            "'bad.dae': geometry 'box' <polylist> 1: count='6' but it holds 5 <vcount> numbers");
}

TEST(ColladaMeshBadInput, ScenesThatNameWhatIsNotThereOrNeverEnd) {
  EXPECT_EQ(colladaError(boxTextWith("url=\"#box\"", "url=\"#cup\"")),
            "'bad.dae': <instance_geometry url='#cup'>: no geometry with id 'cup'");
  EXPECT_EQ(colladaError(boxTextWith("url=\"#box\"", "url=\"parts.dae#box\"")),
            "'bad.dae': <instance_geometry url='parts.dae#box'>: url='parts.dae#box' is not a "
            "reference '#id' into this file (another file's elements are not read)");
  EXPECT_EQ(colladaError(boxTextWith("url=\"#scene\"", "url=\"#box\"")),
            "'bad.dae': <instance_visual_scene url='#box'>: no visual_scene with id 'box'");
  // A node that instantiates itself, one level down.
  EXPECT_EQ(colladaError(boxTextWith("<instance_geometry url=\"#box\"/>",
                                     "<node id=\"inner\"><instance_node url=\"#node0\"/></node>")),
            "'bad.dae': <instance_node url='#node0'>: instantiates a node it is part of (a cycle)");
  // Ten instances of ten instances ... six levels: 10^6 boxes, 12 million triangles.
  std::string nodes = "<node id=\"n0\"><instance_geometry url=\"#box\"/></node>";
  for (int level = 1; level <= 6; ++level) {
    nodes += "<node id=\"n" + std::to_string(level) + "\">";
    for (int k = 0; k < 10; ++k) {
      nodes += "<instance_node url=\"#n" + std::to_string(level - 1) + "\"/>";
    }
    nodes += "</node>";
  }
  std::string text =
      boxTextWith("<instance_geometry url=\"#box\"/>", "<instance_node url=\"#n6\"/>");
  text.insert(text.find("<library_visual_scenes>"), "<library_nodes>" + nodes + "</library_nodes>");
  EXPECT_EQ(colladaError(text),
            "'bad.dae': its scene places more than 1000000 triangles "
            "(instances of instances?): not read");
  // The same without geometry: a million nodes visited.
  text.replace(text.find("<instance_geometry url=\"#box\"/></node>"), 32, "</node>");
  EXPECT_EQ(colladaError(text),
            "'bad.dae': its scene places more than 1000000 nodes (instances "
            "of instances?): not read");
}

TEST(ColladaMeshBadInput, TransformsThatAreNotTheirNumbers) {
  const std::string node = "'bad.dae': <node id='node0'>";
  const std::pair<std::string, std::string> cases[] = {
      {"<translate>1 2</translate>", node + " <translate> holds 2 numbers, not 3"},
      {"<scale>1 nan 1</scale>", node + " <scale> number 2 'nan' is not a finite number"},
      {"<matrix>1 0 0 0 0 1 0 0 0 0 1 0</matrix>", node + " <matrix> holds 12 numbers, not 16"},
      {"<rotate>0 0 0 90</rotate>", node + " <rotate>: the axis 0 0 0 is no direction"},
      {"<lookat>0 0 1 0 0 0 0 1 0</lookat>",
       node + " <lookat>: not read by mcws (write the node's transform as <matrix>, <translate>, "
              "<rotate> and <scale>)"}};
  for (const auto& [transform, expected] : cases) {
    test::ColladaBox box = millimetreBox();
    box.nodes = {transform};
    EXPECT_EQ(colladaError(test::colladaBoxText(box)), expected);
  }
}

TEST(ColladaMesh, PolygonHolesAreNotCutInstanceNodesNameNodesAnywhereTheFirstIdCounts) {
  // A 4 x 4 square with a 2 x 2 hole (<ph>): the outer square is read whole (2 triangles, 16 m^2),
  // as a collision shape should (a hole in a face does not let anything through a closed body).
  const std::string geometry =
      "<geometry id=\"sq\"><mesh><source id=\"sq-p\"><float_array id=\"sq-a\" count=\"24\">"
      "0 0 0 4 0 0 4 4 0 0 4 0 1 1 0 3 1 0 3 3 0 1 3 0</float_array><technique_common>"
      "<accessor source=\"#sq-a\" count=\"8\" stride=\"3\"/></technique_common></source>"
      "<vertices id=\"sq-v\"><input semantic=\"POSITION\" source=\"#sq-p\"/></vertices>"
      "<polygons count=\"1\"><input semantic=\"VERTEX\" source=\"#sq-v\" offset=\"0\"/>"
      "<ph><p>0 1 2 3</p><h>4 7 6 5</h></ph></polygons></mesh></geometry>";
  // A node of the visual scene, instantiated again by another with a translation of 10 along z;
  // a second element with the geometry's id (the first of an id counts).
  const std::string text =
      "<COLLADA><library_geometries>" + geometry +
      "<geometry id=\"sq\"/></library_geometries><library_visual_scenes><visual_scene "
      "id=\"s\"><node id=\"a\">"
      "<instance_geometry url=\"#sq\"/></node><node><translate>0 0 10</translate>"
      "<instance_node url=\"#a\"/></node></visual_scene></library_visual_scenes></COLLADA>";
  const TriangleMesh mesh = parseColladaMesh(text, "sq.dae");
  ASSERT_EQ(mesh.triangles.size(), 4u);
  double area = 0.0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d n = (mesh.vertices[t[1]] - mesh.vertices[t[0]])
                                  .cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
    EXPECT_GT(n.z(), 0.0);  // counter-clockwise seen from +z, as written
    area += 0.5 * n.norm();
  }
  EXPECT_NEAR(area, 2 * 16.0, 1e-12);
  expectBounds(mesh, {0, 0, 0}, {4, 4, 10});
  EXPECT_EQ(mesh.vertices.size(), 8u);  // the 4 corners the triangles use, once per instance
}

TEST(ColladaMeshBadInput, UnitThatIsNotALength) {
  test::ColladaBox box = millimetreBox();
  for (const char* unit : {"abc", "0", "-0.001", "nan", "1e10", "0.001m"}) {
    box.unit_meter = unit;
    EXPECT_EQ(colladaError(test::colladaBoxText(box)),
              std::string("'bad.dae': <unit meter='") + unit +
                  "'>: the length of the file's unit must be a number > 0 [m] (at most 1e9)");
  }
}

TEST(ColladaMeshBadInput, MissingFileAndUnreadableMeshInAUrdf) {
  test::TempDir dir;
  try {
    readMeshFile(dir.file("none.dae"));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "'" + dir.file("none.dae") + "': file does not exist");
  }
  // Through a URDF: the file and the link first, then the mesh's own line.
  test::writeFile(dir.file("bad.dae"), "<COLLADA/>");
  test::writeFile(dir.file("arm.urdf"),
                  "<robot name='arm'><link name='base'/><link name='tool'><collision><geometry>"
                  "<mesh filename='bad.dae'/></geometry></collision></link>"
                  "<joint name='j1' type='revolute'><parent link='base'/><child link='tool'/>"
                  "<axis xyz='0 0 1'/><limit lower='-1' upper='1' effort='1' velocity='1'/>"
                  "</joint></robot>");
  const Robot robot = loadRobotUrdf(dir.file("arm.urdf"));
  try {
    loadCollisionModel(robot, dir.file("arm.urdf"));
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_THAT(message,
                ::testing::StartsWith(dir.file("arm.urdf") + ": link 'tool' <collision> 1: mesh '" +
                                      dir.file("bad.dae") + "': "));
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace mcws
