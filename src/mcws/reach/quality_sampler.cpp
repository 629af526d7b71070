#include "mcws/reach/quality_sampler.h"

#include <vector>

namespace mcws {
namespace {

/// The robot whose tool point is the recorded point (the flange for SamplePoint::kFlange).
Robot recordedChain(Robot robot, SamplePoint point) {
  if (point == SamplePoint::kFlange) robot.T_flange_tool = Eigen::Isometry3d::Identity();
  return robot;
}

}  // namespace

QualitySampler::QualitySampler(const Robot& robot, const RobotSamplerOptions& options,
                               const PointGenerator& points, const QualityOptions& quality)
    : joints_(robot, options),
      chain_(recordedChain(robot, options.point)),
      points_(points),
      quality_(quality) {
  quality.check();
}

void QualitySampler::generate(std::uint64_t first, std::size_t count, QualityPoint* out) const {
  std::vector<WorkspacePoint, Eigen::aligned_allocator<WorkspacePoint>> points(count);
  points_.generate(first, count, points.data());
  const int n = chain_.dof();
  Jacobian J(6, n);
  Eigen::Matrix3d R;
  Eigen::Vector3d p;
  double q[kMaxJoints];
  for (std::size_t k = 0; k < count; ++k) {
    const WorkspacePoint& in = points[k];
    QualityPoint& point = out[k];
    point = QualityPoint();
    point.x = in.x;
    point.y = in.y;
    point.z = in.z;
    for (int j = 0; j < kMaxJoints; ++j) point.q[j] = in.q[j];
    point.label = in.label;
    joints_.jointValues(first + k, q);
    chain_.toolPoseAndJacobian(q, R, p, J.data());
    const Quality quality = jacobianQuality(J, quality_);
    point.manipulability = static_cast<float>(quality.manipulability);
    point.inverse_condition = static_cast<float>(quality.inverse_condition);
  }
}

}  // namespace mcws
