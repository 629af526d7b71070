#include "mcws/reach/base_placement.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <fstream>
#include <numeric>
#include <sstream>
#include <string>

#include "mcws/core/error.h"
#include "mcws/core/first_error.h"
#include "mcws/io/gnuplot.h"

namespace mcws {

bool mapReaches(const ReachMap& map, const ReachTarget& target, const Eigen::Vector3d& offset,
                double approach_tolerance, float* manipulability) {
  const long found = map.find(target.pose.translation() - offset);
  if (found < 0) return false;
  const auto v = static_cast<std::size_t>(found);
  const Eigen::Matrix3d& R = target.pose.linear();
  bool reached = false;
  if (!target.free_roll) {
    reached = map.reached(v, map.bins().bin(R.col(2), R.col(0)));
  } else {
    const SpherePartition& sphere = map.bins().sphere();
    reached = map.approachReached(v, sphere.region(R.col(2)));
    // Rings of directions around the approach out to the tolerance, spaced at most half a
    // region's diameter (about 3.5 / sqrt(N) rad) apart, along and across the rings.
    const double spacing = 1.75 / std::sqrt(static_cast<double>(sphere.regions()));
    const double tolerance = std::min(approach_tolerance, M_PI);  // beyond pi: every direction
    const int rings = tolerance > 0.0 ? static_cast<int>(std::ceil(tolerance / spacing)) : 0;
    for (int ring = 1; ring <= rings && !reached; ++ring) {
      const double tilt = tolerance * ring / rings;
      const int probes =
          std::max(8, static_cast<int>(std::ceil(2.0 * M_PI * std::sin(tilt) / spacing)));
      for (int k = 0; k < probes && !reached; ++k) {
        const double turn = 2.0 * M_PI * k / probes;
        const Eigen::Vector3d d =
            std::cos(tilt) * R.col(2) +
            std::sin(tilt) * (std::cos(turn) * R.col(0) + std::sin(turn) * R.col(1));
        reached = map.approachReached(v, sphere.region(d));
      }
    }
  }
  if (reached && manipulability) *manipulability = map.bestManipulability(v);
  return reached;
}

std::vector<std::size_t> candidatesToConfirm(const std::vector<BaseCandidate>& candidates,
                                             const PlacementOptions& options) {
  std::vector<std::size_t> order(candidates.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const BaseCandidate &x = candidates[a], &y = candidates[b];
    if (x.map_share != y.map_share) return x.map_share > y.map_share;
    return x.map_score > y.map_score;
  });
  std::size_t confirm = options.confirm < 0
                            ? order.size()
                            : std::min(order.size(), static_cast<std::size_t>(options.confirm));
  if (options.confirm_margin >= 0.0 && !order.empty()) {
    // A hair below, so a share equal to the best less the margin is in despite rounding.
    const double floor = candidates[order.front()].map_share - options.confirm_margin - 1e-12;
    while (confirm < order.size() && candidates[order[confirm]].map_share >= floor) ++confirm;
  }
  order.resize(confirm);
  return order;
}

std::vector<BaseCandidate> placeBase(
    const ReachMap& map, const ReachStudy& study, const std::vector<ReachTarget>& targets,
    const std::vector<Eigen::Vector3d>& offsets, const PlacementOptions& options,
    const std::function<void(std::size_t, std::size_t)>& progress) {
  if (targets.empty()) throw Error("base placement: no targets");
  if (offsets.empty()) throw Error("base placement: no base positions");
  std::vector<BaseCandidate> candidates(offsets.size());
  const double n = static_cast<double>(targets.size());
  for (std::size_t c = 0; c < offsets.size(); ++c) {
    BaseCandidate& candidate = candidates[c];
    candidate.offset = offsets[c];
    std::size_t reached = 0;
    double score = 0.0;
    for (const ReachTarget& target : targets) {
      float best = 0.f;
      if (mapReaches(map, target, offsets[c], options.approach_tolerance, &best)) {
        ++reached;
        score += best;
      }
    }
    candidate.map_share = static_cast<double>(reached) / n;
    candidate.map_score = score / n;
  }
  const std::vector<std::size_t> order = candidatesToConfirm(candidates, options);
  const std::size_t confirm = order.size();
  // Parallel over (candidate, target) pairs, a block of candidates at a time (a region per
  // candidate would wait at its barrier after a handful of targets; all pairs at once would hold
  // every result in memory).
  const std::size_t n_targets = targets.size();
  const std::size_t block = std::max<std::size_t>(1, (std::size_t{1} << 16) / n_targets);
  const int threads = study.options().threads > 0 ? study.options().threads : omp_get_num_procs();
  std::vector<TargetReach> results;
  for (std::size_t first = 0; first < confirm; first += block) {
    const std::size_t count = std::min(block, confirm - first);
    results.assign(count * n_targets, TargetReach());
    FirstError error;
#pragma omp parallel for schedule(dynamic) num_threads(threads)
    for (std::size_t i = 0; i < results.size(); ++i) {
      error.run(i, [&] {
        Eigen::Isometry3d move = Eigen::Isometry3d::Identity();
        move.translation() = candidates[order[first + i / n_targets]].offset;
        results[i] = study.evaluate(targets[i % n_targets], move);
      });
    }
    error.rethrow();
    for (std::size_t k = 0; k < count; ++k) {
      BaseCandidate& candidate = candidates[order[first + k]];
      candidate.ik = summarize(std::vector<TargetReach>(
          results.begin() + static_cast<std::ptrdiff_t>(k * n_targets),
          results.begin() + static_cast<std::ptrdiff_t>((k + 1) * n_targets)));
      candidate.confirmed = true;
    }
    if (progress) progress(first + count, confirm);
  }
  return candidates;
}

