// The workspace envelope mesh (mcws_envelope): its volume, area and topology against closed forms
// on hand-built solids, the envelope of a uniform ball against the ball and delaunayMeasure(),
// and its files read back by PCL's VTK-based reader.
#include "mcws/workspace/envelope.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <pcl/PolygonMesh.h>
#include <pcl/io/vtk_lib_io.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "mcws/core/error.h"
#include "mcws/workspace/sampler.h"
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

TEST(WorkspaceEnvelope, FilesReadBackWithTheirVerticesAndTriangles) {
  const TriangleSurface s = octahedron(1.5);
  test::TempDir dir;
  for (const char* name : {"o.ply", "o.stl", "o.vtk"}) {
    const std::string path = dir.file(name);
    std::FILE* out = std::fopen(path.c_str(), "wb");
    ASSERT_NE(out, nullptr);
    writeSurface(s, meshFormatOf(path), "solid octahedron, r = 1.5", out);
    std::fclose(out);
    pcl::PolygonMesh mesh;
    ASSERT_GT(pcl::io::loadPolygonFile(path, mesh), 0) << name;
    EXPECT_EQ(mesh.polygons.size(), 8u) << name;
    pcl::PointCloud<pcl::PointXYZ> points;
    pcl::fromPCLPointCloud2(mesh.cloud, points);
    // STL repeats each corner per triangle (VTK's reader may merge them); the corners are
    // the octahedron's vertices either way.
    for (const auto& p : points) EXPECT_NEAR(p.getVector3fMap().norm(), 1.5f, 1e-6f) << name;
    EXPECT_GE(points.size(), 6u) << name;
  }
  EXPECT_THROW(meshFormatOf("envelope.obj"), Error);
  EXPECT_EQ(meshFormatOf("ENVELOPE.PLY"), MeshFormat::kPly);
}

}  // namespace
}  // namespace mcws
