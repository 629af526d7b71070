#pragma once
/// \file
/// \brief Motion planning of an arm whose base sways, after the maintenance-arm patent (steps s10
/// to s70), and the validation of the chosen path on fresh base poses.

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mcws/collision/collision_checker.h"
#include "mcws/planning/motion_certifier.h"
#include "mcws/planning/path_merge.h"
#include "mcws/planning/roadmap.h"
#include "mcws/planning/sway.h"

namespace mcws {

/// \brief What a round's best path must meet to be accepted (step s50).
enum class Acceptance {
  /// The upper end of the 95 % Wilson interval of the path's whole-path collision rate over the
  /// n planning poses (the share of poses for which it collides anywhere along its length) is at
  /// most max_collision_probability.
  kWholePath,
  /// The patent's literal reading: P (a mean of segment free rates) is at least the threshold.
  /// P stays near 1 while the path collides for a large share of the poses.
  kPatentP,
};

/// \brief "whole_path" or "patent_p", as the scenario file writes it.
const char* acceptanceName(Acceptance acceptance);

/// \brief Everything the method of the maintenance-arm patent takes (step s10 and the readings mcws
/// makes of it).
struct SwayPlanningProblem {
  Robot robot;                  ///< its T_world_base is the measured ("first static") pose
  CollisionModel collision;     ///< arm, tool and the obstacles around it
  Eigen::VectorXd start, goal;  ///< [rad | length unit]
  SwayModel sway;               ///< step s20: how the base moves about the measured pose
  std::size_t base_poses{100};  ///< n
  std::size_t candidates{10};   ///< m
  double diversity{0.5};        ///< diversePaths() penalty
  double segment_length{0.5};   ///< step s41's resolution [scaled joint distance]
  ScoreOptions score;           ///< step s45 (reference_distance: set to D0 by the planner)
  Acceptance acceptance{Acceptance::kWholePath};  ///< step s50's criterion
  /// kWholePath: the largest acceptable upper end of the 95 % Wilson interval of the whole-path
  /// collision rate [fraction in (0, 1)].
  double max_collision_probability{0.05};
  double threshold{0.9};  ///< kPatentP: least acceptable P of the best path [fraction]
  /// A goal in collision at the measured base pose may be freed by shifting the base (step s70),
  /// which moves the tool's end away from the target; false: such a goal ends the planning.
  bool allow_goal_shift{false};
  double base_step{0.0};   ///< step s70: shift along the line per round [length unit]
  double base_range{0.0};  ///< step s70: largest shift either way [length unit]
  RoadmapOptions roadmap;  ///< includes the joint scales and the seed
  std::uint64_t seed{1};   ///< base poses (the roadmap has its own in `roadmap`)
  std::size_t validation_poses{10000};
  /// Obstacle padding of the comparison planner [length unit]; negative: 2 sigma of the
  /// displacement of the arm's farthest point (see padding()).
  double padding{-1.0};
};

/// \brief Safety numbers of one path for a set of base poses.
struct PathSafety {
  VertexPath vertices;                     ///< roadmap vertices
  std::vector<Eigen::VectorXd> waypoints;  ///< the configurations of those vertices
  double length{0.0};                      ///< D at the goal [scaled joint distance]
  double probability{0.0};                 ///< the patent's P at the goal: a mean of segment rates
  std::size_t segments{0};
  std::size_t free_poses{0};  ///< base poses for which the whole path is free
  double free_fraction{0.0};
  ProportionInterval free_interval;  ///< 95 % Wilson interval of free_fraction
  /// Base poses for which the path collides anywhere along its length (n - free_poses).
  std::size_t colliding_poses{0};
  double collision_rate{0.0};             ///< colliding_poses / n [fraction]
  ProportionInterval collision_interval;  ///< 95 % Wilson interval of collision_rate
  std::size_t worst_segment{0};           ///< index along the path, from 0
  double worst_probability{1.0};
  Eigen::VectorXd worst_from, worst_to;  ///< the worst segment's end configurations
};

/// \brief One round of steps s20 to s47 at one base offset along the line.
struct PlanningRound {
  double base_offset{0.0};  ///< [length unit] along the line
  RoadmapStatus status{RoadmapStatus::kNotConnected};
  std::size_t roadmap_vertices{0}, roadmap_edges{0};
  double reference_distance{0.0};      ///< D0: straight start-to-goal distance
  std::vector<PathSafety> candidates;  ///< as found (step s30), before any splice
  std::vector<SharedNodeDecision> decisions;
  std::optional<PathSafety> best;  ///< the global best path (step s47), when connected
  bool accepted{false};            ///< best meets the problem's acceptance criterion (s50)
  /// How far the goal's tool point lies from where it lies for the measured base pose
  /// (SwayPlanner::goalDisplacement()) [length unit].
  double goal_displacement{0.0};
  double seconds{0.0};             ///< wall time of the round
  double roadmap_seconds{0.0};     ///< of which growing the roadmap (step s30)
  double evaluation_seconds{0.0};  ///< of which the segments' free states (s41, s42)
};

/// \brief The validation of one path on fresh base poses.
struct ValidationRow {
  std::string name;     ///< "chosen", "shortest", "padded"
  bool planned{false};  ///< false: its planner found no path, and the numbers below mean nothing
  std::string status;   ///< roadmap status of its planner
  double length{0.0};   ///< [scaled joint distance]; planned rows only
  std::size_t colliding{0}, poses{0};
  double collision_probability{0.0};  ///< planned rows only
  ProportionInterval interval;        ///< 95 % Wilson interval; planned rows only
  double padding{0.0};                ///< the padded row's margin [length unit]
  double seconds{0.0};                ///< wall time (the padded row: its roadmap included)
  double planning_seconds{0.0};       ///< the padded row: growing its roadmap and its shortest path
};

/// \brief The whole result of mcws_plan.
struct SwayPlanningResult {
  std::vector<PlanningRound> rounds;    ///< offset 0 first, then the base adjustments (s70)
  std::optional<std::size_t> accepted;  ///< the round whose best path meets the criterion
  /// The round whose best path is validated (when plan() is asked to): the accepted one, or when
  /// none is, the one closest to the criterion; empty when no round found a path.
  std::optional<std::size_t> validated;
  std::vector<ValidationRow> validation;
  double validation_seconds{0.0};
};

/// \brief Stages a long run reports (stage name, done, total).
using PlanningProgress = std::function<void(const std::string&, std::size_t, std::size_t)>;

/// \brief The planner of the maintenance-arm patent.
class SwayPlanner {
 public:
  /// \throws mcws::Error for a bad problem: the messages name the field and value.
  explicit SwayPlanner(SwayPlanningProblem problem);
  ~SwayPlanner();

