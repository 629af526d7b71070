#include "mcws/filters/orthant_boundary.h"

#include <cmath>

#include "mcws/filters/impl/orthant_boundary.hpp"
#include "mcws/workspace/point_types.h"

namespace mcws {

double orthantAutoFactor(std::size_t n, int dimensions) {
  // Expected false boundary points ~ (orthants x frames) n P(orthant empty) = 16 n P; P as in
  // orthant_boundary.h; solved for 16 n P = 1/2, i.e. P = 1 / (32 n).
  const double log_term = std::log(32.0 * static_cast<double>(std::max<std::size_t>(n, 2)));
  return dimensions == 2 ? std::sqrt(4.0 / M_PI * log_term) : std::cbrt(6.0 / M_PI * log_term);
}

unsigned orthantFrames(unsigned frames, int dimensions) {
  using Frames = OrthantBoundary<pcl::PointXYZ>;
  if (frames == 0) {
    return dimensions == 2 ? Frames::kAnyRotation : Frames::kAxisFrame | Frames::kOutwardFrame;
  }
  if (dimensions == 3 && (frames & Frames::kAnyRotation)) {
    frames = (frames & ~Frames::kAnyRotation) | Frames::kAxisFrame | Frames::kOutwardFrame;
  }
  return frames;
}

template class OrthantBoundary<pcl::PointXYZ>;
template class OrthantBoundary<pcl::PointXYZL>;
template class OrthantBoundary<WorkspacePoint>;

}  // namespace mcws
