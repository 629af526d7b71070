#pragma once
/// \file
/// \brief The workspace point type: a position, the joint values that produced it, a label.

#include <pcl/point_types.h>
#include <pcl/register_point_struct.h>

#include <cstdint>

namespace mcws {

/// \brief Most joints a WorkspacePoint records (a 7-axis arm on a rail fits).
constexpr int kMaxJoints = 8;

/// \brief Label values of WorkspacePoint::label: 0 free, else the lowest code of a collision
/// found (mcws::CollisionChecker).
enum WorkspaceLabel : std::uint32_t {
  kLabelFree = 0,         ///< no collision (or not checked)
  kLabelLinkLink = 1,     ///< two links of the arm collide
  kLabelToolLink = 2,     ///< the tool collides with a link it is not mounted on
  kLabelEnvironment = 3,  ///< a link or the tool collides with an environment object
};

/// \brief A Monte Carlo workspace sample.
///
/// PCD fields: `x y z` [length unit] (float), `q1 .. q8` the joint values that produced the
/// point [rad | length unit] (float; zero beyond the robot's joints), `label` (uint32, as in
/// pcl::PointXYZL). Tools that know only pcl::PointXYZ or pcl::PointXYZL read these files too.
struct EIGEN_ALIGN16 WorkspacePoint {
  PCL_ADD_POINT4D;
  union {
    float q[kMaxJoints];
    struct {
      float q1, q2, q3, q4, q5, q6, q7, q8;
    };
  };
  std::uint32_t label;

  WorkspacePoint() : data{0.f, 0.f, 0.f, 1.f}, q{}, label(kLabelFree) {}
  PCL_MAKE_ALIGNED_OPERATOR_NEW
};

/// \brief A workspace sample with the arm's quality there (mcws_sample --quality).
///
/// PCD fields: those of WorkspacePoint, then `manipulability` (float, Yoshikawa's index of
/// mcws::Quality) and `inverse_condition` (float, sigma_min / sigma_max of the Jacobian, [1]).
/// Tools that read WorkspacePoint read these files too.
struct EIGEN_ALIGN16 QualityPoint {
  PCL_ADD_POINT4D;
  union {
    float q[kMaxJoints];
    struct {
      float q1, q2, q3, q4, q5, q6, q7, q8;
    };
  };
  std::uint32_t label;
  float manipulability;
  float inverse_condition;

  QualityPoint()
      : data{0.f, 0.f, 0.f, 1.f},
        q{},
        label(kLabelFree),
        manipulability(0.f),
        inverse_condition(0.f) {}
  PCL_MAKE_ALIGNED_OPERATOR_NEW
};

}  // namespace mcws

// clang-format off
POINT_CLOUD_REGISTER_POINT_STRUCT(mcws::WorkspacePoint,
    (float, x, x) (float, y, y) (float, z, z)
    (float, q1, q1) (float, q2, q2) (float, q3, q3) (float, q4, q4)
    (float, q5, q5) (float, q6, q6) (float, q7, q7) (float, q8, q8)
    (std::uint32_t, label, label))
POINT_CLOUD_REGISTER_POINT_STRUCT(mcws::QualityPoint,
    (float, x, x) (float, y, y) (float, z, z)
    (float, q1, q1) (float, q2, q2) (float, q3, q3) (float, q4, q4)
    (float, q5, q5) (float, q6, q6) (float, q7, q7) (float, q8, q8)
    (std::uint32_t, label, label)
    (float, manipulability, manipulability) (float, inverse_condition, inverse_condition))
// clang-format on
