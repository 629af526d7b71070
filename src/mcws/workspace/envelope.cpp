#include "mcws/workspace/envelope.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <tuple>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/core/file_name.h"
#include "mcws/io/atomic_file.h"
#include "mcws/io/gnuplot.h"

namespace mcws {
namespace {

/// At most this many corrections of the offset; each is a Newton step on V(t), nearly linear.
constexpr int kOffsetSteps = 8;
/// The offset stops when the enclosed volume is within this share of the target.
constexpr double kVolumeTolerance = 1e-9;

Eigen::Vector3d centroid(const TriangleSurface& surface) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& v : surface.vertices) sum += v;
  return surface.vertices.empty() ? sum : Eigen::Vector3d(sum / surface.vertices.size());
}

/// (b - a) x (c - a) of triangle t: twice its area, along its outward normal.
Eigen::Vector3d doubleAreaNormal(const TriangleSurface& s, const std::array<std::uint32_t, 3>& t) {
  const Eigen::Vector3d& a = s.vertices[t[0]];
  return (s.vertices[t[1]] - a).cross(s.vertices[t[2]] - a);
}

void put(std::FILE* out, const void* data, std::size_t size) {
  if (std::fwrite(data, 1, size, out) != size) {
    throw Error(std::string("writing the mesh failed: ") + std::strerror(errno));
  }
}

void putText(std::FILE* out, const std::string& text) { put(out, text.data(), text.size()); }

/// A comment on one line: line breaks become spaces.
std::string oneLine(std::string text) {
  std::replace_if(
      text.begin(), text.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  return text;
}

void writePly(const TriangleSurface& s, const std::string& comment, std::FILE* out) {
  putText(out, "ply\nformat binary_little_endian 1.0\ncomment " + oneLine(comment) +
                   "\nelement vertex " + std::to_string(s.vertices.size()) +
                   "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                   std::to_string(s.triangles.size()) +
                   "\nproperty list uchar int vertex_indices\nend_header\n");
  for (const auto& v : s.vertices) {
    const float xyz[3] = {static_cast<float>(v.x()), static_cast<float>(v.y()),
                          static_cast<float>(v.z())};
    put(out, xyz, sizeof xyz);
  }
  for (const auto& t : s.triangles) {
    unsigned char record[13];
    record[0] = 3;
    for (int k = 0; k < 3; ++k) {
      const auto index = static_cast<std::int32_t>(t[k]);
      std::memcpy(record + 1 + 4 * k, &index, 4);
    }
    put(out, record, sizeof record);
  }
}

void writeStl(const TriangleSurface& s, const std::string& comment, std::FILE* out) {
  char header[80] = {};
  const std::string text = oneLine(comment);
  // "solid" at the start would make readers take the binary file for ASCII STL.
  std::memcpy(header, text.data(), std::min<std::size_t>(text.size(), sizeof header));
  if (std::strncmp(header, "solid", 5) == 0) header[0] = 'S';
  put(out, header, sizeof header);
  const auto count = static_cast<std::uint32_t>(s.triangles.size());
  put(out, &count, 4);
  for (const auto& t : s.triangles) {
    const Eigen::Vector3d n = doubleAreaNormal(s, t).normalized();
    float record[12] = {static_cast<float>(n.x()), static_cast<float>(n.y()),
                        static_cast<float>(n.z())};
    for (int k = 0; k < 3; ++k) {
      for (int axis = 0; axis < 3; ++axis) {
        record[3 + 3 * k + axis] = static_cast<float>(s.vertices[t[k]][axis]);
      }
    }
    put(out, record, sizeof record);
    const std::uint16_t attributes = 0;
    put(out, &attributes, 2);
  }
}

void writeVtk(const TriangleSurface& s, const std::string& comment, std::FILE* out) {
  putText(out, "# vtk DataFile Version 3.0\n" + oneLine(comment).substr(0, 255) +
                   "\nASCII\nDATASET POLYDATA\nPOINTS " + std::to_string(s.vertices.size()) +
                   " float\n");
  char line[128];
  for (const auto& v : s.vertices) {
    const int n = std::snprintf(line, sizeof line, "%.9g %.9g %.9g\n", v.x(), v.y(), v.z());
    put(out, line, static_cast<std::size_t>(n));
  }
  putText(out, "POLYGONS " + std::to_string(s.triangles.size()) + " " +
                   std::to_string(4 * s.triangles.size()) + "\n");
  for (const auto& t : s.triangles) {
    const int n = std::snprintf(line, sizeof line, "3 %u %u %u\n", t[0], t[1], t[2]);
    put(out, line, static_cast<std::size_t>(n));
  }
}

}  // namespace

