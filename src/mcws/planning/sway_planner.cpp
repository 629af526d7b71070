#include "mcws/planning/sway_planner.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "mcws/core/decimal.h"
#include "mcws/core/error.h"
#include "mcws/core/first_error.h"
#include "mcws/kinematics/forward_kinematics.h"

namespace mcws {

const char* acceptanceName(Acceptance acceptance) {
  return acceptance == Acceptance::kPatentP ? "patent_p" : "whole_path";
}

namespace {

/// Calls `cancel_check` (when set) on the thread that called the library, thread 0 of an OpenMP
/// team (the Python bindings look for Ctrl-C there only); inside a FirstError::run, so what it
/// throws skips the loop's items not yet started and is rethrown after the loop.
void checkOnCallingThread(const CancelCheck& cancel_check) {
  if (cancel_check && omp_get_thread_num() == 0) cancel_check();
}

/// Base poses of a run and what bounds their effect on a clearance.
struct PoseSet {
  std::vector<Eigen::Isometry3d> T_world_base;  ///< the displaced base poses
  std::vector<MotionCertifier::DisplacementBound> bounds;
  Eigen::Vector3d pivot{Eigen::Vector3d::Zero()};  ///< world
  double max_sin{0.0}, max_shift{0.0};
};

/// Displacements about the sway frame moved by the base offset, applied to the measured base.
PoseSet makePoses(const std::vector<Eigen::Isometry3d>& displacements,
                  const Eigen::Isometry3d& T_world_base, const Eigen::Vector3d& pivot) {
  PoseSet poses;
  poses.pivot = pivot;
  for (const Eigen::Isometry3d& displacement : displacements) {
    poses.T_world_base.push_back(displacement * T_world_base);
    poses.bounds.push_back(MotionCertifier::displacementBound(displacement, pivot));
    poses.max_sin = std::max(poses.max_sin, poses.bounds.back().sin_term);
    poses.max_shift = std::max(poses.max_shift, poses.bounds.back().shift);
  }
  return poses;
}

/// A polyline in joint space with its checkpoints' clearances for the nominal base: a segment is
/// free for a displaced base when the nominal clearances, less how far the displacement can move
/// each body, still certify it (MotionCertifier's test); otherwise it is checked exactly.
class PolylineCheck {
 public:
  PolylineCheck(const MotionCertifier& certifier, const Eigen::Isometry3d& T_nominal,
                const PoseSet& poses, std::vector<Eigen::VectorXd> points,
                CollisionChecker::Scratch& scratch)
      : certifier_(certifier), poses_(poses), points_(std::move(points)) {
    const std::size_t pairs = certifier.pairs(PairSet::kEnvironment).size();
    bounds_.resize(segments());
    for (std::size_t k = 0; k < segments(); ++k)
      certifier.motionBounds(points_[k], points_[k + 1], PairSet::kEnvironment, bounds_[k]);
    for (const std::vector<double>& b : bounds_)
      for (double v : b) cap_ = std::max(cap_, v + certifier.options().resolution);
    clearance_.resize(points_.size());
    pivot_reach_.resize(points_.size());
    const CollisionChecker& checker = certifier.checker();
    for (std::size_t k = 0; k < points_.size(); ++k) {
      double motion = 0.0;
      for (std::size_t s : {k - 1, k}) {
        if (s < segments())
          for (double b : bounds_[s]) motion = std::max(motion, b);
      }
      // Bodies' bounding spheres about the pivot, then clearances capped where no pose needs
      // more.
      checker.place(points_[k].data(), T_nominal, scratch);
      pivot_reach_[k].resize(pairs);
      double farthest = 0.0;
      for (std::size_t e = 0; e < pairs; ++e) {
        const int body = certifier.environmentBody(e);
        const CollisionChecker::BodySphere sphere = checker.bodySphere(body);
        pivot_reach_[k][e] =
            (checker.bodyPose(body, scratch) * sphere.center - poses.pivot).norm() + sphere.radius;
        farthest = std::max(farthest, pivot_reach_[k][e]);
      }
      const double cap = motion + poses.max_sin * farthest + poses.max_shift + 1e-6;
      certifier.clearances(points_[k], T_nominal, PairSet::kEnvironment, cap, scratch,
                           clearance_[k]);
    }
  }

