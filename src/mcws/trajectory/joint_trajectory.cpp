#include "mcws/trajectory/joint_trajectory.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "mcws/core/error.h"

namespace mcws {
namespace {

/// Values this close to a limit (relative to max(1, |limit|)) count as on it: the end points of a
/// move to a limit evaluate to the limit only up to rounding.
constexpr double kLimitTolerance = 1e-9;
/// More samples than this is a mistake in the rate or duration (tens of gigabytes of CSV).
constexpr double kMaxSamples = 1e8;

void checkFinite(const Eigen::VectorXd& q, const std::string& what) {
  if (!q.allFinite()) throw Error(what + " has a value that is not a finite number");
}

void checkDuration(double duration, const std::string& what) {
  if (!std::isfinite(duration) || duration <= 0.0) {
    std::ostringstream msg;
    msg << what << " " << duration << " s is not a positive number";
    throw Error(msg.str());
  }
}

/// p(x) = sum c[i] x^i by Horner.
double horner(const Eigen::VectorXd& c, double x) {
  double value = 0.0;
  for (Eigen::Index i = c.size() - 1; i >= 0; --i) value = value * x + c[i];
  return value;
}

/// Coefficients of dp/dx.
Eigen::VectorXd derivative(const Eigen::VectorXd& c) {
  if (c.size() <= 1) return Eigen::VectorXd::Zero(1);
  Eigen::VectorXd d(c.size() - 1);
  for (Eigen::Index i = 1; i < c.size(); ++i) d[i - 1] = static_cast<double>(i) * c[i];
  return d;
}

/// Real roots of p (coefficients lowest first) in [0, h], ascending.
std::vector<double> rootsIn(const Eigen::VectorXd& c, double h) {
  // On u = x / h in [0, 1] every coefficient has the size of the value it contributes.
  Eigen::VectorXd scaled = c;
  double power = 1.0;
  for (Eigen::Index i = 0; i < c.size(); ++i, power *= h) scaled[i] = c[i] * power;
  const double size = scaled.cwiseAbs().maxCoeff();
  if (size == 0.0) return {};
  Eigen::Index degree = scaled.size() - 1;
  while (degree > 0 && std::abs(scaled[degree]) <= 1e-13 * size) --degree;
  std::vector<double> roots;
  if (degree == 1) {
    roots.push_back(-scaled[0] / scaled[1]);
  } else if (degree >= 2) {
    // Eigenvalues of the companion matrix of the monic polynomial.
    Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(degree, degree);
    for (Eigen::Index i = 0; i < degree; ++i)
      companion(0, i) = -scaled[degree - 1 - i] / scaled[degree];
    for (Eigen::Index i = 1; i < degree; ++i) companion(i, i - 1) = 1.0;
    const Eigen::VectorXcd eigenvalues =
        Eigen::EigenSolver<Eigen::MatrixXd>(companion, false).eigenvalues();
    const Eigen::VectorXd monic = scaled.head(degree + 1) / scaled[degree];
    const Eigen::VectorXd slope = derivative(monic);
    for (const std::complex<double>& z : eigenvalues) {
      if (std::abs(z.imag()) > 1e-6) continue;
      double u = z.real();
      for (int step = 0; step < 3; ++step) {  // polish
        const double d = horner(slope, u);
        if (d == 0.0) break;
        u -= horner(monic, u) / d;
      }
      roots.push_back(u);
    }
  }
  std::vector<double> inside;
  for (double u : roots) {
    if (u >= -1e-12 && u <= 1.0 + 1e-12) inside.push_back(std::clamp(u, 0.0, 1.0) * h);
  }
  std::sort(inside.begin(), inside.end());
  return inside;
}

std::string unitOf(const Robot& robot, int joint) {
  return robot.joints[joint].type == JointType::kRevolute ? "rad" : unitName(robot.length_unit);
}

}  // namespace

const char* profileName(TimeProfile profile) {
  return profile == TimeProfile::kCubic ? "cubic" : "quintic";
}

TimeProfile profileFromName(const std::string& name) {
  if (name == "cubic") return TimeProfile::kCubic;
  if (name == "quintic") return TimeProfile::kQuintic;
  throw Error("profile '" + name + "' is not quintic or cubic");
}

Blend blend(TimeProfile profile, double u) {
  u = std::clamp(u, 0.0, 1.0);
  const double u2 = u * u;
  if (profile == TimeProfile::kCubic)
    return {u2 * (3.0 - 2.0 * u), 6.0 * u * (1.0 - u), 6.0 - 12.0 * u};
  return {u2 * u * (10.0 + u * (-15.0 + 6.0 * u)), 30.0 * u2 * (1.0 - u) * (1.0 - u),
          60.0 * u * (1.0 - u) * (1.0 - 2.0 * u)};
}

JointTrajectory::JointTrajectory(std::vector<double> knot_times,
                                 std::vector<Eigen::MatrixXd> coefficients)
    : knots_(std::move(knot_times)), coefficients_(std::move(coefficients)) {
  if (coefficients_.empty() || knots_.size() != coefficients_.size() + 1) {
    throw Error("trajectory: " + std::to_string(knots_.size()) + " knot times for " +
                std::to_string(coefficients_.size()) + " segments");
  }
  if (knots_.front() != 0.0) throw Error("trajectory: the first knot time must be 0");
  for (std::size_t k = 0; k < coefficients_.size(); ++k) {
    if (!(knots_[k + 1] > knots_[k]) || !std::isfinite(knots_[k + 1])) {
      throw Error("trajectory: knot times must increase (segment " + std::to_string(k + 1) + ")");
    }
    if (coefficients_[k].rows() != coefficients_.front().rows() || coefficients_[k].cols() < 1 ||
        !coefficients_[k].allFinite()) {
      throw Error("trajectory: segment " + std::to_string(k + 1) + " has bad coefficients");
    }
  }
}

int JointTrajectory::segmentAt(double t) const {
  const auto it = std::upper_bound(knots_.begin() + 1, knots_.end() - 1, t);
  return static_cast<int>(it - knots_.begin()) - 1;
}

void JointTrajectory::evaluate(double t, Eigen::VectorXd& q, Eigen::VectorXd& qd,
                               Eigen::VectorXd& qdd) const {
  t = std::clamp(t, 0.0, duration());
  const int k = segmentAt(t);
  const double x = t - knots_[k];
  const Eigen::MatrixXd& c = coefficients_[k];
  q = Eigen::VectorXd::Zero(dof());
  qd = Eigen::VectorXd::Zero(dof());
  qdd = Eigen::VectorXd::Zero(dof());
  for (Eigen::Index i = c.cols() - 1; i >= 0; --i) {
    const double di = static_cast<double>(i);
    q = q * x + c.col(i);
    if (i >= 1) qd = qd * x + di * c.col(i);
    if (i >= 2) qdd = qdd * x + di * (di - 1.0) * c.col(i);
  }
}

Eigen::VectorXd JointTrajectory::position(double t) const {
  Eigen::VectorXd q, qd, qdd;
  evaluate(t, q, qd, qdd);
  return q;
}

Eigen::VectorXd JointTrajectory::velocity(double t) const {
  Eigen::VectorXd q, qd, qdd;
  evaluate(t, q, qd, qdd);
  return qd;
}

Eigen::VectorXd JointTrajectory::acceleration(double t) const {
  Eigen::VectorXd q, qd, qdd;
  evaluate(t, q, qd, qdd);
  return qdd;
}

JointTrajectory pointToPoint(const Eigen::VectorXd& q_start, const Eigen::VectorXd& q_goal,
                             double duration, TimeProfile profile) {
  if (q_start.size() != q_goal.size() || q_start.size() == 0) {
    throw Error("point-to-point move: start has " + std::to_string(q_start.size()) +
                " joint values but goal has " + std::to_string(q_goal.size()));
  }
  checkFinite(q_start, "point-to-point move: start");
  checkFinite(q_goal, "point-to-point move: goal");
  checkDuration(duration, "point-to-point move: duration");
  const Eigen::VectorXd D = q_goal - q_start;
  const double T = duration;
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(q_start.size(), 6);
  c.col(0) = q_start;
  if (profile == TimeProfile::kCubic) {  // D (3u^2 - 2u^3)
    c.col(2) = 3.0 * D / (T * T);
    c.col(3) = -2.0 * D / (T * T * T);
    c.conservativeResize(Eigen::NoChange, 4);
  } else {  // D (10u^3 - 15u^4 + 6u^5)
    c.col(3) = 10.0 * D / std::pow(T, 3);
    c.col(4) = -15.0 * D / std::pow(T, 4);
    c.col(5) = 6.0 * D / std::pow(T, 5);
  }
  return JointTrajectory({0.0, T}, {c});
}

JointTrajectory cubicSpline(const std::vector<Eigen::VectorXd>& points,
                            const std::vector<double>& times) {
  const std::size_t n = points.size();
  if (n < 2) throw Error("spline: needs at least two points, got " + std::to_string(n));
  if (times.size() != n) {
    throw Error("spline: " + std::to_string(n) + " points but " + std::to_string(times.size()) +
                " times");
  }
  const Eigen::Index dof = points.front().size();
  for (std::size_t k = 0; k < n; ++k) {
    const std::string what = "spline: point " + std::to_string(k + 1);
    if (points[k].size() != dof || dof == 0) {
      throw Error(what + " has " + std::to_string(points[k].size()) +
                  " joint values, point 1 has " + std::to_string(dof));
    }
    checkFinite(points[k], what);
  }
  std::vector<double> h(n - 1);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    h[k] = times[k + 1] - times[k];
    if (!(h[k] > 0.0) || !std::isfinite(h[k])) throw Error("spline: times must increase");
  }

