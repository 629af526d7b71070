#pragma once
// A COLLADA (.dae) file of an axis-aligned box, written by the tests that read .dae meshes (the
// mesh reader's tests, the URDF and quick-start tests), so that no public mesh file is copied into
// the repository and every number the reader should give is worked out by hand from the box.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace mcws {
namespace test {

/// What the file holds.
struct ColladaBox {
  Eigen::Vector3d lo{0, 0, 0};  ///< the box's lowest corner [file units]
  Eigen::Vector3d hi{1, 1, 1};  ///< its highest corner [file units]
  std::string unit_meter;       ///< `<unit meter>`'s text; none when empty (metres)
  std::string up_axis{"Z_UP"};  ///< `<up_axis>`'s text; none when empty
  /// One `<node>` instantiating the box per entry, the entry's text placed in it before the
  /// `<instance_geometry>` (a transform such as "<translate>1 0 0</translate>", or nothing).
  std::vector<std::string> nodes{""};
  bool quads{false};     ///< the six faces as a `<polylist>` of quads, not 12 triangles
  std::string first_x;   ///< the text of vertex 1's x, when not empty (e.g. "nan")
  bool no_faces{false};  ///< the geometry has vertices and no face
};

/// The corners, 0 = lo, then counter-clockwise on the bottom, the same on the top.
inline std::vector<Eigen::Vector3d> colladaBoxCorners(const ColladaBox& box) {
  const Eigen::Vector3d& a = box.lo;
  const Eigen::Vector3d& b = box.hi;
  return {{a.x(), a.y(), a.z()}, {b.x(), a.y(), a.z()}, {b.x(), b.y(), a.z()},
          {a.x(), b.y(), a.z()}, {a.x(), a.y(), b.z()}, {b.x(), a.y(), b.z()},
          {b.x(), b.y(), b.z()}, {a.x(), b.y(), b.z()}};
}

/// The `<geometry id="box" name="box">` element of `box` (its mesh named by `id`'s prefix).
inline std::string colladaBoxGeometry(const ColladaBox& box, const std::string& id = "box") {
  std::string positions;
  const std::vector<Eigen::Vector3d> corners = colladaBoxCorners(box);
  for (std::size_t v = 0; v < corners.size(); ++v) {
    for (int k = 0; k < 3; ++k) {
      std::string number = std::to_string(corners[v][k]);
      if (v == 0 && k == 0 && !box.first_x.empty()) number = box.first_x;
      positions += (positions.empty() ? "" : " ") + number;
    }
  }
  const std::string triangles = "<triangles count=\"12\"><input semantic=\"VERTEX\" source=\"#" +
                                id +
                                "-vertices\" offset=\"0\"/><p>0 2 1 0 3 2 4 5 6 4 6 7 0 1 5 0 5 4 "
                                "1 2 6 1 6 5 2 3 7 2 7 6 3 0 4 3 4 7</p></triangles>";
  const std::string quads = "<polylist count=\"6\"><input semantic=\"VERTEX\" source=\"#" + id +
                            "-vertices\" offset=\"0\"/><vcount>4 4 4 4 4 4</vcount>"
                            "<p>0 3 2 1 4 5 6 7 0 1 5 4 1 2 6 5 2 3 7 6 3 0 4 7</p></polylist>";
  return "<geometry id=\"" + id + "\" name=\"" + id + "\"><mesh>\n    <source id=\"" + id +
         "-positions\"><float_array id=\"" + id + "-array\" count=\"24\">" + positions +
         "</float_array><technique_common><accessor source=\"#" + id +
         "-array\" count=\"8\" stride=\"3\"><param name=\"X\" type=\"float\"/><param name=\"Y\" "
         "type=\"float\"/><param name=\"Z\" type=\"float\"/></accessor></technique_common>"
         "</source>\n    <vertices id=\"" +
         id +
         "-vertices\"><input semantic=\"POSITION\" "
         "source=\"#" +
         id + "-positions\"/></vertices>\n    " +
         (box.no_faces ? std::string()
          : box.quads  ? quads
                       : triangles) +
         "\n  </mesh></geometry>";
}

/// The COLLADA 1.4.1 text of `box`; faces wound counter-clockwise seen from outside.
inline std::string colladaBoxText(const ColladaBox& box) {
  std::string text =
      "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
      "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
      "  <asset>";
  if (!box.unit_meter.empty()) text += "<unit name=\"unit\" meter=\"" + box.unit_meter + "\"/>";
  if (!box.up_axis.empty()) text += "<up_axis>" + box.up_axis + "</up_axis>";
  text += "</asset>\n  <library_geometries>" + colladaBoxGeometry(box) +
          "</library_geometries>\n"
          "  <library_visual_scenes><visual_scene id=\"scene\">";
  for (std::size_t n = 0; n < box.nodes.size(); ++n) {
    text += "<node id=\"node" + std::to_string(n) + "\">" + box.nodes[n] +
            "<instance_geometry url=\"#box\"/></node>";
  }
  text +=
      "</visual_scene></library_visual_scenes>\n"
      "  <scene><instance_visual_scene url=\"#scene\"/></scene>\n</COLLADA>\n";
  return text;
}

}  // namespace test
}  // namespace mcws
