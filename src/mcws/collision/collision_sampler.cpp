#include "mcws/collision/collision_sampler.h"

namespace mcws {

LabelledRobotSampler::LabelledRobotSampler(const Robot& robot, const RobotSamplerOptions& options,
                                           const CollisionChecker& checker)
    : sampler_(robot, options), checker_(checker) {}

void LabelledRobotSampler::generate(std::uint64_t first, std::size_t count,
                                    WorkspacePoint* out) const {
  LabelledSampler<RobotSampler>(sampler_, checker_).generate(first, count, out);
}

}  // namespace mcws