  /// \brief Steps s20 to s47 with the base shifted by `offset` along the line [length unit].
  /// `cancel_check` (when set) is called on the calling thread every few milliseconds of the
  /// roadmap's growth and the segments' checks: what it throws ends the call (no result).
  PlanningRound planRound(double offset, const PlanningProgress& progress = {},
                          const CancelCheck& cancel_check = {}) const;

  /// \brief Whether a path meets the problem's acceptance criterion (step s50): for kWholePath,
  /// the upper end of the 95 % Wilson interval of its whole-path collision rate over the n
  /// planning poses is at most max_collision_probability; for kPatentP, P >= threshold.
  bool accepts(const PathSafety& path) const;

  /// \brief Steps s20 to s70: offset 0, then +step, -step, +2 step, ... within the range until
  /// the best path is accepted; a start in collision at the measured pose, or a goal in
  /// collision there without allow_goal_shift, ends the planning after the first round. Then
  /// validates the accepted (or, when none is, the closest to acceptance) round's best path
  /// against the shortest and the padded shortest path (when `validate`). `cancel_check` as
  /// planRound(), and also within the validation.
  SwayPlanningResult plan(bool validate, const PlanningProgress& progress = {},
                          const CancelCheck& cancel_check = {}) const;

  /// \brief Collision probability of a path over `poses` fresh base poses (a seed distinct
  /// from the planning one) at a base offset; `cancel_check` as planRound().
  ValidationRow validate(const std::string& name, const std::vector<Eigen::VectorXd>& waypoints,
                         double offset, const CancelCheck& cancel_check = {}) const;

  /// \brief How far the tool point of the goal configuration moves when the base is shifted by
  /// `offset` along the line [length unit]: the tool then ends this far from the target it
  /// reaches from the measured base pose.
  double goalDisplacement(double offset) const;

  /// \brief The padding of the comparison planner [length unit]: problem.padding, or when
  /// negative, twice the root-mean-square displacement over the n base poses of the point of
  /// the arm farthest from the pivot (its tool point at start and at goal, the larger).
  double padding() const;

  /// \brief Free state (1 free, 0 colliding) of the straight joint-space motion from qa to qb
  /// for each of the n base poses, with the base shifted by `offset` along the line (the
  /// environment pairs only: self-collisions do not depend on the base).
  std::vector<std::uint8_t> motionFreeStates(const Eigen::VectorXd& qa, const Eigen::VectorXd& qb,
                                             double offset) const;

  /// \brief Fraction of the n base poses for which configuration q collides (Figure 2b of
  /// the maintenance-arm patent, generalised), at base offset 0.
  double collisionFraction(const Eigen::VectorXd& q) const;

  const SwayPlanningProblem& problem() const { return problem_; }
  const CollisionChecker& checker() const { return *checker_; }
  /// \brief World motions of the n planning base poses.
  const std::vector<Eigen::Isometry3d>& displacements() const { return displacements_; }

 private:
  Eigen::Isometry3d measuredBase(double offset) const;
  /// Base offsets in the order step s70 tries them: 0, +step, -step, +2 step, ... [length unit].
  std::vector<double> baseOffsets() const;
  /// Validates the best path of result.validated against the shortest and the padded path.
  void validateRound(SwayPlanningResult& result, const PlanningProgress& progress,
                     const CancelCheck& cancel_check) const;
  /// The padded comparison planner's path at a base offset, validated.
  ValidationRow validatePadded(double offset, const CancelCheck& cancel_check) const;
  /// The n planning displacements about the sway frame moved by `offset`.
  std::vector<Eigen::Isometry3d> movedDisplacements(const std::vector<Eigen::Isometry3d>& base,
                                                    double offset) const;

  SwayPlanningProblem problem_;
  std::unique_ptr<CollisionChecker> checker_;
  std::unique_ptr<MotionCertifier> certifier_;
  std::unique_ptr<SwaySampler> sampler_;
  std::vector<Eigen::Isometry3d> displacements_;
};

}  // namespace mcws
