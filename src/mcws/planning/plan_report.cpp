#include "mcws/planning/plan_report.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include "mcws/core/decimal.h"
#include "mcws/core/error.h"
#include "mcws/io/gnuplot.h"
#include "mcws/sampling/sample_report.h"

namespace mcws {

namespace {

using io::gnuplotQuoted;

std::string jointUnit(const Scenario& scenario, int j) {
  return scenario.problem.robot.joints[j].type == JointType::kRevolute
             ? "rad"
             : unitName(scenario.problem.robot.length_unit);
}

std::string configuration(const Scenario& scenario, const Eigen::VectorXd& q) {
  std::string out = "[";
  for (int j = 0; j < q.size(); ++j) {
    out += (j ? ", " : "") + formatNumber(q[j], 4) + " " + jointUnit(scenario, j);
  }
  return out + "]";
}

nlohmann::json vectorJson(const Eigen::VectorXd& q) {
  return std::vector<double>(q.data(), q.data() + q.size());
}

nlohmann::json pathJson(const PathSafety& path) {
  nlohmann::json out{
      {"vertices", path.vertices},
      {"length", path.length},
      {"probability", path.probability},
      {"segments", path.segments},
      {"whole_path_free_poses", path.free_poses},
      {"whole_path_free_fraction", path.free_fraction},
      {"whole_path_free_interval_95", {path.free_interval.low, path.free_interval.high}},
      {"whole_path_colliding_poses", path.colliding_poses},
      {"whole_path_collision_rate", path.collision_rate},
      {"whole_path_collision_interval_95",
       {path.collision_interval.low, path.collision_interval.high}},
      {"worst_segment",
       {{"index", path.worst_segment},
        {"probability", path.worst_probability},
        {"from", vectorJson(path.worst_from)},
        {"to", vectorJson(path.worst_to)}}}};
  out["waypoints"] = nlohmann::json::array();
  for (const Eigen::VectorXd& q : path.waypoints) out["waypoints"].push_back(vectorJson(q));
  return out;
}

/// The configuration of a roadmap vertex, from the candidates that pass through it.
Eigen::VectorXd vertexConfiguration(const PlanningRound& round, std::size_t vertex) {
  for (const PathSafety& path : round.candidates) {
    for (std::size_t k = 0; k < path.vertices.size(); ++k)
      if (path.vertices[k] == vertex) return path.waypoints[k];
  }
  return {};
}

/// "ok", the refusal when some round found a path ("above_max_collision_probability" or
/// "below_threshold"), else the roadmap status of the last round.
std::string overallStatus(const SwayPlanningProblem& problem, const SwayPlanningResult& result) {
  if (result.accepted) return "ok";
  if (result.validated) {
    return problem.acceptance == Acceptance::kPatentP ? "below_threshold"
                                                      : "above_max_collision_probability";
  }
  return roadmapStatusName(result.rounds.back().status);
}

/// The acceptance criterion in words.
std::string criterion(const SwayPlanningProblem& problem) {
  if (problem.acceptance == Acceptance::kPatentP)
    return "patent_p: the patent's P >= threshold " + formatNumber(problem.threshold);
  return "whole_path: the upper end of the 95 % Wilson interval of the whole-path collision rate "
         "over the n = " +
         std::to_string(problem.base_poses) + " planning poses <= max_collision_probability " +
         formatNumber(problem.max_collision_probability);
}

/// When even a path free for all n poses is refused (the upper end at 0 of n is z^2 / (n + z^2)),
/// a note with the fewest poses that can pass: n >= z^2 (1 - max) / max; else "".
std::string fewestPoses(const SwayPlanningProblem& problem) {
  const double most = problem.max_collision_probability;
  if (wilsonInterval(0, problem.base_poses).high <= most) return "";
  // z^2 from the interval itself (at n = 1 the upper end is z^2 / (1 + z^2)); a step either way
  // settles the rounding.
  const double u = wilsonInterval(0, 1).high, z2 = u / (1.0 - u);
  auto n = static_cast<std::size_t>(std::ceil(z2 * (1.0 - most) / most));
  while (wilsonInterval(0, n).high > most) ++n;
  while (n > 1 && wilsonInterval(0, n - 1).high <= most) --n;
  return "; with n = " + std::to_string(problem.base_poses) +
         " poses not even a path free for all of them can pass: sway: poses must be at least " +
         std::to_string(n);
}

/// Why a best path is accepted or refused, in words.
std::string verdict(const SwayPlanningProblem& problem, const PathSafety& path, bool accepted) {
  if (problem.acceptance == Acceptance::kPatentP) {
    return std::string(accepted ? "accepted" : "refused") + ": P " +
           formatFixed(path.probability, 4) + (accepted ? " >= " : " < ") + "threshold " +
           formatNumber(problem.threshold) + " (patent_p)";
  }
  return std::string(accepted ? "accepted" : "refused") +
         ": the upper end of the 95 % interval of the whole-path collision rate, " +
         formatFixed(path.collision_interval.high, 4) + (accepted ? ", is at most" : ", exceeds") +
         " max_collision_probability " + formatNumber(problem.max_collision_probability) +
         " (whole_path)";
}

}  // namespace

std::string pathCsv(const Scenario& scenario, const PathSafety& path) {
  const Robot& robot = scenario.problem.robot;
  std::string out = "D";
  for (int j = 0; j < robot.dof(); ++j)
    out += "," + robot.joints[j].name + "_" + jointUnit(scenario, j);
  out += "\n";
  double distance = 0.0;
  for (std::size_t k = 0; k < path.waypoints.size(); ++k) {
    if (k > 0) {
      distance += scaledDistance(path.waypoints[k - 1], path.waypoints[k],
                                 scenario.problem.roadmap.joint_scale);
    }
    out += formatNumber(distance, 12);
    for (int j = 0; j < robot.dof(); ++j) out += "," + formatNumber(path.waypoints[k][j], 12);
    out += "\n";
  }
  return out;
}

namespace {

/// The units of every number of the JSON report.
nlohmann::json unitsJson(const Scenario& scenario) {
  const SwayPlanningProblem& problem = scenario.problem;
  nlohmann::json units{{"length", unitName(problem.robot.length_unit)},
                       {"angle", "rad"},
                       {"distance", scenario.distance_unit},
                       {"probability", "fraction in [0, 1]"},
                       {"time", "s"}};
  nlohmann::json joint_units = nlohmann::json::array();
  for (int j = 0; j < problem.robot.dof(); ++j) joint_units.push_back(jointUnit(scenario, j));
  units["configuration"] = joint_units;
  return units;
}

/// A shared node of a round: where it is, the paths through it and the one that dominates.
nlohmann::json sharedNodeJson(const PlanningRound& round, const SharedNodeDecision& decision) {
  nlohmann::json node{{"vertex", decision.vertex},
                      {"configuration", vectorJson(vertexConfiguration(round, decision.vertex))},
                      {"winner", decision.winner},
                      {"loops_cut", decision.looped},
                      {"paths", nlohmann::json::array()}};
  for (std::size_t k = 0; k < decision.paths.size(); ++k) {
    node["paths"].push_back({{"candidate", decision.paths[k]},
                             {"distance", decision.values[k].distance},
                             {"probability", decision.values[k].probability},
                             {"score", decision.scores[k]}});
  }
  return node;
}

nlohmann::json roundJson(const PlanningRound& round) {
  nlohmann::json r{{"base_offset", round.base_offset},
                   {"goal_displacement", round.goal_displacement},
                   {"roadmap_status", roadmapStatusName(round.status)},
                   {"roadmap_vertices", round.roadmap_vertices},
                   {"roadmap_edges", round.roadmap_edges},
                   {"reference_distance", round.reference_distance},
                   {"seconds", round.seconds},
                   {"roadmap_seconds", round.roadmap_seconds},
                   {"evaluation_seconds", round.evaluation_seconds},
                   {"candidates", nlohmann::json::array()},
                   {"shared_nodes", nlohmann::json::array()}};
  for (const PathSafety& path : round.candidates) r["candidates"].push_back(pathJson(path));
  for (const SharedNodeDecision& decision : round.decisions)
    r["shared_nodes"].push_back(sharedNodeJson(round, decision));
  if (round.best) {
    r["best"] = pathJson(*round.best);
    r["best"]["accepted"] = round.accepted;
  }
  return r;
}

/// The validation's rows, and the planned rows' numbers by name.
nlohmann::json validationJson(const SwayPlanningProblem& problem,
                              const SwayPlanningResult& result) {
  nlohmann::json v{{"poses", problem.validation_poses},
                   {"seconds", result.validation_seconds},
                   {"rows", nlohmann::json::array()}};
  for (const ValidationRow& row : result.validation) {
    // A row whose planner found no path has a status and no numbers: no length 0 or
    // probability 0 that reads as a perfect path.
    nlohmann::json item{{"name", row.name},
                        {"planned", row.planned},
                        {"status", row.planned ? "planned" : "no_path"},
                        {"roadmap_status", row.status},
                        {"seconds", row.seconds}};
    if (row.planned) {
      item["length"] = row.length;
      item["poses"] = row.poses;
      item["colliding_poses"] = row.colliding;
      item["collision_probability"] = row.collision_probability;
      item["interval_95"] = {row.interval.low, row.interval.high};
    }
    if (row.name == "padded") {
      item["padding"] = row.padding;
      item["planning_seconds"] = row.planning_seconds;
    }
    v["rows"].push_back(item);
    if (row.planned) {
      v[row.name + "_collision_probability"] = row.collision_probability;
      v[row.name + "_interval_95"] = {row.interval.low, row.interval.high};
      v[row.name + "_length"] = row.length;
    }
    if (row.name == "padded") v["padding"] = row.padding;
  }
  return v;
}

/// The report's head: the scenario, the acceptance criterion and the units.
void reportHeader(const Scenario& scenario, std::ostream& out) {
  const SwayPlanningProblem& problem = scenario.problem;
  out << "scenario " << scenario.name << " (" << scenario.robot_path
      << "): n = " << problem.base_poses << " base poses in the " << problem.sway.confidence * 100
      << " % region, m = " << problem.candidates << " candidates, rule "
      << (problem.score.rule == ScoreRule::kLiteral ? "literal (P - D)" : "weighted (P - w D / D0)")
      << ", w = " << problem.score.weight << "\n"
      << "acceptance " << criterion(problem) << "\n"
      << "units: lengths " << unitName(problem.robot.length_unit)
      << ", angles rad, times s; D = " << scenario.distance_unit
      << " (dimensionless, as are D0, w and the scores); P, the threshold and the free and "
         "collision rates are fractions in [0, 1]; so is max_collision_probability; P is the "
         "patent's mean of segment free rates, not the probability that the whole path is free; a "
         "path's whole-path collision rate is the share of base poses for which it collides "
         "anywhere along its length\n";
}

/// A round's candidates, one table line each.
void reportCandidates(const SwayPlanningProblem& problem, const PlanningRound& round,
                      std::ostream& out) {
  out << "  cand  length D  P (patent)  whole path collides: poses, rate [95 % CI]  "
         "worst segment: index, P\n";
  for (std::size_t c = 0; c < round.candidates.size(); ++c) {
    const PathSafety& path = round.candidates[c];
    char line[200];
    std::snprintf(line, sizeof line,
                  "  %4zu  %8.3f  %10.4f  %5zu of %-5zu %.3f [%.3f, %.3f]        %4zu, %.3f\n", c,
                  path.length, path.probability, path.colliding_poses, problem.base_poses,
                  path.collision_rate, path.collision_interval.low, path.collision_interval.high,
                  path.worst_segment, path.worst_probability);
    out << line;
  }
}

/// A round's shared nodes, one line each: the paths through it and the one that dominates.
void reportSharedNodes(const Scenario& scenario, const PlanningRound& round, std::ostream& out) {
  for (const SharedNodeDecision& decision : round.decisions) {
    out << "  shared node " << decision.vertex << " "
        << configuration(scenario, vertexConfiguration(round, decision.vertex)) << ":";
    for (std::size_t k = 0; k < decision.paths.size(); ++k) {
      out << " cand " << decision.paths[k] << " (D " << formatFixed(decision.values[k].distance, 3)
          << ", P " << formatFixed(decision.values[k].probability, 4) << ", score "
          << formatFixed(decision.scores[k], 4) << ")";
    }
    out << " -> cand " << decision.winner << " dominates";
    if (!decision.looped.empty()) {
      out << "; loop cut from cand";
      for (std::size_t c : decision.looped) out << " " << c;
    }
    out << "\n";
  }
}

/// Round r (from 0): its roadmap and, when it found paths, its candidates, shared nodes and best
/// path with the verdict.
void reportRound(const Scenario& scenario, std::size_t r, const PlanningRound& round,
                 std::ostream& out) {
  const SwayPlanningProblem& problem = scenario.problem;
  const std::string length_unit = unitName(problem.robot.length_unit);
  out << "\nround " << r + 1 << ": base offset " << round.base_offset << " " << length_unit
      << " along the line (goal's tool point " << formatNumber(round.goal_displacement, 4) << " "
      << length_unit << " from the target): roadmap " << round.roadmap_vertices << " vertices, "
      << round.roadmap_edges << " edges (" << roadmapStatusName(round.status)
      << "), D0 = " << formatNumber(round.reference_distance, 4) << ", "
      << formatFixed(round.seconds, 2) << " s (roadmap " << formatFixed(round.roadmap_seconds, 2)
      << " s, segments " << formatFixed(round.evaluation_seconds, 2) << " s)\n";
  if (!round.best) return;
  reportCandidates(problem, round, out);
  reportSharedNodes(scenario, round, out);
  const PathSafety& best = *round.best;
  out << "  best path: length " << formatFixed(best.length, 3) << ", P "
      << formatFixed(best.probability, 4) << ", whole path collides for " << best.colliding_poses
      << " of " << problem.base_poses << " poses (rate " << formatFixed(best.collision_rate, 3)
      << " [" << formatFixed(best.collision_interval.low, 3) << ", "
      << formatFixed(best.collision_interval.high, 3) << "]), worst segment " << best.worst_segment
      << " of " << best.segments << " (P " << formatFixed(best.worst_probability, 3) << ", from "
      << configuration(scenario, best.worst_from) << " to "
      << configuration(scenario, best.worst_to) << ")\n";
  out << "  " << verdict(problem, best, round.accepted) << "\n";
}

/// The validation's rows, one line each.
void reportValidation(const Scenario& scenario, const SwayPlanningResult& result,
                      std::ostream& out) {
  const SwayPlanningProblem& problem = scenario.problem;
  out << "\nvalidation on " << problem.validation_poses
      << " fresh base poses (another seed), whole-path collision probability";
  if (!result.accepted)
    out << " (\"chosen\": round " << *result.validated + 1 << "'s best path, refused)";
  out << ":\n";
  for (const ValidationRow& row : result.validation) {
    char line[200];
    if (!row.planned) {
      std::snprintf(line, sizeof line, "  %-9s no path (roadmap %s)", row.name.c_str(),
                    row.status.c_str());
    } else {
      std::snprintf(line, sizeof line,
                    "  %-9s length %8.3f  collides %.4f [%.4f, %.4f] (%zu of %zu)",
                    row.name.c_str(), row.length, row.collision_probability, row.interval.low,
                    row.interval.high, row.colliding, row.poses);
    }
    out << line;
    if (row.name == "padded") {
      out << ", obstacles padded by " << formatNumber(row.padding, 3) << " "
          << unitName(problem.robot.length_unit);
    }
    out << ", " << formatFixed(row.seconds, 2) << " s\n";
  }
}

}  // namespace

nlohmann::json planJson(const Scenario& scenario, const SwayPlanningResult& result) {
  const SwayPlanningProblem& problem = scenario.problem;
  nlohmann::json out{{"scenario", scenario.name},
                     {"robot", problem.robot.name},
                     {"robot_file", scenario.robot_path},
                     {"tip", tipName(problem.robot)},
                     {"length_unit", unitName(problem.robot.length_unit)},
                     {"units", unitsJson(scenario)},
                     {"status", overallStatus(problem, result)},
                     {"rule", problem.score.rule == ScoreRule::kLiteral ? "literal" : "weighted"},
                     {"weight", problem.score.weight},
                     {"acceptance", acceptanceName(problem.acceptance)},
                     {"max_collision_probability", problem.max_collision_probability},
                     {"threshold", problem.threshold},
                     {"allow_goal_shift", problem.allow_goal_shift},
                     {"base_poses", problem.base_poses},
                     {"candidates_requested", problem.candidates},
                     {"confidence", problem.sway.confidence},
                     {"rounds", nlohmann::json::array()}};
  for (const PlanningRound& round : result.rounds) out["rounds"].push_back(roundJson(round));
  if (result.validated) out["validated_round"] = *result.validated;
  if (result.accepted) {
    const PlanningRound& round = result.rounds[*result.accepted];
    out["accepted_round"] = *result.accepted;
    out["chosen"] = pathJson(*round.best);
    if (round.base_offset != 0.0) {
      out["goal_displacement"] = {{"value", round.goal_displacement},
                                  {"unit", unitName(problem.robot.length_unit)},
                                  {"base_offset", round.base_offset}};
    }
  }
  if (!result.validation.empty()) out["validation"] = validationJson(problem, result);
  return out;
}

std::string planReport(const Scenario& scenario, const SwayPlanningResult& result) {
  const SwayPlanningProblem& problem = scenario.problem;
  const std::string length_unit = unitName(problem.robot.length_unit);
  std::ostringstream out;
  reportHeader(scenario, out);
  for (std::size_t r = 0; r < result.rounds.size(); ++r)
    reportRound(scenario, r, result.rounds[r], out);
  if (!result.validation.empty()) reportValidation(scenario, result, out);
  out << "\nstatus: ";
  if (result.accepted) {
    const PlanningRound& round = result.rounds[*result.accepted];
    out << "ok: round " << *result.accepted + 1 << "'s best path is accepted ("
        << acceptanceName(problem.acceptance) << ")";
    if (round.base_offset != 0.0) {
      out << "; the base is shifted " << formatNumber(round.base_offset) << " " << length_unit
          << " along the line, so the tool ends " << formatNumber(round.goal_displacement, 4) << " "
          << length_unit << " from the target it reaches from the measured base pose "
          << "(goal_displacement)";
    }
  } else {
    out << noPathStatus(scenario, result);
  }
  out << "\n";
  return out.str();
}

std::string noPathStatus(const Scenario& scenario, const SwayPlanningResult& result) {
  const SwayPlanningProblem& problem = scenario.problem;
  const std::string status = overallStatus(problem, result);
  const std::string range = problem.base_step > 0.0 ? "at every base offset within the range"
                                                    : "(no base shift: base_step 0)";
  if (result.validated) {
    const PathSafety& best = *result.rounds[*result.validated].best;
    if (problem.acceptance == Acceptance::kPatentP) {
      return status + ": the best path's P stays below the threshold " +
             formatNumber(problem.threshold) + " " + range + " (highest " +
             formatFixed(best.probability, 4) + ")";
    }
    return status + ": the best path's whole-path collision rate over the " +
           std::to_string(problem.base_poses) +
           " planning poses has the upper end of its 95 % interval above " +
           "max_collision_probability " + formatNumber(problem.max_collision_probability) + " " +
           range + " (lowest " + formatFixed(best.collision_interval.high, 4) + ", " +
           std::to_string(best.colliding_poses) + " of " + std::to_string(problem.base_poses) +
           " poses colliding)" + fewestPoses(problem);
  }
  const PlanningRound& first = result.rounds.front();
  if (result.rounds.size() == 1 && first.status == RoadmapStatus::kStartInvalid)
    return status + " at the measured base pose (a base shift cannot move the arm's start)";
  if (result.rounds.size() == 1 && first.status == RoadmapStatus::kGoalInvalid &&
      !problem.allow_goal_shift)
    return status + " at the measured base pose (allow_goal_shift: false)";
  return status + " " + range;
}

std::vector<PlanningRound> scanOffsets(const SwayPlanner& planner,
                                       const PlanningProgress& progress) {
  const SwayPlanningProblem& p = planner.problem();
  const int steps = p.base_step <= 0.0
                        ? 0
                        : static_cast<int>(std::floor(p.base_range / p.base_step * (1.0 + 1e-12)));
  const auto total = static_cast<std::size_t>(2 * steps + 1);
  PlanningProgress inner;
  if (progress) {
    inner = [&](const std::string& stage, std::size_t done, std::size_t all) {
      progress("offset scan: " + stage, done, all);
    };
  }
  std::vector<PlanningRound> rounds;
  for (int k = -steps; k <= steps; ++k) {
    if (progress) progress("offset scan", rounds.size(), total);
    rounds.push_back(planner.planRound(k * p.base_step, inner));
  }
  if (progress) progress("offset scan", rounds.size(), total);
  return rounds;
}

std::string renderOffsetsPng(const Scenario& scenario, const std::vector<PlanningRound>& rounds) {
  io::ScratchDir dir;
  const std::string data = dir.file("offsets.dat"), png = dir.file("offsets.png");
  {
    std::ofstream file(data);
    for (const PlanningRound& round : rounds) {
      if (round.best) {
        file << round.base_offset << " " << round.best->probability << " "
             << round.best->free_fraction << " " << 1.0 - round.best->collision_interval.high
             << "\n";
      }
    }
  }
  const std::string unit = unitName(scenario.problem.robot.length_unit);
  std::ostringstream gp;
  gp << "set terminal pngcairo noenhanced size 900,600 font 'Sans,11'\n"
     << "set output " << gnuplotQuoted(png) << "\n"
     << "set title " << gnuplotQuoted(scenario.name + ": best path against the base offset") << "\n"
     << "set xlabel " << gnuplotQuoted("base offset along the line [" + unit + "]") << "\n"
     << "set ylabel 'probability'\nset yrange [0:1.05]\nset grid\nset key bottom right\n"
     << "plot " << gnuplotQuoted(data) << " using 1:2 with linespoints lw 2 pt 7 title "
     << "'P (patent: mean of segment free rates)', " << gnuplotQuoted(data)
     << " using 1:3 with linespoints lw 2 pt 5 title 'whole path free fraction', "
     << gnuplotQuoted(data)
     << " using 1:4 with linespoints lw 1 pt 4 title 'its lower 95 % bound (whole_path)', ";
  if (scenario.problem.acceptance == Acceptance::kPatentP) {
    gp << scenario.problem.threshold
       << " with lines dt 2 lc rgb 'black' title 'threshold on P (patent_p)'\n";
  } else {
    gp << 1.0 - scenario.problem.max_collision_probability
       << " with lines dt 2 lc rgb 'black' title '1 - max_collision_probability'\n";
  }
  return io::runGnuplot(dir, gp.str(), png);
}

std::string renderConfigurationSpacePng(const Scenario& scenario, const SwayPlanner& planner,
                                        const PlanningRound& round, int cells) {
  const Robot& robot = scenario.problem.robot;
  if (robot.dof() != 2) {
    throw Error("the configuration-space picture needs a two-joint robot; '" + robot.name +
                "' has " + std::to_string(robot.dof()));
  }
  io::ScratchDir dir;
  const std::string grid = dir.file("grid.dat"), png = dir.file("cspace.png");
  const Joint& a = robot.joints[0];
  const Joint& b = robot.joints[1];
  {
    std::ofstream file(grid);
    Eigen::VectorXd q(2);
    for (int i = 0; i < cells; ++i) {
      for (int k = 0; k < cells; ++k) {
        q[0] = a.lower + (a.upper - a.lower) * (i + 0.5) / cells;
        q[1] = b.lower + (b.upper - b.lower) * (k + 0.5) / cells;
        file << q[0] << " " << q[1] << " " << planner.collisionFraction(q) << "\n";
      }
      file << "\n";
    }
  }
  std::ostringstream gp;
  gp << "set terminal pngcairo noenhanced size 1000,900 font 'Sans,11'\n"
     << "set output " << gnuplotQuoted(png) << "\n"
     << "set title "
     << gnuplotQuoted(scenario.name +
                      ": share of base poses in collision, candidates and the "
                      "chosen path")
     << "\n"
     << "set xlabel " << gnuplotQuoted(a.name + " [" + jointUnit(scenario, 0) + "]") << "\n"
     << "set ylabel " << gnuplotQuoted(b.name + " [" + jointUnit(scenario, 1) + "]") << "\n"
     << "set xrange [" << a.lower << ":" << a.upper << "]\nset yrange [" << b.lower << ":"
     << b.upper << "]\n"
     << "set cbrange [0:1]\nset cblabel 'fraction of base poses colliding'\n"
     << "set palette defined (0 'white', 0.01 '#fde0c5', 0.5 '#f08a4b', 1 '#7f2704')\n"
     << "set key outside below\n";
  std::string plot = "plot " + gnuplotQuoted(grid) + " using 1:2:3 with image notitle";
  for (std::size_t c = 0; c < round.candidates.size(); ++c) {
    const std::string file = dir.file("cand" + std::to_string(c) + ".dat");
    std::ofstream out(file);
    for (const Eigen::VectorXd& q : round.candidates[c].waypoints)
      out << q[0] << " " << q[1] << "\n";
    plot += ", " + gnuplotQuoted(file) + " using 1:2 with lines lw 1.5 dt " +
            std::to_string(2 + c % 4) + " title " + gnuplotQuoted("candidate " + std::to_string(c));
  }
  if (round.best) {
    const std::string file = dir.file("best.dat");
    std::ofstream out(file);
    for (const Eigen::VectorXd& q : round.best->waypoints) out << q[0] << " " << q[1] << "\n";
    plot +=
        ", " + gnuplotQuoted(file) + " using 1:2 with lines lw 4 lc rgb '#08519c' title 'chosen'";
  }
  int label = 1;
  for (std::size_t d = 0; d < round.decisions.size(); ++d) {
    const SharedNodeDecision& decision = round.decisions[d];
    const Eigen::VectorXd q = vertexConfiguration(round, decision.vertex);
    if (q.size() != 2) continue;
    gp << "set label " << label++ << " "
       << gnuplotQuoted("X" + std::to_string(d + 1) + ": cand " + std::to_string(decision.winner))
       << " at " << q[0] << "," << q[1] << " offset 0.6,0.6 front\n";
    gp << "set object " << label++ << " circle at " << q[0] << "," << q[1]
       << " size char 0.5 fc rgb 'black' fs solid front\n";
  }
  gp << plot << "\n";
  return io::runGnuplot(dir, gp.str(), png);
}

}  // namespace mcws
