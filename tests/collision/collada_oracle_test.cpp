// mcws's COLLADA reader against assimp (the library RViz and MoveIt read .dae meshes with), the
// independent oracle, as KDL is the kinematics' oracle: on valid files built here (the box as
// triangles, quads and polygons, strips and fans, units, every transform, nested nodes,
// <instance_node>, two instances of one geometry) both give the same placed triangles. Assimp is
// read as mcws read it before its own reader: its root transform (unit and up axis) replaced by
// the file's unit alone. Assimp reads floats, mcws doubles: the comparison allows float rounding.
#include <gtest/gtest.h>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <Eigen/Core>
#include <array>
#include <assimp/Importer.hpp>
#include <string>
#include <vector>

#include "collision/collada_box.h"
#include "mcws/collision/collada_mesh.h"

namespace mcws {
namespace {

using PlacedTriangle = std::array<Eigen::Vector3d, 3>;

/// The placed triangles of a mesh [m].
std::vector<PlacedTriangle> placedTriangles(const TriangleMesh& mesh) {
  std::vector<PlacedTriangle> out;
  for (const auto& t : mesh.triangles) {
    out.push_back({mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]});
  }
  return out;
}

/// The placed triangles assimp reads from `text` [m]: every node's meshes placed by its
/// transforms, the root's replaced by the file's `unit` [m].
std::vector<PlacedTriangle> assimpTriangles(const std::string& text, double unit) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFileFromMemory(
      text.data(), text.size(), aiProcess_Triangulate | aiProcess_ValidateDataStructure, "dae");
  EXPECT_NE(scene, nullptr) << importer.GetErrorString();
  std::vector<PlacedTriangle> out;
  if (scene == nullptr || scene->mRootNode == nullptr) return out;
  struct Open {
    const aiNode* node;
    Eigen::Matrix4d T;
  };
  Eigen::Matrix4d T_root = Eigen::Matrix4d::Identity();
  T_root.topLeftCorner<3, 3>() *= unit;
  std::vector<Open> open{{scene->mRootNode, T_root}};
  while (!open.empty()) {
    const Open placed = open.back();
    open.pop_back();
    for (unsigned k = 0; k < placed.node->mNumMeshes; ++k) {
      const aiMesh& mesh = *scene->mMeshes[placed.node->mMeshes[k]];
      for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        if (mesh.mFaces[f].mNumIndices != 3) continue;
        PlacedTriangle triangle;
        for (int c = 0; c < 3; ++c) {
          const aiVector3D& v = mesh.mVertices[mesh.mFaces[f].mIndices[c]];
          triangle[c] = (placed.T * Eigen::Vector4d(v.x, v.y, v.z, 1.0)).head<3>();
        }
        out.push_back(triangle);
      }
    }
    for (unsigned c = 0; c < placed.node->mNumChildren; ++c) {
      const aiNode* child = placed.node->mChildren[c];
      Eigen::Matrix4d T_child;
      for (unsigned r = 0; r < 4; ++r) {
        for (unsigned k = 0; k < 4; ++k) T_child(r, k) = child->mTransformation[r][k];
      }
      open.push_back({child, placed.T * T_child});
    }
  }
  return out;
}

/// The surface's area [m^2] and the signed volume it encloses [m^3] (the divergence theorem).
std::pair<double, double> areaAndVolume(const std::vector<PlacedTriangle>& triangles) {
  double area = 0.0, six_volume = 0.0;
  for (const auto& t : triangles) {
    area += 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).norm();
    six_volume += t[0].dot(t[1].cross(t[2]));
  }
  return {area, six_volume / 6.0};
}

/// True when `a` is `b`, corner for corner, starting at any of b's corners (same winding), each
/// corner within `relative` times (1 + its distance from the origin).
bool sameTriangle(const PlacedTriangle& a, const PlacedTriangle& b, double relative) {
  for (int shift = 0; shift < 3; ++shift) {
    bool same = true;
    for (int c = 0; c < 3; ++c) {
      same = same && (a[c] - b[(c + shift) % 3]).norm() <= relative * (1.0 + a[c].norm());
    }
    if (same) return true;
  }
  return false;
}

/// assimp reads coordinates and transforms as floats (24 bits, 6e-8 relative): the relative
/// difference allowed for corners, areas and volumes after a few float operations.
constexpr double kOracleRelative = 1e-6;

