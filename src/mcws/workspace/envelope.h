#pragma once
/// \file
/// \brief The workspace envelope as a triangle mesh: the boundary of the region mcws_measure
/// measures, closed and oriented outward, enclosing the same volume; its checks and its files.

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstdio>
#include <string>

#include "mcws/workspace/measure.h"

namespace mcws {

/// \brief The envelope of a 3-D cloud and what it was made from.
struct Envelope {
  TriangleSurface mesh;
  RegionMeasure measure;  ///< delaunayMeasure() of the cloud (its volume is the target)
  double volume{0.0};     ///< enclosed by `mesh` [length unit^3]
  double area{0.0};       ///< of `mesh` [length unit^2]
  double offset{0.0};     ///< outward offset of the alpha surface [length unit] (see below)
  /// Net volume the repairs that make the surface a 2-manifold add to the kept tetrahedra before
  /// the offset: cavities and the smaller sides of pinches kept (+), the smaller parts of the
  /// region that touch the rest at a single vertex dropped (-) [length unit^3]. Well under a per
  /// mille on uniform, refined and plain joint-space clouds alike.
  double filled{0.0};
  /// Whether the surface is a closed 2-manifold (the filling converged).
  bool manifold{false};
};

/// \brief The envelope of the region a cloud samples: the surface of delaunayMeasure()'s kept
/// tetrahedra (the alpha shape at the same alpha), each vertex then moved outward along its
/// normal by one common distance so that the mesh encloses the measured volume.
///
/// The kept tetrahedra fill the region up to its outermost samples, `uncorrected`; the edge
/// correction (Efron's identity) adds the band the samples miss along the edge. The offset that
/// makes the mesh enclose `measure` is about that band's mean width, (measure - uncorrected) /
/// area: a fraction of a spacing. With options.edge_correction false (refined clouds) there is
/// no offset. Vertex normals are the area-weighted sums of the adjacent triangles' normals.
/// \throws mcws::Error as delaunayMeasure(), and when the offset does not converge (a surface too
///   folded for it).
Envelope workspaceEnvelope(const pcl::PointCloud<pcl::PointXYZ>& points,
                           const MeasureOptions& options);

/// \brief Volume enclosed by a closed, outward-oriented surface (divergence theorem)
/// [length unit^3].
double enclosedVolume(const TriangleSurface& surface);
/// \brief Total area of the triangles [length unit^2].
double surfaceArea(const TriangleSurface& surface);
/// \brief Moves every vertex by `distance` along its unit normal (area-weighted sum of the
/// adjacent triangles' normals; a vertex whose normals cancel stays).
TriangleSurface offsetSurface(const TriangleSurface& surface, double distance);

/// \brief How a triangle surface is connected.
struct SurfaceTopology {
  std::size_t vertices{0}, edges{0}, triangles{0};
  std::size_t open_edges{0};          ///< edges of one triangle only
  std::size_t non_manifold_edges{0};  ///< edges of more than two triangles
  std::size_t misoriented_edges{0};   ///< edges two triangles run in the same direction
  long euler_characteristic{0};       ///< V - E + F: 2 for a sphere-like closed surface
  /// Closed and consistently oriented: every edge in exactly two triangles, once each way.
  bool closedAndOriented() const {
    return open_edges == 0 && non_manifold_edges == 0 && misoriented_edges == 0;
  }
};
SurfaceTopology surfaceTopology(const TriangleSurface& surface);

/// \brief The file formats an envelope surface is written in (mcws::MeshFormat is what
/// robot meshes are read from).
enum class SurfaceFormat { kPly, kStl, kVtk };
/// \brief The format a file name's extension names (.ply, .stl, .vtk, any case).
/// \throws mcws::Error naming the file for any other extension.
SurfaceFormat surfaceFormatOf(const std::string& path);
/// \brief Writes the surface: binary little-endian PLY (float vertices, int faces), binary STL
/// (with each triangle's unit normal) or legacy ASCII VTK POLYDATA. `comment` goes into the PLY
/// and VTK headers and the STL's 80-byte header (cut to fit). \throws mcws::Error on a write
/// error.
void writeSurface(const TriangleSurface& surface, SurfaceFormat format, const std::string& comment,
                  std::FILE* out);

/// \brief Writes the surface to `path` in the format its extension names (surfaceFormatOf()),
/// appearing whole on success (io::AtomicFile, committed into the io::OutputSet alive on the
/// thread, if any), its comment "mcws_envelope of <source>, lengths in <length_unit>".
/// \param source what the cloud is: io::describeCloud(), "robot 'arm', tip tool0, from a.pcd"
///   (robot first: an STL header keeps 80 bytes), or the cloud's path.
/// \throws mcws::Error naming the file for another extension, or when it cannot be written.
void saveSurface(const TriangleSurface& surface, const std::string& path, const std::string& source,
                 const std::string& length_unit);

/// \brief A shaded picture of the surface from two views (front-left from above, and from the
/// side along -y), drawn by gnuplot (pm3d lighting on the triangles), axes in `unit`, under the
/// title "<title>: workspace envelope of <tip>, N triangles" (without " of <tip>" when `tip` is
/// empty): `title` the robot's name (or the cloud's file name), `tip` the frame measured.
/// \return the PNG's bytes. \throws mcws::Error when gnuplot fails or the surface is empty.
std::string renderEnvelopePng(const TriangleSurface& surface, const std::string& title,
                              const std::string& unit, const std::string& tip = "");

}  // namespace mcws
