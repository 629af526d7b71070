#pragma once
/// \file
/// \brief How well the arm can move its tool at a joint vector: Yoshikawa's manipulability and
/// the inverse condition number of the Jacobian.

#include <string>

#include "mcws/kinematics/jacobian.h"
#include "mcws/kinematics/robot.h"

namespace mcws {

/// \brief Which rows of the geometric Jacobian the quality measures.
enum class QualityTask {
  /// The tool point's velocity only (rows 0-2, J_v). For arms that place a point (fewer than six
  /// joints): a planar 2R arm's manipulability is then l1 l2 |sin q2|.
  kPosition,
  /// The whole twist, the velocity rows divided by the characteristic length L (J_s = [J_v / L;
  /// J_w], dimensionless), so a rotation of 1 rad weighs as much as a move of L.
  kFull,
};

/// \brief Name of a task ("position", "full").
const char* qualityTaskName(QualityTask task);
/// \brief Task from its name. \throws mcws::Error naming the bad name and the known ones.
QualityTask parseQualityTask(const std::string& name);

/// \brief Settings of jacobianQuality().
struct QualityOptions {
  QualityTask task{QualityTask::kFull};
  /// L of QualityTask::kFull [length unit]; must be positive and finite.
  double characteristic_length{1.0};
  /// \throws mcws::Error for a characteristic length that is not positive and finite.
  void check() const;
};

/// \brief What an engineer expects for this robot: the full twist with L = the chain's length
/// scale (chainLengthScale()) for arms with six or more joints, the tool point's velocity for
/// fewer (their 6 x n Jacobian never has full row rank).
QualityOptions defaultQualityOptions(const Robot& robot);

/// \brief Quality of one joint vector.
struct Quality {
  /// Yoshikawa's manipulability, the product of the k = min(rows, n) singular values of the
  /// measured Jacobian: sqrt(det(J J^T)) when n >= rows, sqrt(det(J^T J)) when n < rows
  /// (Yoshikawa 1985). [length unit^n] for QualityTask::kPosition (revolute joints), [1] for
  /// QualityTask::kFull.
  double manipulability{0.0};
  /// sigma_min / sigma_max of those k singular values, in [0, 1]: 0 at a singularity, 1 where
  /// the arm moves the same in every direction [1].
  double inverse_condition{0.0};
};

/// \brief Quality of a geometric Jacobian (mcws::Jacobian, 6 x n, n >= 1), from its singular
/// value decomposition.
/// \throws mcws::Error for a non-positive or non-finite characteristic length.
Quality jacobianQuality(const Jacobian& J, const QualityOptions& options);

/// \brief Yoshikawa's manipulability alone, as jacobianQuality(J, options).manipulability but from
/// the Cholesky factor of the k x k Gram matrix (about ten times cheaper than the SVD). The Gram
/// matrix squares the condition number, so the two agree to about 1e-12 relative where the
/// inverse condition is 1e-2 or more, and to about 64 eps / inverse_condition^2 nearer a
/// singularity; at a singularity the result is 0 where the factorisation fails and otherwise a
/// tiny value (about 1e-8 sigma_max^k), not exactly 0.
/// \throws mcws::Error as jacobianQuality() for a bad characteristic length.
/// \param J column-major 6 x n (a Jacobian's data()), 1 <= n <= 8.
double manipulability(const double* J, int n, const QualityOptions& options);

}  // namespace mcws
