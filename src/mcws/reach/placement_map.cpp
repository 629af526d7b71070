#include "mcws/reach/placement_map.h"

#include <fstream>
#include <nlohmann/json.hpp>

#include "mcws/core/error.h"
#include "mcws/core/input_files.h"
#include "mcws/sampling/sampler.h"

namespace mcws {

namespace {

/// Checks the map's header `h` (see readPlacementMap()); nlohmann's exceptions pass.
void checkHeader(const nlohmann::json& h, const std::string& path, const Robot& robot,
                 const std::string& robot_file, const std::string& manipulability) {
  const std::string unit = unitName(robot.length_unit);
  if (!h.is_object() || h.value("robot", "") != robot.name || h.value("length_unit", "") != unit) {
    throw Error(path + ": the map is of robot '" + (h.is_object() ? h.value("robot", "?") : "?") +
                "' in " + (h.is_object() ? h.value("length_unit", "?") : "?") + ", not of '" +
                robot.name + "' in " + unit);
  }
  const io::CloudProvenance recorded = robotProvenance(robot);
  if (!h.contains("robot_sha256") || !h["robot_sha256"].is_string()) {
    throw Error(path +
                ": the map predates the record of its robot file's SHA-256; re-make it "
                "with mcws_reach --robot " +
                robot_file + " --map " + path);
  }
  if (h["robot_sha256"].get<std::string>() != recorded.sha256) {
    throw Error(path + ": the map was made from robot file " + h.value("robot_file", "?") +
                " (sha256 " + h["robot_sha256"].get<std::string>().substr(0, 12) +
                "...), not from --robot " + robot_file + " (sha256 " +
                recorded.sha256.substr(0, 12) +
                "...): the robot file has changed since, or "
                "is another; re-make the map with mcws_reach");
  }
  // One URDF holds several chains (--base, --tip); a map that records none predates the record.
  if (h.contains("tip_link") &&
      (h.value("base_link", "") != robot.base_link || h.value("tip_link", "") != robot.tip_link)) {
    throw Error(path + ": the map was made for the chain from link '" + h.value("base_link", "") +
                "' to link '" + h.value("tip_link", "") + "', not for the chain from '" +
                robot.base_link + "' to '" + robot.tip_link + "' (--base, --tip)");
  }
  if (h.value("collision", false)) {
    throw Error(path +
                ": the map counts only samples free of the environment at the robot's "
                "base (mcws_reach --collision); placement needs a map without it");
  }
  const nlohmann::json wanted = nlohmann::json::parse(manipulability);
  if (h.contains("manipulability") && !h["manipulability"].is_null() &&
      h["manipulability"] != wanted) {
    throw Error(path + ": the map's manipulability is measured as " + h["manipulability"].dump() +
                ", not as " + wanted.dump() + " (--quality-task, --length)");
  }
}

}  // namespace

void checkPlacementMap(const std::string& header, const std::string& path, const Robot& robot,
                       const std::string& robot_file, const std::string& manipulability,
                       std::uint64_t& samples) {
  const nlohmann::json h = nlohmann::json::parse(header, nullptr, false);
  // A header member of the wrong type (a number for "robot") throws nlohmann's own exception,
  // whose message names no file: one line naming the map instead.
  try {
    checkHeader(h, path, robot, robot_file, manipulability);
    samples = h.value("samples", 0ULL);
  } catch (const nlohmann::json::exception& e) {
    const std::string what = e.what();  // "[json.exception.type_error.302] type must be ..."
    throw Error(path + ": the map's header has a member of the wrong type: " +
                what.substr(what.find(']') == std::string::npos ? 0 : what.find(']') + 2));
  }
}

ReachMap readPlacementMap(const std::string& path, const Robot& robot,
                          const std::string& robot_file, const std::string& manipulability,
                          std::uint64_t& samples) {
  requireInputFile(path, "reachability map");  // regular file, noted as an input of the run
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the reachability map");
  std::string header;
  ReachMap map = ReachMap::read(in, path, &header);
  checkPlacementMap(header, path, robot, robot_file, manipulability, samples);
  return map;
}

}  // namespace mcws