  // Velocities v_k at the points: v_0 = v_{n-1} = 0; continuity of acceleration at each via k:
  //   v_{k-1}/h_{k-1} + 2 (1/h_{k-1} + 1/h_k) v_k + v_{k+1}/h_k
  //     = 3 ((p_k - p_{k-1})/h_{k-1}^2 + (p_{k+1} - p_k)/h_k^2),
  // solved for all joints at once by the Thomas algorithm (strictly diagonally dominant).
  std::vector<Eigen::VectorXd> v(n, Eigen::VectorXd::Zero(dof));
  if (n > 2) {
    const std::size_t m = n - 2;  // unknowns v_1 .. v_{n-2}
    std::vector<double> lower(m), diag(m), upper(m);
    std::vector<Eigen::VectorXd> rhs(m);
    for (std::size_t i = 0; i < m; ++i) {
      const std::size_t k = i + 1;
      lower[i] = 1.0 / h[k - 1];
      diag[i] = 2.0 * (1.0 / h[k - 1] + 1.0 / h[k]);
      upper[i] = 1.0 / h[k];
      rhs[i] = 3.0 * ((points[k] - points[k - 1]) / (h[k - 1] * h[k - 1]) +
                      (points[k + 1] - points[k]) / (h[k] * h[k]));
    }
    for (std::size_t i = 1; i < m; ++i) {
      const double w = lower[i] / diag[i - 1];
      diag[i] -= w * upper[i - 1];
      rhs[i] -= w * rhs[i - 1];
    }
    v[m] = rhs[m - 1] / diag[m - 1];
    for (std::size_t i = m - 1; i-- > 0;) v[i + 1] = (rhs[i] - upper[i] * v[i + 2]) / diag[i];
  }

