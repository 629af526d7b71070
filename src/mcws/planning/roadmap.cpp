#include "mcws/planning/roadmap.h"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/ValidStateSampler.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/datastructures/NearestNeighborsLinear.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/util/Console.h>
#include <algorithm>
#include <boost/graph/dijkstra_shortest_paths.hpp>
#include <cmath>
#include <deque>
#include <exception>
#include <limits>
#include <unordered_map>

#include "mcws/core/counter_rng.h"
#include "mcws/core/error.h"
#include "mcws/core/first_error.h"

namespace mcws {

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

/// Joint values of an OMPL state of the scaled joint space.
Eigen::VectorXd jointsOf(const ob::State* state, const Eigen::VectorXd& scale) {
  const double* u = state->as<ob::RealVectorStateSpace::StateType>()->values;
  return Eigen::Map<const Eigen::VectorXd>(u, scale.size()).cwiseQuotient(scale);
}

void setJoints(ob::State* state, const Eigen::VectorXd& q, const Eigen::VectorXd& scale) {
  double* u = state->as<ob::RealVectorStateSpace::StateType>()->values;
  Eigen::Map<Eigen::VectorXd>(u, scale.size()) = q.cwiseProduct(scale);
}

/// Draw `index` of the uniform stream within the joint limits.
Eigen::VectorXd counterSample(const Robot& robot, const CounterRng& rng, std::uint64_t index) {
  Eigen::VectorXd q(robot.dof());
  for (int j = 0; j < robot.dof(); ++j) {
    const Joint& joint = robot.joints[j];
    q[j] = joint.lower + (joint.upper - joint.lower) * rng.uniform(index, j);
  }
  return q;
}

/// Uniform milestones within the limits from a counter-based stream: draw i depends only on the
/// seed and i, so the roadmap does not depend on OMPL's global random generator.
class CounterSampler : public ob::ValidStateSampler {
 public:
  CounterSampler(const ob::SpaceInformation* si, const Robot& robot, const Eigen::VectorXd& scale,
                 std::uint64_t seed)
      : ob::ValidStateSampler(si), robot_(robot), scale_(scale), rng_(seed) {
    name_ = "mcws_counter";
  }
  bool sample(ob::State* state) override {
    setJoints(state, counterSample(robot_, rng_, index_++), scale_);
    return si_->isValid(state);
  }
  bool sampleNear(ob::State* state, const ob::State* /*near*/, double /*distance*/) override {
    return sample(state);  // PRM's growth never asks for it; its expansion step is not used
  }

