// The envelope from the shell of exposed points (MeasureOptions::shell, the default) against the
// envelope from the triangulation of every point (shell = false), the independent reference: the
// same triangles over the same vertices, the same volume, on a ball, a hollow ball (a cavity), a
// solid torus (a handle), the de-icing arm's refined cloud and a lattice (cospherical points
// everywhere, ties CGAL breaks by its symbolic perturbation).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <string>

#include "mcws/core/error.h"
#include "mcws/filters/orthant_boundary.h"
#include "mcws/kinematics/robot_yaml.h"
#include "mcws/sampling/sampler.h"
#include "mcws/workspace/envelope.h"
#include "mcws/workspace/refine.h"
#include "test_support.h"

namespace mcws {
namespace {

/// The two envelopes' volumes and vertices differ by rounding only: the kept tetrahedra's total
/// is summed over other tetrahedra where the shell leaves points out (to about 1e-15 of it), which
/// moves the offset fitted to the measured volume by as little (relative, of the cloud's extent).
constexpr double kShellTolerance = 1e-11;

/// `n` points uniform in the part of the box [-1, 1]^3 that `inside` accepts (rejection, a fixed
/// seed).
template <typename Inside>
pcl::PointCloud<pcl::PointXYZ> uniformIn(std::size_t n, std::uint64_t seed, const Inside& inside) {
  std::mt19937_64 rng(seed);
  const auto coordinate = [&] { return 2.0 * static_cast<double>(rng() >> 11) * 0x1.0p-53 - 1.0; };
  pcl::PointCloud<pcl::PointXYZ> cloud;
  while (cloud.size() < n) {
    const double x = coordinate(), y = coordinate(), z = coordinate();
    if (inside(x, y, z)) cloud.push_back(pcl::PointXYZ(x, y, z));
  }
  return cloud;
}

/// The envelope from the shell and from every point: the same triangles, vertices and volume,
/// and the shell smaller than the cloud (so the comparison is not of one computation with
/// itself). \return the shell's.
Envelope expectShellEnvelopeIsTheWholeOne(const pcl::PointCloud<pcl::PointXYZ>& cloud,
                                          MeasureOptions options, const std::string& name) {
  SCOPED_TRACE(name + ", threads " + std::to_string(options.threads));
  options.shell = false;
  const Envelope whole = workspaceEnvelope(cloud, options);
  options.shell = true;
  const Envelope shell = workspaceEnvelope(cloud, options);
  EXPECT_LT(shell.measure.triangulated, whole.measure.triangulated);
  EXPECT_EQ(shell.mesh.triangles, whole.mesh.triangles);
  EXPECT_EQ(shell.mesh.vertices.size(), whole.mesh.vertices.size());
  if (shell.mesh.vertices.size() != whole.mesh.vertices.size()) return shell;
  double extent = 0.0, moved = 0.0;
  for (std::size_t k = 0; k < whole.mesh.vertices.size(); ++k) {
    extent = std::max(extent, whole.mesh.vertices[k].cwiseAbs().maxCoeff());
    moved = std::max(moved, (shell.mesh.vertices[k] - whole.mesh.vertices[k]).norm());
  }
  EXPECT_LE(moved, kShellTolerance * extent);
  if (!options.edge_correction) {  // no offset
    EXPECT_EQ(shell.mesh.vertices, whole.mesh.vertices);
  }
  EXPECT_NEAR(shell.volume / whole.volume, 1.0, kShellTolerance);
  EXPECT_NEAR(shell.measure.uncorrected / whole.measure.uncorrected, 1.0, kShellTolerance);
  EXPECT_EQ(shell.measure.outside, whole.measure.outside);
  EXPECT_EQ(shell.manifold, whole.manifold);
  EXPECT_TRUE(surfaceTopology(shell.mesh).closedAndOriented());
  return shell;
}

TEST(ShellEnvelope, BallWithAndWithoutTheEdgeCorrectionOnOneAndTwoThreads) {
  const std::size_t n = 12000 / test::kSanitizerShrink;
  const auto ball = [](double x, double y, double z) { return x * x + y * y + z * z <= 1.0; };
  const pcl::PointCloud<pcl::PointXYZ> cloud = uniformIn(n, 1, ball);
  MeasureOptions efron, none;
  none.edge_correction = false;
  none.alpha_factor = 5.0;
  for (const int threads : {1, 2}) {
    efron.threads = none.threads = threads;
    expectShellEnvelopeIsTheWholeOne(cloud, efron, "ball, Efron");
    expectShellEnvelopeIsTheWholeOne(cloud, none, "ball, no correction");
  }
  // At alpha 3 the shell is thinner: some boundary vertices' stars reach left-out points, which
  // join before the surface is taken (as the edge correction needs them too).
  none.alpha_factor = 3.0;
  expectShellEnvelopeIsTheWholeOne(cloud, none, "ball, no correction, alpha 3");
}

TEST(ShellEnvelope, HollowBallAndSolidTorus) {
  // Halved, not shrunk 8x, under the sanitizers: at 1500 points every point of the hollow ball
  // and of the torus is exposed (no shell to compare), and neither shape is there to find.
  const std::size_t n = 12000 / (test::kSanitizerShrink > 1 ? 2 : 1);
  // A ball with a ball-shaped cavity of radius 0.6: the envelope fills the cavity (a sphere,
  // Euler characteristic 2), its volume, 4/3 pi 0.6^3 = 0.905, in `filled`.
  const auto hollow = [](double x, double y, double z) {
    const double r2 = x * x + y * y + z * z;
    return r2 <= 1.0 && r2 >= 0.36;
  };
  const pcl::PointCloud<pcl::PointXYZ> hollow_cloud = uniformIn(n, 2, hollow);
  const Envelope hollow_envelope =
      expectShellEnvelopeIsTheWholeOne(hollow_cloud, MeasureOptions{}, "hollow ball");
  EXPECT_EQ(surfaceTopology(hollow_envelope.mesh).euler_characteristic, 2);
  // The kept tetrahedra stop about a spacing (0.07) short of the cavity's sphere.
  EXPECT_NEAR(hollow_envelope.filled, 4.0 / 3.0 * M_PI * std::pow(0.6, 3), 0.15);
  // A solid torus (major radius 0.65, minor 0.3): one handle (Euler characteristic 0).
  const auto torus = [](double x, double y, double z) {
    const double ring = std::hypot(x, y) - 0.65;
    return ring * ring + z * z <= 0.09;
  };
  const pcl::PointCloud<pcl::PointXYZ> torus_cloud = uniformIn(n, 3, torus);
  MeasureOptions sparse;  // alpha 2: the edge pinches often, the repairs fill and drop
  sparse.alpha_factor = 2.0;
  expectShellEnvelopeIsTheWholeOne(torus_cloud, sparse, "torus, alpha 2");
  const Envelope torus_envelope =
      expectShellEnvelopeIsTheWholeOne(torus_cloud, MeasureOptions{}, "torus");
  EXPECT_EQ(surfaceTopology(torus_envelope.mesh).euler_characteristic, 0);
}

TEST(ShellEnvelope, RefinedDeicingCloud) {
  // mcws_sample, mcws_boundary (3-D), mcws_refine and mcws_envelope --correction none in small:
  // refined samples crowd onto the joint-limit surfaces, the spacing varies by orders of
  // magnitude and the surface pinches where the wedge's flat sides meet.
  const std::size_t n = 10000 / test::kSanitizerShrink;
  const Robot robot = loadRobot(test::robotPath("deicing"));
  auto plain =
      std::make_shared<pcl::PointCloud<WorkspacePoint>>(sampleCloud(RobotSampler(robot, {}), n, 2));
  OrthantBoundary<WorkspacePoint> boundary;
  boundary.setInputCloud(plain);
  pcl::PointCloud<WorkspacePoint> rim;
  boundary.filter(rim);
  *plain += sampleCloud(RefineSampler(robot, rim, {}), n, 3);
  pcl::PointCloud<pcl::PointXYZ> cloud;
  for (const auto& p : *plain) cloud.push_back(pcl::PointXYZ(p.x, p.y, p.z));
  MeasureOptions none;  // as mcws_envelope --correction none
  none.edge_correction = false;
  none.alpha_factor = 5.0;
  expectShellEnvelopeIsTheWholeOne(cloud, none, "refined de-icing");
  expectShellEnvelopeIsTheWholeOne(cloud, MeasureOptions{}, "refined de-icing, Efron");
}

TEST(ShellEnvelope, LatticeBallAndAPlane) {
  // The grid points of a ball of 12 steps: every cell's circumsphere passes through more than
  // four points; the triangulations break the ties alike.
  pcl::PointCloud<pcl::PointXYZ> lattice;
  const int r = 12;
  for (int i = -r; i <= r; ++i) {
    for (int j = -r; j <= r; ++j) {
      for (int k = -r; k <= r; ++k) {
        if (i * i + j * j + k * k <= r * r) lattice.push_back(pcl::PointXYZ(i, j, k));
      }
    }
  }
  expectShellEnvelopeIsTheWholeOne(lattice, MeasureOptions{}, "lattice ball");
  // All points in a plane: no volume, the same refusal either way.
  pcl::PointCloud<pcl::PointXYZ> flat;
  for (int i = 0; i < 20; ++i) {
    for (int j = 0; j < 20; ++j) flat.push_back(pcl::PointXYZ(i, j, 0.0f));
  }
  for (const bool shell : {false, true}) {
    MeasureOptions options;
    options.shell = shell;
    EXPECT_THROW(
        {
          try {
            workspaceEnvelope(flat, options);
          } catch (const Error& e) {
            EXPECT_STREQ(e.what(), "the points lie in a plane: no volume");
            throw;
          }
        },
        Error);
  }
}

}  // namespace
}  // namespace mcws
