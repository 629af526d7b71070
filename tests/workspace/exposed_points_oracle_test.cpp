// exposedPoints() against the Delaunay triangulation of every point (CGAL): a point is exposed at
// r exactly when it is on the convex hull or a vertex of a simplex whose circumradius is at least
// r. Clouds that a too tight bound would get wrong (flat faces, voids just wider and narrower than
// the radius, lattices with radii at their circumradii, clusters, radii that vary per point), in
// 2-D and 3-D, and how far beyond that set the flags reach on uniform clouds.
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "mcws/workspace/exposed_points.h"
#include "workspace/shape_cloud.h"

namespace mcws {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vertex3 = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, K>;
using Delaunay3 = CGAL::Delaunay_triangulation_3<
    K, CGAL::Triangulation_data_structure_3<Vertex3, CGAL::Delaunay_triangulation_cell_base_3<K>>>;
using Vertex2 = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, K>;
using Delaunay2 = CGAL::Delaunay_triangulation_2<
    K, CGAL::Triangulation_data_structure_2<Vertex2, CGAL::Triangulation_face_base_2<K>>>;

/// The points an empty ball of their radius touches: on the hull, or a vertex of a Delaunay
/// simplex whose circumradius is at least the radius.
std::vector<char> trulyExposed(const pcl::PointCloud<pcl::PointXYZ>& cloud, int dimensions,
                               const std::vector<double>& radius) {
  std::vector<char> exposed(cloud.size(), 0);
  const auto mark = [&](std::uint32_t v, double squared) {
    if (squared >= radius[v] * radius[v]) exposed[v] = 1;
  };
  if (dimensions == 3) {
    std::vector<std::pair<K::Point_3, std::uint32_t>> input;
    for (std::uint32_t i = 0; i < cloud.size(); ++i)
      input.emplace_back(K::Point_3(cloud[i].x, cloud[i].y, cloud[i].z), i);
    const Delaunay3 dt(input.begin(), input.end());
    for (const auto c : dt.all_cell_handles()) {
      const bool infinite = dt.is_infinite(c);
      const double squared =
          infinite ? HUGE_VAL
                   : CGAL::squared_radius(c->vertex(0)->point(), c->vertex(1)->point(),
                                          c->vertex(2)->point(), c->vertex(3)->point());
      for (int k = 0; k < 4; ++k) {
        if (!dt.is_infinite(c->vertex(k))) mark(c->vertex(k)->info(), squared);
      }
    }
  } else {
    std::vector<std::pair<K::Point_2, std::uint32_t>> input;
    for (std::uint32_t i = 0; i < cloud.size(); ++i)
      input.emplace_back(K::Point_2(cloud[i].x, cloud[i].y), i);
    const Delaunay2 dt(input.begin(), input.end());
    for (const auto f : dt.all_face_handles()) {
      const bool infinite = dt.is_infinite(f);
      const double squared =
          infinite ? HUGE_VAL
                   : CGAL::squared_radius(f->vertex(0)->point(), f->vertex(1)->point(),
                                          f->vertex(2)->point());
      for (int k = 0; k < 3; ++k) {
        if (!dt.is_infinite(f->vertex(k))) mark(f->vertex(k)->info(), squared);
      }
    }
  }
  return exposed;
}

struct Outcome {
  std::size_t wrong{0};    ///< flagged covered, but an empty ball of their radius touches them
  std::size_t truly{0};    ///< exposed by the triangulation
  std::size_t flagged{0};  ///< exposed by exposedPoints()
};

/// exposedPoints() (on 1 and 2 threads: the same flags) against trulyExposed().
Outcome compare(const pcl::PointCloud<pcl::PointXYZ>& cloud, int dimensions,
                const std::vector<double>& radius) {
  const ExposedPoints flags = exposedPoints(cloud, dimensions, radius, 2);
  EXPECT_EQ(exposedPoints(cloud, dimensions, radius, 1).exposed, flags.exposed);
  const std::vector<char> truly = trulyExposed(cloud, dimensions, radius);
  Outcome outcome;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    outcome.wrong += truly[i] && !flags.exposed[i];
    outcome.truly += truly[i];
    outcome.flagged += flags.exposed[i];
  }
  EXPECT_EQ(outcome.flagged, flags.count);
  return outcome;
}

/// A uniform cloud of `n` points in the box [-1, 1]^D, drawn with `seed`, less those for which
/// `drop` says so.
template <typename Drop>
pcl::PointCloud<pcl::PointXYZ> uniformBox(int dimensions, std::size_t n, unsigned seed,
                                          const Drop& drop) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  pcl::PointCloud<pcl::PointXYZ> cloud;
  while (cloud.size() < n) {
    pcl::PointXYZ p(u(rng), u(rng), dimensions == 3 ? u(rng) : 0.0f);
    if (!drop(p)) cloud.push_back(p);
  }
  return cloud;
}

TEST(ExposedPointsOracle, VoidsJustWiderAndNarrowerThanTheRadius) {
  // A uniform cube and square with a round void of radius 0.98, 1 and 1.02 times the points'
  // radius (3.5 spacings): the points on its rim are exposed only when the void is wide enough,
  // and the test must tell them apart from the covered ones around.
  for (const int dimensions : {2, 3}) {
    const std::size_t n = dimensions == 3 ? 30000 : 20000;
    const double spacing = std::pow(std::pow(2.0, dimensions) / n, 1.0 / dimensions);
    const double r = 3.5 * spacing;
    for (const double hole : {0.98, 1.0, 1.02}) {
      const auto cloud = uniformBox(dimensions, n, 7, [&](const pcl::PointXYZ& p) {
        return std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z) < hole * r;
      });
      const Outcome outcome = compare(cloud, dimensions, std::vector<double>(cloud.size(), r));
      EXPECT_EQ(outcome.wrong, 0u) << dimensions << "-D, void " << hole;
    }
  }
}

