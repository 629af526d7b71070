#pragma once
/// \file
/// \brief Poses on the command line: "x y z roll pitch yaw" or the 16 numbers of a 4x4
/// homogeneous matrix, row by row, checked and turned into an Eigen::Isometry3d.

#include <Eigen/Geometry>
#include <string>

namespace mcws::app {

/// \brief "x y z roll pitch yaw": translation [length unit] and fixed-axis angles [rad],
/// R = Rz(yaw) Ry(pitch) Rx(roll) (as URDF).
/// \throws UsageError naming `flag` for a value that is not a finite number or a count other
///   than 6.
Eigen::Isometry3d parsePose(const std::string& text, const std::string& flag);

/// \brief 16 numbers, row by row, of a homogeneous 4x4 pose (poseFromTypedMatrix()).
/// \throws UsageError naming `flag` for a value that is not a finite number, a count other than
///   16, a last row other than 0 0 0 1, or a rotation that is not orthonormal within
///   mcws::kTypedRotationTolerance or is a reflection.
Eigen::Isometry3d parseMatrix(const std::string& text, const std::string& flag);

}  // namespace mcws::app
