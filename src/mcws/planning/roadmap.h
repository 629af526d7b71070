#pragma once
/// \file
/// \brief A probabilistic roadmap of collision-free configurations for the measured base pose
/// (the maintenance-arm patent, step s30), grown with OMPL's PRM and copied into a plain Boost
/// graph.

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mcws/core/cancel_check.h"
#include "mcws/planning/k_shortest_paths.h"
#include "mcws/planning/motion_certifier.h"

namespace mcws {

/// \brief How the roadmap is grown.
struct RoadmapOptions {
  std::size_t nodes{400};       ///< milestones sampled before start and goal are added
  std::size_t max_nodes{3200};  ///< the roadmap grows by `nodes` until start and goal connect
  unsigned neighbours{10};      ///< k of PRM's k-nearest connection strategy
  std::uint64_t seed{1};
  /// Milestones added at a time, their validity and their motions to the neighbours PRM will
  /// connect them to checked on all threads first; 0: OMPL's growth one milestone at a time on
  /// one thread. The roadmap is the same either way, for any thread count.
  std::size_t batch{64};
  /// Joint-space distance scale of each joint [1/rad or 1/length unit]: distances and the
  /// roadmap's edge weights are sqrt(sum (scale_i dq_i)^2).
  Eigen::VectorXd joint_scale;
};

/// \brief Outcome of growing a roadmap.
enum class RoadmapStatus {
  kConnected,     ///< start and goal are in one component
  kStartInvalid,  ///< the start configuration collides
  kGoalInvalid,   ///< the goal configuration collides
  kNotConnected,  ///< max_nodes milestones did not connect start and goal
};

/// \brief Name of a status ("connected", "start_in_collision", ...).
const char* roadmapStatusName(RoadmapStatus status);

/// \brief A roadmap: configurations, the graph with scaled joint-space edge lengths, the start
/// and goal vertices and each vertex's distance from the start through the graph.
struct Roadmap {
  std::vector<Eigen::VectorXd> configurations;  ///< per vertex [rad | length unit]
  RoadmapGraph graph;
  std::size_t start{0}, goal{0};
  std::vector<double> distance_from_start;  ///< Dijkstra distances (infinity when unreachable)
  RoadmapStatus status{RoadmapStatus::kNotConnected};
};

/// \brief Grows a PRM (Kavraki, Svestka, Latombe, Overmars, "Probabilistic roadmaps for path
/// planning in high-dimensional configuration spaces", IEEE T-RA 12(4), 1996) with OMPL's
/// ompl::geometric::PRM over the joint box scaled by `joint_scale`.
///
/// Milestones are drawn uniformly within the joint limits from a counter-based stream (sample i
/// depends only on the seed and i) and kept when collision-free with the base at
/// T_world_base; every edge is checked exactly by `certifier` (MotionCertifier: nothing between
/// two milestones is missed). Milestones are added in order with exact nearest neighbours, so
/// the roadmap depends only on the seed; the validity of draws and the motions of each batch of
/// milestones are checked on all threads first (RoadmapOptions::batch), which changes nothing
/// in the roadmap. Start and goal are added last, each joined to its k nearest milestones.
/// `cancel_check` (when set) is called before each milestone is added (with batch 0: as the
/// growth's termination condition is): what it throws stops the growth and is rethrown.
/// \throws mcws::Error for a start or goal of the wrong size or outside the limits, or a bad
///   option (no nodes, a scale that is not positive).
Roadmap buildRoadmap(const MotionCertifier& certifier, const Eigen::Isometry3d& T_world_base,
                     const Eigen::VectorXd& start, const Eigen::VectorXd& goal,
                     const RoadmapOptions& options, const CancelCheck& cancel_check = {});

/// \brief Scaled joint-space distance sqrt(sum (scale_i (b_i - a_i))^2).
double scaledDistance(const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                      const Eigen::VectorXd& scale);

}  // namespace mcws