/// mcws's and assimp's triangles of `text` are the same: the same count, area and signed volume,
/// and, when `same_split` (no polygon of more than four corners that the two could split along
/// other diagonals), each of mcws's triangles is one of assimp's with the same winding.
void expectAsAssimpReads(const std::string& text, double unit, bool same_split = true) {
  const std::vector<PlacedTriangle> ours = placedTriangles(parseColladaMesh(text, "oracle.dae"));
  const std::vector<PlacedTriangle> theirs = assimpTriangles(text, unit);
  ASSERT_EQ(ours.size(), theirs.size());
  ASSERT_FALSE(ours.empty());
  const auto [our_area, our_volume] = areaAndVolume(ours);
  const auto [their_area, their_volume] = areaAndVolume(theirs);
  EXPECT_NEAR(our_area, their_area, 3 * kOracleRelative * their_area);
  EXPECT_NEAR(our_volume, their_volume, 3 * kOracleRelative * std::abs(their_volume));
  if (!same_split) return;
  std::vector<bool> used(theirs.size(), false);
  for (std::size_t k = 0; k < ours.size(); ++k) {
    bool found = false;
    for (std::size_t j = 0; j < theirs.size() && !found; ++j) {
      if (used[j] || !sameTriangle(ours[k], theirs[j], kOracleRelative)) continue;
      used[j] = found = true;
    }
    EXPECT_TRUE(found) << "mcws's triangle " << k + 1 << " (" << ours[k][0].transpose() << " | "
                       << ours[k][1].transpose() << " | " << ours[k][2].transpose()
                       << ") is not one of assimp's";
  }
}

/// A COLLADA file: `geometries` in <library_geometries>, `nodes` in <library_nodes>, `scene` the
/// visual scene's nodes, `unit` its <unit meter> (none when empty).
std::string colladaFile(const std::string& geometries, const std::string& scene,
                        const std::string& nodes = "", const std::string& unit = "") {
  return "<?xml version=\"1.0\"?>\n<COLLADA xmlns=\"http://www.collada.org/2005/11/"
         "COLLADASchema\" version=\"1.4.1\"><asset>" +
         (unit.empty() ? std::string() : "<unit meter=\"" + unit + "\"/>") +
         "<up_axis>Z_UP</up_axis></asset><library_geometries>" + geometries +
         "</library_geometries>" +
         (nodes.empty() ? std::string() : "<library_nodes>" + nodes + "</library_nodes>") +
         "<library_visual_scenes><visual_scene id=\"scene\">" + scene +
         "</visual_scene></library_visual_scenes><scene><instance_visual_scene url=\"#scene\"/>"
         "</scene></COLLADA>\n";
}

/// The box of collada_box.h with other faces: `faces` replaces its <triangles>.
std::string boxWithFaces(const std::string& faces, const std::string& id = "box") {
  test::ColladaBox box;
  box.lo = {10, 20, 30};
  box.hi = {110, 220, 330};
  std::string geometry = test::colladaBoxGeometry(box, id);
  const std::size_t from = geometry.find("<triangles"), to = geometry.find("</triangles>") + 12;
  return geometry.replace(from, to - from, faces);
}

TEST(ColladaOracle, TheBoxAsTrianglesAndAsQuadsInEveryUnit) {
  test::ColladaBox box;
  box.lo = {10, 20, 30};
  box.hi = {110, 220, 330};
  for (const char* unit : {"", "0.001", "0.0254"}) {
    box.unit_meter = unit;
    for (const bool quads : {false, true}) {
      box.quads = quads;
      expectAsAssimpReads(test::colladaBoxText(box), *unit ? std::stod(unit) : 1.0);
    }
  }
}

TEST(ColladaOracle, EveryTransformAndTheirOrder) {
  test::ColladaBox box;
  box.lo = {10, 20, 30};
  box.hi = {110, 220, 330};
  box.unit_meter = "0.001";
  box.nodes = {
      "<translate>500 -20 7.5</translate>",
      "<rotate>0 0 1 90</rotate>",
      "<rotate>0.6 0 0.8 37</rotate>",
      "<scale>2 0.5 3</scale>",
      "<matrix>0 -1 0 100 1 0 0 200 0 0 1 300 0 0 0 1</matrix>",
      "<translate>500 0 0</translate><rotate>0 0 1 90</rotate><scale>1 2 1</scale>",
      "<scale>1 2 1</scale><rotate>0 0 1 90</rotate><translate>500 0 0</translate>",
      "<rotate>1 0 0 -30</rotate><matrix>1 0 0 5 0 0.8 -0.6 6 0 0.6 0.8 7 0 0 0 1</matrix>"};
  const std::string text = test::colladaBoxText(box);
  expectAsAssimpReads(text, 0.001);
  EXPECT_EQ(parseColladaMesh(text, "t.dae").triangles.size(), 12 * box.nodes.size());
}