  std::size_t segments() const { return points_.size() - 1; }

  /// Do the nominal clearances, less how far pose j can move each body, certify segment k?
  bool certifiedByBounds(std::size_t k, std::size_t j) const {
    const MotionCertifier::DisplacementBound& d = poses_.bounds[j];
    const std::vector<double>& bounds = bounds_[k];
    for (std::size_t e = 0; e < bounds.size(); ++e) {
      const double a = clearance_[k][e] - d.sin_term * pivot_reach_[k][e] - d.shift;
      const double b = clearance_[k + 1][e] - d.sin_term * pivot_reach_[k + 1][e] - d.shift;
      if (!(a > 0.0 && b > 0.0 && a + b > bounds[e])) return false;
    }
    return true;
  }
  const std::vector<Eigen::VectorXd>& points() const { return points_; }

  /// Is segment k free with the base at pose j?
  bool segmentFree(std::size_t k, std::size_t j, CollisionChecker::Scratch& scratch) const {
    return certifiedByBounds(k, j) ||
           certifier_.motionFree(points_[k], points_[k + 1], poses_.T_world_base[j],
                                 PairSet::kEnvironment, scratch);
  }

  /// Is the whole polyline free with the base at pose j? Segments the nominal clearances do not
  /// certify are checked exactly, each checkpoint's clearances computed once.
  bool pathFree(std::size_t j, CollisionChecker::Scratch& scratch) const {
    std::vector<double> at_start, at_end;
    bool have_start = false;
    const Eigen::Isometry3d& T = poses_.T_world_base[j];
    auto exact = [&](std::size_t k, std::vector<double>& out) {
      certifier_.clearances(points_[k], T, PairSet::kEnvironment, cap_, scratch, out);
      return std::all_of(out.begin(), out.end(), [](double v) { return v > 0.0; });
    };
    for (std::size_t k = 0; k < segments(); ++k) {
      if (certifiedByBounds(k, j)) {
        have_start = false;
        continue;
      }
      if (!have_start && !exact(k, at_start)) return false;
      if (!exact(k + 1, at_end)) return false;
      if (!certifier_.motionFree(points_[k], at_start, points_[k + 1], at_end, T,
                                 PairSet::kEnvironment, scratch))
        return false;
      std::swap(at_start, at_end);
      have_start = true;
    }
    return true;
  }

 private:
  const MotionCertifier& certifier_;
  const PoseSet& poses_;
  std::vector<Eigen::VectorXd> points_;
  std::vector<std::vector<double>> bounds_;  ///< per segment, per environment pair
  double cap_{0.0};  ///< the largest motion bound: exact clearances are needed up to it
  std::vector<std::vector<double>> clearance_;    ///< per checkpoint, per environment pair
  std::vector<std::vector<double>> pivot_reach_;  ///< per checkpoint, per environment pair
};

/// The points that cut the line from a to b into equal segments no longer than `length`.
std::vector<Eigen::VectorXd> subdivide(const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                                       const Eigen::VectorXd& scale, double length) {
  const double distance = scaledDistance(a, b, scale);
  const std::size_t count =
      std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(distance / length - 1e-9)));
  std::vector<Eigen::VectorXd> points;
  for (std::size_t k = 0; k <= count; ++k)
    points.push_back(a + (b - a) * (static_cast<double>(k) / static_cast<double>(count)));
  return points;
}

/// Undirected edge key.
std::pair<std::size_t, std::size_t> edgeKey(std::size_t u, std::size_t v) {
  return {std::min(u, v), std::max(u, v)};
}

/// Free states of one roadmap edge's segments (from the lower-numbered vertex) for each pose.
struct EdgeStates {
  double length{0.0};
  std::vector<std::vector<std::uint8_t>> free;  ///< [segment][pose]
  std::vector<double> probability;              ///< [segment]
  std::vector<Eigen::VectorXd> points;
};

/// The evaluated edges of a round, by edgeKey.
using EdgeMap = std::map<std::pair<std::size_t, std::size_t>, EdgeStates>;

}  // namespace

