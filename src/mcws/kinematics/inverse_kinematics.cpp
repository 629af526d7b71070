#include "mcws/kinematics/inverse_kinematics.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <vector>

#include "mcws/core/counter_rng.h"
#include "mcws/core/error.h"
#include "mcws/kinematics/jacobian.h"

namespace mcws {

/// What IkSolver prepares once per robot.
struct IkSolver::Prepared {
  /// Joint limits as the solver uses them.
  struct JointRange {
    double lower, upper;  ///< projection bounds
    bool wraps;           ///< revolute with a full turn or more: wrap by 2 pi instead of clamping
    double sample_lower, sample_upper;  ///< where restarts draw from
  };
  KinematicChain chain;
  std::vector<JointRange> ranges;
  double inverse_reach;            ///< 1 / the chain's length scale [1 / length unit]
  std::vector<double> step_scale;  ///< 1 for revolute joints, pi / stroke for prismatic ones
};

namespace {

using JointRange = IkSolver::Prepared::JointRange;

constexpr double kTwoPi = 2.0 * M_PI;
/// Largest |R^T R - I| entry of an accepted target rotation: far above the rounding of a
/// rotation composed in double (~1e-15), far below any real mistake.
constexpr double kOrthonormalTolerance = 1e-9;

// ---- checks shared by both solvers -------------------------------------------------------------

void checkTarget(const Eigen::Isometry3d& T, const char* who) {
  const Eigen::Matrix4d& M = T.matrix();
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      if (!std::isfinite(M(r, c))) {
        std::ostringstream msg;
        msg << who << ": target pose entry (" << r << ", " << c << ") is " << M(r, c)
            << ", not a finite number";
        throw Error(msg.str());
      }
    }
  }
  if (M.row(3) != Eigen::RowVector4d(0, 0, 0, 1)) {
    throw Error(std::string(who) + ": target pose's last row is not 0 0 0 1");
  }
  const Eigen::Matrix3d R = M.topLeftCorner<3, 3>();
  const double deviation = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (deviation > kOrthonormalTolerance || R.determinant() < 0.0) {
    std::ostringstream msg;
    msg << who << ": target rotation is not orthonormal (|R^T R - I| = " << deviation
        << ", det R = " << R.determinant() << ")";
    throw Error(msg.str());
  }
}

void checkSeed(const Robot& robot, const Eigen::VectorXd& q_seed) {
  robot.checkSize(q_seed);
  for (int i = 0; i < robot.dof(); ++i) {
    if (!std::isfinite(q_seed[i])) {
      std::ostringstream msg;
      msg << "IK seed value of joint '" << robot.joints[i].name << "' is " << q_seed[i]
          << ", not a finite number";
      throw Error(msg.str());
    }
  }
}

/// Rotation vector (axis * angle) of a rotation matrix, the inverse of the exponential map.
Eigen::Vector3d rotationVector(const Eigen::Matrix3d& R) {
  const Eigen::Vector3d v(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));  // 2 sin(a) u
  const double s = 0.5 * v.norm();
  const double c = 0.5 * (R.trace() - 1.0);
  if (c > -0.9) {  // angle below ~154 deg: v is well conditioned
    const double angle = std::atan2(s, c);
    return v * (s > 1e-12 ? 0.5 * angle / s : 0.5);  // angle / sin(angle) -> 1
  }
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

std::vector<JointRange> jointRanges(const Robot& robot, double reach) {
  std::vector<JointRange> ranges;
  for (const Joint& joint : robot.joints) {
    JointRange r{joint.lower, joint.upper, false, joint.lower, joint.upper};
    const bool revolute = joint.type == JointType::kRevolute;
    r.wraps = revolute && std::isfinite(r.lower) && std::isfinite(r.upper) &&
              r.upper - r.lower >= kTwoPi - 1e-9;
    // Unbounded joints: restarts draw from one turn, or from one reach of travel.
    const double width = revolute ? kTwoPi : 2.0 * reach;
    if (!std::isfinite(r.lower)) {
      r.sample_lower = std::isfinite(r.upper) ? r.upper - width : -0.5 * width;
    }
    if (!std::isfinite(r.upper)) r.sample_upper = r.sample_lower + width;
    ranges.push_back(r);
  }
  return ranges;
}

