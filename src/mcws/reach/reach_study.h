#pragma once
/// \file
/// \brief Reach study of target poses (as ROS-Industrial REACH): for each target, whether the
/// robot reaches it (inverse kinematics, collision model), with which joint values, how well
/// (manipulability) and how far from a collision (clearance); and the same for the robot moved
/// to other base positions (base placement).

#include <pcl/point_types.h>
#include <pcl/register_point_struct.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "mcws/collision/collision_checker.h"
#include "mcws/kinematics/inverse_kinematics.h"
#include "mcws/kinematics/robot.h"
#include "mcws/points/point_types.h"
#include "mcws/reach/quality.h"

namespace mcws {

/// \brief One target of a study: a tool pose in the world frame [length unit].
struct ReachTarget {
  Eigen::Isometry3d pose{Eigen::Isometry3d::Identity()};
  /// Only the tool point and the direction of the tool's z axis (the approach) count; the roll
  /// about it is free (a point with a surface normal: the approach is minus the normal).
  bool free_roll{true};
};

/// \brief A point-and-normal target: the tool point at `point`, its z axis along -normal (the
/// tool approaches the surface); the x axis is OrientationBins::rollReference() of the approach.
/// \throws mcws::Error for a non-finite point or a normal that is zero or not finite.
ReachTarget targetFromNormal(const Eigen::Vector3d& point, const Eigen::Vector3d& normal);

/// \brief Settings of ReachStudy.
struct ReachStudyOptions {
  /// Largest accepted angle between the tool's approach (or, for a full pose, its rotation) and
  /// the target's [rad]. 0: as exact as the IK tolerance (1e-6 rad).
  double approach_tolerance{0.0};
  /// Inverse kinematics starts per target: the middle of the joint ranges, then random joint
  /// vectors; each start runs `ik` (its own restarts included). Every converged solution is
  /// kept and the best chosen (collision-free first, then the highest manipulability), so more
  /// starts find better solutions, not only some solution.
  int starts{4};
  /// Position tolerance, budgets and the seed of the solves. position_only and free_roll are set
  /// per target, and orientation_tolerance from approach_tolerance (1e-6 rad when that is 0).
  IkOptions ik;
  QualityOptions quality;
  /// Clearances at or above this are reported as this value [length unit] (saves FCL distance
  /// queries between far-apart bodies).
  double clearance_cap{std::numeric_limits<double>::infinity()};
  /// Worker threads over the targets, 0 = all cores. Results do not depend on it.
  int threads{0};
  /// \throws mcws::Error for a negative or non-finite tolerance, starts < 1, IK budgets or a
  ///   position tolerance solveIk() would refuse, a bad quality or cap.
  void check() const;
};

/// \brief The outcome for one target.
struct TargetReach {
  /// IK found the pose (within the tolerances) and, with a collision model, the chosen solution
  /// is collision-free.
  bool reached{false};
  /// IK found the pose, collisions aside.
  bool solved{false};
  /// Label of the chosen solution (kLabelFree without a collision model).
  std::uint32_t label{kLabelFree};
  /// The chosen solution, or the best attempt [rad | length unit].
  Eigen::VectorXd q;
  double position_error{0.0};  ///< |p_target - p(q)| [length unit]
  /// Angle between the tool's approach and the target's (free roll) or of R_target R(q)^T [rad].
  double orientation_error{0.0};
  double manipulability{0.0};  ///< at q (ReachStudyOptions::quality); 0 when not solved
  /// Smallest distance between any checked pair of bodies at q [length unit], capped at
  /// clearance_cap; 0 when colliding; infinity without a collision model or when not solved.
  double clearance{std::numeric_limits<double>::infinity()};
  /// The target's score: the manipulability when reached, 0 otherwise.
  double score() const { return reached ? manipulability : 0.0; }
};

/// \brief Share reached and mean score of a study's results.
struct ReachSummary {
  std::size_t targets{0}, reached{0}, solved{0};
  double share_reached{0.0};  ///< reached / targets [1]
  double mean_score{0.0};     ///< mean of TargetReach::score() over all targets
  /// Mean manipulability over the reached targets (0 when none is).
  double mean_manipulability_reached{0.0};
  /// Smallest clearance of a reached target [length unit] (infinity when none is or without a
  /// collision model).
  double min_clearance_reached{std::numeric_limits<double>::infinity()};
};
ReachSummary summarize(const std::vector<TargetReach>& results);

/// \brief Reaches targets with one robot and, optionally, its collision model.
///
/// Each target is solved from ReachStudyOptions::starts starting joint vectors by solveIk(): a
/// full pose (6 rows) or a point and approach (free roll: 5 conditions); with approach_tolerance >
/// 0, a start that fails (an arm with fewer joints cannot meet the orientation exactly) gets a
/// second solve of the point alone from the first one's best joint vector, accepted when its
/// orientation error is within the tolerance. The base may be moved: the robot displaced rigidly by
/// `T_move` (world frame) reaches target T where the robot in place reaches T_move^-1 T, and its
/// bodies are checked at T_move * T_world_base against the fixed environment.
class ReachStudy {
 public:
  /// \param checker the robot's collision checker, or nullptr for kinematics only; must outlive
  ///   the study.
  /// \throws mcws::Error for bad options.
  ReachStudy(const Robot& robot, const CollisionChecker* checker, const ReachStudyOptions& options);

