// A pose typed as a 4x4 matrix (poseFromTypedMatrix): a rotation printed with 4 decimals becomes
// the nearest rotation, a wrong last row, a rotation off by more than the tolerance and a
// reflection are refused with the message the tools print after their flag.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "mcws/core/error.h"
#include "mcws/kinematics/robot.h"

namespace mcws {
namespace {

/// The message of what `M` throws ("" when it throws nothing).
std::string failure(const Eigen::Matrix4d& M) {
  try {
    poseFromTypedMatrix(M);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(TypedPose, AMatrixPrintedWith4DecimalsBecomesTheNearestRotation) {
  Eigen::Matrix4d M;           // Rz(30 deg) rounded to 4 decimals, translation (1, 2, 3)
  M << 0.8660, -0.5000, 0, 1,  //
      0.5000, 0.8660, 0, 2,    //
      0, 0, 1, 3,              //
      0, 0, 0, 1;
  const Eigen::Isometry3d T = poseFromTypedMatrix(M);
  const Eigen::Matrix3d R = T.linear();
  EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
  // The nearest rotation of a scaled rotation s Rz(a) is Rz(a): a = atan2(0.5, 0.866).
  const double angle = std::atan2(0.5, 0.866);
  EXPECT_NEAR(R(0, 0), std::cos(angle), 1e-12);
  EXPECT_NEAR(R(1, 0), std::sin(angle), 1e-12);
  EXPECT_EQ(T.translation(), Eigen::Vector3d(1, 2, 3));
}

TEST(TypedPose, AWrongLastRowARotationOffTheToleranceAndAReflectionAreRefused) {
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
  M(3, 2) = 1.0;
  EXPECT_EQ(failure(M), "last row is 0 0 1 1, not 0 0 0 1");
  M = Eigen::Matrix4d::Identity();
  M(0, 1) = 0.01;  // |R^T R - I| = 0.01, above kTypedRotationTolerance (1e-3)
  EXPECT_EQ(failure(M),
            "the rotation is not orthonormal (|R^T R - I| = 0.01, at most 0.001 accepted)");
  M = Eigen::Matrix4d::Identity();
  M(2, 2) = -1.0;
  EXPECT_EQ(failure(M), "the rotation is a reflection (det R = -1.000000)");
}

}  // namespace
}  // namespace mcws
