#pragma once
// A validation shape's samples as plain XYZ points (the points the measures and filters take).

#include <pcl/common/io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstddef>
#include <cstdint>

#include "mcws/sampling/sampler.h"

namespace mcws::test {

/// `n` samples of `shape` drawn with `seed` (one thread).
inline pcl::PointCloud<pcl::PointXYZ> shapeCloud(Shape shape, std::size_t n, std::uint64_t seed) {
  pcl::PointCloud<pcl::PointXYZ> cloud;
  pcl::copyPointCloud(sampleCloud(ShapeSampler(shape, seed), n, 0), cloud);
  return cloud;
}

}  // namespace mcws::test
