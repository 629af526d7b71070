#include "mcws/reach/pose_batch.h"

#include <algorithm>
#include <cmath>

#include "mcws/core/error.h"
#include "mcws/core/libmvec.h"  // vector sin, cos, atan2 for the simd loops

namespace mcws {
namespace {

constexpr int L = PoseBatch::kLanes;

Eigen::Matrix3d rotationTakingZTo(const Eigen::Vector3d& axis) {
  return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis).toRotationMatrix();
}

/// y[lane] = E * x[lane] for 3-vectors laid out [a * L + lane], plus E's translation if `point`.
inline void transform(const double* E, double* v, bool point) {
  const double tx = point ? E[3] : 0.0, ty = point ? E[7] : 0.0, tz = point ? E[11] : 0.0;
#pragma omp simd
  for (int k = 0; k < L; ++k) {
    const double x = v[k], y = v[L + k], z = v[2 * L + k];
    v[k] = E[0] * x + E[1] * y + E[2] * z + tx;
    v[L + k] = E[4] * x + E[5] * y + E[6] * z + ty;
    v[2 * L + k] = E[8] * x + E[9] * y + E[10] * z + tz;
  }
}

/// Rotates 3-vectors laid out [a * L + lane] about z by the angles whose cos and sin are c, s.
inline void turn(const double* c, const double* s, double* v) {
#pragma omp simd
  for (int k = 0; k < L; ++k) {
    const double x = v[k];
    v[k] = c[k] * x - s[k] * v[L + k];
    v[L + k] = s[k] * x + c[k] * v[L + k];
  }
}

/// Product of the diagonal of the Cholesky factor of the m x m Gram matrices G (G[(a*m+b)*L+k]),
/// lane-wise; 0 for a lane whose matrix is not positive definite. Every loop runs over the lanes
/// innermost, so each vectorises.
void choleskyDiagonalProduct(double* G, int m, double* out) {
  double product[L], singular[L];
  for (int k = 0; k < L; ++k) product[k] = 1.0, singular[k] = 0.0;
  for (int j = 0; j < m; ++j) {
    double d[L], inverse[L];
    for (int k = 0; k < L; ++k) d[k] = G[(j * m + j) * L + k];
    for (int r = 0; r < j; ++r) {
      const double* g = G + (j * m + r) * L;
#pragma omp simd
      for (int k = 0; k < L; ++k) d[k] -= g[k] * g[k];
    }
#pragma omp simd
    for (int k = 0; k < L; ++k) {
      const bool positive = d[k] > 0.0;
      singular[k] = positive ? singular[k] : 1.0;
      const double root = std::sqrt(positive ? d[k] : 1.0);
      product[k] *= root;
      inverse[k] = 1.0 / root;
    }
    for (int i = j + 1; i < m; ++i) {
      double v[L];
      for (int k = 0; k < L; ++k) v[k] = G[(i * m + j) * L + k];
      for (int r = 0; r < j; ++r) {
        const double *gi = G + (i * m + r) * L, *gj = G + (j * m + r) * L;
#pragma omp simd
        for (int k = 0; k < L; ++k) v[k] -= gi[k] * gj[k];
      }
#pragma omp simd
      for (int k = 0; k < L; ++k) G[(i * m + j) * L + k] = v[k] * inverse[k];
    }
  }
  for (int k = 0; k < L; ++k) out[k] = singular[k] != 0.0 ? 0.0 : product[k];
}

/// Manipulability of each lane's Jacobian J[column][row][lane] (n columns, the tool frame) as
/// mcws::manipulability() measures it with `quality`: the rows the task measures, velocity rows
/// scaled by 1 / L for the full twist (in place), then sqrt det of J^T J or J J^T.
void manipulabilities(double (*J)[6][L], int n, const QualityOptions& quality,
                      double* manipulability) {
  // The rows the task measures, velocity rows scaled by 1 / L for the full twist.
  const int rows = quality.task == QualityTask::kPosition ? 3 : 6;
  if (rows == 6) {
    const double scale = 1.0 / quality.characteristic_length;
    for (int j = 0; j < n; ++j) {
      for (int r = 0; r < 3; ++r) {
        for (int k = 0; k < L; ++k) J[j][r][k] *= scale;
      }
    }
  }
  const int m = std::min(rows, n);
  double G[8 * 8 * L];
  for (int a = 0; a < m; ++a) {
    for (int b = 0; b <= a; ++b) {
      double* g = G + (a * m + b) * L;
      for (int k = 0; k < L; ++k) g[k] = 0.0;
      if (n <= rows) {  // J^T J: columns a and b
        for (int r = 0; r < rows; ++r) {
#pragma omp simd
          for (int k = 0; k < L; ++k) g[k] += J[a][r][k] * J[b][r][k];
        }
      } else {  // J J^T: rows a and b
        for (int j = 0; j < n; ++j) {
#pragma omp simd
          for (int k = 0; k < L; ++k) g[k] += J[j][a][k] * J[j][b][k];
        }
      }
    }
  }
  choleskyDiagonalProduct(G, m, manipulability);
}

}  // namespace

