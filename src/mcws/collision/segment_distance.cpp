#include "mcws/collision/segment_distance.h"

#include <algorithm>

namespace mcws {

double segmentDistanceSquared(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1,
                              const Eigen::Vector3d& p2, const Eigen::Vector3d& q2) {
  double s = 0.0, t = 0.0;
  return segmentDistanceSquared(p1, q1, p2, q2, s, t);
}

double segmentDistanceSquared(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1,
                              const Eigen::Vector3d& p2, const Eigen::Vector3d& q2, double& s,
                              double& t) {
  // Ericson (2005), ClosestPtSegmentSegment: s and t parametrise the two segments.
  constexpr double kEpsilon = 1e-18;  // squared length below which a segment is a point
  const Eigen::Vector3d d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  s = 0.0;
  t = 0.0;
  if (a <= kEpsilon && e <= kEpsilon) return r.squaredNorm();
  if (a <= kEpsilon) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= kEpsilon) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return (p1 + d1 * s - (p2 + d2 * t)).squaredNorm();
}

}  // namespace mcws
