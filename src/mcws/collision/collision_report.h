#pragma once
/// \file
/// \brief Collision results as a report (mcws_collide --json, mcws_sample --collision --json)
/// gives them: labels by name, distances with their unit.

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "mcws/collision/collision_checker.h"
#include "mcws/kinematics/robot.h"
#include "mcws/sampling/sampler.h"

namespace mcws {

/// \brief The URDF links with geometry that `body` carries (CollisionModel::link_bodies, pairs of
/// link and body), in the model's order; empty for a body no link names (a YAML model's tool).
std::vector<std::string> bodyLinks(
    const std::string& body, const std::vector<std::pair<std::string, std::string>>& link_bodies);

/// \brief What a report names a body by: its links joined by '+' (bodyLinks()), or the body's
/// own name when no link names it or `link_bodies` is empty (a YAML model).
std::string bodyLabel(const std::string& body,
                      const std::vector<std::pair<std::string, std::string>>& link_bodies);

/// \brief The check of one joint vector as JSON: "robot", "length_unit", "label" and its
/// "label_name", "pairs_checked", and "pairs" (`shown`, pairsToShow()), each with its bodies "a"
/// and "b", its "kind" (the label a collision of the pair gives), "colliding" and, where known,
/// its "distance" [length unit] (negative: the penetration depth); with "units". With
/// `link_bodies` (CollisionModel::link_bodies of a URDF model, whose bodies are named by joint),
/// each pair also names the URDF links with geometry of its bodies, "links_a" and "links_b".
nlohmann::json collisionReportJson(
    const Robot& robot, std::uint32_t label, std::size_t checked,
    const std::vector<PairReport>& shown,
    const std::vector<std::pair<std::string, std::string>>& link_bodies = {});

/// \brief The points per collision label of a labelled sampling of `samples` samples, by label
/// name (labelName()): for each of free, link-link, tool-link and environment its "label", the
/// "count" and the "fraction" of all samples.
nlohmann::json labelCountsJson(const SampleSummary& result, std::size_t samples);

}  // namespace mcws