SwayPlanner::SwayPlanner(SwayPlanningProblem problem) : problem_(std::move(problem)) {
  const SwayPlanningProblem& p = problem_;
  if (p.base_poses == 0) throw Error("base_poses (n) must be at least 1");
  if (p.candidates == 0) throw Error("candidates (m) must be at least 1");
  if (!(p.segment_length > 0.0) || !std::isfinite(p.segment_length))
    throw Error("segment_length " + formatNumber(p.segment_length) + " must be > 0");
  if (!(p.diversity >= 0.0) || !std::isfinite(p.diversity))
    throw Error("diversity " + formatNumber(p.diversity) + " must be >= 0");
  if (!(p.base_step >= 0.0) || !(p.base_range >= 0.0) || !std::isfinite(p.base_step) ||
      !std::isfinite(p.base_range))
    throw Error("base adjustment step and range must be >= 0");
  if (!std::isfinite(p.threshold)) throw Error("threshold must be a finite number");
  if (p.validation_poses == 0) throw Error("validation poses must be at least 1");
  p.robot.checkSize(p.start);
  p.robot.checkSize(p.goal);
  checker_ = std::make_unique<CollisionChecker>(p.robot, p.collision);
  certifier_ = std::make_unique<MotionCertifier>(p.robot, *checker_);
  sampler_ = std::make_unique<SwaySampler>(p.sway);
  displacements_ = sampler_->displacements(p.seed, p.base_poses);
}

SwayPlanner::~SwayPlanner() = default;

Eigen::Isometry3d SwayPlanner::measuredBase(double offset) const {
  Eigen::Isometry3d shift = Eigen::Isometry3d::Identity();
  shift.translation() = offset * sampler_->frame().linear().col(0);
  return shift * problem_.robot.T_world_base;
}

std::vector<Eigen::Isometry3d> SwayPlanner::movedDisplacements(
    const std::vector<Eigen::Isometry3d>& base, double offset) const {
  Eigen::Isometry3d shift = Eigen::Isometry3d::Identity();
  shift.translation() = offset * sampler_->frame().linear().col(0);
  std::vector<Eigen::Isometry3d> moved;
  moved.reserve(base.size());
  for (const Eigen::Isometry3d& d : base) moved.push_back(shift * d * shift.inverse());
  return moved;
}

std::vector<std::uint8_t> SwayPlanner::motionFreeStates(const Eigen::VectorXd& qa,
                                                        const Eigen::VectorXd& qb,
                                                        double offset) const {
  problem_.robot.checkSize(qa);
  problem_.robot.checkSize(qb);
  const Eigen::Isometry3d T_nominal = measuredBase(offset);
  const PoseSet poses =
      makePoses(movedDisplacements(displacements_, offset), T_nominal,
                T_nominal * problem_.robot.T_world_base.inverse() * problem_.sway.pivot);
  CollisionChecker::Scratch scratch;
  const PolylineCheck check(*certifier_, T_nominal, poses, {qa, qb}, scratch);
  std::vector<std::uint8_t> free(poses.T_world_base.size());
  for (std::size_t j = 0; j < free.size(); ++j) free[j] = check.segmentFree(0, j, scratch);
  return free;
}

double SwayPlanner::padding() const {
  if (problem_.padding >= 0.0) return problem_.padding;
  double largest = 0.0;
  for (const Eigen::VectorXd* q : {&problem_.start, &problem_.goal}) {
    const Eigen::Vector3d p = toolPose(problem_.robot, *q).translation();
    double sum = 0.0;
    for (const Eigen::Isometry3d& d : displacements_) sum += (d * p - p).squaredNorm();
    largest = std::max(largest, std::sqrt(sum / static_cast<double>(displacements_.size())));
  }
  return 2.0 * largest;
}

double SwayPlanner::collisionFraction(const Eigen::VectorXd& q) const {
  CollisionChecker::Scratch scratch;
  std::size_t colliding = 0;
  for (const Eigen::Isometry3d& d : displacements_) {
    colliding += checker_->label(q.data(), d * problem_.robot.T_world_base, scratch) != kLabelFree;
  }
  return static_cast<double>(colliding) / static_cast<double>(displacements_.size());
}