 private:
  const Robot& robot_;
  Eigen::VectorXd scale_;
  CounterRng rng_;
  std::uint64_t index_{0};
};

/// Every roadmap edge checked exactly (MotionCertifier), not at discrete resolution.
class CertifiedMotionValidator : public ob::MotionValidator {
 public:
  CertifiedMotionValidator(const ob::SpaceInformationPtr& si, const MotionCertifier& certifier,
                           const Eigen::Isometry3d& T_world_base, const Eigen::VectorXd& scale)
      : ob::MotionValidator(si),
        certifier_(certifier),
        T_world_base_(T_world_base),
        scale_(scale) {}
  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    if (const auto ahead = checked_.find({s1, s2}); ahead != checked_.end()) {
      (ahead->second ? valid_ : invalid_)++;
      return ahead->second;
    }
    const Eigen::VectorXd q1 = jointsOf(s1, scale_), q2 = jointsOf(s2, scale_);
    certifier_.motionBounds(q1, q2, PairSet::kAll, bounds_);
    double cap = certifier_.options().resolution;
    for (double b : bounds_) cap = std::max(cap, b + certifier_.options().resolution);
    const std::vector<double>* c1 = clearances(s1, q1, cap);
    const std::vector<double>* c2 = c1 ? clearances(s2, q2, cap) : nullptr;
    const bool free =
        c1 && c2 && certifier_.motionFree(q1, *c1, q2, *c2, T_world_base_, PairSet::kAll, scratch_);
    (free ? valid_ : invalid_)++;
    return free;
  }
  /// \brief Checks the motions `edges` (first, second) on all threads, ahead of PRM's calls of
  /// checkMotion(), which then look them up: the answers are exact, so the roadmap is the one
  /// the calls would have made one by one. Forgets the edges checked before.
  void checkAhead(const std::vector<std::pair<const ob::State*, const ob::State*>>& edges) {
    checked_.clear();
    // The ends' clearances, each to the largest cap its motions need, computed once: their cache
    // entries are made here, so the parallel loop below writes into entries it does not move.
    std::vector<double> caps(edges.size());
    std::unordered_map<const ob::State*, double> need;
    std::vector<double> bounds;
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const auto [s1, s2] = edges[e];
      certifier_.motionBounds(jointsOf(s1, scale_), jointsOf(s2, scale_), PairSet::kAll, bounds);
      double cap = certifier_.options().resolution;
      for (double b : bounds) cap = std::max(cap, b + certifier_.options().resolution);
      caps[e] = cap;
      for (const ob::State* s : {s1, s2}) need[s] = std::max(need[s], cap);
    }
    std::vector<std::pair<const ob::State*, double>> ends(need.begin(), need.end());
    for (const auto& [state, cap] : ends) cache_[state];
    std::vector<char> free(edges.size(), 0);
    FirstError error;
#pragma omp parallel
    {
      CollisionChecker::Scratch scratch;
#pragma omp for schedule(dynamic)
      for (std::size_t k = 0; k < ends.size(); ++k) {
        error.run(k, [&] {
          Cached& cached = cache_.find(ends[k].first)->second;
          if (cached.cap < ends[k].second) {
            certifier_.clearances(jointsOf(ends[k].first, scale_), T_world_base_, PairSet::kAll,
                                  ends[k].second, scratch, cached.values);
            cached.cap = ends[k].second;
          }
        });
      }
#pragma omp for schedule(dynamic)
      for (std::size_t e = 0; e < edges.size(); ++e) {
        error.run(ends.size() + e, [&] {
          const auto [s1, s2] = edges[e];
          const std::vector<double>& c1 = cache_.find(s1)->second.values;
          const std::vector<double>& c2 = cache_.find(s2)->second.values;
          const auto clear = [](const std::vector<double>& c) {
            return std::all_of(c.begin(), c.end(), [](double v) { return v > 0.0; });
          };
          free[e] = clear(c1) && clear(c2) &&
                    certifier_.motionFree(jointsOf(s1, scale_), c1, jointsOf(s2, scale_), c2,
                                          T_world_base_, PairSet::kAll, scratch);
        });
      }
    }
    error.rethrow();
    for (std::size_t e = 0; e < edges.size(); ++e) checked_.emplace(edges[e], free[e] != 0);
  }

  bool checkMotion(const ob::State* s1, const ob::State* s2,
                   std::pair<ob::State*, double>& last_valid) const override {
    const bool free = checkMotion(s1, s2);
    if (!free) {  // only "free or not" is exact; report the start as the last valid state
      if (last_valid.first) si_->copyState(last_valid.first, s1);
      last_valid.second = 0.0;
    }
    return free;
  }

 private:
  /// A milestone's clearances, computed once: PRM checks each milestone against k neighbours.
  /// Recomputed when a motion needs them beyond the cap they were computed to. nullptr when the
  /// state collides.
  const std::vector<double>* clearances(const ob::State* state, const Eigen::VectorXd& q,
                                        double cap) const {
    Cached& cached = cache_[state];
    if (cached.cap < cap) {
      certifier_.clearances(q, T_world_base_, PairSet::kAll, cap, scratch_, cached.values);
      cached.cap = cap;
    }
    for (double v : cached.values)
      if (v <= 0.0) return nullptr;
    return &cached.values;
  }

  struct Cached {
    double cap{-1.0};
    std::vector<double> values;
  };
  const MotionCertifier& certifier_;
  Eigen::Isometry3d T_world_base_;
  Eigen::VectorXd scale_;
  mutable CollisionChecker::Scratch scratch_;
  mutable std::vector<double> bounds_;
  mutable std::unordered_map<const ob::State*, Cached> cache_;
  struct PairHash {
    std::size_t operator()(const std::pair<const ob::State*, const ob::State*>& p) const {
      return std::hash<const void*>()(p.first) * 31u ^ std::hash<const void*>()(p.second);
    }
  };
  std::unordered_map<std::pair<const ob::State*, const ob::State*>, bool, PairHash> checked_;
};