double enclosedVolume(const TriangleSurface& surface) {
  // Tetrahedra from a point near the surface (its vertices' centroid), for precision far from
  // the origin.
  const Eigen::Vector3d o = centroid(surface);
  double six_volume = 0.0;
  for (const auto& t : surface.triangles) {
    const Eigen::Vector3d a = surface.vertices[t[0]] - o, b = surface.vertices[t[1]] - o,
                          c = surface.vertices[t[2]] - o;
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

double surfaceArea(const TriangleSurface& surface) {
  double twice = 0.0;
  for (const auto& t : surface.triangles) twice += doubleAreaNormal(surface, t).norm();
  return twice / 2.0;
}

TriangleSurface offsetSurface(const TriangleSurface& surface, double distance) {
  std::vector<Eigen::Vector3d> normal(surface.vertices.size(), Eigen::Vector3d::Zero());
  for (const auto& t : surface.triangles) {
    const Eigen::Vector3d n = doubleAreaNormal(surface, t);
    for (const std::uint32_t k : t) normal[k] += n;
  }
  TriangleSurface moved = surface;
  for (std::size_t k = 0; k < moved.vertices.size(); ++k) {
    const double length = normal[k].norm();
    if (length > 0.0) moved.vertices[k] += distance / length * normal[k];
  }
  return moved;
}

SurfaceTopology surfaceTopology(const TriangleSurface& surface) {
  SurfaceTopology topology;
  topology.vertices = surface.vertices.size();
  topology.triangles = surface.triangles.size();
  std::vector<std::tuple<std::uint32_t, std::uint32_t, bool>> edges;  // (low, high, low -> high)
  edges.reserve(3 * surface.triangles.size());
  for (const auto& t : surface.triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      edges.emplace_back(std::min(a, b), std::max(a, b), a < b);
    }
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && std::get<0>(edges[j]) == std::get<0>(edges[i]) &&
           std::get<1>(edges[j]) == std::get<1>(edges[i])) {
      ++j;
    }
    ++topology.edges;
    const std::size_t uses = j - i;
    if (uses == 1) ++topology.open_edges;
    if (uses > 2) ++topology.non_manifold_edges;
    if (uses == 2 && std::get<2>(edges[i]) == std::get<2>(edges[i + 1])) {
      ++topology.misoriented_edges;
    }
    i = j;
  }
  topology.euler_characteristic = static_cast<long>(topology.vertices) -
                                  static_cast<long>(topology.edges) +
                                  static_cast<long>(topology.triangles);
  return topology;
}

Envelope workspaceEnvelope(const pcl::PointCloud<pcl::PointXYZ>& points,
                           const MeasureOptions& options) {
  MeasureOptions with_surface = options;
  with_surface.surface = true;
  Envelope envelope;
  envelope.measure = delaunayMeasure(points, 3, with_surface);
  const TriangleSurface alpha_surface = std::move(envelope.measure.surface);
  envelope.measure.surface = {};
  envelope.manifold = envelope.measure.surface_is_manifold;
  envelope.mesh = alpha_surface;
  envelope.volume = enclosedVolume(envelope.mesh);
  envelope.filled = envelope.volume - envelope.measure.uncorrected;
  envelope.area = surfaceArea(envelope.mesh);
  const double target = envelope.measure.measure;
  for (int step = 0; options.edge_correction && step < kOffsetSteps; ++step) {
    if (std::abs(envelope.volume - target) <= kVolumeTolerance * target) break;
    envelope.offset += (target - envelope.volume) / envelope.area;
    envelope.mesh = offsetSurface(alpha_surface, envelope.offset);
    envelope.volume = enclosedVolume(envelope.mesh);
    envelope.area = surfaceArea(envelope.mesh);
  }
  if (options.edge_correction && std::abs(envelope.volume - target) > 1e-6 * target) {
    throw Error("the envelope's outward offset did not converge (volume " +
                std::to_string(envelope.volume) + " for " + std::to_string(target) +
                "): the alpha surface is too folded to offset");
  }
  return envelope;
}