namespace {

/// Safety numbers of a vertex path from the edges' free states.
PathSafety pathSafety(const VertexPath& path, const Roadmap& roadmap, const EdgeMap& edges,
                      std::size_t poses) {
  PathSafety safety;
  safety.vertices = path;
  for (std::size_t v : path) safety.waypoints.push_back(roadmap.configurations[v]);
  std::vector<std::uint8_t> whole(poses, 1);
  double sum = 0.0;
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    const EdgeStates& edge = edges.at(edgeKey(path[k], path[k + 1]));
    const bool forward = path[k] < path[k + 1];
    safety.length += edge.length;
    const std::size_t count = edge.probability.size();
    for (std::size_t s = 0; s < count; ++s) {
      const std::size_t i = forward ? s : count - 1 - s;
      const double p = edge.probability[i];
      sum += p;
      if (p < safety.worst_probability || safety.worst_from.size() == 0) {
        safety.worst_probability = p;
        safety.worst_segment = safety.segments;
        safety.worst_from = edge.points[forward ? i : i + 1];
        safety.worst_to = edge.points[forward ? i + 1 : i];
      }
      for (std::size_t j = 0; j < poses; ++j) whole[j] &= edge.free[i][j];
      ++safety.segments;
    }
  }
  safety.probability = safety.segments ? sum / static_cast<double>(safety.segments) : 1.0;
  for (std::uint8_t f : whole) safety.free_poses += f;
  safety.free_fraction = static_cast<double>(safety.free_poses) / static_cast<double>(poses);
  safety.free_interval = wilsonInterval(safety.free_poses, poses);
  safety.colliding_poses = poses - safety.free_poses;
  safety.collision_rate = static_cast<double>(safety.colliding_poses) / static_cast<double>(poses);
  safety.collision_interval = wilsonInterval(safety.colliding_poses, poses);
  return safety;
}

/// The straight edge from a to b cut into segments of at most segment_length, each segment's
/// free state for every pose (checked exactly) and its free-state probability.
EdgeStates edgeStates(const MotionCertifier& certifier, const SwayPlanningProblem& p,
                      const Eigen::Isometry3d& T_nominal, const PoseSet& poses,
                      const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                      CollisionChecker::Scratch& scratch) {
  const Eigen::VectorXd& scale = p.roadmap.joint_scale;
  EdgeStates edge;
  edge.length = scaledDistance(a, b, scale);
  const PolylineCheck check(certifier, T_nominal, poses, subdivide(a, b, scale, p.segment_length),
                            scratch);
  edge.points = check.points();
  edge.free.assign(check.segments(), std::vector<std::uint8_t>(poses.T_world_base.size()));
  edge.probability.assign(check.segments(), 0.0);
  for (std::size_t s = 0; s < check.segments(); ++s) {
    std::size_t free = 0;
    for (std::size_t j = 0; j < poses.T_world_base.size(); ++j) {
      edge.free[s][j] = check.segmentFree(s, j, scratch);
      free += edge.free[s][j];
    }
    edge.probability[s] = static_cast<double>(free) / static_cast<double>(p.base_poses);
  }
  return edge;
}

/// The free states of every edge of the candidate paths, the edges in parallel.
EdgeMap evaluateEdges(const MotionCertifier& certifier, const SwayPlanningProblem& p,
                      const Roadmap& roadmap, const std::vector<VertexPath>& candidates,
                      const Eigen::Isometry3d& T_nominal, const PoseSet& poses,
                      const PlanningProgress& progress, const CancelCheck& cancel_check) {
  EdgeMap edges;
  for (const VertexPath& path : candidates)
    for (std::size_t k = 0; k + 1 < path.size(); ++k) edges[edgeKey(path[k], path[k + 1])];
  std::vector<EdgeMap::value_type*> work;
  for (auto& item : edges) work.push_back(&item);
  std::size_t done = 0;
  FirstError error;
#pragma omp parallel
  {
    CollisionChecker::Scratch scratch;
#pragma omp for schedule(dynamic)
    for (std::size_t w = 0; w < work.size(); ++w) {
      error.run(w, [&] {
        const auto [u, v] = work[w]->first;
        work[w]->second = edgeStates(certifier, p, T_nominal, poses, roadmap.configurations[u],
                                     roadmap.configurations[v], scratch);
        checkOnCallingThread(cancel_check);
      });
      // Nothing may leave a critical region: the guard stays inside it.
#pragma omp critical(mcws_plan_progress)
      error.run(w, [&] {
        if (progress) progress("segments", ++done, work.size());
      });
    }
  }
  error.rethrow();
  return edges;
}

