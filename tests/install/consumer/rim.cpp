// The rim of a PCL user's own cloud with the installed mcws::OrthantBoundary, used like any PCL
// filter. 20000 points uniform in the unit disk (radius 1 m, x-y plane) from the standard
// library's generator; every boundary point must lie near the rim and the filter's two modes must
// split the cloud. Exit 0 when they do.
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <random>

#include "mcws/filters/orthant_boundary.h"

int main() {
  constexpr std::size_t kPoints = 20000;
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  std::mt19937 random(7);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  while (cloud->size() < kPoints) {
    const float x = uniform(random), y = uniform(random);
    if (x * x + y * y <= 1.0f) cloud->push_back(pcl::PointXYZ(x, y, 0.0f));
  }

  mcws::OrthantBoundary<pcl::PointXYZ> boundary;
  boundary.setInputCloud(cloud);
  boundary.setPlane(mcws::BoundaryPlane::kXY);
  pcl::PointCloud<pcl::PointXYZ> rim, inside;
  boundary.filter(rim);
  boundary.setNegative(true);
  boundary.filter(inside);

  // Boundary points within two mean spacings h of the rim r = 1 m.
  const double h = std::sqrt(M_PI / kPoints);
  std::size_t near_rim = 0;
  for (const pcl::PointXYZ& p : rim) near_rim += 1.0 - std::hypot(p.x, p.y) <= 2.0 * h;
  std::cout << rim.size() << " boundary points, " << near_rim << " within " << 2.0 * h
            << " m of the rim, " << inside.size() << " inside\n";
  return !rim.empty() && rim.size() + inside.size() == kPoints && near_rim >= 0.95 * rim.size() ? 0
                                                                                                : 1;
}
