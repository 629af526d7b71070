#pragma once
/// \file
/// \brief Inverse kinematics of a serial chain: the robust damped-least-squares solver with joint
/// limits and seeded restarts, and the Newton iteration of Liu, Han, Xu & Li 2021.

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <string>

#include "mcws/kinematics/robot.h"

namespace mcws {

/// \brief How an IK solve ended.
enum class IkStatus {
  kConverged,      ///< the pose is reached within the tolerances
  kMaxIterations,  ///< the iteration budget ran out while the error was still falling
  kNoSolution,     ///< every attempt stalled away from the target (likely unreachable)
};

/// \brief Name of a status ("converged", "max_iterations", "no_solution").
const char* ikStatusName(IkStatus status);

/// \brief Settings of solveIk().
struct IkOptions {
  double position_tolerance{1e-6};     ///< largest accepted |p_target - p| [length unit]
  double orientation_tolerance{1e-6};  ///< largest accepted rotation angle error [rad]
  int max_iterations{100};             ///< iterations per attempt (seed or restart)
  int restarts{20};                    ///< random restarts after the attempt from the seed
  bool position_only{false};           ///< match the tool point only (arms with < 6 joints)
  /// Match the tool point and the direction of the tool's z axis only; the rotation about that
  /// axis is free (a target given as a point and an approach direction: nozzles, brushes, drills,
  /// the point-and-normal targets of a reach study). orientation_error is then the angle between
  /// the tool's z axis and the target's [rad]. Ignored when position_only is set.
  bool free_roll{false};
  std::uint64_t seed{1};  ///< seed of the restarts' random joint vectors
  /// Damping lambda^2 of the first step of each attempt, dimensionless (position rows are
  /// divided by the chain's reach); it then adapts, Levenberg-Marquardt style.
  double damping{1e-2};
};

/// \brief Outcome of an IK solve.
struct IkResult {
  IkStatus status{IkStatus::kNoSolution};
  /// The solution, or the best found (least weighted error) [rad | length unit].
  Eigen::VectorXd q;
  int iterations{0};              ///< iterations over all attempts
  int attempts{0};                ///< attempts made: 1 + restarts used
  double position_error{0.0};     ///< |p_target - p(q)| [length unit]
  double orientation_error{0.0};  ///< angle of R_target R(q)^T [rad]
  bool converged() const { return status == IkStatus::kConverged; }
};

/// \brief How close an attempt that did not converge came, for a message (4 digits): "no
/// solution (max_iterations): the best pose found is 0.3 mm and 0.01 rad away, after 2000
/// iterations from 8 starts", in the length unit of `robot`.
std::string describeIkFailure(const Robot& robot, const IkResult& result);

/// \brief Robust inverse kinematics: the joint vector within limits whose tool pose is
/// T_world_tool_target.
///
/// Each attempt iterates damped least squares on the 6-D pose error e = (p* - p, log(R* R^T))
/// (position rows divided by the chain's reach so both halves are dimensionless):
/// dq = J^T (J J^T + lambda^2 I)^-1 e, with lambda adapted as in Levenberg-Marquardt (Marquardt
/// 1963; Wampler 1986 and Nakamura & Hanafusa 1986 for damping near singularities): a step that
/// lowers |e| is kept and lambda shrinks, otherwise it is retried with a larger lambda. Joint
/// values are projected into their limits after every step (joints whose range spans a full turn
/// are wrapped instead); a joint held by its limit drops out of the step, which the others then
/// make up for; no joint moves more than 1 rad per step. An attempt that stalls ends early; the
/// next one starts from a random joint vector drawn from `options.seed` and the attempt number, so
/// equal inputs give equal results. In position-only mode e and J keep their first three rows; in
/// free-roll mode the rotation error is the rotation vector taking the tool's z axis z onto the
/// target's z* (axis z x z*, angle between them) and J's rotation rows lose their part along z,
/// which does not move z.
///
/// \param robot the chain.
/// \param T_world_tool_target the wanted tool pose [length unit]; its rotation must be
///   orthonormal (1e-9).
/// \param q_seed first guess, one value per joint [rad | length unit]; projected into the limits.
/// \param options tolerances, budgets, seed.
/// \return the status; q is within the joint limits. An unreachable pose is not an error.
/// \throws mcws::Error for a non-finite or non-rigid target, a q_seed of the wrong size or with
///   non-finite values, or non-positive tolerances or budgets.
IkResult solveIk(const Robot& robot, const Eigen::Isometry3d& T_world_tool_target,
                 const Eigen::VectorXd& q_seed, const IkOptions& options = {});

/// \brief solveIk() for many poses of one robot: the chain is prepared once (the joint axes turned
/// onto z, limits and scales read), not once per solve.
class IkSolver {
 public:
  /// \param robot the chain (copied).
  explicit IkSolver(const Robot& robot);
  /// \brief As solveIk(robot, T_world_tool_target, q_seed, options).
  IkResult solve(const Eigen::Isometry3d& T_world_tool_target, const Eigen::VectorXd& q_seed,
                 const IkOptions& options = {}) const;

  struct Prepared;

 private:
  Robot robot_;
  std::shared_ptr<const Prepared> prepared_;
};

/// \brief The inverse kinematics of Liu, Han, Xu & Li 2021 (section 1.2): Newton iteration
/// q_{k+1} = q_k + J_H^-1 (H* - H(q_k)) on the six entries H = (r11, r22, r33, px, py, pz) of
/// the tool pose, J_H = dH/dq (analytic), stopping when |q_{k+1} - q_k| <= step_tolerance.
///
/// Faithful to the paper: no damping, no joint limits, and six joints needed (J_H square). The
/// three diagonal entries do not fix the orientation uniquely, so the result's
/// orientation_error (of the full pose) tells whether the pose was really reached.
/// \param step_tolerance the paper's 0.001 [rad | length unit].
/// \return kConverged when the step fell below step_tolerance, kMaxIterations when the budget
///   ran out, kNoSolution when J_H became singular or the iteration diverged.
/// \throws mcws::Error when the robot does not have six joints, for a step_tolerance that is not
///   positive or a max_iterations below 1, or as solveIk() for the target and q_seed.
IkResult solveIkNewtonPoseEntries(const Robot& robot, const Eigen::Isometry3d& T_world_tool_target,
                                  const Eigen::VectorXd& q_seed, double step_tolerance = 1e-3,
                                  int max_iterations = 100);

}  // namespace mcws