/// Steps s43 to s47 for a round's candidate paths: the merge at shared nodes, and the safety
/// numbers of each candidate and of the best path.
void chooseBest(const std::vector<VertexPath>& candidates, const Roadmap& roadmap,
                const EdgeMap& edges, const ScoreOptions& score, std::size_t poses,
                PlanningRound& round) {
  const EdgeValuesFn values = [&](std::size_t u, std::size_t v) {
    const EdgeStates& edge = edges.at(edgeKey(u, v));
    EdgeValues out;
    out.length = edge.length;
    out.segments = static_cast<int>(edge.probability.size());
    for (double q : edge.probability) out.probability_sum += q;
    return out;
  };
  const MergeResult merged = mergeAtSharedNodes(
      candidates, values, [&](std::size_t v) { return roadmap.distance_from_start[v]; }, score);
  for (const VertexPath& path : candidates)
    round.candidates.push_back(pathSafety(path, roadmap, edges, poses));
  round.decisions = merged.decisions;
  round.best = pathSafety(merged.paths[merged.best], roadmap, edges, poses);
}

/// The round whose best path comes closest to the acceptance criterion (the lowest upper end of
/// the collision interval, or the highest P); empty when no round found a path.
std::optional<std::size_t> closestRound(const std::vector<PlanningRound>& rounds,
                                        Acceptance acceptance) {
  std::optional<std::size_t> closest;
  for (std::size_t r = 0; r < rounds.size(); ++r) {
    const std::optional<PathSafety>& best = rounds[r].best;
    if (!best) continue;
    if (!closest) {
      closest = r;
      continue;
    }
    const PathSafety& held = *rounds[*closest].best;
    const bool closer = acceptance == Acceptance::kPatentP
                            ? best->probability > held.probability
                            : best->collision_interval.high < held.collision_interval.high;
    if (closer) closest = r;
  }
  return closest;
}

}  // namespace

PlanningRound SwayPlanner::planRound(double offset, const PlanningProgress& progress,
                                     const CancelCheck& cancel_check) const {
  const auto started = std::chrono::steady_clock::now();
  const SwayPlanningProblem& p = problem_;
  PlanningRound round;
  round.base_offset = offset;
  round.goal_displacement = goalDisplacement(offset);
  const Eigen::Isometry3d T_nominal = measuredBase(offset);
  const Eigen::VectorXd& scale = p.roadmap.joint_scale;
  round.reference_distance = scaledDistance(p.start, p.goal, scale);

  // s10: "分别测量机器人的基座相对于作业对象的第一静态位姿、机器人的操作臂的初始构型" (measure the
  // base's first static pose relative to the work object and the arm's initial configuration):
  // T_nominal, problem_.start.
  // s30:
  // "将第一静态位姿作为操作臂的基座位姿，对操作臂进行路径规划，给出操作臂从初始构型到达预设目标
  // 构型的m条非碰撞路径" (with the first static pose as the arm's base pose, plan m collision-free
  // paths from the initial to the target configuration): one PRM roadmap, m diverse paths.
  if (progress) progress("roadmap", 0, 1);
  const Roadmap roadmap =
      buildRoadmap(*certifier_, T_nominal, p.start, p.goal, p.roadmap, cancel_check);
  round.status = roadmap.status;
  round.roadmap_vertices = boost::num_vertices(roadmap.graph);
  round.roadmap_edges = boost::num_edges(roadmap.graph);
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  };
  round.roadmap_seconds = elapsed();
  if (progress) progress("roadmap", 1, 1);
  if (roadmap.status != RoadmapStatus::kConnected) {
    round.seconds = elapsed();
    return round;
  }
  const std::vector<VertexPath> candidates =
      diversePaths(roadmap.graph, roadmap.start, roadmap.goal, p.candidates, p.diversity);

  // s20: "将第一静态位姿作为高斯概率分布函数的均值，采用高斯概率分布函数生成n组第二静态位姿数据"
  // (the first static pose as the mean of a Gaussian, draw n second static poses): the n
  // displacements (SwaySampler), about the sway frame moved with the base.
  const PoseSet poses =
      makePoses(movedDisplacements(displacements_, offset), T_nominal,
                measuredBase(offset) * problem_.robot.T_world_base.inverse() * p.sway.pivot);

  // s41: "对m条非碰撞路径进行分段处理，并测量获得操作臂在每个分段的节点构型与初始构型的欧氏距离"
  // (cut the paths into segments; the distance of each node from the initial configuration):
  // each edge cut into segments of at most segment_length; D accumulates along the path.
  // s42: "获得相邻节点构型之间路径段在n组基座位姿数据下的自由状态 ...
  // 将n组自由状态累加除以n获得路径段 的第二自由状态概率" (each segment's free state for the n base
  // poses, summed and divided by n): free states for every pose, checked exactly.
  const EdgeMap edges =
      evaluateEdges(*certifier_, p, roadmap, candidates, T_nominal, poses, progress, cancel_check);
  round.evaluation_seconds = elapsed() - round.roadmap_seconds;

  // s43 - s47: "判断节点构型是否有2条或2条以上非碰撞路径经过 ...
  // 选择出第一自由状态概率与欧氏距离数学 差值最大的非碰撞路径作为优势路径 ...
  // 将在目标节点处选出的优势路径作为全局最优路径" (at nodes that two or more paths pass, the path
  // with the largest difference of free-state probability and distance dominates; the dominant path
  // at the goal is the global best): mergeAtSharedNodes, shared nodes visited in increasing roadmap
  // distance from the start.
  ScoreOptions score = p.score;
  score.reference_distance = round.reference_distance;
  chooseBest(candidates, roadmap, edges, score, p.base_poses, round);
  round.accepted = accepts(*round.best);
  round.seconds = elapsed();
  return round;
}

