#include "common/pose_args.h"

#include <cmath>
#include <sstream>

#include "common/app.h"
#include "common/flags.h"
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
  return asUsageError(flag, [&] { return poseFromTypedMatrix(M); });
}

}  // namespace mcws::app
