// The workspace envelope mesh (mcws_envelope): its volume, area and topology against closed forms
// on hand-built solids, the envelope of a uniform ball against the ball and delaunayMeasure(),
// its files read back by PCL's VTK-based reader, and its datasheet views against hand-worked
// examples (the octahedron's sections, fans of samples seen from above).
#include "mcws/workspace/envelope.h"

#include "mcws/workspace/drawing.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <pcl/PolygonMesh.h>
#include <pcl/io/vtk_lib_io.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "mcws/core/error.h"
#include "mcws/sampling/sampler.h"
#include "test_support.h"

namespace mcws {
namespace {

/// The regular octahedron with vertices at distance r on the axes, faces outward:
/// volume 4/3 r^3, area 4 sqrt(3) r^2.
TriangleSurface octahedron(double r) {
  TriangleSurface s;
  s.vertices = {{r, 0, 0}, {-r, 0, 0}, {0, r, 0}, {0, -r, 0}, {0, 0, r}, {0, 0, -r}};
  // +x +y +z is counter-clockwise from outside; the others by symmetry.
  s.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                 {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return s;
}

TEST(EnvelopeMesh, VolumeAreaAndTopologyOfAnOctahedron) {
  const TriangleSurface s = octahedron(2.0);
  EXPECT_NEAR(enclosedVolume(s), 4.0 / 3.0 * 8.0, 1e-12);
  EXPECT_NEAR(surfaceArea(s), 4.0 * std::sqrt(3.0) * 4.0, 1e-12);
  const SurfaceTopology t = surfaceTopology(s);
  EXPECT_EQ(t.vertices, 6u);
  EXPECT_EQ(t.edges, 12u);
  EXPECT_EQ(t.euler_characteristic, 2);
  EXPECT_TRUE(t.closedAndOriented());
  // Shifted far from the origin the volume keeps its precision (tetrahedra from the centroid).
  TriangleSurface far = s;
  for (auto& v : far.vertices) v += Eigen::Vector3d(1e6, -2e6, 3e6);
  EXPECT_NEAR(enclosedVolume(far), 4.0 / 3.0 * 8.0, 1e-6);
}

TEST(EnvelopeMesh, TopologyFindsFlippedAndMissingTriangles) {
  TriangleSurface flipped = octahedron(1.0);
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  EXPECT_EQ(surfaceTopology(flipped).misoriented_edges, 3u);
  EXPECT_FALSE(surfaceTopology(flipped).closedAndOriented());
  TriangleSurface open = octahedron(1.0);
  open.triangles.pop_back();
  EXPECT_EQ(surfaceTopology(open).open_edges, 3u);
  EXPECT_EQ(surfaceTopology(open).euler_characteristic, 1);  // a disk
}

TEST(EnvelopeMesh, OffsetMovesEachVertexAlongItsNormal) {
  // Each octahedron vertex's four faces are symmetric about its axis: the normal is the axis, and
  // an offset d gives the octahedron of radius r + d.
  const TriangleSurface moved = offsetSurface(octahedron(1.0), 0.25);
  EXPECT_NEAR(enclosedVolume(moved), 4.0 / 3.0 * std::pow(1.25, 3), 1e-12);
  EXPECT_NEAR(moved.vertices[4].z(), 1.25, 1e-15);
}

pcl::PointCloud<pcl::PointXYZ> ball(std::size_t n, std::uint64_t seed) {
  pcl::PointCloud<pcl::PointXYZ> cloud;
  pcl::copyPointCloud(sampleCloud(ShapeSampler(Shape::kBall, seed), n, 0), cloud);
  return cloud;
}

TEST(WorkspaceEnvelope, UniformBallGivesAClosedSphereEnclosingTheMeasuredVolume) {
  const std::size_t n = 30000;
  const double spacing = std::cbrt(4.0 / 3.0 * M_PI / n);  // mean spacing, 0.052
  const Envelope e = workspaceEnvelope(ball(n, 3), MeasureOptions{});
  const SurfaceTopology t = surfaceTopology(e.mesh);
  EXPECT_TRUE(t.closedAndOriented());
  EXPECT_EQ(t.euler_characteristic, 2);
  EXPECT_TRUE(e.manifold);
  EXPECT_NEAR(e.volume / e.measure.measure, 1.0, 1e-6);
  EXPECT_NEAR(e.volume / (4.0 / 3.0 * M_PI), 1.0, 0.005);
  // The offset is the band the samples miss: a fraction of the mean spacing, and the filled
  // cavities and pinches a small share of the volume.
  EXPECT_GT(e.offset, 0.0);
  EXPECT_LT(e.offset, 0.5 * spacing);
  EXPECT_LT(e.filled, 0.005 * e.measure.uncorrected);
  // Every vertex lies within a spacing of the unit sphere.
  for (const auto& v : e.mesh.vertices) EXPECT_NEAR(v.norm(), 1.0, spacing);
}

TEST(WorkspaceEnvelope, WithoutTheCorrectionItIsTheKeptTetrahedraAndTheSameForAnyThreadCount) {
  MeasureOptions options;
  options.edge_correction = false;
  options.alpha_factor = 5.0;
  options.threads = 1;
  const pcl::PointCloud<pcl::PointXYZ> cloud = ball(20000, 4);
  const Envelope one = workspaceEnvelope(cloud, options);
  options.threads = 2;
  const Envelope two = workspaceEnvelope(cloud, options);
  EXPECT_EQ(one.offset, 0.0);
  EXPECT_NEAR(one.volume, one.measure.uncorrected + one.filled, 1e-9);
  EXPECT_EQ(one.mesh.vertices, two.mesh.vertices);
  EXPECT_EQ(one.mesh.triangles, two.mesh.triangles);
}

TEST(WorkspaceEnvelope, ACancelCheckSplitsTheInsertionNotTheMeshAndWhatItThrowsEndsTheCall) {
  // 40000 points: two pieces of the insertion (32768 and 7232), so at least two checks.
  const pcl::PointCloud<pcl::PointXYZ> cloud = ball(40000, 6);
  const Envelope whole = workspaceEnvelope(cloud, MeasureOptions{});
  MeasureOptions options;
  int checks = 0;
  options.cancel_check = [&] { ++checks; };
  const Envelope pieces = workspaceEnvelope(cloud, options);
  EXPECT_GE(checks, 2);
  EXPECT_EQ(pieces.mesh.vertices, whole.mesh.vertices);
  EXPECT_EQ(pieces.mesh.triangles, whole.mesh.triangles);
  EXPECT_EQ(pieces.measure.measure, whole.measure.measure);
  struct Stop {};
  options.cancel_check = [] { throw Stop{}; };
  EXPECT_THROW(workspaceEnvelope(cloud, options), Stop);
}

TEST(WorkspaceEnvelope, FilesReadBackWithTheirVerticesAndTriangles) {
  const TriangleSurface s = octahedron(1.5);
  test::TempDir dir;
  // PCL's VTK-based readers (STL, VTK) fill a pcl::PointCloud<PointXYZ> inside libpcl_io whose
  // vector resize binds to this executable's Eigen allocator; the sanitizer build allocates as the
  // libraries do (EIGEN_MALLOC_ALREADY_ALIGNED, top CMakeLists.txt), so every build reads all
  // three.
  for (const char* name : {"o.ply", "o.stl", "o.vtk"}) {
    const std::string path = dir.file(name);
    std::FILE* out = std::fopen(path.c_str(), "wb");
    ASSERT_NE(out, nullptr);
    writeSurface(s, surfaceFormatOf(path), "solid octahedron, r = 1.5", out);
    std::fclose(out);
    pcl::PolygonMesh mesh;
    ASSERT_GT(pcl::io::loadPolygonFile(path, mesh), 0) << name;
    EXPECT_EQ(mesh.polygons.size(), 8u) << name;
    // STL repeats each corner per triangle (VTK's reader may merge them); the corners are
    // the octahedron's vertices either way. The floats are read from the blob.
    const std::size_t points = mesh.cloud.width * mesh.cloud.height;
    ASSERT_GE(points, 6u) << name;
    ASSERT_GE(mesh.cloud.fields.size(), 3u) << name;
    for (std::size_t i = 0; i < points; ++i) {
      float xyz[3];
      for (int axis = 0; axis < 3; ++axis) {
        const pcl::PCLPointField& field = mesh.cloud.fields[axis];
        ASSERT_EQ(field.name, std::string(1, static_cast<char>('x' + axis))) << name;
        std::memcpy(&xyz[axis], &mesh.cloud.data[i * mesh.cloud.point_step + field.offset],
                    sizeof(float));
      }
      EXPECT_NEAR(std::sqrt(xyz[0] * xyz[0] + xyz[1] * xyz[1] + xyz[2] * xyz[2]), 1.5f, 1e-6f)
          << name;
    }
  }
  EXPECT_THROW(surfaceFormatOf("envelope.obj"), Error);
  EXPECT_EQ(surfaceFormatOf("ENVELOPE.PLY"), SurfaceFormat::kPly);
}

TEST(EnvelopeDrawing, SectionsOfAnOctahedronThroughItsAxis) {
  // Vertices on the axes at 1.5: the plane y = 0 holds four of them (they count as in front of
  // it) and cuts the square |s| + |z| <= 1.5, area 4.5, counter-clockwise.
  const TriangleSurface s = octahedron(1.5);
  const EnvelopeSection front = envelopeSection(s, 0.0);
  ASSERT_EQ(front.loops.size(), 1u);
  EXPECT_NEAR(front.area, 4.5, 1e-12);
  EXPECT_NEAR(front.front_reach, 1.5, 1e-12);
  EXPECT_NEAR(front.back_reach, 1.5, 1e-12);
  EXPECT_NEAR(front.highest, 1.5, 1e-12);
  EXPECT_NEAR(front.lowest, -1.5, 1e-12);
  // At 45 degrees: |x| + |y| <= 1.5 - |z| along (1, 1) / sqrt 2 reaches s = (1.5 - |z|) / sqrt 2,
  // a rhombus of area 4.5 / sqrt 2.
  const EnvelopeSection diagonal = envelopeSection(s, M_PI / 4);
  ASSERT_EQ(diagonal.loops.size(), 1u);
  EXPECT_NEAR(diagonal.area, 4.5 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(diagonal.front_reach, 1.5 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(diagonal.back_reach, 1.5 / std::sqrt(2.0), 1e-12);
  // Turned inside out the loop runs clockwise: a hole.
  TriangleSurface inside_out = s;
  for (auto& t : inside_out.triangles) std::swap(t[1], t[2]);
  EXPECT_NEAR(envelopeSection(inside_out, 0.3).area, -envelopeSection(s, 0.3).area, 1e-12);
}

TEST(EnvelopeDrawing, TwoBodiesGiveTwoLoopsAndAMissedOrOpenSurfaceIsRefused) {
  TriangleSurface two = octahedron(1.0);
  const std::size_t n = two.vertices.size();
  for (std::size_t i = 0; i < n; ++i)
    two.vertices.push_back(two.vertices[i] + Eigen::Vector3d(-5, 0, 0));
  for (std::size_t i = 0, m = two.triangles.size(); i < m; ++i) {
    auto t = two.triangles[i];
    for (auto& k : t) k += static_cast<std::uint32_t>(n);
    two.triangles.push_back(t);
  }
  const EnvelopeSection section = envelopeSection(two, 0.0);
  EXPECT_EQ(section.loops.size(), 2u);
  EXPECT_NEAR(section.area, 2 * 2.0, 1e-12);  // two squares |s - c| + |z| <= 1
  EXPECT_NEAR(section.back_reach, 6.0, 1e-12);
  EXPECT_NEAR(section.front_reach, 1.0, 1e-12);
  // Moved off the axis along y by 2, the plane y = 0 misses it.
  TriangleSurface away = octahedron(1.0);
  for (auto& v : away.vertices) v.y() += 2.0;
  EXPECT_THROW(envelopeSection(away, 0.0), Error);
  TriangleSurface open = octahedron(1.0);
  open.triangles.pop_back();
  EXPECT_THROW(envelopeSection(open, 0.0), Error);
}

/// Points at distances `radii` from the z axis at whole degrees from `from` up to `to`
/// (counter-clockwise, wrapping past 180): the centres of 1-degree bins.
void addFan(pcl::PointCloud<pcl::PointXYZ>& cloud, int from, int to,
            std::initializer_list<double> radii) {
  for (int d = from; d != to; d = d == 179 ? -180 : d + 1) {
    const double a = d * M_PI / 180.0;
    for (const double r : radii)
      cloud.push_back(pcl::PointXYZ(r * std::cos(a), r * std::sin(a), 0.1f * d));
  }
}

TEST(EnvelopeDrawing, TopViewOfSamplesBinByBin) {
  const double degree = M_PI / 180.0;
  // A fan from -30 to 44 degrees between 2 and 5, its bin at 10 degrees reaching only 4.2 (less
  // than 90 % of 5), and one sample 1.5 behind the axis.
  pcl::PointCloud<pcl::PointXYZ> cloud;
  addFan(cloud, -30, 10, {2.0, 3.3, 5.0});
  addFan(cloud, 10, 11, {2.0, 4.2});
  addFan(cloud, 11, 45, {2.0, 5.0});
  addFan(cloud, 179, -180, {1.5});
  const EnvelopeTopView view = sampleTopView(cloud, 360);
  ASSERT_EQ(view.outer.size(), 360u);
  for (int k = 0; k < 360; ++k) {
    const int d = k - 180;  // bin k is centred on d degrees
    if (d >= -30 && d < 45) {
      EXPECT_NEAR(view.inner[k], 2.0, 1e-6) << d;
      EXPECT_NEAR(view.outer[k], d == 10 ? 4.2 : 5.0, 1e-6) << d;
    } else if (d == 179) {
      EXPECT_NEAR(view.outer[k], 1.5, 1e-6);
    } else {
      EXPECT_TRUE(std::isnan(view.outer[k]) && std::isnan(view.inner[k])) << d;
    }
  }
  EXPECT_NEAR(view.max_reach, 5.0, 1e-6);
  EXPECT_NEAR(view.min_reach, 1.5, 1e-6);
  // The longest run at full reach is -30..9 (40 bins, 39 degrees centre to centre), the 4.2 bin
  // cutting off 11..44 (34 bins).
  EXPECT_NEAR(view.sweep, 39 * degree, 1e-12);
  EXPECT_NEAR(view.sweep_from, -30 * degree, 1e-12);
  EXPECT_NEAR(view.sweep_to, 9 * degree, 1e-12);

  // A run across +-180 degrees (150 up to -151), and the whole circle.
  pcl::PointCloud<pcl::PointXYZ> back;
  addFan(back, 150, -150, {1.0});
  addFan(back, 0, 10, {0.5});
  const EnvelopeTopView behind = sampleTopView(back, 360);
  EXPECT_NEAR(behind.sweep, 59 * degree, 1e-12);
  EXPECT_NEAR(behind.sweep_from, 150 * degree, 1e-12);
  EXPECT_NEAR(behind.sweep_to, -151 * degree, 1e-12);
  pcl::PointCloud<pcl::PointXYZ> ring;
  addFan(ring, -180, 179, {3.0});
  addFan(ring, 179, -180, {3.0});
  const EnvelopeTopView round = sampleTopView(ring, 360);
  EXPECT_NEAR(round.sweep, 2 * M_PI, 1e-12);
  EXPECT_NEAR(round.sweep_from, -M_PI, 1e-12);
  EXPECT_NEAR(round.sweep_to, M_PI, 1e-12);

  EXPECT_THROW(sampleTopView(cloud, 4), Error);
  pcl::PointCloud<pcl::PointXYZ> none;
  none.push_back(pcl::PointXYZ(std::nanf(""), 0.0f, 0.0f));
  EXPECT_THROW(sampleTopView(none, 360), Error);
}

TEST(EnvelopeDrawing, PngAndSvgFilesAndTheirNames) {
  pcl::PointCloud<pcl::PointXYZ> corners;
  for (const auto& v : octahedron(1.5).vertices)
    corners.push_back(pcl::PointXYZ(v.x(), v.y(), v.z()));
  const EnvelopeDrawing drawing = envelopeDrawing(octahedron(1.5), corners, 0.0, 72);
  EXPECT_NEAR(drawing.highest, 1.5, 1e-12);
  EXPECT_NEAR(drawing.lowest, -1.5, 1e-12);
  const std::string png = renderEnvelopeDrawing(drawing, DrawingFormat::kPng, "octahedron", "m");
  EXPECT_EQ(png.rfind("\x89PNG", 0), 0u);
  const std::string svg = renderEnvelopeDrawing(drawing, DrawingFormat::kSvg, "octahedron", "m");
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("1.50 m"), std::string::npos);  // a dimension with its unit
  EXPECT_EQ(drawingFormatOf("range.SVG"), DrawingFormat::kSvg);
  EXPECT_EQ(drawingFormatOf("range.png"), DrawingFormat::kPng);
  EXPECT_THROW(drawingFormatOf("range.pdf"), Error);
}

}  // namespace
}  // namespace mcws