ValidationRow SwayPlanner::validate(const std::string& name,
                                    const std::vector<Eigen::VectorXd>& waypoints, double offset,
                                    const CancelCheck& cancel_check) const {
  const auto started = std::chrono::steady_clock::now();
  const SwayPlanningProblem& p = problem_;
  ValidationRow row;
  row.name = name;
  row.planned = true;
  row.status = roadmapStatusName(RoadmapStatus::kConnected);
  row.poses = p.validation_poses;
  const Eigen::VectorXd& scale = p.roadmap.joint_scale;
  std::vector<Eigen::VectorXd> points{waypoints.front()};
  for (std::size_t k = 0; k + 1 < waypoints.size(); ++k) {
    row.length += scaledDistance(waypoints[k], waypoints[k + 1], scale);
    const std::vector<Eigen::VectorXd> part =
        subdivide(waypoints[k], waypoints[k + 1], scale, p.segment_length);
    points.insert(points.end(), part.begin() + 1, part.end());
  }
  // Fresh poses: a seed of their own, far from the planning seed's stream.
  const std::uint64_t seed = p.seed ^ 0x5DEECE66DULL;
  const Eigen::Isometry3d T_nominal = measuredBase(offset);
  const PoseSet poses =
      makePoses(movedDisplacements(sampler_->displacements(seed, p.validation_poses), offset),
                T_nominal, T_nominal * p.robot.T_world_base.inverse() * p.sway.pivot);
  CollisionChecker::Scratch scratch;
  const PolylineCheck check(*certifier_, T_nominal, poses, std::move(points), scratch);
  std::size_t colliding = 0;
  FirstError error;
#pragma omp parallel reduction(+ : colliding)
  {
    CollisionChecker::Scratch local;
#pragma omp for schedule(dynamic, 64)
    for (std::size_t j = 0; j < p.validation_poses; ++j)
      error.run(j, [&] {
        colliding += !check.pathFree(j, local);
        checkOnCallingThread(cancel_check);
      });
  }
  error.rethrow();
  row.colliding = colliding;
  row.collision_probability =
      static_cast<double>(colliding) / static_cast<double>(p.validation_poses);
  row.interval = wilsonInterval(colliding, p.validation_poses);
  row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return row;
}

bool SwayPlanner::accepts(const PathSafety& path) const {
  if (problem_.acceptance == Acceptance::kPatentP) return path.probability >= problem_.threshold;
  return path.collision_interval.high <= problem_.max_collision_probability;
}

double SwayPlanner::goalDisplacement(double offset) const {
  Robot shifted = problem_.robot;
  shifted.T_world_base = measuredBase(offset);
  return (toolPose(shifted, problem_.goal).translation() -
          toolPose(problem_.robot, problem_.goal).translation())
      .norm();
}