/// OMPL's PRM with its milestone insertion opened up, so that start and goal are added after
/// the roadmap has grown (PRM::solve() would grow it on a second thread, which is not
/// reproducible).
class RoadmapBuilder : public og::PRM {
 public:
  using og::PRM::PRM;
  Vertex add(const ob::State* state) { return addMilestone(si_->cloneState(state)); }

  /// \brief Adds `states` (taking them over) as milestones in order, their motions to the
  /// neighbours PRM will pick checked ahead on all threads: PRM connects a new milestone to its
  /// k nearest among the milestones before it (OMPL's KStrategy on NearestNeighborsLinear, which
  /// sorts the milestones in the order they were added), so those neighbours are known before
  /// the milestones are added. A motion not foreseen is checked when PRM asks for it.
  void addBatch(const std::vector<ob::State*>& states, unsigned k,
                CertifiedMotionValidator& validator, const CancelCheck& cancel_check) {
    std::vector<const ob::State*> before;
    for (Vertex v = 0; v < boost::num_vertices(g_); ++v) before.push_back(stateProperty_[v]);
    std::vector<std::pair<const ob::State*, const ob::State*>> edges;
    std::vector<std::size_t> order;
    std::vector<double> distance;
    for (const ob::State* state : states) {
      distance.resize(before.size());
      order.resize(before.size());
      for (std::size_t i = 0; i < before.size(); ++i) {
        distance[i] = si_->distance(before[i], state);
        order[i] = i;
      }
      const auto nearer = [&](std::size_t a, std::size_t b) { return distance[a] < distance[b]; };
      if (order.size() > k) {
        std::partial_sort(order.begin(), order.begin() + k, order.end(), nearer);
        order.resize(k);
      } else {
        std::sort(order.begin(), order.end(), nearer);
      }
      for (std::size_t i : order) edges.emplace_back(before[i], state);
      before.push_back(state);
    }
    validator.checkAhead(edges);
    for (std::size_t i = 0; i < states.size(); ++i) {
      if (cancel_check) {
        try {
          cancel_check();
        } catch (...) {  // the states not added are still ours
          for (std::size_t j = i; j < states.size(); ++j) si_->freeState(states[j]);
          validator.checkAhead({});
          throw;
        }
      }
      addMilestone(states[i]);
    }
    validator.checkAhead({});  // nothing looked up past the batch
  }
  /// Exact, deterministic k nearest neighbours (OMPL's default GNAT picks pivots at random).
  void useExactNeighbours() {
    setNearestNeighbors<ompl::NearestNeighborsLinear>();
    nn_->setDistanceFunction(
        [this](const Vertex a, const Vertex b) { return distanceFunction(a, b); });
  }
};

void checkEnd(const Robot& robot, const Eigen::VectorXd& q, const char* what) {
  try {
    robot.checkJointVector(q);
  } catch (const Error& e) {
    throw Error(std::string(what) + ": " + e.what());
  }
}

}  // namespace

const char* roadmapStatusName(RoadmapStatus status) {
  switch (status) {
    case RoadmapStatus::kConnected:
      return "connected";
    case RoadmapStatus::kStartInvalid:
      return "start_in_collision";
    case RoadmapStatus::kGoalInvalid:
      return "goal_in_collision";
    case RoadmapStatus::kNotConnected:
      return "not_connected";
  }
  return "unknown";
}

double scaledDistance(const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                      const Eigen::VectorXd& scale) {
  return (b - a).cwiseProduct(scale).norm();
}

