#pragma once
/// \file
/// \brief The maintenance-arm patent, step s20: base poses of a robot that sways on the line it
/// hangs from, drawn from a Gaussian centred on the measured pose and kept inside a confidence
/// region.

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mcws {

/// \brief A small rigid displacement of the base, (x, y, z [length unit], roll, pitch, yaw
/// [rad]) in the sway frame.
using SwayVector = Eigen::Matrix<double, 6, 1>;

/// \brief How the base of a line robot moves about its measured pose.
///
/// The sway frame has its origin at `pivot`, a point on the line the robot hangs from, and its
/// x axis along the line; its y axis is horizontal (world z cross x) and its z axis completes
/// the frame (up when the line is horizontal). A sway vector (x, y, z, roll, pitch, yaw) is the
/// rigid motion Trans(x, y, z) * Rz(yaw) * Ry(pitch) * Rx(roll) in that frame, so roll swings the
/// robot about the line and x slides it along the line.
struct SwayModel {
  Eigen::Vector3d pivot{Eigen::Vector3d::Zero()};            ///< world [length unit]
  Eigen::Vector3d line_direction{Eigen::Vector3d::UnitX()};  ///< world, any length > 0
  /// Covariance of the sway vector [length unit^2, length unit * rad, rad^2].
  Eigen::Matrix<double, 6, 6> covariance{Eigen::Matrix<double, 6, 6>::Zero()};
  /// Share of the Gaussian's mass kept: samples lie inside the ellipsoid of this probability.
  double confidence{0.95};
};

/// \brief World-to-sway-frame placement of a model (origin at the pivot, x along the line).
/// \throws mcws::Error when the line direction is zero or not finite.
Eigen::Isometry3d swayFrame(const SwayModel& model);

/// \brief The world motion of a sway vector: T_world_base' = displacement * T_world_base.
Eigen::Isometry3d swayDisplacement(const Eigen::Isometry3d& T_world_sway, const SwayVector& xi);

/// \brief Quantile of the chi-square distribution: the r with P(chi^2_dof <= r) = p.
/// \throws mcws::Error for p outside (0, 1) or dof < 1.
double chiSquareQuantile(double p, int dof);

/// \brief A two-sided confidence interval for a proportion.
struct ProportionInterval {
  double low{0.0}, high{1.0};
};

/// \brief Wilson's score interval (Wilson 1927) for `successes` out of `trials` at the given
/// two-sided confidence (default 95 %). \throws mcws::Error for trials = 0 or successes > trials.
ProportionInterval wilsonInterval(std::size_t successes, std::size_t trials,
                                  double confidence = 0.95);

/// \brief Draws sway vectors from N(0, covariance) truncated to its confidence ellipsoid.
///
/// The maintenance-arm patent, step s20:
/// "将第一静态位姿作为高斯概率分布函数的均值，采用高斯概率分布函数生成n组第二静态位姿 数据 ...
/// n在高斯概率分布函数的一定置信区间取值" (the first static pose is the mean of a Gaussian that
/// gives n second static poses, taken within a confidence interval of it).
///
/// With covariance = V diag(lambda) V^T (rank r), a sample is xi = V_r diag(sqrt(lambda_r)) z
/// where z is uniform in direction and |z|^2 follows chi^2_r truncated at its `confidence`
/// quantile (drawn by inverting the CDF), which is exactly the Gaussian conditioned on the
/// Mahalanobis radius. Sample i depends only on the seed and i (mcws::CounterRng), so any
/// number of threads draws the same poses.
class SwaySampler {
 public:
  /// \throws mcws::Error naming the field for a covariance that is not finite, not symmetric
  ///   or not positive semi-definite (with its most negative eigenvalue), a confidence outside
  ///   (0, 1), or a bad line direction.
  explicit SwaySampler(const SwayModel& model);

  /// \brief Sway vector of sample i.
  SwayVector vector(std::uint64_t seed, std::uint64_t i) const;
  /// \brief World motions of samples 0 .. n-1.
  std::vector<Eigen::Isometry3d> displacements(std::uint64_t seed, std::size_t n) const;
  /// \brief Rank of the covariance (the number of directions the base moves in).
  int rank() const { return rank_; }
  /// \brief Squared Mahalanobis radius of the kept region (0 when the rank is 0).
  double chiSquareRadius() const { return radius_squared_; }
  /// \brief Squared Mahalanobis length of a sway vector in the covariance's range.
  double mahalanobisSquared(const SwayVector& xi) const;
  const SwayModel& model() const { return model_; }
  const Eigen::Isometry3d& frame() const { return T_world_sway_; }

 private:
  SwayModel model_;
  Eigen::Isometry3d T_world_sway_;
  Eigen::Matrix<double, 6, Eigen::Dynamic> factor_;  ///< V_r diag(sqrt(lambda_r))
  Eigen::Matrix<double, 6, Eigen::Dynamic> whiten_;  ///< V_r diag(1 / sqrt(lambda_r))
  int rank_{0};
  double radius_squared_{0.0};
};

}  // namespace mcws
