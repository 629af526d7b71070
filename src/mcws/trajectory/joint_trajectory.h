#pragma once
/// \file
/// \brief Joint-space trajectories: point-to-point blends (the quintic of Liu, Han, Xu & Li 2021,
/// the cubic) and cubic splines through via points, sampling at a rate, and limit checks.
///
/// Units: time [s]; joint values [rad] for revolute joints and the robot's length unit for
/// prismatic joints; velocities and accelerations in those units per [s] and [s^2].

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mcws/kinematics/robot.h"

namespace mcws {

/// \brief Shape of a point-to-point move.
enum class TimeProfile {
  /// s(u) = 3u^2 - 2u^3: zero velocity at both ends, peak velocity 1.5 D/T.
  kCubic,
  /// s(u) = 10u^3 - 15u^4 + 6u^5 (Liu, Han, Xu & Li 2021, eq. (10)): zero velocity and acceleration
  /// at both ends, peak velocity 1.875 D/T.
  kQuintic,
};

/// \brief "cubic" or "quintic".
const char* profileName(TimeProfile profile);
/// \brief The profile called `name` ("cubic", "quintic"). \throws mcws::Error otherwise.
TimeProfile profileFromName(const std::string& name);

/// \brief Normalised blend s(u) and its derivatives ds/du, d2s/du2 at u in [0, 1] (u is clamped).
struct Blend {
  double s{0.0}, ds{0.0}, dds{0.0};
};
Blend blend(TimeProfile profile, double u);

/// \brief A piecewise polynomial q(t), t in [0, duration()], one polynomial per joint and segment.
///
/// Segment k covers [t_k, t_{k+1}]; on it q_j(t) = sum_i c_k(j, i) (t - t_k)^i.
class JointTrajectory {
 public:
  /// \param knot_times t_0 = 0 < t_1 < ... < t_n [s].
  /// \param coefficients n matrices of dof rows, one column per power (lowest first).
  /// \throws mcws::Error when the sizes do not match or the times are not increasing.
  JointTrajectory(std::vector<double> knot_times, std::vector<Eigen::MatrixXd> coefficients);

  int dof() const { return static_cast<int>(coefficients_.front().rows()); }
  /// \brief Total time [s].
  double duration() const { return knots_.back(); }
  /// \brief Segment boundaries t_0 = 0, ..., t_n = duration() [s].
  const std::vector<double>& knotTimes() const { return knots_; }
  /// \brief Coefficients of segment k (dof x powers).
  const Eigen::MatrixXd& coefficients(int segment) const { return coefficients_[segment]; }
  int segmentCount() const { return static_cast<int>(coefficients_.size()); }

  /// \brief Position, velocity and acceleration at time t (clamped to [0, duration()]).
  void evaluate(double t, Eigen::VectorXd& q, Eigen::VectorXd& qd, Eigen::VectorXd& qdd) const;
  Eigen::VectorXd position(double t) const;
  Eigen::VectorXd velocity(double t) const;
  Eigen::VectorXd acceleration(double t) const;

 private:
  int segmentAt(double t) const;

  std::vector<double> knots_;
  std::vector<Eigen::MatrixXd> coefficients_;
};

/// \brief Move from q_start to q_goal in `duration` seconds with a blend:
/// q(t) = q_start + (q_goal - q_start) s(t / duration).
/// \throws mcws::Error when the sizes differ, a value is not finite or duration is not > 0.
JointTrajectory pointToPoint(const Eigen::VectorXd& q_start, const Eigen::VectorXd& q_goal,
                             double duration, TimeProfile profile);

/// \brief Clamped cubic spline through `points` at `times`: passes every point, starts and ends
/// at rest (zero velocity), position, velocity and acceleration continuous at the via points
/// (the C2 conditions give a tridiagonal system for the via velocities). Through two points it is
/// the cubic point-to-point move.
/// \param points at least two joint vectors of one size.
/// \param times one strictly increasing time per point, the first 0 [s].
/// \throws mcws::Error for mismatched sizes, non-finite values or times not increasing.
JointTrajectory cubicSpline(const std::vector<Eigen::VectorXd>& points,
                            const std::vector<double>& times);

/// \brief `count` evenly spaced times from 0 to `duration` (via points reached at equal
/// intervals). \throws mcws::Error unless count >= 2 and duration > 0.
std::vector<double> evenTimes(std::size_t count, double duration);

/// \brief A trajectory sampled in time: row i of q, qd, qdd belongs to t[i].
struct SampledTrajectory {
  std::vector<double> t;  ///< [s]
  Eigen::MatrixXd q;      ///< samples x dof
  Eigen::MatrixXd qd;     ///< samples x dof, per [s]
  Eigen::MatrixXd qdd;    ///< samples x dof, per [s^2]
  int size() const { return static_cast<int>(t.size()); }
};

/// \brief Number of samples sampleTrajectory() makes for a duration and rate: the times k / rate
/// below the duration, and the duration itself.
/// \throws mcws::Error unless duration > 0 and rate > 0 are finite.
std::size_t sampleCount(double duration, double rate);

/// \brief Samples at t = k / rate, k = 0, 1, ..., and at t = duration() (the last interval is
/// shorter when duration() * rate is not a whole number).
/// \param rate samples per second [Hz].
SampledTrajectory sampleTrajectory(const JointTrajectory& trajectory, double rate);

/// \brief Checks the whole trajectory (not only samples) against the robot's joint limits and,
/// when `max_velocity` is not empty, |qd_j(t)| <= max_velocity[j]. Extremes are found exactly,
/// from the roots of the derivative of each polynomial piece.
/// \throws mcws::Error naming the joint, the time [s], the value and the limit of the earliest
///   violation (at a local extreme or a segment end), e.g. "joint 'j2' reaches 3.3 rad at
///   t = 4.25 s, above its upper limit 3.14 rad".
void checkTrajectoryLimits(const Robot& robot, const JointTrajectory& trajectory,
                           const Eigen::VectorXd& max_velocity = Eigen::VectorXd());

}  // namespace mcws
