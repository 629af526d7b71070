#include "mcws/workspace/refine_report.h"

#include "mcws/sampling/sample_report.h"

namespace mcws {

nlohmann::json refineSummary(const Robot& robot, std::size_t boundary_points, std::size_t samples,
                             std::size_t copied, const RefineOptions& options,
                             const std::vector<std::string>& pinned,
                             const io::SamplingRecord& sampling) {
  return {{"robot", robot.name},
          {"tip", tipName(robot, options.point)},
          {"boundary_points", boundary_points},
          {"samples", samples},
          {"copied", copied},
          {"points", copied + samples},
          {"spread", options.spread},
          {"length_unit", unitName(robot.length_unit)},
          {"pinned", pinned},
          {"point", sampling.point},
          {"collision", sampling.collision},
          {"seed", options.seed},
          {"units", {{"spread", "joint ranges"}}}};
}

}  // namespace mcws
