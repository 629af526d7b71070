#include "mcws/planning/sway.h"

#include <Eigen/Eigenvalues>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>
#include <cmath>

#include "mcws/core/counter_rng.h"
#include "mcws/core/decimal.h"
#include "mcws/core/error.h"

namespace mcws {

namespace {}  // namespace

Eigen::Isometry3d swayFrame(const SwayModel& model) {
  const double length = model.line_direction.norm();
  if (!std::isfinite(length) || length == 0.0 || !model.pivot.allFinite()) {
    throw Error("sway: line direction must be a finite non-zero vector and the pivot finite");
  }
  const Eigen::Vector3d x = model.line_direction / length;
  Eigen::Vector3d y = Eigen::Vector3d::UnitZ().cross(x);
  if (y.norm() < 1e-9)
    y = x.cross(Eigen::Vector3d::UnitX()).norm() > 1e-9
            ? Eigen::Vector3d(x.cross(Eigen::Vector3d::UnitX()))
            : Eigen::Vector3d(x.cross(Eigen::Vector3d::UnitY()));
  y.normalize();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear().col(0) = x;
  T.linear().col(1) = y;
  T.linear().col(2) = x.cross(y);
  T.translation() = model.pivot;
  return T;
}

Eigen::Isometry3d swayDisplacement(const Eigen::Isometry3d& T_world_sway, const SwayVector& xi) {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.linear() = (Eigen::AngleAxisd(xi[5], Eigen::Vector3d::UnitZ()) *
                     Eigen::AngleAxisd(xi[4], Eigen::Vector3d::UnitY()) *
                     Eigen::AngleAxisd(xi[3], Eigen::Vector3d::UnitX()))
                        .toRotationMatrix();
  motion.translation() = xi.head<3>();
  return T_world_sway * motion * T_world_sway.inverse();
}

double chiSquareQuantile(double p, int dof) {
  if (!(p > 0.0 && p < 1.0))
    throw Error("chi-square quantile: probability " + formatNumber(p) + " is outside (0, 1)");
  if (dof < 1) throw Error("chi-square quantile: " + std::to_string(dof) + " degrees of freedom");
  return boost::math::quantile(boost::math::chi_squared(dof), p);
}

ProportionInterval wilsonInterval(std::size_t successes, std::size_t trials, double confidence) {
  if (trials == 0) throw Error("Wilson interval: no trials");
  if (successes > trials) {
    throw Error("Wilson interval: " + std::to_string(successes) + " successes out of " +
                std::to_string(trials) + " trials");
  }
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw Error("Wilson interval: confidence " + formatNumber(confidence) + " is outside (0, 1)");
  }
  const double z =
      boost::math::quantile(boost::math::normal(), 0.5 + 0.5 * confidence);  // 1.96 at 95 %
  const double n = static_cast<double>(trials);
  const double p = static_cast<double>(successes) / n;
  const double z2n = z * z / n;
  const double centre = (p + 0.5 * z2n) / (1.0 + z2n);
  const double half = z * std::sqrt(p * (1.0 - p) / n + 0.25 * z2n / n) / (1.0 + z2n);
  // At k = 0 (k = n) the lower (upper) end is 0 (1) exactly; centre - half rounds to 3e-18.
  return {successes == 0 ? 0.0 : std::max(0.0, centre - half),
          successes == trials ? 1.0 : std::min(1.0, centre + half)};
}

SwaySampler::SwaySampler(const SwayModel& model) : model_(model) {
  if (!(model.confidence > 0.0 && model.confidence < 1.0)) {
    throw Error("sway: confidence " + formatNumber(model.confidence) + " is outside (0, 1)");
  }
  T_world_sway_ = swayFrame(model);
  const Eigen::Matrix<double, 6, 6>& C = model.covariance;
  if (!C.allFinite()) throw Error("sway: covariance has a non-finite entry");
  const double scale = C.cwiseAbs().maxCoeff();
  if ((C - C.transpose()).cwiseAbs().maxCoeff() > 1e-12 * scale) {
    throw Error("sway: covariance is not symmetric");
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eigen(C);
  const Eigen::Matrix<double, 6, 1> lambda = eigen.eigenvalues();
  const double tolerance = 1e-12 * std::max(scale, 1e-300);
  if (lambda.minCoeff() < -tolerance) {
    throw Error("sway: covariance is not positive semi-definite (eigenvalue " +
                formatNumber(lambda.minCoeff()) + ")");
  }
  for (int k = 0; k < 6; ++k) rank_ += lambda[k] > tolerance ? 1 : 0;
  factor_.resize(6, rank_);
  whiten_.resize(6, rank_);
  for (int k = 6 - rank_, column = 0; k < 6; ++k, ++column) {
    factor_.col(column) = eigen.eigenvectors().col(k) * std::sqrt(lambda[k]);
    whiten_.col(column) = eigen.eigenvectors().col(k) / std::sqrt(lambda[k]);
  }
  if (rank_ > 0) radius_squared_ = chiSquareQuantile(model.confidence, rank_);
}

SwayVector SwaySampler::vector(std::uint64_t seed, std::uint64_t i) const {
  if (rank_ == 0) return SwayVector::Zero();
  const CounterRng rng(seed);
  // Direction: r standard normals by Box-Muller (streams 0-5), normalised.
  Eigen::VectorXd z(rank_);
  for (int k = 0; k < rank_; k += 2) {
    const double u1 = 1.0 - rng.uniform(i, k), u2 = rng.uniform(i, k + 1);
    const double radius = std::sqrt(-2.0 * std::log(u1));
    z[k] = radius * std::cos(2.0 * M_PI * u2);
    if (k + 1 < rank_) z[k + 1] = radius * std::sin(2.0 * M_PI * u2);
  }
  const double norm = z.norm();
  if (norm == 0.0) {
    z.setZero();
    z[0] = 1.0;
  } else {
    z /= norm;
  }
  // Mahalanobis radius: chi^2_r conditioned on <= its confidence quantile (stream 6).
  const double u = rng.uniform(i, 6) * model_.confidence;
  const double r2 = u > 0.0 ? boost::math::quantile(boost::math::chi_squared(rank_), u) : 0.0;
  return factor_ * (std::sqrt(r2) * z);
}

std::vector<Eigen::Isometry3d> SwaySampler::displacements(std::uint64_t seed, std::size_t n) const {
  std::vector<Eigen::Isometry3d> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    out.push_back(swayDisplacement(T_world_sway_, vector(seed, i)));
  return out;
}

double SwaySampler::mahalanobisSquared(const SwayVector& xi) const {
  return rank_ == 0 ? 0.0 : (whiten_.transpose() * xi).squaredNorm();
}

}  // namespace mcws
