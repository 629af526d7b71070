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

/// \brief The samples of another generator labelled as LabelledRobotSampler labels its own: for
/// a sampler in a module above collision, such as the refinement's RefineSampler (mcws_refine
/// labels the new samples of a cloud mcws_sample --collision made).
/// \tparam Sampler a PointGenerator with `void jointValues(std::uint64_t index, double* q) const`
///   giving the joint values of sample `index` exactly as generate() draws them.
template <class Sampler>
class LabelledSampler : public PointGenerator {
 public:
  /// \param sampler and \param checker must outlive this sampler.
  LabelledSampler(const Sampler& sampler, const CollisionChecker& checker)
      : sampler_(sampler), checker_(checker) {}
  void generate(std::uint64_t first, std::size_t count, WorkspacePoint* out) const override {
    sampler_.generate(first, count, out);
    CollisionChecker::Scratch scratch;
    double q[kMaxJoints];
    for (std::size_t k = 0; k < count; ++k) {
      sampler_.jointValues(first + k, q);
      out[k].label = checker_.label(q, scratch);
    }
  }

 private:
  const Sampler& sampler_;
  const CollisionChecker& checker_;
};

}  // namespace mcws
