#include "mcws/workspace/exposed_points.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/sampling/sampler.h"
#include "mcws/workspace/detail/radius_classes.h"
#include "workspace/shape_cloud.h"

namespace mcws {
namespace {

using test::shapeCloud;

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vertex = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, K>;
using Delaunay = CGAL::Delaunay_triangulation_3<
    K, CGAL::Triangulation_data_structure_3<Vertex, CGAL::Delaunay_triangulation_cell_base_3<K>>>;

/// Counts the covered points that are a vertex of a Delaunay tetrahedron (of every point, CGAL)
/// whose circumradius is at least the point's radius: the circumball is empty and its sphere
/// passes through the vertex, so such a vertex is exposed and calling it covered is wrong.
std::size_t wronglyCovered(const pcl::PointCloud<pcl::PointXYZ>& cloud,
                           const std::vector<double>& radius, const ExposedPoints& flags) {
  std::vector<std::pair<K::Point_3, std::uint32_t>> input;
  for (std::uint32_t i = 0; i < cloud.size(); ++i)
    input.emplace_back(K::Point_3(cloud[i].x, cloud[i].y, cloud[i].z), i);
  const Delaunay dt(input.begin(), input.end());
  std::vector<char> wrong(cloud.size(), 0);
  for (const auto c : dt.finite_cell_handles()) {
    const double r = std::sqrt(CGAL::squared_radius(c->vertex(0)->point(), c->vertex(1)->point(),
                                                    c->vertex(2)->point(), c->vertex(3)->point()));
    for (int k = 0; k < 4; ++k) {
      const std::uint32_t v = c->vertex(k)->info();
      if (!flags.exposed[v] && r >= radius[v]) wrong[v] = 1;
    }
  }
  std::size_t count = 0;
  for (const char w : wrong) count += w;
  return count;
}

TEST(ExposedPoints, NoCoveredPointIsAVertexOfAnEmptyBallOfItsRadius) {
  // Uniform radii of 3 and 1.5 mean spacings, and radii that vary from point to point (every
  // class of the grid), on a ball and a cube (edges and corners).
  for (const Shape shape : {Shape::kBall, Shape::kBox}) {
    const auto cloud = shapeCloud(shape, 20000, 3);
    const double spacing = std::cbrt(shapeMeasure(shape) / cloud.size());
    for (const double factor : {3.0, 1.5, 0.0}) {
      std::vector<double> radius(cloud.size());
      for (std::size_t i = 0; i < cloud.size(); ++i) {
        radius[i] =
            factor > 0.0 ? factor * spacing : (1.5 + 3.0 * ((i * 7919) % 1000) / 1000.0) * spacing;
      }
      const ExposedPoints flags = exposedPoints(cloud, 3, radius, 2);
      EXPECT_EQ(wronglyCovered(cloud, radius, flags), 0u) << factor;
      // Not trivially right: the interior is proven covered at 3 spacings (the ball is 17
      // spacings in radius; the exposed shell is 3-5 spacings deep, 61 % of its points).
      if (factor == 3.0) {
        EXPECT_LT(flags.count, cloud.size() * 3 / 4) << static_cast<int>(shape);
      }
      std::size_t count = 0;
      for (const char e : flags.exposed) count += e;
      EXPECT_EQ(count, flags.count);
    }
  }
}

TEST(ExposedPoints, ThePointsOnAnEmptyBallAreExposed) {
  // A cubic lattice of spacing 1 in [-14, 14]^3 without the points within 4 of the origin: the
  // empty ball of radius 4 around it touches (4, 0, 0) and its five mirror images, which must be
  // exposed at radius 4 (and at 3.9: a smaller ball inside the void touches them too), while
  // (9, 0, 0), between the void and the faces, is covered.
  pcl::PointCloud<pcl::PointXYZ> lattice;
  for (int x = -14; x <= 14; ++x)
    for (int y = -14; y <= 14; ++y)
      for (int z = -14; z <= 14; ++z)
        if (x * x + y * y + z * z >= 16) lattice.push_back(pcl::PointXYZ(x, y, z));
  for (const double r : {4.0, 3.9}) {
    const ExposedPoints flags =
        exposedPoints(lattice, 3, std::vector<double>(lattice.size(), r), 1);
    for (std::size_t i = 0; i < lattice.size(); ++i) {
      const auto& p = lattice[i];
      const int far = std::abs(p.x) + std::abs(p.y) + std::abs(p.z);
      if (far == 4 && (p.x == 0) + (p.y == 0) + (p.z == 0) == 2) {
        EXPECT_TRUE(flags.exposed[i]) << p.x << " " << p.y << " " << p.z;
      }
      if (p.x == 9 && p.y == 0 && p.z == 0) {
        EXPECT_FALSE(flags.exposed[i]) << r;
      }
    }
  }
}

TEST(ExposedPoints, TwoDimensionsIgnoreZAndRejectBadArguments) {
  // A disk's rim is exposed, its centre covered (but where chance leaves two neighbouring cells
  // nearly empty: a few per cent); z plays no part.
  auto cloud = shapeCloud(Shape::kDisk, 20000, 5);
  for (std::size_t i = 0; i < cloud.size(); ++i) cloud[i].z = static_cast<float>(i % 7);
  const double spacing = std::sqrt(M_PI / cloud.size());
  const ExposedPoints flags =
      exposedPoints(cloud, 2, std::vector<double>(cloud.size(), 3 * spacing));
  std::size_t rim = 0, centre_covered = 0, centre = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const double r = std::hypot(cloud[i].x, cloud[i].y);
    if (r > 1.0 - spacing) rim += flags.exposed[i];
    if (r < 0.5) {
      ++centre;
      centre_covered += !flags.exposed[i];
    }
  }
  EXPECT_GT(rim, 0u);
  EXPECT_GT(centre_covered, 0.9 * centre);
  EXPECT_THROW(exposedPoints(cloud, 4, std::vector<double>(cloud.size(), 1.0)), Error);
  EXPECT_THROW(exposedPoints(cloud, 2, std::vector<double>(3, 1.0)), Error);
}

TEST(RadiusClasses, SameClassAsTheLogarithmForEveryRadius) {
  // The table's bisection against radiusClass() (the logarithm, then down while above), at each
  // class's lower radius, a float step and a relative 1e-9 either side of it, and in between.
  std::mt19937 rng(3);
  for (const double smallest : {0.0137, 1.0, 0.1, 3.3e-5, 7.0e4}) {
    const double largest = smallest * std::pow(detail::kClassRatio, 60.5);
    const detail::RadiusClasses class_for(smallest, largest);
    std::vector<double> radii{smallest, largest};
    for (int j = 0; j <= 60; ++j) {
      const double lower = smallest * std::pow(detail::kClassRatio, j);
      for (const double r :
           {lower, std::nextafter(lower, 0.0), std::nextafter(lower, 1e300), lower * (1.0 - 1e-9),
            lower * (1.0 + 1e-9), lower * (1.0 + 2e-9), lower * (1.0 + 1e-12)}) {
        if (r >= smallest && r <= largest) radii.push_back(r);
      }
      std::uniform_real_distribution<double> within(lower, lower * detail::kClassRatio);
      for (int k = 0; k < 20; ++k) radii.push_back(std::min(within(rng), largest));
    }
    for (const double r : radii) {
      ASSERT_EQ(class_for(r), detail::radiusClass(r, smallest))
          << "radius " << r << ", smallest " << smallest;
    }
  }
}

}  // namespace
}  // namespace mcws
