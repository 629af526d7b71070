#include "mcws/collision/collision_sampler.h"

namespace mcws {

LabelledRobotSampler::LabelledRobotSampler(const Robot& robot, const RobotSamplerOptions& options,
                                           const CollisionChecker& checker)
    : sampler_(robot, options), checker_(checker) {}

void LabelledRobotSampler::generate(std::uint64_t first, std::size_t count,
                                    WorkspacePoint* out) const {
  sampler_.generate(first, count, out);
  CollisionChecker::Scratch scratch;
  double q[kMaxJoints];
  for (std::size_t k = 0; k < count; ++k) {
    sampler_.jointValues(first + k, q);
    out[k].label = checker_.label(q, scratch);
  }
}

}  // namespace mcws
