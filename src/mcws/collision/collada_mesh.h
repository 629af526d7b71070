#pragma once
/// \file
/// \brief Triangle meshes from COLLADA (.dae) files, the mesh format of many ROS robot
/// descriptions, read by assimp (the library RViz and MoveIt read them with) and checked as
/// mcws's own STL and OBJ reader checks its files.

#include <string>

#include "mcws/collision/mesh_file.h"

namespace mcws {

/// \brief Parses the bytes of a COLLADA file into triangles [m].
///
/// The rules are those of the ROS tools that show and check a robot description (RViz's and
/// MoveIt's mesh loaders, Gazebo's):
/// - every `<node>` of the scene that instantiates a geometry adds its triangles (polygons and
///   triangle strips as assimp triangulates them; lines and points are skipped), placed by the
///   node's and its parents' transforms; a geometry instantiated twice is there twice;
/// - the file's `<asset><unit meter="...">` (the length of its unit in metres; 1 when absent, as
///   COLLADA says) is applied, so the vertices are in metres whatever unit the file was written
///   in (RViz reads the same attribute, and Gazebo applies it too);
/// - the file's `<up_axis>` is ignored: the vertices keep the axes they are written in, the
///   URDF's Z up. Assimp would turn a Z_UP file to its own Y-up convention; RViz, MoveIt's
///   geometric_shapes and Gazebo do not rotate meshes by `<up_axis>` (they drop assimp's root
///   transform), so neither does mcws, and a mesh sits where RViz draws it.
/// Vertices are not merged (each instance keeps its own).
///
/// \param bytes the file's contents.
/// \param source the file name for messages.
/// \return the triangles [m]; none when the scene has no triangle (parseMesh() refuses that).
/// \throws mcws::Error "'source': ..." for a file that is not XML or whose root element is not
///   `<COLLADA>`, a `<unit meter>` that is not a number > 0, a file assimp cannot read (with
///   assimp's reason), or a vertex coordinate that is not a finite number ("'source': mesh 'box'
///   vertex 3: x coordinate nan is not a finite number") or, placed and in metres, larger than
///   kLargestMeshCoordinate in size.
TriangleMesh parseColladaMesh(const std::string& bytes, const std::string& source);

}  // namespace mcws