TEST(ColladaOracle, NestedNodesAndInstanceNodes) {
  const std::string geometry = boxWithFaces(
      "<triangles count=\"12\"><input semantic=\"VERTEX\" source=\"#box-vertices\" offset=\"0\"/>"
      "<p>0 2 1 0 3 2 4 5 6 4 6 7 0 1 5 0 5 4 1 2 6 1 6 5 2 3 7 2 7 6 3 0 4 3 4 7</p></triangles>");
  // A part in the library, placed twice, each time inside two levels of nodes.
  const std::string part =
      "<node id=\"part\"><rotate>1 0 0 90</rotate><instance_geometry url=\"#box\"/>"
      "<node id=\"inner\"><translate>0 0 400</translate><instance_geometry url=\"#box\"/></node>"
      "</node>";
  const std::string scene =
      "<node id=\"a\"><translate>1000 0 0</translate><node id=\"b\"><rotate>0 0 1 45</rotate>"
      "<instance_node url=\"#part\"/><instance_geometry url=\"#box\"/></node></node>"
      "<node id=\"c\"><scale>0.5 0.5 0.5</scale><instance_node url=\"#part\"/></node>";
  const std::string text = colladaFile(geometry, scene, part, "0.01");
  expectAsAssimpReads(text, 0.01);
  // part (2 boxes) twice, and the box in b: 5 boxes of 12 triangles.
  EXPECT_EQ(parseColladaMesh(text, "n.dae").triangles.size(), 5u * 12u);
}

TEST(ColladaOracle, PolygonsStripsAndFansWithOtherInputs) {
  // A normal input at offset 1: the <p> lists (position, normal) pairs.
  const std::string inputs =
      "<input semantic=\"VERTEX\" source=\"#box-vertices\" offset=\"0\"/>"
      "<input semantic=\"NORMAL\" source=\"#box-normals\" offset=\"1\"/>";
  const auto pairs = [](const std::string& corners) {
    std::string out;
    std::size_t from = 0;
    while (from < corners.size()) {
      const std::size_t end = std::min(corners.find(' ', from), corners.size());
      out += (out.empty() ? "" : " ") + corners.substr(from, end - from) + " 0";
      from = end + 1;
    }
    return out;
  };
  std::string polygons = "<polygons count=\"6\">" + inputs;
  for (const char* face : {"0 3 2 1", "4 5 6 7", "0 1 5 4", "1 2 6 5", "2 3 7 6", "3 0 4 7"}) {
    polygons += "<p>" + pairs(face) + "</p>";
  }
  polygons += "</polygons>";
  // The bottom and top as fans, the sides as one strip around the box.
  const std::string fans_and_strip = "<trifans count=\"2\">" + inputs + "<p>" + pairs("0 3 2 1") +
                                     "</p><p>" + pairs("4 5 6 7") + "</p></trifans>" +
                                     "<tristrips count=\"1\">" + inputs + "<p>" +
                                     pairs("4 0 5 1 6 2 7 3 4 0") + "</p></tristrips>";
  const std::string normals =
      "<source id=\"box-normals\"><float_array id=\"box-normal-array\" count=\"3\">0 0 1"
      "</float_array><technique_common><accessor source=\"#box-normal-array\" count=\"1\" "
      "stride=\"3\"><param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/>"
      "<param name=\"Z\" type=\"float\"/></accessor></technique_common></source>";
  for (const std::string& faces : {polygons, fans_and_strip}) {
    std::string geometry = boxWithFaces(faces);
    geometry.insert(geometry.find("<vertices"), normals);
    const std::string text =
        colladaFile(geometry, "<node><instance_geometry url=\"#box\"/></node>");
    expectAsAssimpReads(text, 1.0);
    // Hand-worked: the box of 100 x 200 x 300, every face outward.
    const TriangleMesh mesh = parseColladaMesh(text, "p.dae");
    EXPECT_EQ(mesh.triangles.size(), 12u);
    EXPECT_NEAR(areaAndVolume(placedTriangles(mesh)).second, 100.0 * 200.0 * 300.0, 1e-6);
  }
}

}  // namespace
}  // namespace mcws
