#pragma once
/// \file
/// \brief Triangle meshes from STL (binary or ASCII) and Wavefront OBJ files, read by a small
/// strict reader of mcws's own, and from COLLADA (.dae) files, read by mcws's COLLADA reader
/// (mcws/collision/collada_mesh.h): every mistake is one mcws::Error naming the file, the line (or
/// triangle, or vertex) and the bad value, nothing is printed, and no vertex that is not a finite
/// number of sensible size reaches the collision library.

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace mcws {

/// \brief A triangle mesh [robot length unit].
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;  ///< vertex indices
};

/// \brief The format of a mesh file.
enum class MeshFormat { kStl, kObj, kCollada };

/// \brief The largest size of a vertex coordinate a mesh file may hold: the bound of every number
/// of a robot file (YamlReader::kLargestNumber, and the URDF reader's), 1000 km for a robot in
/// metres. A larger one is a unit or export mistake, and a mesh that large makes the collision
/// library's distance iterations fail (FCL prints "too many iterations" and answers wrongly).
constexpr double kLargestMeshCoordinate = 1e9;

/// \brief Parses the bytes of a mesh file.
///
/// - STL: binary when the file's size is 84 + 50 n bytes for the n triangles its header counts
///   (whatever its first bytes), otherwise ASCII (`solid`, then `facet normal` / `outer loop` /
///   three `vertex x y z` / `endloop` / `endfacet` per triangle, `endsolid`; keywords in any
///   case; several solids may follow each other). Corners at the same coordinates become one
///   vertex. Normals are read as numbers and not used.
/// - OBJ: `v x y z` (with an optional w, or r g b colours, ignored), `f` with three or more
///   corners `i`, `i/t`, `i//n` or `i/t/n` (1-based, or negative from the last vertex so far),
///   fanned into triangles from the first corner; `vt`, `vn`, `vp`, `l`, `p`, `g`, `o`, `s`,
///   `usemtl`, `mtllib` and `#` comments are skipped; any other keyword is an error (a typo there
///   would silently drop geometry).
/// - COLLADA: parseColladaMesh(): the triangles of every node of the scene, placed by the node
///   transforms, in metres (the file's `<unit meter>` applied; its `<up_axis>` ignored, as ROS
///   does).
///
/// \param bytes the file's contents.
/// \param format STL, OBJ or COLLADA.
/// \param source the file name for messages.
/// \return the vertices as written [file units; m for COLLADA] and the triangles.
/// \throws mcws::Error "'source': ..." naming the line (ASCII STL, OBJ) or triangle (binary STL)
///   and the value, for a malformed file, a coordinate that is not a finite number or larger
///   than kLargestMeshCoordinate in size, a face with a missing vertex, or no triangle at all.
TriangleMesh parseMesh(const std::string& bytes, MeshFormat format, const std::string& source);

/// \brief Reads a mesh file with parseMesh(), the format by its extension (.stl, .obj or .dae, in
/// any case). The file must be a regular file (mcws::requireInputFile(path, "collision mesh"),
/// which also notes it as an input of the run). \throws mcws::Error "'path': file does not exist",
/// "'path': not an STL, OBJ or COLLADA (.dae)
///   file (by its extension)", as requireInputFile() and as parseMesh().
TriangleMesh readMeshFile(const std::string& path);

}  // namespace mcws