std::vector<double> SwayPlanner::baseOffsets() const {
  const SwayPlanningProblem& p = problem_;
  std::vector<double> offsets{0.0};
  if (p.base_step > 0.0) {
    for (int k = 1; k * p.base_step <= p.base_range * (1.0 + 1e-12); ++k) {
      offsets.push_back(k * p.base_step);
      offsets.push_back(-k * p.base_step);
    }
  }
  return offsets;
}

SwayPlanningResult SwayPlanner::plan(bool validate_paths, const PlanningProgress& progress,
                                     const CancelCheck& cancel_check) const {
  const SwayPlanningProblem& p = problem_;
  SwayPlanningResult result;
  // s50: "判断全局最优路径的自由状态概率是否大于等于预设自由状态概率阈值" (is the best path's
  // free-state probability at least the threshold?); s60: if so it is executed; s70: "如果否，
  // 则调整所述机器人的所述第一静态位姿，然后重新进行所述操作臂的运动路径规划" (if not, adjust the
  // robot's first static pose and plan again): the base moves along the line, both ways.
  for (double offset : baseOffsets()) {
    result.rounds.push_back(planRound(offset, progress, cancel_check));
    const PlanningRound& round = result.rounds.back();
    if (round.accepted) {
      result.accepted = result.rounds.size() - 1;
      break;
    }
    // The start is where the arm is now: in collision at the measured pose, the model and the
    // robot disagree, and no base shift can mend that. A goal in collision there is freed by a
    // shift only when the scenario allows the tool to end away from the target.
    if (offset == 0.0 && (round.status == RoadmapStatus::kStartInvalid ||
                          (round.status == RoadmapStatus::kGoalInvalid && !p.allow_goal_shift)))
      break;
    // A roadmap that does not connect, a goal in collision (when allowed) or a path refused at
    // this offset: the next offset may do better, so step s70 goes on.
  }
  // The round to validate: the accepted one, or else the one closest to the criterion.
  result.validated = result.accepted ? result.accepted : closestRound(result.rounds, p.acceptance);
  if (validate_paths && result.validated) validateRound(result, progress, cancel_check);
  return result;
}

void SwayPlanner::validateRound(SwayPlanningResult& result, const PlanningProgress& progress,
                                const CancelCheck& cancel_check) const {
  const auto started = std::chrono::steady_clock::now();
  const PlanningRound& round = result.rounds[*result.validated];
  // Each path's validation starts with a check on this thread: the checks within it are made by
  // whichever pose thread 0 takes, which a short validation may leave without one.
  const auto step = [&](std::size_t done) {
    if (progress) progress("validation", done, 3);
    if (cancel_check && done < 3) cancel_check();
  };
  step(0);
  result.validation.push_back(
      validate("chosen", round.best->waypoints, round.base_offset, cancel_check));
  step(1);
  result.validation.push_back(
      validate("shortest", round.candidates.front().waypoints, round.base_offset, cancel_check));
  step(2);
  result.validation.push_back(validatePadded(round.base_offset, cancel_check));
  step(3);
  result.validation_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

ValidationRow SwayPlanner::validatePadded(double offset, const CancelCheck& cancel_check) const {
  // The usual answer: the shortest path for obstacles padded by the 2-sigma displacement.
  const SwayPlanningProblem& p = problem_;
  const auto started = std::chrono::steady_clock::now();
  MotionCertifierOptions padded_options;
  padded_options.environment_margin = padding();
  const MotionCertifier padded(p.robot, *checker_, padded_options);
  const Roadmap roadmap =
      buildRoadmap(padded, measuredBase(offset), p.start, p.goal, p.roadmap, cancel_check);
  ValidationRow row;
  const double planning_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (roadmap.status == RoadmapStatus::kConnected) {
    const VertexPath path = kShortestPaths(roadmap.graph, roadmap.start, roadmap.goal, 1).front();
    std::vector<Eigen::VectorXd> waypoints;
    for (std::size_t v : path) waypoints.push_back(roadmap.configurations[v]);
    row = validate("padded", waypoints, offset, cancel_check);
  } else {
    row.name = "padded";
    row.status = roadmapStatusName(roadmap.status);
    row.poses = p.validation_poses;
  }
  row.padding = padded_options.environment_margin;
  row.planning_seconds = planning_seconds;
  row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return row;
}

}  // namespace mcws
