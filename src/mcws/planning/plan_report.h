#pragma once
/// \file
/// \brief What mcws_plan writes: the chosen path as CSV, the report as text and JSON, the
/// configuration-space picture (Figures 2 and 3 of the maintenance-arm patent) and P against the
/// base offset.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mcws/planning/scenario.h"

namespace mcws {

/// \brief The path as CSV: a header `D,<joint>_<unit>,...` (D: scaled joint-space distance from
/// the start; units rad and the robot's length unit), then one configuration per row.
std::string pathCsv(const Scenario& scenario, const PathSafety& path);

/// \brief The report as one JSON object (every number's unit in its key or a `units` entry):
/// "robot" (its name), "robot_file" (the scenario's robot file), "tip" (tipName()) among them.
nlohmann::json planJson(const Scenario& scenario, const SwayPlanningResult& result);

/// \brief The report as text: every candidate, every shared node, the base adjustments, the
/// validation.
std::string planReport(const Scenario& scenario, const SwayPlanningResult& result);

/// \brief Why no path was accepted, one line that starts with the JSON's status:
/// "start_in_collision", "goal_in_collision", "not_connected", "above_max_collision_probability"
/// (acceptance whole_path) or "below_threshold" (patent_p), then what was measured against what.
std::string noPathStatus(const Scenario& scenario, const SwayPlanningResult& result);

/// \brief Rounds at every base offset -range, ..., 0, ..., +range (step apart), for a plot of
/// P against the offset. `progress` (when set) hears ("offset scan", rounds done, rounds) as each
/// round starts and ends, and each round's own stages as "offset scan: <stage>".
std::vector<PlanningRound> scanOffsets(const SwayPlanner& planner,
                                       const PlanningProgress& progress = {});

/// \brief PNG of P, of the whole-path free fraction and of the lower end of its 95 % interval
/// (1 - the upper end of the collision rate's) of each round's best path against its base offset,
/// with the acceptance criterion's line. \throws mcws::Error when gnuplot fails.
std::string renderOffsetsPng(const Scenario& scenario, const std::vector<PlanningRound>& rounds);

/// \brief PNG of a two-joint configuration space (Figure 2b of the maintenance-arm patent,
/// generalised): each cell coloured by the fraction of the n base poses for which it collides, with
/// the candidate paths, the chosen path, the shared nodes and the decision taken at each.
/// \param cells cells per joint axis.
/// \throws mcws::Error for a robot without exactly two joints, or when gnuplot fails.
std::string renderConfigurationSpacePng(const Scenario& scenario, const SwayPlanner& planner,
                                        const PlanningRound& round, int cells);

}  // namespace mcws
