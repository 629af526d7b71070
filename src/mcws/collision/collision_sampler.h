#pragma once
/// \file
/// \brief Monte Carlo workspace samples labelled by collision (Fu, Hu, Chen & Pan 2016, section 2).

#include "mcws/collision/collision_checker.h"
#include "mcws/sampling/sampler.h"

namespace mcws {

/// \brief RobotSampler's samples, each labelled by CollisionChecker::label() of the joint values
/// that produced it: kLabelFree, kLabelLinkLink, kLabelToolLink or kLabelEnvironment.
///
/// A sample's label depends only on its joint values, so the labelled cloud is the same for any
/// thread count. Each call of generate() (one block of samples on one thread) uses its own
/// CollisionChecker::Scratch.
class LabelledRobotSampler : public PointGenerator {
 public:
  /// \param checker must outlive the sampler.
  /// \throws mcws::Error as RobotSampler.
  LabelledRobotSampler(const Robot& robot, const RobotSamplerOptions& options,
                       const CollisionChecker& checker);
  void generate(std::uint64_t first, std::size_t count, WorkspacePoint* out) const override;

 private:
  RobotSampler sampler_;
  const CollisionChecker& checker_;
};

}  // namespace mcws
