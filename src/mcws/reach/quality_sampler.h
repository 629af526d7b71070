#pragma once
/// \file
/// \brief Workspace samples with the arm's quality at each (mcws_sample --quality).

#include "mcws/kinematics/jacobian.h"
#include "mcws/reach/quality.h"
#include "mcws/sampling/sampler.h"

namespace mcws {

/// \brief The points of another generator (RobotSampler, LabelledRobotSampler) with the
/// manipulability and inverse condition number of the Jacobian at each sample's joint values
/// (mcws::Quality), the Jacobian taken at the recorded point (tool or flange).
class QualitySampler : public BasicPointGenerator<QualityPoint> {
 public:
  /// \param points the samples (must outlive this); their joint values must be those RobotSampler
  ///   draws with `options` (true of RobotSampler and LabelledRobotSampler with the same options).
  /// \throws mcws::Error as RobotSampler, or for a bad characteristic length.
  QualitySampler(const Robot& robot, const RobotSamplerOptions& options,
                 const PointGenerator& points, const QualityOptions& quality);
  void generate(std::uint64_t first, std::size_t count, QualityPoint* out) const override;

 private:
  RobotSampler joints_;
  KinematicChain chain_;
  const PointGenerator& points_;
  QualityOptions quality_;
};

}  // namespace mcws