double project(double x, const JointRange& r) {
  if (x >= r.lower && x <= r.upper) return x;
  if (r.wraps) {
    x = r.lower + std::fmod(x - r.lower, kTwoPi);
    if (x < r.lower) x += kTwoPi;
  }
  return std::min(std::max(x, r.lower), r.upper);
}

// ---- the damped least squares solver ------------------------------------------------------------

/// Everything one solve needs, fixed before the first attempt.
struct Problem {
  const IkSolver::Prepared& chain;
  Eigen::Matrix3d R_target;
  Eigen::Vector3d p_target;
  IkOptions options;
};

/// Rotation vector of the shortest rotation taking the unit vector `from` onto the unit vector
/// `to` (axis from x to, angle between them; any axis normal to `from` when they are opposite).
Eigen::Vector3d axisAlignment(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  const Eigen::Vector3d axis = from.cross(to);
  const double s = axis.norm();
  const double c = from.dot(to);
  if (s > 1e-12) return axis * (std::atan2(s, c) / s);
  if (c > 0.0) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d other =
      std::abs(from.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return from.cross(other).normalized() * M_PI;
}

/// Levenberg-Marquardt schedule of lambda^2: times kDampingDown after a step that lowered the
/// error, times kDampingUp after one that did not (tuned on bench_ik's poses: mean iterations
/// within 10 % over 0.1 .. 0.5 and 4 .. 10).
constexpr double kDampingDown = 0.3;
constexpr double kDampingUp = 10.0;
/// lambda^2 never drops below this: keeps J J^T + lambda^2 I positive definite while changing a
/// regular Newton step by a relative 1e-12 / sigma_min^2 (sigma of the reach-scaled Jacobian).
constexpr double kMinDamping = 1e-12;
/// An attempt gives up when lambda^2 has grown this large (the step is a tiny gradient step) ...
constexpr double kMaxDamping = 1e6;
/// ... or after kMaxSlowSteps accepted steps in a row that each cut |e|^2 by less than 10 %: a
/// local minimum, often a joint held by its limit. Restarting then is cheaper than crawling.
constexpr int kMaxSlowSteps = 5;
constexpr double kSlowProgress = 0.9;
/// Largest step of a revolute joint per iteration [rad] (prismatic: pi per full stroke); longer
/// steps are shortened, keeping their direction. Far from the target, Newton steps of several
/// radians are common and mostly rejected.
constexpr double kMaxStep = 1.0;

enum class AttemptEnd { kConverged, kStalled, kBudget };

/// Rows: 6 (pose) or 3 (position only); Dof: 6 or Eigen::Dynamic.
template <int Rows, int Dof>
class DlsSolver {
 public:
  using MatrixJ = Eigen::Matrix<double, 6, Dof>;
  using MatrixW = Eigen::Matrix<double, Rows, Dof>;
  using VectorQ = Eigen::Matrix<double, Dof, 1>;
  using VectorE = Eigen::Matrix<double, Rows, 1>;

  explicit DlsSolver(const Problem& problem) : problem_(problem), n_(problem.chain.chain.dof()) {
    for (State* s : {&current_, &trial_, &best_}) {
      s->q.resize(n_);
      s->J.resize(6, n_);
    }
    Jw_.resize(Rows, n_);
    dq_.resize(n_);
    A_joint_.resize(n_, n_);
  }

  IkResult solve(const Eigen::VectorXd& q_seed) {
    const IkOptions& options = problem_.options;
    const CounterRng rng(options.seed);
    IkResult result;
    best_.cost = std::numeric_limits<double>::infinity();
    bool budget_ran_out = false;
    for (int attempt = 0; attempt <= options.restarts; ++attempt) {
      for (int i = 0; i < n_; ++i) {
        const JointRange& r = problem_.chain.ranges[i];
        current_.q[i] = attempt == 0 ? project(q_seed[i], r)
                                     : r.sample_lower + (r.sample_upper - r.sample_lower) *
                                                            uniform(rng, attempt, i);
      }
      const AttemptEnd end = runAttempt(result.iterations);
      result.attempts = attempt + 1;
      if (current_.cost < best_.cost) std::swap(best_, current_);
      if (end == AttemptEnd::kConverged) {
        result.status = IkStatus::kConverged;
        break;
      }
      budget_ran_out = budget_ran_out || end == AttemptEnd::kBudget;
    }
    if (result.status != IkStatus::kConverged) {
      result.status = budget_ran_out ? IkStatus::kMaxIterations : IkStatus::kNoSolution;
    }
    result.q = best_.q;
    result.position_error = best_.position_error;
    result.orientation_error = best_.orientation_error;
    return result;
  }

 private:
  struct State {
    VectorQ q;
    MatrixJ J;
    VectorE e;          ///< weighted error
    double cost{0.0};   ///< |e|^2
    Eigen::Vector3d z;  ///< the tool's z axis (free roll)
    double position_error{0.0}, orientation_error{0.0};
  };

  /// Joint j of restart `attempt`: 16 streams per counter index, as many indices as needed.
  double uniform(const CounterRng& rng, int attempt, int joint) const {
    const std::uint64_t per_attempt =
        (static_cast<std::uint64_t>(n_) + CounterRng::kStreams - 1) / CounterRng::kStreams;
    return rng.uniform(static_cast<std::uint64_t>(attempt) * per_attempt +
                           static_cast<std::uint64_t>(joint) / CounterRng::kStreams,
                       static_cast<std::uint64_t>(joint) % CounterRng::kStreams);
  }

  void evaluate(State& s) const {
    Eigen::Matrix3d R;
    Eigen::Vector3d p;
    problem_.chain.chain.toolPoseAndJacobian(s.q.data(), R, p, s.J.data());
    const Eigen::Vector3d e_p = problem_.p_target - p;
    s.position_error = e_p.norm();
    s.e.template head<3>() = e_p * problem_.chain.inverse_reach;
    if constexpr (Rows == 6) {
      s.z = R.col(2);
      const Eigen::Vector3d e_o = problem_.options.free_roll
                                      ? axisAlignment(s.z, problem_.R_target.col(2))
                                      : rotationVector(problem_.R_target * R.transpose());
      s.orientation_error = e_o.norm();
      s.e.template tail<3>() = e_o;
    } else {
      s.orientation_error = rotationVector(problem_.R_target * R.transpose()).norm();
    }
    s.cost = s.e.squaredNorm();
  }

  bool withinTolerance(const State& s) const {
    return s.position_error <= problem_.options.position_tolerance &&
           (Rows == 3 || s.orientation_error <= problem_.options.orientation_tolerance);
  }

  /// dq = Jw^T (Jw Jw^T + lambda2 I)^-1 e, or (Jw^T Jw + lambda2 I)^-1 Jw^T e when there are fewer
  /// joints than error rows (the same vector). A joint resting on a limit that the step would push
  /// it through is then taken out (its column zeroed) and the step solved again, so the other
  /// joints make up for it (an active set of one pass). Returns false when a factorisation fails.
  bool step(const State& s, double lambda2) {
    Jw_ = s.J.template topRows<Rows>();
    Jw_.template topRows<3>() *= problem_.chain.inverse_reach;
    if constexpr (Rows == 6) {
      if (problem_.options.free_roll) {  // turning about z does not move z
        const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - s.z * s.z.transpose();
        Jw_.template bottomRows<3>() = across * s.J.template bottomRows<3>();
      }
    }
    if (!solveStep(s.e, lambda2)) return false;
    bool locked = false;
    for (int i = 0; i < n_; ++i) {
      const JointRange& r = problem_.chain.ranges[i];
      if (r.wraps) continue;
      if ((s.q[i] >= r.upper && dq_[i] > 0.0) || (s.q[i] <= r.lower && dq_[i] < 0.0)) {
        Jw_.col(i).setZero();
        locked = true;
      }
    }
    return !locked || solveStep(s.e, lambda2);
  }

  bool solveStep(const VectorE& e, double lambda2) {
    if (n_ >= Rows) {
      Eigen::Matrix<double, Rows, Rows> A = Jw_ * Jw_.transpose();
      A.diagonal().array() += lambda2;
      llt_task_.compute(A);
      if (llt_task_.info() != Eigen::Success) return false;
      dq_.noalias() = Jw_.transpose() * llt_task_.solve(e);
    } else {
      A_joint_.noalias() = Jw_.transpose() * Jw_;
      A_joint_.diagonal().array() += lambda2;
      llt_joint_.compute(A_joint_);
      if (llt_joint_.info() != Eigen::Success) return false;
      dq_ = llt_joint_.solve(Jw_.transpose() * e);
    }
    return dq_.allFinite();
  }

  AttemptEnd runAttempt(int& iterations) {
    const IkOptions& options = problem_.options;
    evaluate(current_);
    double lambda2 = std::max(options.damping, kMinDamping);
    int slow = 0;
    for (int k = 0; k < options.max_iterations; ++k) {
      if (withinTolerance(current_)) return AttemptEnd::kConverged;
      ++iterations;
      if (!step(current_, lambda2)) {
        lambda2 *= kDampingUp;
        if (lambda2 > kMaxDamping) return AttemptEnd::kStalled;
        continue;
      }
      double biggest = 0.0;
      for (int i = 0; i < n_; ++i) {
        biggest = std::max(biggest, std::abs(dq_[i]) * problem_.chain.step_scale[i]);
      }
      if (biggest > kMaxStep) dq_ *= kMaxStep / biggest;
      for (int i = 0; i < n_; ++i)
        trial_.q[i] = project(current_.q[i] + dq_[i], problem_.chain.ranges[i]);
      evaluate(trial_);
      if (trial_.cost < current_.cost) {
        slow = trial_.cost > kSlowProgress * current_.cost ? slow + 1 : 0;
        std::swap(current_, trial_);
        lambda2 = std::max(lambda2 * kDampingDown, kMinDamping);
      } else {
        lambda2 *= kDampingUp;
      }
      if (lambda2 > kMaxDamping || slow >= kMaxSlowSteps) return AttemptEnd::kStalled;
    }
    return withinTolerance(current_) ? AttemptEnd::kConverged : AttemptEnd::kBudget;
  }

  const Problem& problem_;
  const int n_;
  State current_, trial_, best_;
  MatrixW Jw_;
  VectorQ dq_;
  Eigen::Matrix<double, Dof, Dof> A_joint_;
  Eigen::LLT<Eigen::Matrix<double, Rows, Rows>> llt_task_;
  Eigen::LLT<Eigen::Matrix<double, Dof, Dof>> llt_joint_;
};

void checkOptions(const IkOptions& o) {
  const bool valid = o.position_tolerance > 0.0 && std::isfinite(o.position_tolerance) &&
                     o.orientation_tolerance > 0.0 && std::isfinite(o.orientation_tolerance) &&
                     o.max_iterations >= 1 && o.restarts >= 0 && o.damping >= 0.0 &&
                     std::isfinite(o.damping);
  if (valid) return;
  std::ostringstream msg;
  if (!(o.position_tolerance > 0.0) || !std::isfinite(o.position_tolerance)) {
    msg << "IK position tolerance " << o.position_tolerance << " is not a positive number";
  } else if (!(o.orientation_tolerance > 0.0) || !std::isfinite(o.orientation_tolerance)) {
    msg << "IK orientation tolerance " << o.orientation_tolerance << " is not a positive number";
  } else if (o.max_iterations < 1) {
    msg << "IK max_iterations " << o.max_iterations << " is not at least 1";
  } else if (o.restarts < 0) {
    msg << "IK restarts " << o.restarts << " is negative";
  } else if (!(o.damping >= 0.0) || !std::isfinite(o.damping)) {
    msg << "IK damping " << o.damping << " is not a non-negative number";
  } else {
    return;
  }
  throw Error(msg.str());
}

}  // namespace

