#pragma once
/// \file
/// \brief Triangle meshes from COLLADA (.dae) files, the mesh format of many ROS robot
/// descriptions, read by mcws's own reader (on TinyXML) and checked as mcws's STL and OBJ reader
/// checks its files. Its tests compare it with assimp, the library RViz and MoveIt read .dae
/// files with.

#include <string>

#include "mcws/collision/mesh_file.h"

namespace mcws {

/// \brief Parses the bytes of a COLLADA file into triangles [m].
///
/// The rules are those of the ROS tools that show and check a robot description (RViz's and
/// MoveIt's mesh loaders, Gazebo's):
/// - the scene is the `<visual_scene>` that `<scene><instance_visual_scene url>` names (the first
///   one when there is none); every `<node>` of it that instantiates a geometry
///   (`<instance_geometry url>`) adds the geometry's triangles, placed by the node's and its
///   parents' transforms (`<matrix>` row by row, `<translate>`, `<rotate>` about an axis by
///   degrees, `<scale>`, applied in the order written; a `<lookat>` or `<skew>` is refused);
///   `<instance_node url>` instantiates another node's subtree (in `<library_nodes>` or anywhere);
///   a geometry instantiated twice is there twice; vertices are not merged;
/// - a geometry is the triangles of its `<mesh>`'s `<triangles>`, `<polylist>`, `<polygons>`,
///   `<trifans>` and `<tristrips>` (`<lines>`, `<linestrips>` skipped); a polygon of more than 3
///   corners is split into a fan from its first corner (assimp ear-clips: the two agree on the
///   convex polygons CAD exporters write), a strip's every other triangle turned to face the same
///   way, and the holes of a `<ph>` are not cut (its outer polygon is read whole);
/// - the file's `<asset><unit meter="...">` (the length of its unit in metres; 1 when absent, as
///   COLLADA says) is applied, so the vertices are in metres whatever unit the file was written
///   in (RViz reads the same attribute, and Gazebo applies it too);
/// - the file's `<up_axis>` is ignored: the vertices keep the axes they are written in, the
///   URDF's Z up. Assimp would turn a Z_UP file to its own Y-up convention; RViz, MoveIt's
///   geometric_shapes and Gazebo do not rotate meshes by `<up_axis>` (they drop assimp's root
///   transform), so neither does mcws, and a mesh sits where RViz draws it.
/// Every size and index is checked against what the file holds before anything is allocated by
/// it, and the triangles placed (and nodes visited) are at most ten per byte of the file (at least
/// a million, at most 50 million), so that instances of instances cannot grow without bound.
///
/// \param bytes the file's contents.
/// \param source the file name for messages.
/// \return the triangles [m]; none when the scene has no triangle (parseMesh() refuses that).
/// \throws mcws::Error one line "'source': ..." naming the element for a file that is not XML or
///   whose root element is not `<COLLADA>`, a `<unit meter>` that is not a number > 0, a missing
///   attribute COLLADA requires, a reference "#id" to an element the file does not hold
///   ("'source': <instance_geometry url='#nope'>: no geometry with id 'nope'"), a count that is
///   not what the element holds, an index past its accessor, a cycle of `<instance_node>`s, too
///   many triangles placed, or a vertex coordinate that is not a finite number ("'source': mesh
///   'box' vertex 3: x coordinate nan is not a finite number") or, placed and in metres, larger
///   than kLargestMeshCoordinate in size.
TriangleMesh parseColladaMesh(const std::string& bytes, const std::string& source);

}  // namespace mcws
