#include "mcws/reach/reach_report.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "mcws/collision/collision_checker.h"

namespace mcws {

nlohmann::json qualitySummary(const QualityOptions& quality, const Robot& robot) {
  // Position task: each of the k = min(n, 3) singular values is a length per rad; a prismatic
  // joint's column has no length, so the unit is then a mixture the JSON says it is.
  const bool prismatic =
      std::any_of(robot.joints.begin(), robot.joints.end(),
                  [](const Joint& joint) { return joint.type == JointType::kPrismatic; });
  const std::string unit = unitName(robot.length_unit);
  return {{"task", qualityTaskName(quality.task)},
          {"characteristic_length", quality.characteristic_length},
          {"characteristic_length_unit", unit},
          {"manipulability_unit",
           quality.task == QualityTask::kFull ? std::string("1")
           : prismatic ? "mixed: " + unit + " per rad for each revolute joint, 1 for each prismatic"
                       : unit + "^" + std::to_string(std::min(robot.dof(), 3))}};
}

nlohmann::json mapSummary(const Robot& robot, const ReachGrid& grid, const ReachSampling& sampling,
                          std::uint64_t samples, const ReachMap& map, bool collision) {
  const std::string unit = unitName(robot.length_unit);
  const double voxel_volume = std::pow(grid.resolution, 3);
  return {{"robot", robot.name},
          {"length_unit", unit},
          {"resolution", grid.resolution},
          {"orientations", grid.directions},
          {"rolls", grid.rolls},
          {"orientation_bins", map.bins().size()},
          {"direction_partition", "EQ (Leopardi 2006), approach = tool z axis"},
          {"samples", samples},
          {"samples_counted", map.samples()},
          {"seed", sampling.seed},
          {"voxels", map.size()},
          {"occupied_volume", static_cast<double>(map.size()) * voxel_volume},
          {"occupied_volume_unit", unit + "^3"},
          {"mean_reachability", map.meanReachability()},
          {"manipulability", sampling.manipulability ? qualitySummary(sampling.quality, robot)
                                                     : nlohmann::json(nullptr)},
          {"collision", collision}};
}

nlohmann::json studySummary(const Robot& robot, const ReachStudyOptions& options,
                            const std::vector<TargetReach>& results, bool collision) {
  nlohmann::json unreached = nlohmann::json::array();
  for (std::size_t i = 0; i < results.size(); ++i) {
    if (results[i].reached) continue;
    unreached.push_back({{"target", i},
                         {"solved", results[i].solved},
                         {"label", results[i].solved ? nlohmann::json(labelName(results[i].label))
                                                     : nlohmann::json(nullptr)},
                         {"position_error", results[i].position_error},
                         {"orientation_error_deg", results[i].orientation_error * 180.0 / M_PI}});
  }
  const ReachSummary summary = summarize(results);
  const std::string unit = unitName(robot.length_unit);
  const auto finiteOrNull = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nullptr; };
  return {{"robot", robot.name},
          {"length_unit", unit},
          {"targets", summary.targets},
          {"reached", summary.reached},
          {"solved", summary.solved},
          {"share_reached", summary.share_reached},
          {"mean_score", summary.mean_score},
          {"score", "manipulability where reached, 0 elsewhere"},
          {"mean_manipulability_reached", summary.mean_manipulability_reached},
          {"manipulability", qualitySummary(options.quality, robot)},
          {"min_clearance_reached", finiteOrNull(summary.min_clearance_reached)},
          {"clearance_unit", unit},
          {"collision", collision},
          {"approach_tolerance_deg", options.approach_tolerance * 180.0 / M_PI},
          {"ik_starts", options.starts},
          {"seed", options.ik.seed},
          {"unreached", unreached}};
}

nlohmann::json candidateJson(const BaseCandidate& c) {
  nlohmann::json j = {{"offset", {c.offset.x(), c.offset.y(), c.offset.z()}},
                      {"map_share", c.map_share},
                      {"map_score", c.map_score}};
  j["ik_share"] = c.confirmed ? nlohmann::json(c.ik.share_reached) : nullptr;
  j["ik_score"] = c.confirmed ? nlohmann::json(c.ik.mean_score) : nullptr;
  return j;
}