std::vector<Eigen::Vector3d> offsetGrid(const std::vector<double>& xs,
                                        const std::vector<double>& ys,
                                        const std::vector<double>& zs) {
  std::vector<Eigen::Vector3d> all;
  all.reserve(xs.size() * ys.size() * zs.size());
  for (double x : xs) {
    for (double y : ys) {
      for (double z : zs) all.emplace_back(x, y, z);
    }
  }
  return all;
}

int bestCandidate(const std::vector<BaseCandidate>& candidates) {
  int best = -1;
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const BaseCandidate& x = candidates[c];
    if (!x.confirmed) continue;
    if (best < 0) {
      best = static_cast<int>(c);
      continue;
    }
    const ReachSummary& b = candidates[static_cast<std::size_t>(best)].ik;
    if (x.ik.share_reached > b.share_reached ||
        (x.ik.share_reached == b.share_reached && x.ik.mean_score > b.mean_score)) {
      best = static_cast<int>(c);
    }
  }
  return best;
}

std::string renderPlacementPng(const std::vector<BaseCandidate>& candidates,
                               const std::string& title, const std::string& unit) {
  io::ScratchDir dir;
  const std::string map_data = dir.file("map.dat"), ik_data = dir.file("ik.dat"),
                    png = dir.file("placement.png");
  std::size_t confirmed = 0;
  {
    // Several candidates at one x (a grid): the best of them.
    std::vector<std::pair<double, double>> map_best, ik_best;
    auto keep = [](std::vector<std::pair<double, double>>& best, double x, double share) {
      for (auto& [bx, bs] : best) {
        if (bx == x) {
          bs = std::max(bs, share);
          return;
        }
      }
      best.emplace_back(x, share);
    };
    for (const BaseCandidate& c : candidates) {
      keep(map_best, c.offset.x(), 100.0 * c.map_share);
      if (c.confirmed) keep(ik_best, c.offset.x(), 100.0 * c.ik.share_reached);
    }
    std::sort(map_best.begin(), map_best.end());
    std::sort(ik_best.begin(), ik_best.end());
    std::ofstream map_out(map_data), ik_out(ik_data);
    for (const auto& [x, s] : map_best) map_out << x << ' ' << s << '\n';
    for (const auto& [x, s] : ik_best) ik_out << x << ' ' << s << '\n';
    confirmed = ik_best.size();
  }
  std::ostringstream gp;
  gp << "set terminal pngcairo noenhanced size 1000,600 font 'Sans,11'\n"
     << "set output " << io::gnuplotQuoted(png) << "\n"
     << "set title " << io::gnuplotQuoted(title + ": targets reached against the base position")
     << "\nset xlabel " << io::gnuplotQuoted("base moved along x [" + unit + "]")
     << "\nset ylabel 'targets reached [%]'\nset yrange [0:105]\nset grid\nset key bottom right\n"
     << "plot " << io::gnuplotQuoted(map_data)
     << " using 1:2 with linespoints lw 2 pt 7 ps 0.6 lc rgb '#4686fb' title "
        "'reachability map (estimate)'";
  if (confirmed > 0) {
    gp << ", " << io::gnuplotQuoted(ik_data)
       << " using 1:2 with points pt 9 ps 1.6 lc rgb '#7a0403' title 'inverse kinematics "
          "(confirmed)'";
  }
  gp << "\n";
  return io::runGnuplot(dir, gp.str(), png);
}

std::vector<BasePoint> basePoints(const std::vector<BaseCandidate>& candidates,
                                  const Eigen::Isometry3d& T_world_base) {
  std::vector<BasePoint> points;
  for (const BaseCandidate& c : candidates) {
    BasePoint p;
    p.getVector3fMap() = (T_world_base.translation() + c.offset).cast<float>();
    p.map_share = static_cast<float>(c.map_share);
    p.map_score = static_cast<float>(c.map_score);
    if (c.confirmed) {
      p.ik_share = static_cast<float>(c.ik.share_reached);
      p.ik_score = static_cast<float>(c.ik.mean_score);
    }
    points.push_back(p);
  }
  return points;
}

}  // namespace mcws