std::string describeIkFailure(const Robot& robot, const IkResult& result) {
  std::ostringstream msg;
  msg.precision(4);
  msg << "no solution (" << ikStatusName(result.status) << "): the best pose found is "
      << result.position_error << " " << unitName(robot.length_unit) << " and "
      << result.orientation_error << " rad away, after " << result.iterations << " iterations from "
      << result.attempts << " starts";
  return msg.str();
}

const char* ikStatusName(IkStatus status) {
  switch (status) {
    case IkStatus::kConverged:
      return "converged";
    case IkStatus::kMaxIterations:
      return "max_iterations";
    case IkStatus::kNoSolution:
      return "no_solution";
  }
  return "?";
}

IkSolver::IkSolver(const Robot& robot) : robot_(robot) {
  auto prepared = std::make_shared<Prepared>(Prepared{KinematicChain(robot), {}, 1.0, {}});
  const double reach = chainLengthScale(robot);
  prepared->ranges = jointRanges(robot, reach);
  prepared->inverse_reach = 1.0 / reach;
  for (const Joint& joint : robot.joints) {
    const double stroke = joint.upper - joint.lower;
    const bool scaled =
        joint.type == JointType::kPrismatic && stroke > 0.0 && std::isfinite(stroke);
    prepared->step_scale.push_back(scaled ? M_PI / stroke : 1.0);
  }
  prepared_ = std::move(prepared);
}