PoseBatch::PoseBatch(const Robot& robot) {
  const int n = robot.dof();
  if (n > 8) throw Error(robot.source + ": more than 8 joints");
  refuseMimicJoints(robot, "the reach map's pose kernel");
  // As PointKinematics: E_0 = T_world_base P_0 A_0, E_i = A_{i-1}^T P_i A_i.
  Eigen::Matrix3d A_previous_inverse = Eigen::Matrix3d::Identity();
  for (int i = 0; i < n; ++i) {
    const Joint& joint = robot.joints[i];
    const Eigen::Matrix3d A = rotationTakingZTo(joint.axis.normalized());
    Eigen::Isometry3d E = Eigen::Isometry3d::Identity();
    E.linear() = A_previous_inverse;
    E = (i == 0 ? robot.T_world_base : E) * joint.T_parent_joint;
    E.linear() = E.linear() * A;
    std::array<double, 12> m{};
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) m[4 * r + c] = E.matrix()(r, c);
    }
    fixed_.push_back(m);
    revolute_.push_back(joint.type == JointType::kRevolute);
    A_previous_inverse = A.transpose();
  }
  Eigen::Isometry3d E_last = Eigen::Isometry3d::Identity();
  E_last.linear() = A_previous_inverse;
  const Eigen::Isometry3d T_last_tool =
      (n == 0 ? robot.T_world_base : E_last) * robot.T_last_flange * robot.T_flange_tool;
  R_last_ = T_last_tool.linear();
  p_last_ = T_last_tool.translation();
}

void PoseBatch::poses(const double* q, double* p, double* approach, double* x_axis,
                      const QualityOptions* quality, double* manipulability) const {
  const int n = dof();
  // The tool point and the tool's three axes, each a 3-vector per lane.
  double R[3][3 * L];
  double J[8][6][L];  // column j, row r: the Jacobian in the tool frame
  for (int k = 0; k < L; ++k) {
    for (int a = 0; a < 3; ++a) {
      p[a * L + k] = p_last_[a];
      for (int c = 0; c < 3; ++c) R[c][a * L + k] = R_last_(a, c);
    }
  }
  for (int i = n - 1; i >= 0; --i) {
    const double* qi = q + i * L;
    if (revolute_[i]) {
      double c[L], s[L];
#pragma omp simd
      for (int k = 0; k < L; ++k) c[k] = std::cos(qi[k]);
#pragma omp simd
      for (int k = 0; k < L; ++k) s[k] = std::sin(qi[k]);
      turn(c, s, p);
      for (auto& axis : R) turn(c, s, axis);
      if (quality) {
        // z x p = (-p_y, p_x, 0); in the tool frame R^T (z x p), and z is R^T z (row 2 of R).
#pragma omp simd
        for (int k = 0; k < L; ++k) {
          for (int c3 = 0; c3 < 3; ++c3) {
            J[i][c3][k] = -p[L + k] * R[c3][k] + p[k] * R[c3][L + k];
            J[i][3 + c3][k] = R[c3][2 * L + k];
          }
        }
      }
    } else {
#pragma omp simd
      for (int k = 0; k < L; ++k) p[2 * L + k] += qi[k];
      if (quality) {
#pragma omp simd
        for (int k = 0; k < L; ++k) {
          for (int c3 = 0; c3 < 3; ++c3) {
            J[i][c3][k] = R[c3][2 * L + k];
            J[i][3 + c3][k] = 0.0;
          }
        }
      }
    }
    transform(fixed_[i].data(), p, true);
    for (auto& axis : R) transform(fixed_[i].data(), axis, false);
  }
  std::copy_n(R[2], 3 * L, approach);
  std::copy_n(R[0], 3 * L, x_axis);
  if (!quality) return;

  manipulabilities(J, n, *quality, manipulability);
}

}  // namespace mcws
