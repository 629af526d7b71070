#include "common/pose_args.h"

#include <Eigen/SVD>
#include <cmath>
#include <sstream>

#include "common/app.h"
#include "mcws/kinematics/robot.h"

namespace mcws::app {
namespace {

/// The largest value a pose or matrix entry may have, as robot files cap their lengths: beyond,
/// squared distances lose every digit (1e300 once read as 0 away).
constexpr double kMaxPoseValue = 1e9;

Eigen::VectorXd numbers(const std::string& text, const std::string& flag, int count,
                        const char* what) {
  const Eigen::VectorXd values = parseNumberList(text, flag);
  if (values.size() != count) {
    throw UsageError("--" + flag + ": " + std::to_string(values.size()) + " values given, " +
                     std::to_string(count) + " wanted (" + what + ")");
  }
  for (Eigen::Index k = 0; k < values.size(); ++k) {
    if (std::abs(values[k]) > kMaxPoseValue) {
      std::ostringstream msg;
      msg << "--" << flag << ": value " << k + 1 << " (" << values[k]
          << ") is out of range (at most 1e9 in size, as in robot files)";
      throw UsageError(msg.str());
    }
  }
  return values;
}

}  // namespace

Eigen::Isometry3d parsePose(const std::string& text, const std::string& flag) {
  const Eigen::VectorXd v = numbers(text, flag, 6, "x y z roll pitch yaw");
  return poseFromXyzRpy(v.head<3>(), v.tail<3>());
}

Eigen::Isometry3d parseMatrix(const std::string& text, const std::string& flag) {
  const Eigen::VectorXd v = numbers(text, flag, 16, "a 4x4 matrix, row by row");
  const Eigen::Matrix4d M =
      Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(v.data());
  if (M.row(3) != Eigen::RowVector4d(0, 0, 0, 1)) {
    std::ostringstream msg;
    msg << "--" << flag << ": last row is "
        << M.row(3).format(Eigen::IOFormat(Eigen::StreamPrecision, Eigen::DontAlignCols, " "))
        << ", not 0 0 0 1";
    throw UsageError(msg.str());
  }
  const Eigen::Matrix3d R = M.topLeftCorner<3, 3>();
  const double deviation = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (deviation > kTypedRotationTolerance) {
    std::ostringstream msg;
    msg << "--" << flag << ": the rotation is not orthonormal (|R^T R - I| = " << deviation
        << ", at most " << kTypedRotationTolerance << " accepted)";
    throw UsageError(msg.str());
  }
  if (R.determinant() < 0.0) {
    throw UsageError("--" + flag + ": the rotation is a reflection (det R = " +
                     std::to_string(R.determinant()) + ")");
  }
  // The nearest rotation (Frobenius norm): U V^T of R's singular value decomposition.
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = svd.matrixU() * svd.matrixV().transpose();
  T.translation() = M.topRightCorner<3, 1>();
  return T;
}

}  // namespace mcws::app
