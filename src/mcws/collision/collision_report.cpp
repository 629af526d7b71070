#include "mcws/collision/collision_report.h"

namespace mcws {

std::vector<std::string> bodyLinks(
    const std::string& body, const std::vector<std::pair<std::string, std::string>>& link_bodies) {
  std::vector<std::string> links;
  for (const auto& [link, carrier] : link_bodies) {
    if (carrier == body) links.push_back(link);
  }
  return links;
}

std::string bodyLabel(const std::string& body,
                      const std::vector<std::pair<std::string, std::string>>& link_bodies) {
  std::string label;
  for (const std::string& link : bodyLinks(body, link_bodies)) {
    label += (label.empty() ? "" : "+") + link;
  }
  return label.empty() ? body : label;
}

nlohmann::json collisionReportJson(
    const Robot& robot, std::uint32_t label, std::size_t checked,
    const std::vector<PairReport>& shown,
    const std::vector<std::pair<std::string, std::string>>& link_bodies) {
  const auto links = [&](const std::string& body) {
    nlohmann::json names = nlohmann::json::array();
    for (const std::string& link : bodyLinks(body, link_bodies)) names.push_back(link);
    return names;
  };
  nlohmann::json out;
  out["robot"] = robot.name;
  out["length_unit"] = unitName(robot.length_unit);
  out["units"] = {{"pairs.distance", unitName(robot.length_unit)}};
  out["label"] = label;
  out["label_name"] = labelName(label);
  out["pairs_checked"] = checked;
  out["pairs"] = nlohmann::json::array();
  for (const PairReport& pair : shown) {
    nlohmann::json item{{"a", pair.body_a},
                        {"b", pair.body_b},
                        {"kind", labelName(pair.label)},
                        {"colliding", pair.colliding}};
    if (pair.depth_known) item["distance"] = pair.distance;
    if (!link_bodies.empty()) {
      item["links_a"] = links(pair.body_a);
      item["links_b"] = links(pair.body_b);
    }
    out["pairs"].push_back(item);
  }
  return out;
}

nlohmann::json labelCountsJson(const SampleSummary& result, std::size_t samples) {
  nlohmann::json labels;
  for (std::uint32_t label : {kLabelFree, kLabelLinkLink, kLabelToolLink, kLabelEnvironment}) {
    const auto found = result.label_counts.find(label);
    const std::size_t count = found == result.label_counts.end() ? 0 : found->second;
    labels[labelName(label)] = {
        {"label", label}, {"count", count}, {"fraction", double(count) / double(samples)}};
  }
  return labels;
}

}  // namespace mcws
