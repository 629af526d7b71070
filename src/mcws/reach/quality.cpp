#include "mcws/reach/quality.h"

#include <Eigen/Cholesky>
#include <Eigen/SVD>
#include <cmath>

#include "mcws/core/decimal.h"
#include "mcws/core/error.h"

namespace mcws {
namespace {

/// At most 8 joints and 6 rows: fixed-capacity matrices, no heap allocation per sample.
using SmallMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 8, 8>;

/// The rows of J that the task measures, velocity rows scaled by 1 / L for the full twist.
SmallMatrix measuredRows(const double* J, int n, const QualityOptions& options) {
  const Eigen::Map<const Eigen::Matrix<double, 6, Eigen::Dynamic>> full(J, 6, n);
  if (options.task == QualityTask::kPosition) return full.topRows<3>();
  SmallMatrix A = full;
  A.topRows<3>() /= options.characteristic_length;
  return A;
}

}  // namespace

void QualityOptions::check() const {
  if (!(characteristic_length > 0.0) || !std::isfinite(characteristic_length)) {
    throw Error("quality: the characteristic length must be positive and finite, not " +
                formatNumber(characteristic_length));
  }
}

const char* qualityTaskName(QualityTask task) {
  return task == QualityTask::kPosition ? "position" : "full";
}

QualityTask parseQualityTask(const std::string& name) {
  if (name == "position") return QualityTask::kPosition;
  if (name == "full") return QualityTask::kFull;
  throw Error("unknown quality task '" + name + "' (position, full)");
}

QualityOptions defaultQualityOptions(const Robot& robot) {
  QualityOptions options;
  options.task = robot.dof() >= 6 ? QualityTask::kFull : QualityTask::kPosition;
  options.characteristic_length = chainLengthScale(robot);
  return options;
}

Quality jacobianQuality(const Jacobian& J, const QualityOptions& options) {
  options.check();
  if (J.cols() < 1 || J.cols() > 8) throw Error("quality: a Jacobian needs 1 to 8 columns");
  const SmallMatrix A = measuredRows(J.data(), static_cast<int>(J.cols()), options);
  const Eigen::JacobiSVD<SmallMatrix> svd(A);
  const auto& sigma = svd.singularValues();  // min(rows, n) values, largest first
  Quality quality;
  quality.manipulability = sigma.prod();
  quality.inverse_condition = sigma[0] > 0.0 ? sigma[sigma.size() - 1] / sigma[0] : 0.0;
  return quality;
}

double manipulability(const double* J, int n, const QualityOptions& options) {
  options.check();
  const SmallMatrix A = measuredRows(J, n, options);
  const SmallMatrix gram =
      n <= A.rows() ? SmallMatrix(A.transpose() * A) : SmallMatrix(A * A.transpose());
  const Eigen::LLT<SmallMatrix> llt(gram);
  if (llt.info() != Eigen::Success) return 0.0;
  // det(gram) = prod(diag(L))^2, so sqrt(det) is the product of the factor's diagonal.
  return llt.matrixLLT().diagonal().prod();
}

}  // namespace mcws