namespace {

/// buildRoadmap's arguments checked.
void checkArguments(const Robot& robot, const Eigen::VectorXd& start, const Eigen::VectorXd& goal,
                    const RoadmapOptions& options) {
  checkEnd(robot, start, "start");
  checkEnd(robot, goal, "goal");
  const Eigen::VectorXd& scale = options.joint_scale;
  if (scale.size() != robot.dof() || !(scale.array() > 0.0).all() || !scale.allFinite()) {
    throw Error("roadmap: joint scales must be " + std::to_string(robot.dof()) +
                " positive numbers");
  }
  if (options.nodes == 0 || options.neighbours == 0) {
    throw Error("roadmap: nodes and neighbours must be at least 1");
  }
}

/// The joint space scaled by options.joint_scale, its states and motions checked by the
/// certifier at T_world_base, sampled by the counter-based sampler of options.seed. The
/// arguments must outlive it.
ob::SpaceInformationPtr scaledSpace(const MotionCertifier& certifier,
                                    const Eigen::Isometry3d& T_world_base,
                                    const RoadmapOptions& options,
                                    CollisionChecker::Scratch& scratch,
                                    std::shared_ptr<CertifiedMotionValidator>& validator) {
  const Robot& robot = certifier.robot();
  const Eigen::VectorXd& scale = options.joint_scale;
  auto space = std::make_shared<ob::RealVectorStateSpace>(robot.dof());
  ob::RealVectorBounds bounds(robot.dof());
  for (int j = 0; j < robot.dof(); ++j) {
    bounds.setLow(j, robot.joints[j].lower * scale[j]);
    bounds.setHigh(j, robot.joints[j].upper * scale[j]);
  }
  space->setBounds(bounds);
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker([&certifier, &T_world_base, &options,
                               &scratch](const ob::State* state) {
    return certifier.configurationFree(jointsOf(state, options.joint_scale), T_world_base, scratch);
  });
  validator = std::make_shared<CertifiedMotionValidator>(si, certifier, T_world_base, scale);
  si->setMotionValidator(validator);
  si->setValidStateSamplerAllocator([&certifier, &options](const ob::SpaceInformation* info) {
    return std::make_shared<CounterSampler>(info, certifier.robot(), options.joint_scale,
                                            options.seed);
  });
  si->setup();
  return si;
}

/// Copies PRM's graph into the roadmap (edges weighted by the scaled distance) with the roadmap
/// distances from the start. \return whether the goal is reached.
bool copyRoadmap(const og::PRM::Graph& g, std::size_t start, std::size_t goal,
                 const Eigen::VectorXd& scale, Roadmap& roadmap) {
  const std::size_t n = boost::num_vertices(g);
  roadmap.configurations.resize(n);
  const auto states = boost::get(og::PRM::vertex_state_t(), g);
  for (std::size_t v = 0; v < n; ++v) roadmap.configurations[v] = jointsOf(states[v], scale);
  roadmap.graph = RoadmapGraph(n);
  for (auto [e, end] = boost::edges(g); e != end; ++e) {
    const std::size_t a = boost::source(*e, g), b = boost::target(*e, g);
    boost::add_edge(a, b,
                    scaledDistance(roadmap.configurations[a], roadmap.configurations[b], scale),
                    roadmap.graph);
  }
  roadmap.start = start;
  roadmap.goal = goal;
  roadmap.distance_from_start.assign(n, std::numeric_limits<double>::infinity());
  boost::dijkstra_shortest_paths(
      roadmap.graph, roadmap.start,
      boost::distance_map(boost::make_iterator_property_map(
          roadmap.distance_from_start.begin(), boost::get(boost::vertex_index, roadmap.graph))));
  for (double& d : roadmap.distance_from_start) {  // Boost marks the unreached with max()
    if (d == std::numeric_limits<double>::max()) d = std::numeric_limits<double>::infinity();
  }
  return std::isfinite(roadmap.distance_from_start[roadmap.goal]);
}

/// OMPL's own growth, a milestone at a time (RoadmapOptions::batch 0): `cancel_check` is called
/// as the growth's termination condition is, and what it throws is rethrown after the growth.
void growOneByOne(og::PRM& prm, std::size_t count, const CancelCheck& cancel_check) {
  std::exception_ptr cancelled;
  prm.growRoadmap(ob::PlannerTerminationCondition([&] {
    if (cancel_check && !cancelled) {
      try {
        cancel_check();
      } catch (...) {
        cancelled = std::current_exception();
      }
    }
    return cancelled || prm.milestoneCount() >= count;
  }));
  if (cancelled) std::rethrow_exception(cancelled);
}

/// The valid draws of the counter-based stream in order (CounterSampler's milestones), their
/// validity checked on all threads a chunk at a time.
class MilestoneStream {
 public:
  MilestoneStream(const MotionCertifier& certifier, const Eigen::Isometry3d& T_world_base,
                  const RoadmapOptions& options)
      : certifier_(certifier),
        T_world_base_(T_world_base),
        scale_(options.joint_scale),
        rng_(options.seed) {}