SurfaceFormat surfaceFormatOf(const std::string& path) {
  const std::string extension = lowercaseExtension(path);
  if (extension == ".ply") return SurfaceFormat::kPly;
  if (extension == ".stl") return SurfaceFormat::kStl;
  if (extension == ".vtk") return SurfaceFormat::kVtk;
  throw Error(path + ": not a mesh file name this tool writes (.ply, .stl or .vtk)");
}

void writeSurface(const TriangleSurface& surface, SurfaceFormat format, const std::string& comment,
                  std::FILE* out) {
  switch (format) {
    case SurfaceFormat::kPly:
      writePly(surface, comment, out);
      break;
    case SurfaceFormat::kStl:
      writeStl(surface, comment, out);
      break;
    case SurfaceFormat::kVtk:
      writeVtk(surface, comment, out);
      break;
  }
}

void saveSurface(const TriangleSurface& surface, const std::string& path, const std::string& source,
                 const std::string& length_unit) {
  const SurfaceFormat format = surfaceFormatOf(path);
  io::AtomicFile file(path);
  try {
    writeSurface(surface, format, "mcws_envelope of " + source + ", lengths in " + length_unit,
                 file.stream());
  } catch (const Error& e) {
    throw Error("cannot write '" + path + "': " + e.what());
  }
  file.commit();
}

std::string renderEnvelopePng(const TriangleSurface& surface, const std::string& title,
                              const std::string& unit, const std::string& tip) {
  if (surface.triangles.empty()) throw Error("envelope picture: the surface has no triangles");
  io::ScratchDir dir;
  const std::string data = dir.file("triangles.dat"), png = dir.file("envelope.png");
  {
    std::ofstream out(data);
    out.precision(7);
    for (const auto& t : surface.triangles) {  // gnuplot's polygons: corners, blank lines between
      for (const std::uint32_t k : t) {
        const Eigen::Vector3d& v = surface.vertices[k];
        out << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
      }
      out << "\n\n";
    }
    if (!out) throw Error("envelope picture: writing the triangles failed");
  }
  std::ostringstream gp;
  const std::string polygons = "splot " + io::gnuplotQuoted(data) +
                               " with polygons fs solid 1.0 noborder fc rgb '#5b8fc9' notitle\n";
  gp << "set terminal pngcairo noenhanced size 1400,700 font 'Sans,11'\n"
     << "set output " << io::gnuplotQuoted(png) << "\n"
     << "set multiplot layout 1,2 title "
     << io::gnuplotQuoted(title + ": workspace envelope" + (tip.empty() ? "" : " of " + tip) +
                          ", " + std::to_string(surface.triangles.size()) + " triangles")
     << "\nset view equal xyz\nset xyplane 0\nunset colorbox\n"
     << "set pm3d depthorder lighting primary 0.55 specular 0.25\n"
     << "set xlabel " << io::gnuplotQuoted("x [" + unit + "]") << "\nset ylabel "
     << io::gnuplotQuoted("y [" + unit + "]") << "\nset zlabel "
     << io::gnuplotQuoted("z [" + unit + "]") << " rotate parallel\n"
     << "set title 'from the front left, above'\nset view 60, 30\n"
     << polygons << "set title 'from the side (along +y)'\nset view 90, 0\n"
     << polygons << "unset multiplot\n";
  return io::runGnuplot(dir, gp.str(), png);
}

}  // namespace mcws