  // Cubic Hermite segments.
  std::vector<Eigen::MatrixXd> coefficients;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const Eigen::VectorXd slope = (points[k + 1] - points[k]) / h[k];
    Eigen::MatrixXd c(dof, 4);
    c.col(0) = points[k];
    c.col(1) = v[k];
    c.col(2) = (3.0 * slope - 2.0 * v[k] - v[k + 1]) / h[k];
    c.col(3) = (v[k] + v[k + 1] - 2.0 * slope) / (h[k] * h[k]);
    coefficients.push_back(c);
  }
  return JointTrajectory(times, coefficients);
}

std::vector<double> evenTimes(std::size_t count, double duration) {
  if (count < 2) throw Error("even times: needs at least two points");
  checkDuration(duration, "even times: duration");
  std::vector<double> times(count);
  for (std::size_t k = 0; k < count; ++k) {
    times[k] = duration * static_cast<double>(k) / static_cast<double>(count - 1);
  }
  times.back() = duration;
  return times;
}

std::size_t sampleCount(double duration, double rate) {
  checkDuration(duration, "sampling: duration");
  if (!std::isfinite(rate) || rate <= 0.0) {
    std::ostringstream msg;
    msg << "sampling: rate " << rate << " Hz is not a positive number";
    throw Error(msg.str());
  }
  const double whole = std::floor(duration * rate * (1.0 + 1e-12));
  if (whole + 2.0 > kMaxSamples) {
    std::ostringstream msg;
    msg << "sampling: " << duration << " s at " << rate << " Hz gives more than 1e8 samples";
    throw Error(msg.str());
  }
  const std::size_t below = static_cast<std::size_t>(whole) + 1;  // k = 0 .. whole
  // The duration itself, unless k = whole already lands on it.
  const bool lands = std::abs(whole / rate - duration) <= 1e-9 * duration;
  return lands ? below : below + 1;
}

