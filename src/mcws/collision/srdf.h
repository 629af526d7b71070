#pragma once
/// \file
/// \brief The `<disable_collisions>` entries of an SRDF file (the Semantic Robot Description
/// Format of MoveIt): pairs of links the collision checker need not test. Read and written here
/// with the TinyXML that urdfdom already links, since srdfdom is not packaged in Debian 12.

#include <string>
#include <vector>

#include "mcws/collision/collision_model.h"

namespace mcws {

/// \brief One `<disable_collisions link1="..." link2="..." reason="..."/>` entry.
struct DisabledCollision {
  std::string link1, link2;
  /// MoveIt's reasons: "Adjacent" (parent and child, or fixed together), "Default" (in collision
  /// at the default joint values), "Always" (in every sample), "Never" (in no sample), "User".
  std::string reason;

  bool operator==(const DisabledCollision& o) const {
    return link1 == o.link1 && link2 == o.link2 && reason == o.reason;
  }
};

/// \brief The `<disable_collisions>` entries of an SRDF document, in file order; every other
/// element (groups, end effectors, virtual joints) is skipped.
/// \param text the XML text; \param source its file name, for messages.
/// \throws mcws::Error "source: ...", one line: malformed XML (TinyXML's message and line), a
///   root element that is not `<robot>`, an entry without link1 or link2 or pairing a link with
///   itself, and as detail::checkXmlNesting() (nesting, UTF-8, XML declaration).
std::vector<DisabledCollision> parseSrdf(const std::string& text, const std::string& source);

/// \brief parseSrdf() of a file. \throws mcws::Error when it cannot be read or is larger than
/// kMaxUrdfBytes, and as parseSrdf().
std::vector<DisabledCollision> loadSrdf(const std::string& path);

/// \brief An SRDF document `<robot name="robot_name">` holding `pairs` in order, which
/// parseSrdf() and MoveIt's srdfdom read back.
std::string srdfText(const std::string& robot_name, const std::vector<DisabledCollision>& pairs);

/// \brief Adds to `model.allowed` every pair of bodies whose links with geometry are all
/// disabled two by two by `pairs` (a body made of several links fixed together is left checked
/// against another unless every pair of their links is disabled). Pairs naming a link without
/// geometry remove nothing.
/// \param source the SRDF file's name, for messages.
/// \throws mcws::Error "source: disable_collisions link1="a" link2="b": 'b' is not a link of the
///   robot" for a name that is not one of the robot's links (CollisionModel::link_names, or a YAML
///   model's body names).
void applySrdf(CollisionModel& model, const std::vector<DisabledCollision>& pairs,
               const std::string& source);

}  // namespace mcws