IkResult IkSolver::solve(const Eigen::Isometry3d& T_world_tool_target,
                         const Eigen::VectorXd& q_seed, const IkOptions& options) const {
  checkTarget(T_world_tool_target, "solveIk");
  checkSeed(robot_, q_seed);
  checkOptions(options);
  const Problem problem{*prepared_, T_world_tool_target.linear(), T_world_tool_target.translation(),
                        options};
  if (options.position_only) return DlsSolver<3, Eigen::Dynamic>(problem).solve(q_seed);
  if (robot_.dof() == 6) return DlsSolver<6, 6>(problem).solve(q_seed);
  return DlsSolver<6, Eigen::Dynamic>(problem).solve(q_seed);
}

IkResult solveIk(const Robot& robot, const Eigen::Isometry3d& T_world_tool_target,
                 const Eigen::VectorXd& q_seed, const IkOptions& options) {
  return IkSolver(robot).solve(T_world_tool_target, q_seed, options);
}

IkResult solveIkNewtonPoseEntries(const Robot& robot, const Eigen::Isometry3d& T_world_tool_target,
                                  const Eigen::VectorXd& q_seed, double step_tolerance,
                                  int max_iterations) {
  checkTarget(T_world_tool_target, "solveIkNewtonPoseEntries");
  checkSeed(robot, q_seed);
  if (robot.dof() != 6) {
    throw Error("solveIkNewtonPoseEntries: robot '" + robot.name + "' has " +
                std::to_string(robot.dof()) + " joints, not 6");
  }
  if (!(step_tolerance > 0.0) || max_iterations < 1) {
    std::ostringstream msg;
    msg << "solveIkNewtonPoseEntries: ";
    if (!(step_tolerance > 0.0)) {
      msg << "step tolerance " << step_tolerance << " is not a positive number";
    } else {
      msg << "max_iterations " << max_iterations << " is not at least 1";
    }
    throw Error(msg.str());
  }
  const KinematicChain chain(robot);
  const Eigen::Matrix3d& R_target = T_world_tool_target.linear();
  // H = (r11, r22, r33, px, py, pz): entries 1, 6, 11, 13, 14, 15 of the pose (column-major,
  // Liu, Han, Xu & Li 2021, eq. (3)).
  auto entries = [](const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
    Eigen::Matrix<double, 6, 1> H;
    H << R(0, 0), R(1, 1), R(2, 2), p;
    return H;
  };
  const Eigen::Matrix<double, 6, 1> H_target = entries(R_target, T_world_tool_target.translation());

  IkResult result;
  result.attempts = 1;
  Eigen::Matrix<double, 6, 1> q = q_seed;
  Eigen::Matrix<double, 6, 6> J, J_H;
  Eigen::Matrix3d R;
  Eigen::Vector3d p;
  result.status = IkStatus::kMaxIterations;
  for (int k = 0; k < max_iterations; ++k) {
    chain.toolPoseAndJacobian(q.data(), R, p, J.data());
    // dR/dq_i = [w_i]x R with w_i column i's angular part, so d r_kk / dq_i = (w_i x R e_k)_k.
    for (int i = 0; i < 6; ++i) {
      const Eigen::Vector3d w = J.col(i).tail<3>();
      for (int r = 0; r < 3; ++r) J_H(r, i) = w.cross(R.col(r))[r];
      J_H.col(i).tail<3>() = J.col(i).head<3>();
    }
    const Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>> lu(J_H);
    if (!lu.isInvertible()) {
      result.status = IkStatus::kNoSolution;
      break;
    }
    const Eigen::Matrix<double, 6, 1> dq = lu.solve(H_target - entries(R, p));
    ++result.iterations;
    if (!dq.allFinite()) {
      result.status = IkStatus::kNoSolution;
      break;
    }
    q += dq;
    if (dq.norm() <= step_tolerance) {
      result.status = IkStatus::kConverged;
      break;
    }
  }
  const Eigen::Isometry3d T = chain.toolPose(q.data());
  result.q = q;
  result.position_error = (T_world_tool_target.translation() - T.translation()).norm();
  result.orientation_error = rotationVector(R_target * T.linear().transpose()).norm();
  return result;
}

}  // namespace mcws