nlohmann::json confirmationJson(const PlacementOptions& options,
                                const std::vector<BaseCandidate>& candidates) {
  const auto confirmed = std::count_if(candidates.begin(), candidates.end(),
                                       [](const BaseCandidate& c) { return c.confirmed; });
  return {{"margin_share",
           options.confirm_margin >= 0.0 ? nlohmann::json(options.confirm_margin) : nullptr},
          {"best_by_map", options.confirm},
          {"confirmed", confirmed},
          {"rule",
           "confirmed by IK: every position whose map share is at least the best map share less "
           "margin_share (a fraction of the targets), and the best_by_map best by the map"}};
}

nlohmann::json placementSummary(const Robot& robot, std::size_t targets, const ReachMap& map,
                                const nlohmann::json& map_about, const ReachStudyOptions& options,
                                bool collision, const std::vector<BaseCandidate>& candidates,
                                int best) {
  nlohmann::json table = nlohmann::json::array();
  for (const BaseCandidate& c : candidates) table.push_back(candidateJson(c));
  nlohmann::json best_json = nullptr;
  if (best >= 0) {
    const BaseCandidate& b = candidates[static_cast<std::size_t>(best)];
    best_json = candidateJson(b);
    best_json["reached"] = b.ik.reached;
    const Eigen::Vector3d base = robot.T_world_base.translation() + b.offset;
    best_json["base_position"] = {base.x(), base.y(), base.z()};
  }
  return {{"robot", robot.name},
          {"length_unit", unitName(robot.length_unit)},
          {"targets", targets},
          {"positions", candidates.size()},
          {"map",
           {{"resolution", map.grid().resolution},
            {"orientations", map.grid().directions},
            {"rolls", map.grid().rolls},
            {"about", map_about}}},
          {"score", "manipulability where reached, 0 elsewhere"},
          {"manipulability", qualitySummary(options.quality, robot)},
          {"collision", collision},
          {"approach_tolerance_deg", options.approach_tolerance * 180.0 / M_PI},
          {"best", best_json},
          {"candidates", table}};
}

namespace {

/// A URDF robot's chain (--base, --tip) into a record of the robot: one file holds several
/// chains. Nothing for a D-H robot, whose records stay as they were.
void addChain(nlohmann::json& record, const Robot& robot) {
  if (robot.tip_link.empty()) return;
  record["base_link"] = robot.base_link;
  record["tip_link"] = robot.tip_link;
}

}  // namespace

std::string mapFileHeader(const Robot& robot, const std::string& robot_file,
                          const std::string& robot_sha256, const nlohmann::json& summary) {
  nlohmann::json header{{"robot", robot.name},
                        {"robot_file", robot_file},
                        {"robot_sha256", robot_sha256},
                        {"length_unit", unitName(robot.length_unit)},
                        {"samples", summary["samples"]},
                        {"seed", summary["seed"]},
                        {"collision", summary["collision"]},
                        {"manipulability", summary["manipulability"]}};
  addChain(header, robot);
  return header.dump();
}

std::string checkpointRun(const Robot& robot, const std::string& robot_sha256,
                          const ReachGrid& grid, const ReachSampling& sampling,
                          std::uint64_t samples, bool collision, int processes, int rank) {
  nlohmann::json run{{"robot", robot.name},
                     {"robot_sha256", robot_sha256},
                     {"resolution", grid.resolution},
                     {"orientations", grid.directions},
                     {"rolls", grid.rolls},
                     {"samples", samples},
                     {"seed", sampling.seed},
                     {"collision", collision},
                     {"manipulability", qualitySummary(sampling.quality, robot)},
                     {"with_manipulability", sampling.manipulability},
                     {"processes", processes},
                     {"rank", rank}};
  addChain(run, robot);
  return run.dump();
}

}  // namespace mcws