SampledTrajectory sampleTrajectory(const JointTrajectory& trajectory, double rate) {
  const std::size_t count = sampleCount(trajectory.duration(), rate);
  SampledTrajectory out;
  out.t.resize(count);
  out.q.resize(static_cast<Eigen::Index>(count), trajectory.dof());
  out.qd.resizeLike(out.q);
  out.qdd.resizeLike(out.q);
  Eigen::VectorXd q, qd, qdd;
  for (std::size_t k = 0; k < count; ++k) {
    const double t = k + 1 == count ? trajectory.duration() : static_cast<double>(k) / rate;
    out.t[k] = t;
    trajectory.evaluate(t, q, qd, qdd);
    const auto row = static_cast<Eigen::Index>(k);
    out.q.row(row) = q.transpose();
    out.qd.row(row) = qd.transpose();
    out.qdd.row(row) = qdd.transpose();
  }
  return out;
}

void checkTrajectoryLimits(const Robot& robot, const JointTrajectory& trajectory,
                           const Eigen::VectorXd& max_velocity) {
  if (trajectory.dof() != robot.dof()) {
    throw Error("trajectory has " + std::to_string(trajectory.dof()) + " joints but robot '" +
                robot.name + "' has " + std::to_string(robot.dof()));
  }
  const bool check_velocity = max_velocity.size() > 0;
  if (check_velocity) {
    if (max_velocity.size() != robot.dof()) {
      throw Error("velocity limits: " + std::to_string(max_velocity.size()) +
                  " values for robot '" + robot.name + "' with " + std::to_string(robot.dof()) +
                  " joints");
    }
    for (int j = 0; j < robot.dof(); ++j) {
      if (!(max_velocity[j] > 0.0)) {
        throw Error("velocity limit of joint '" + robot.joints[j].name + "' must be positive");
      }
    }
  }
  // Segment by segment; within the first segment that has any violation, the earliest one
  // (position before velocity, lower joint index first at equal times).
  for (int k = 0; k < trajectory.segmentCount(); ++k) {
    const double t0 = trajectory.knotTimes()[k];
    const double h = trajectory.knotTimes()[k + 1] - t0;
    double first_time = std::numeric_limits<double>::infinity();
    std::string first_message;
    // Extremes of p on the segment are at its ends or its stationary points.
    auto check = [&](const Eigen::VectorXd& p, double lower, double upper, const std::string& what,
                     const std::string& unit) {
      std::vector<double> xs = rootsIn(derivative(p), h);
      xs.insert(xs.begin(), 0.0);
      xs.push_back(h);
      for (double x : xs) {
        const double value = horner(p, x);
        const bool low = value < lower - kLimitTolerance * std::max(1.0, std::abs(lower));
        const bool high = value > upper + kLimitTolerance * std::max(1.0, std::abs(upper));
        // Times equal up to rounding keep the lower joint index.
        if ((!low && !high) || !(t0 + x < first_time - 1e-9 * (1.0 + t0 + h))) continue;
        std::ostringstream msg;
        msg.precision(10);
        msg << what << " reaches " << value << " " << unit << " at t = " << t0 + x << " s, "
            << (high ? "above its upper" : "below its lower") << " limit " << (high ? upper : lower)
            << " " << unit;
        first_time = t0 + x;
        first_message = msg.str();
        return;
      }
    };
    for (int j = 0; j < robot.dof(); ++j) {
      const Joint& joint = robot.joints[j];
      const Eigen::VectorXd position = trajectory.coefficients(k).row(j).transpose();
      check(position, joint.lower, joint.upper, "joint '" + joint.name + "'", unitOf(robot, j));
      if (check_velocity) {
        check(derivative(position), -max_velocity[j], max_velocity[j],
              "velocity of joint '" + joint.name + "'", unitOf(robot, j) + "/s");
      }
    }
    if (!first_message.empty()) throw Error(first_message);
  }
}

}  // namespace mcws