  /// The next `count` valid draws, as new states of `si` (the caller owns them).
  std::vector<ob::State*> next(std::size_t count, const ob::SpaceInformation& si) {
    std::vector<ob::State*> states;
    while (states.size() < count) {
      if (valid_.empty()) checkChunk(std::max<std::size_t>(2 * count, 64));
      const std::uint64_t index = first_++;
      const bool valid = valid_.front();
      valid_.pop_front();
      if (!valid) continue;
      ob::State* state = si.allocState();
      setJoints(state, counterSample(certifier_.robot(), rng_, index), scale_);
      states.push_back(state);
    }
    return states;
  }

 private:
  /// Validity of the next `size` draws after those already checked.
  void checkChunk(std::size_t size) {
    const std::uint64_t from = first_ + valid_.size();
    std::vector<char> valid(size, 0);
    FirstError error;
#pragma omp parallel
    {
      CollisionChecker::Scratch scratch;
#pragma omp for schedule(dynamic, 8)
      for (std::size_t i = 0; i < size; ++i) {
        error.run(i, [&] {
          valid[i] = certifier_.configurationFree(counterSample(certifier_.robot(), rng_, from + i),
                                                  T_world_base_, scratch);
        });
      }
    }
    error.rethrow();
    valid_.insert(valid_.end(), valid.begin(), valid.end());
  }

  const MotionCertifier& certifier_;
  Eigen::Isometry3d T_world_base_;
  Eigen::VectorXd scale_;
  CounterRng rng_;
  std::uint64_t first_{0};  ///< the stream index of valid_.front()
  std::deque<char> valid_;  ///< checked draws not yet taken
};

}  // namespace

Roadmap buildRoadmap(const MotionCertifier& certifier, const Eigen::Isometry3d& T_world_base,
                     const Eigen::VectorXd& start, const Eigen::VectorXd& goal,
                     const RoadmapOptions& options, const CancelCheck& cancel_check) {
  checkArguments(certifier.robot(), start, goal, options);
  Roadmap roadmap;
  CollisionChecker::Scratch scratch;
  if (!certifier.configurationFree(start, T_world_base, scratch)) {
    roadmap.status = RoadmapStatus::kStartInvalid;
    return roadmap;
  }
  if (!certifier.configurationFree(goal, T_world_base, scratch)) {
    roadmap.status = RoadmapStatus::kGoalInvalid;
    return roadmap;
  }

  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  std::shared_ptr<CertifiedMotionValidator> validator;
  const ob::SpaceInformationPtr si =
      scaledSpace(certifier, T_world_base, options, scratch, validator);
  const Eigen::VectorXd& scale = options.joint_scale;
  ob::ScopedState<> start_state(si->getStateSpace()), goal_state(si->getStateSpace());
  setJoints(start_state.get(), start, scale);
  setJoints(goal_state.get(), goal, scale);
  auto problem = std::make_shared<ob::ProblemDefinition>(si);
  problem->setStartAndGoalStates(start_state, goal_state);

  RoadmapBuilder prm(si);
  prm.setProblemDefinition(problem);
  prm.useExactNeighbours();
  prm.setMaxNearestNeighbors(options.neighbours);
  prm.setup();

  MilestoneStream stream(certifier, T_world_base, options);
  auto grow_to = [&](std::size_t count) {
    if (options.batch == 0) return growOneByOne(prm, count, cancel_check);
    while (prm.milestoneCount() < count) {
      std::vector<ob::State*> states =
          stream.next(std::min(options.batch, count - prm.milestoneCount()), *si);
      prm.addBatch(states, options.neighbours, *validator, cancel_check);
    }
  };
  grow_to(options.nodes);
  const auto start_vertex = prm.add(start_state.get());
  const auto goal_vertex = prm.add(goal_state.get());
  bool connected = copyRoadmap(prm.getRoadmap(), start_vertex, goal_vertex, scale, roadmap);
  while (!connected && prm.milestoneCount() < options.max_nodes) {
    grow_to(std::min(options.max_nodes, prm.milestoneCount() + options.nodes));
    connected = copyRoadmap(prm.getRoadmap(), start_vertex, goal_vertex, scale, roadmap);
  }
  roadmap.status = connected ? RoadmapStatus::kConnected : RoadmapStatus::kNotConnected;
  return roadmap;
}

}  // namespace mcws