TEST(ExposedPointsOracle, PointsJustInsideAFlatFace) {
  // A jittered lattice whose top layer is a flat face, with points a small fraction of a
  // spacing below it: covered only when no empty ball reaches them between the face's points.
  for (const int dimensions : {2, 3}) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> jitter(-0.3f, 0.3f), below(0.0f, 0.2f);
    pcl::PointCloud<pcl::PointXYZ> cloud;
    const int side = dimensions == 3 ? 24 : 120, layers = dimensions == 3 ? 24 : 120;
    for (int z = 0; z < (dimensions == 3 ? layers : 1); ++z)
      for (int y = 0; y < (dimensions == 3 ? side : layers); ++y)
        for (int x = 0; x < side; ++x) {
          const bool top = dimensions == 3 ? z + 1 == layers : y + 1 == layers;
          pcl::PointXYZ p(x + jitter(rng), y + jitter(rng), dimensions == 3 ? z + jitter(rng) : 0);
          float& up = dimensions == 3 ? p.z : p.y;
          if (top) up = static_cast<float>(layers - 1) - below(rng);  // the face, a little rough
          cloud.push_back(p);
        }
    for (const double r : {1.5, 2.5, 4.0}) {
      const Outcome outcome = compare(cloud, dimensions, std::vector<double>(cloud.size(), r));
      EXPECT_EQ(outcome.wrong, 0u) << dimensions << "-D, radius " << r;
    }
  }
}

TEST(ExposedPointsOracle, LatticesAtTheirCircumradius) {
  // A square and a cubic lattice of spacing 1 (coordinates exact): every Delaunay simplex has
  // circumradius sqrt(D) / 2, so at that radius every point is exposed (an empty ball passes
  // through each), and a little above it none but the faces' points are (the proof's cells, of
  // half the radius, need a radius about twice the circumradius to tell).
  for (const int dimensions : {2, 3}) {
    pcl::PointCloud<pcl::PointXYZ> cloud;
    const int side = dimensions == 3 ? 20 : 60;
    for (int z = 0; z < (dimensions == 3 ? side : 1); ++z)
      for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) cloud.push_back(pcl::PointXYZ(x, y, z));
    const double circumradius = std::sqrt(static_cast<double>(dimensions)) / 2.0;
    for (const double r : {circumradius, circumradius * 1.2, 2.0, 3.0}) {
      const Outcome outcome = compare(cloud, dimensions, std::vector<double>(cloud.size(), r));
      EXPECT_EQ(outcome.wrong, 0u) << dimensions << "-D, radius " << r;
      if (r == circumradius) {
        EXPECT_EQ(outcome.flagged, cloud.size()) << dimensions << "-D";
      } else if (r >= 2.0) {
        EXPECT_LT(outcome.flagged, cloud.size() / 2) << dimensions << "-D, radius " << r;
      }
    }
  }
}

TEST(ExposedPointsOracle, ClustersWithRadiiThatVaryPerPoint) {
  // Clusters of different densities (so several radius classes and grids) with gaps between
  // them, each point's radius a multiple of its cluster's spacing that varies from point to point.
  for (const int dimensions : {2, 3}) {
    std::mt19937 rng(5);
    std::normal_distribution<float> normal(0.0f, 1.0f);
    pcl::PointCloud<pcl::PointXYZ> cloud;
    std::vector<double> radius;
    const std::vector<double> spreads{0.05, 0.2, 1.0};
    for (std::size_t c = 0; c < spreads.size(); ++c) {
      const std::size_t n = dimensions == 3 ? 8000 : 6000;
      const float cx = 4.0f * static_cast<float>(c);
      const double spacing = spreads[c] * std::pow(1.0 / n, 1.0 / dimensions) * 4.0;
      for (std::size_t k = 0; k < n; ++k) {
        const float s = static_cast<float>(spreads[c]);
        cloud.push_back(pcl::PointXYZ(cx + s * normal(rng), s * normal(rng),
                                      dimensions == 3 ? s * normal(rng) : 0.0f));
        radius.push_back((1.5 + 2.5 * ((k * 7919) % 1000) / 1000.0) * spacing);
      }
    }
    const Outcome outcome = compare(cloud, dimensions, radius);
    EXPECT_EQ(outcome.wrong, 0u) << dimensions << "-D";
    EXPECT_LT(outcome.flagged, cloud.size()) << dimensions << "-D";
  }
}

TEST(ExposedPointsOracle, CloseToTheTriangulation) {
  // A uniform ball and disk at 3 mean spacings: the flags are a superset of the triangulation's
  // exposed points, and the interior is proven covered (the exposed shell is 2 to 4 radii deep,
  // exposedPoints(): about 6 and 4 times the triangulation's count on these clouds).
  for (const Shape shape : {Shape::kBall, Shape::kDisk}) {
    const int dimensions = shape == Shape::kBall ? 3 : 2;
    const auto cloud = test::shapeCloud(shape, 100000, 3);
    const double spacing = std::pow(shapeMeasure(shape) / cloud.size(), 1.0 / dimensions);
    const Outcome outcome =
        compare(cloud, dimensions, std::vector<double>(cloud.size(), 3.0 * spacing));
    EXPECT_EQ(outcome.wrong, 0u) << dimensions << "-D";
    EXPECT_LT(outcome.flagged, 8 * outcome.truly) << dimensions << "-D, " << outcome.truly;
    std::printf("%d-D: %zu flagged, %zu exposed by the triangulation\n", dimensions,
                outcome.flagged, outcome.truly);
  }
}

}  // namespace
}  // namespace mcws
