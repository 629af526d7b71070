#include "mcws/collision/allowed_pairs.h"

#include <algorithm>
#include <map>
#include <string>
#include <utility>

#include "mcws/collision/collision_checker.h"
#include "mcws/core/error.h"
#include "mcws/sampling/sampler.h"

namespace mcws {
namespace {

/// Collision counts of every pair the checker tests.
struct PairCounts {
  std::vector<bool> at_default;
  std::vector<std::size_t> colliding;  ///< samples in which the pair collides
};

PairCounts countCollisions(const Robot& robot, const CollisionChecker& checker, std::size_t samples,
                           std::uint64_t seed) {
  const std::size_t n = checker.pairs().size();
  PairCounts counts{std::vector<bool>(n, false), std::vector<std::size_t>(n, 0)};
  CollisionChecker::Scratch scratch;
  std::vector<double> q(std::size_t(robot.dof()), 0.0);
  for (std::size_t j = 0; j < q.size(); ++j) {
    q[j] = std::clamp(0.0, robot.joints[j].lower, robot.joints[j].upper);
  }
  checker.place(q.data(), robot.T_world_base, scratch);
  for (std::size_t p = 0; p < n; ++p) counts.at_default[p] = checker.collides(p, scratch);
  RobotSamplerOptions options;
  options.seed = seed;
  const RobotSampler sampler(robot, options);
  for (std::size_t s = 0; s < samples; ++s) {
    sampler.jointValues(s, q.data());
    checker.place(q.data(), robot.T_world_base, scratch);
    for (std::size_t p = 0; p < n; ++p) counts.colliding[p] += checker.collides(p, scratch);
  }
  return counts;
}

}  // namespace

std::vector<DisabledCollision> findAllowedPairs(const Robot& robot, const CollisionModel& model,
                                                std::size_t samples, std::uint64_t seed) {
  if (samples == 0) throw Error("findAllowedPairs: needs at least one sample");
  CollisionModel all_pairs = model;
  all_pairs.allowed.clear();
  const CollisionChecker checker(robot, all_pairs);

  std::map<std::string, int> body_index;
  for (int i = 0; i < checker.bodyCount(); ++i) body_index[checker.bodyName(i)] = i;
  std::vector<std::vector<std::string>> links(std::size_t(checker.bodyCount()));
  for (const auto& [link, body] : linkBodies(model)) links[body_index.at(body)].push_back(link);

  std::vector<DisabledCollision> out;
  const auto name = [&](int a, int b, const char* reason) {
    for (const std::string& link_a : links[a]) {
      for (const std::string& link_b : links[b]) out.push_back({link_a, link_b, reason});
    }
  };
  std::map<std::pair<int, int>, std::size_t> tested;  // body pair -> index in pairs()
  for (std::size_t p = 0; p < checker.pairs().size(); ++p) {
    const CollisionPair& pair = checker.pairs()[p];
    tested[std::minmax(pair.body_a, pair.body_b)] = p;
  }
  for (int a = 0; a < checker.bodyCount(); ++a) {
    for (std::size_t i = 0; i < links[a].size(); ++i) {
      for (std::size_t j = i + 1; j < links[a].size(); ++j) {
        out.push_back({links[a][i], links[a][j], "Adjacent"});
      }
    }
    for (int b = a + 1; b < checker.bodyCount(); ++b) {
      if (!tested.count({a, b})) name(a, b, "Adjacent");
    }
  }
  const PairCounts counts = countCollisions(robot, checker, samples, seed);
  for (const char* reason : {"Default", "Always", "Never"}) {
    for (const auto& [bodies, p] : tested) {
      const bool is_default = counts.at_default[p];
      const std::size_t hits = counts.colliding[p];
      const std::string why = is_default        ? "Default"
                              : hits == samples ? "Always"
                              : hits == 0       ? "Never"
                                                : "";
      if (why == reason) name(bodies.first, bodies.second, reason);
    }
  }
  return out;
}

}  // namespace mcws
