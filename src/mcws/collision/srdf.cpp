#include "mcws/collision/srdf.h"

#include <tinyxml.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <utility>

#include "mcws/core/error.h"
#include "mcws/core/markup.h"
#include "mcws/core/text_file.h"
#include "mcws/kinematics/detail/urdf_guard.h"
#include "mcws/kinematics/robot_urdf.h"

namespace mcws {
namespace {

/// The pair as the file wrote it, for messages.
std::string describe(const DisabledCollision& pair) {
  return "disable_collisions link1=\"" + pair.link1 + "\" link2=\"" + pair.link2 + "\"";
}

/// Every name an SRDF of `model` may use.
std::set<std::string> knownLinks(const CollisionModel& model) {
  if (!model.link_names.empty()) return {model.link_names.begin(), model.link_names.end()};
  std::set<std::string> names;
  for (const BodySpec& link : model.links) names.insert(link.name);
  names.insert(model.tool.name);
  for (const BodySpec& object : model.environment) names.insert(object.name);
  return names;
}

}  // namespace

std::vector<DisabledCollision> parseSrdf(const std::string& text, const std::string& source) {
  detail::checkXmlNesting(text, source);
  TiXmlDocument doc;
  doc.Parse(text.c_str(), nullptr, TIXML_ENCODING_UTF8);
  if (doc.Error()) {
    throw Error(source + ": malformed XML on line " + std::to_string(doc.ErrorRow()) + ": " +
                doc.ErrorDesc());
  }
  const TiXmlElement* robot = doc.RootElement();
  if (robot == nullptr || std::string(robot->Value()) != "robot") {
    throw Error(source + ": not an SRDF file (its root element is not <robot>)");
  }
  std::vector<DisabledCollision> pairs;
  for (const TiXmlElement* entry = robot->FirstChildElement("disable_collisions"); entry != nullptr;
       entry = entry->NextSiblingElement("disable_collisions")) {
    const char* link1 = entry->Attribute("link1");
    const char* link2 = entry->Attribute("link2");
    const char* reason = entry->Attribute("reason");
    const std::string where = source + ": line " + std::to_string(entry->Row()) + ": ";
    if (link1 == nullptr || link2 == nullptr || *link1 == '\0' || *link2 == '\0') {
      throw Error(where + "disable_collisions needs link1 and link2");
    }
    DisabledCollision pair{link1, link2, reason == nullptr ? "" : reason};
    if (pair.link1 == pair.link2) {
      throw Error(where + describe(pair) + " pairs a link with itself");
    }
    pairs.push_back(std::move(pair));
  }
  return pairs;
}

std::vector<DisabledCollision> loadSrdf(const std::string& path) {
  std::error_code ec;  // a file that cannot be sized is left to readTextFile's messages
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (!ec && bytes > kMaxUrdfBytes) {
    throw Error(path + ": SRDF of " + std::to_string(bytes) + " bytes is larger than " +
                std::to_string(kMaxUrdfBytes >> 20) + " MiB");
  }
  return parseSrdf(readTextFile(path, "SRDF file"), path);
}

std::string srdfText(const std::string& robot_name, const std::vector<DisabledCollision>& pairs) {
  std::string out = "<?xml version=\"1.0\"?>\n<robot name=\"" + escapeMarkup(robot_name) + "\">\n";
  for (const DisabledCollision& pair : pairs) {
    out += "  <disable_collisions link1=\"" + escapeMarkup(pair.link1) + "\" link2=\"" +
           escapeMarkup(pair.link2) + "\" reason=\"" + escapeMarkup(pair.reason) + "\"/>\n";
  }
  return out + "</robot>\n";
}

void applySrdf(CollisionModel& model, const std::vector<DisabledCollision>& pairs,
               const std::string& source) {
  const std::set<std::string> known = knownLinks(model);
  std::set<std::pair<std::string, std::string>> disabled;
  for (const DisabledCollision& pair : pairs) {
    for (const std::string* name : {&pair.link1, &pair.link2}) {
      if (!known.count(*name)) {
        throw Error(source + ": " + describe(pair) + ": '" + *name +
                    "' is not a link of the robot");
      }
    }
    disabled.insert(std::minmax(pair.link1, pair.link2));
  }
  std::map<std::string, std::vector<std::string>> body_links;  // links with geometry, by body
  for (const auto& [link, body] : linkBodies(model)) body_links[body].push_back(link);
  for (auto a = body_links.begin(); a != body_links.end(); ++a) {
    for (auto b = std::next(a); b != body_links.end(); ++b) {
      bool all = true;
      for (const std::string& link_a : a->second) {
        for (const std::string& link_b : b->second) {
          all = all && disabled.count(std::minmax(link_a, link_b));
        }
      }
      if (all) model.allowed.emplace_back(a->first, b->first);
    }
  }
}

}  // namespace mcws
