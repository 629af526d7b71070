#include "mcws/trajectory/trajectory_report.h"

#include <string>

#include "mcws/trajectory/tool_path.h"

namespace mcws {

nlohmann::json trajectorySummary(const Robot& robot, const SampledTrajectory& samples,
                                 const Eigen::MatrixXd& xyz) {
  nlohmann::json out;
  out["robot"] = robot.name;
  out["length_unit"] = unitName(robot.length_unit);
  out["samples"] = samples.size();
  for (int j = 0; j < robot.dof(); ++j) {
    out["joints"].push_back(robot.joints[j].name);
    out["peak_velocity"].push_back(samples.qd.col(j).cwiseAbs().maxCoeff());
    out["peak_acceleration"].push_back(samples.qdd.col(j).cwiseAbs().maxCoeff());
  }
  const Eigen::Index last = xyz.rows() - 1;
  out["tool_start"] = {xyz(0, 0), xyz(0, 1), xyz(0, 2)};
  out["tool_end"] = {xyz(last, 0), xyz(last, 1), xyz(last, 2)};
  out["tool_path_length"] = pathLength(xyz);
  const std::string length = unitName(robot.length_unit);
  out["units"] = {{"peak_velocity", jointUnits(robot, "/s")},
                  {"peak_acceleration", jointUnits(robot, "/s^2")},
                  {"tool_start", length},
                  {"tool_end", length},
                  {"tool_path_length", length}};
  return out;
}

}  // namespace mcws
