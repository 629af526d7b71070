#include "mcws/planning/roadmap.h"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/ValidStateSampler.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/datastructures/NearestNeighborsLinear.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/util/Console.h>
#include <boost/graph/dijkstra_shortest_paths.hpp>
#include <cmath>
#include <exception>
#include <limits>
#include <unordered_map>

#include "mcws/core/counter_rng.h"
#include "mcws/core/error.h"

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
    Eigen::VectorXd q(robot_.dof());
    for (int j = 0; j < robot_.dof(); ++j) {
      const Joint& joint = robot_.joints[j];
      q[j] = joint.lower + (joint.upper - joint.lower) * rng_.uniform(index_, j);
    }
    ++index_;
    setJoints(state, q, scale_);
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
};

/// OMPL's PRM with its milestone insertion opened up, so that start and goal are added after
/// the roadmap has grown (PRM::solve() would grow it on a second thread, which is not
/// reproducible).
class RoadmapBuilder : public og::PRM {
 public:
  using og::PRM::PRM;
  Vertex add(const ob::State* state) { return addMilestone(si_->cloneState(state)); }
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
                                    CollisionChecker::Scratch& scratch) {
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
  si->setMotionValidator(
      std::make_shared<CertifiedMotionValidator>(si, certifier, T_world_base, scale));
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
  const ob::SpaceInformationPtr si = scaledSpace(certifier, T_world_base, options, scratch);
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

  std::exception_ptr cancelled;  // what cancel_check threw: the growth stops, then it is rethrown
  auto grow_to = [&](std::size_t count) {
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
