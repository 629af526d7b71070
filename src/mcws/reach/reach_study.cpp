#include "mcws/reach/reach_study.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>
#include <string>

#include "mcws/core/counter_rng.h"
#include "mcws/core/error.h"
#include "mcws/core/first_error.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/jacobian.h"

namespace mcws {

namespace {

/// The IK tolerance standing for an approach tolerance of 0 [rad].
constexpr double kExactAngle = 1e-6;

/// Angle between the tool's z axis (or the whole rotation, when the roll counts) and R_target's.
double orientationError(bool free_roll, const Eigen::Matrix3d& R_target, const Eigen::Matrix3d& R) {
  if (free_roll) {
    const Eigen::Vector3d z = R.col(2), z_target = R_target.col(2);
    return std::atan2(z.cross(z_target).norm(), z.dot(z_target));
  }
  return Eigen::AngleAxisd(R_target * R.transpose()).angle();
}

/// b is the better solution of a: solved first, then collision-free, then the higher
/// manipulability; of two unsolved attempts the closer one (position, then orientation).
bool better(const TargetReach& b, const TargetReach& a) {
  if (!a.solved && !b.solved) {
    if (b.position_error != a.position_error) return b.position_error < a.position_error;
    return b.orientation_error < a.orientation_error;
  }
  if (!a.solved) return b.solved;
  if (!b.solved) return false;
  const bool free_a = a.label == kLabelFree, free_b = b.label == kLabelFree;
  if (free_a != free_b) return free_b;
  return b.manipulability > a.manipulability;
}

}  // namespace

void ReachStudyOptions::check() const {
  std::ostringstream msg;
  if (!(approach_tolerance >= 0.0) || !(approach_tolerance <= M_PI)) {
    msg << "approach tolerance " << approach_tolerance << " rad is not within [0, pi]";
  } else if (starts < 1) {
    msg << "IK starts " << starts << " is not at least 1";
  } else if (ik.max_iterations < 1 || ik.restarts < 0) {
    msg << "IK max_iterations " << ik.max_iterations << " or restarts " << ik.restarts
        << " is out of range (>= 1, >= 0)";
  } else if (!(ik.position_tolerance > 0.0) || !std::isfinite(ik.position_tolerance)) {
    msg << "IK position tolerance " << ik.position_tolerance << " is not a positive number";
  } else if (!(clearance_cap > 0.0)) {
    msg << "clearance cap " << clearance_cap << " is not positive";
  } else {
    quality.check();
    return;
  }
  throw Error(msg.str());
}

ReachSummary summarize(const std::vector<TargetReach>& results) {
  ReachSummary s;
  s.targets = results.size();
  double score = 0.0, manipulability = 0.0;
  for (const TargetReach& r : results) {
    s.solved += r.solved ? 1 : 0;
    score += r.score();
    if (!r.reached) continue;
    ++s.reached;
    manipulability += r.manipulability;
    s.min_clearance_reached = std::min(s.min_clearance_reached, r.clearance);
  }
  if (s.targets > 0) {
    s.share_reached = static_cast<double>(s.reached) / static_cast<double>(s.targets);
    s.mean_score = score / static_cast<double>(s.targets);
  }
  if (s.reached > 0)
    s.mean_manipulability_reached = manipulability / static_cast<double>(s.reached);
  return s;
}

ReachStudy::ReachStudy(const Robot& robot, const CollisionChecker* checker,
                       const ReachStudyOptions& options)
    : robot_(robot), checker_(checker), options_(options), solver_(robot) {
  options_.check();
  options_.ik.orientation_tolerance = std::max(options_.approach_tolerance, kExactAngle);
}

Eigen::VectorXd ReachStudy::startOf(int start) const {
  const int n = robot_.dof();
  Eigen::VectorXd q(n);
  const CounterRng rng(options_.ik.seed ^ 0x5eedULL);
  for (int j = 0; j < n; ++j) {
    const Joint& joint = robot_.joints[j];
    const double lower = std::isfinite(joint.lower) ? joint.lower : -M_PI;
    const double upper = std::isfinite(joint.upper) ? joint.upper : M_PI;
    const double u = start == 0 ? 0.5
                                : rng.uniform(static_cast<std::uint64_t>(start),
                                              static_cast<std::uint64_t>(j) % CounterRng::kStreams);
    q[j] = lower + (upper - lower) * u;
  }
  return q;
}

bool ReachStudy::solve(const ReachTarget& target, const Eigen::Isometry3d& T, int start,
                       IkResult& result) const {
  IkOptions ik = options_.ik;
  ik.seed = options_.ik.seed + static_cast<std::uint64_t>(start);
  ik.free_roll = target.free_roll;
  result = solver_.solve(T, startOf(start), ik);
  if (result.converged()) return true;
  // The orientation cannot be met exactly: the point alone, from the closest attempt, and the
  // orientation it leaves.
  if (options_.approach_tolerance <= 0.0) return false;
  ik.position_only = true;
  IkResult point = solver_.solve(T, result.q, ik);
  if (!point.converged()) return false;
  point.orientation_error =
      orientationError(target.free_roll, T.linear(), toolPose(robot_, point.q).linear());
  if (point.orientation_error > options_.approach_tolerance) return false;
  result = point;
  return true;
}

void ReachStudy::assess(TargetReach& reach, const Eigen::Isometry3d& T_move) const {
  reach.manipulability =
      jacobianQuality(toolJacobian(robot_, reach.q), options_.quality).manipulability;
  if (!checker_) return;
  CollisionChecker::Scratch scratch;
  const Eigen::Isometry3d T_world_base = T_move * robot_.T_world_base;
  reach.label = checker_->label(reach.q.data(), T_world_base, scratch);
  reach.clearance = options_.clearance_cap;
  if (reach.label != kLabelFree) {
    reach.clearance = 0.0;
    return;
  }
  checker_->place(reach.q.data(), T_world_base, scratch);
  for (std::size_t pair = 0; pair < checker_->pairs().size(); ++pair) {
    reach.clearance =
        std::min(reach.clearance, checker_->clearance(pair, reach.clearance, scratch));
  }
}

TargetReach ReachStudy::evaluate(const ReachTarget& target, const Eigen::Isometry3d& T_move) const {
  const Eigen::Isometry3d T = T_move.inverse() * target.pose;
  TargetReach best;
  for (int start = 0; start < options_.starts; ++start) {
    IkResult result;
    TargetReach candidate;
    candidate.solved = solve(target, T, start, result);
    candidate.q = result.q;
    candidate.position_error = result.position_error;
    candidate.orientation_error = result.orientation_error;
    if (candidate.solved) assess(candidate, T_move);
    if (start == 0 || better(candidate, best)) best = candidate;
  }
  best.reached = best.solved && best.label == kLabelFree;
  return best;
}

std::vector<TargetReach> ReachStudy::evaluate(
    const std::vector<ReachTarget>& targets, const Eigen::Isometry3d& T_move,
    const std::function<void(std::size_t, std::size_t)>& progress) const {
  std::vector<TargetReach> results(targets.size());
  std::atomic<std::size_t> done{0};
  const int threads = options_.threads > 0 ? options_.threads : omp_get_num_procs();
  FirstError error;
#pragma omp parallel for schedule(dynamic) num_threads(threads)
  for (std::size_t i = 0; i < targets.size(); ++i) {
    error.run(i, [&] {
      results[i] = evaluate(targets[i], T_move);
      const std::size_t finished = ++done;
      if (progress && omp_get_thread_num() == 0) progress(finished, targets.size());
    });
  }
  error.rethrow();
  if (progress) progress(targets.size(), targets.size());
  return results;
}

ReachTargetPoint reachTargetPoint(const ReachTarget& target, const TargetReach& reach) {
  ReachTargetPoint point;
  point.getVector3fMap() = target.pose.translation().cast<float>();
  point.getNormalVector3fMap() = (-target.pose.linear().col(2)).cast<float>();
  if (reach.solved) {
    for (int j = 0; j < std::min<int>(kMaxJoints, static_cast<int>(reach.q.size())); ++j) {
      point.q[j] = static_cast<float>(reach.q[j]);
    }
    if (std::isfinite(reach.clearance)) point.clearance = static_cast<float>(reach.clearance);
  }
  point.label = reach.label;
  point.reached = reach.reached ? 1.f : 0.f;
  point.score = static_cast<float>(reach.score());
  point.manipulability = static_cast<float>(reach.manipulability);
  point.orientation_error = static_cast<float>(reach.orientation_error);
  return point;
}

}  // namespace mcws
