// Example 02: boundary points of a disk with mcws::OrthantBoundary, used as any PCL filter.
//
// 20000 points uniform in the unit disk (radius 1 m, the x-y plane). A point is on the boundary
// when some sector of its neighbourhood holds no neighbour (Yin, Wang & Yu 2010, section 4.3).
#include <pcl/common/io.h>

#include <cmath>
#include <iostream>
#include <memory>

#include "mcws/filters/orthant_boundary.h"
#include "mcws/sampling/sampler.h"

int main() {
  constexpr std::size_t kPoints = 20000;
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  pcl::copyPointCloud(mcws::sampleCloud(mcws::ShapeSampler(mcws::Shape::kDisk, 1), kPoints, 0),
                      *cloud);

  mcws::OrthantBoundary<pcl::PointXYZ> boundary;  // the recommended settings
  boundary.setInputCloud(cloud);
  boundary.setPlane(mcws::BoundaryPlane::kXY);
  pcl::PointCloud<pcl::PointXYZ> rim, interior;
  boundary.filter(rim);
  boundary.setNegative(true);  // negative mode: the interior
  boundary.filter(interior);

  // How many boundary points lie within two mean spacings h of the rim r = 1 m.
  const double h = std::sqrt(M_PI / kPoints);
  std::size_t near_rim = 0;
  for (const pcl::PointXYZ& p : rim) near_rim += 1.0 - std::hypot(p.x, p.y) <= 2.0 * h;
  const double share = rim.empty() ? 0.0 : double(near_rim) / double(rim.size());

  std::cout << rim.size() << " of " << cloud->size() << " points on the boundary, "
            << interior.size() << " inside (median radius " << boundary.usedRadius() * 1000.0
            << " mm)\n"
            << 100.0 * share << " % of them within 2 spacings (" << 2000.0 * h
            << " mm) of the rim\n";
  return !rim.empty() && rim.size() + interior.size() == kPoints && share >= 0.95 ? 0 : 1;
}
