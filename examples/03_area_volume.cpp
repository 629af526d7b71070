// Example 03: area and volume of a sampled region with mcws::delaunayMeasure.
//
// The region's Delaunay triangulation (CGAL), restricted to simplices no wider than 3 local
// spacings and corrected for the band the samples miss along the edge (Efron 1965), on 20000
// points uniform in the unit disk (area pi r^2) and in the unit ball (volume 4/3 pi r^3), r = 1 m.
#include <pcl/common/io.h>

#include <cmath>
#include <iostream>

#include "mcws/sampling/sampler.h"
#include "mcws/workspace/measure.h"

namespace {
/// delaunayMeasure() of `points` samples of `shape`, as a relative error [%] against its closed
/// form, printed with `unit`.
double measureShape(mcws::Shape shape, std::size_t points, const char* what, const char* unit) {
  pcl::PointCloud<pcl::PointXYZ> cloud;
  pcl::copyPointCloud(mcws::sampleCloud(mcws::ShapeSampler(shape, 1), points, 0), cloud);
  const int dimensions = mcws::shapeIsPlanar(shape) ? 2 : 3;
  const mcws::RegionMeasure m = mcws::delaunayMeasure(cloud, dimensions);
  const double exact = mcws::shapeMeasure(shape);
  const double error = 100.0 * (m.measure - exact) / exact;
  std::cout << what << ": " << m.measure << " " << unit << " (closed form " << exact << " " << unit
            << ", error " << error << " %; " << m.boundary_vertices << " boundary vertices)\n";
  return error;
}
}  // namespace

int main() {
  const double area_error = measureShape(mcws::Shape::kDisk, 20000, "disk area", "m^2");
  const double volume_error = measureShape(mcws::Shape::kBall, 20000, "ball volume", "m^3");
  // Check: both within 1 % of the closed form (0.008 % and 0.26 % with this seed).
  return std::abs(area_error) < 1.0 && std::abs(volume_error) < 1.0 ? 0 : 1;
}