  /// \brief One target with the robot moved by T_move.
  TargetReach evaluate(const ReachTarget& target,
                       const Eigen::Isometry3d& T_move = Eigen::Isometry3d::Identity()) const;
  /// \brief Every target (in parallel), results in the targets' order.
  /// \param progress called now and then with (targets done, all), from one thread.
  std::vector<TargetReach> evaluate(
      const std::vector<ReachTarget>& targets,
      const Eigen::Isometry3d& T_move = Eigen::Isometry3d::Identity(),
      const std::function<void(std::size_t, std::size_t)>& progress = {}) const;

  const Robot& robot() const { return robot_; }
  const ReachStudyOptions& options() const { return options_; }

 private:
  /// The starting joint vector number `start` (0: the middle of the ranges).
  Eigen::VectorXd startOf(int start) const;
  /// IK of T (robot in place) from one start; true when within the tolerances.
  bool solve(const ReachTarget& target, const Eigen::Isometry3d& T, int start,
             IkResult& result) const;
  /// Collision label, clearance and manipulability of a solution.
  void assess(TargetReach& reach, const Eigen::Isometry3d& T_move) const;

  Robot robot_;
  const CollisionChecker* checker_;
  ReachStudyOptions options_;
  IkSolver solver_;
};

/// \brief A reach study's result per target as a point (mcws_reach --targets): the heat map.
///
/// PCD fields: `x y z` the target point [length unit]; `normal_x normal_y normal_z` the target's
/// surface normal (minus its approach), so the cloud still reads as pcl::PointNormal; `q1 .. q8`
/// the chosen joint values [rad | length unit] (0 beyond the robot's joints and when not solved);
/// `label` of the chosen solution; `reached` 1 or 0; `score` (TargetReach::score());
/// `manipulability` (the unit of Quality::manipulability); `clearance` [length unit], -1 where
/// not measured (no collision model, or not solved); `orientation_error` [rad] of the chosen (or
/// best) solution. (PCL registers at most 20 fields; the position error is in the JSON.)
struct EIGEN_ALIGN16 ReachTargetPoint {
  PCL_ADD_POINT4D;
  PCL_ADD_NORMAL4D;
  union {
    float q[kMaxJoints];
    struct {
      float q1, q2, q3, q4, q5, q6, q7, q8;
    };
  };
  std::uint32_t label;
  float reached;
  float score;
  float manipulability;
  float clearance;
  float orientation_error;

  ReachTargetPoint()
      : data{0.f, 0.f, 0.f, 1.f},
        data_n{0.f, 0.f, 0.f, 0.f},
        q{},
        label(kLabelFree),
        reached(0.f),
        score(0.f),
        manipulability(0.f),
        clearance(-1.f),
        orientation_error(0.f) {}
  PCL_MAKE_ALIGNED_OPERATOR_NEW
};

/// \brief The heat-map point of a target and its result.
ReachTargetPoint reachTargetPoint(const ReachTarget& target, const TargetReach& reach);

}  // namespace mcws

// clang-format off
POINT_CLOUD_REGISTER_POINT_STRUCT(mcws::ReachTargetPoint,
    (float, x, x) (float, y, y) (float, z, z)
    (float, normal_x, normal_x) (float, normal_y, normal_y) (float, normal_z, normal_z)
    (float, q1, q1) (float, q2, q2) (float, q3, q3) (float, q4, q4)
    (float, q5, q5) (float, q6, q6) (float, q7, q7) (float, q8, q8)
    (std::uint32_t, label, label) (float, reached, reached) (float, score, score)
    (float, manipulability, manipulability) (float, clearance, clearance)
    (float, orientation_error, orientation_error))
// clang-format on
