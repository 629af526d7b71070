#include "mcws/reach/pose_batch.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "mcws/core/error.h"
#include "mcws/core/libmvec.h"  // vector sin, cos for the simd loops

namespace mcws {
namespace {

constexpr int L = PoseBatch::kLanes;
constexpr int kSplat = 4;  ///< copies of each fixed element (the widest kernel's lanes)

// The kernels work on GCC/Clang vectors of two doubles (SSE2, what the build targets) or four
// (AVX, where the processor has it): every operation on one is the same IEEE operation on each
// lane as on a double, and the build enables no fused multiply-add that could contract them, so
// a lane's results are the bits of the scalar formulas in the same order. Every helper is inlined
// into its kernel, so the four-lane one is compiled for AVX with it.
using V2 = double __attribute__((vector_size(16)));
using V4 = double __attribute__((vector_size(32)));
#define MCWS_KERNEL_INLINE inline __attribute__((always_inline))

Eigen::Matrix3d rotationTakingZTo(const Eigen::Vector3d& axis) {
  return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis).toRotationMatrix();
}

template <typename V>
constexpr int kWidth = sizeof(V) / sizeof(double);

template <typename V>
MCWS_KERNEL_INLINE void splat(double x, V& v) {
  for (int i = 0; i < kWidth<V>; ++i) v[i] = x;  // no arithmetic: -0.0 stays -0.0
}
/// V without its alignment, and allowed to alias doubles: how the kernels read arrays.
template <typename V>
struct Loose;
template <>
struct Loose<V2> {
  typedef double type __attribute__((vector_size(16), may_alias, aligned(8)));
};
template <>
struct Loose<V4> {
  typedef double type __attribute__((vector_size(32), may_alias, aligned(8)));
};
template <typename V>
MCWS_KERNEL_INLINE void load(const double* p, V& v) {
  v = *reinterpret_cast<const typename Loose<V>::type*>(p);
}
template <typename V>
MCWS_KERNEL_INLINE void store(double* p, const V& v) {
  std::memcpy(p, &v, sizeof v);
}
/// mask ? a : b, lane-wise (a comparison's mask: all ones or all zeros).
template <typename V, typename Mask>
MCWS_KERNEL_INLINE void select(const Mask& mask, const V& a, const V& b, V& out) {
  Mask ia, ib;
  std::memcpy(&ia, &a, sizeof a);
  std::memcpy(&ib, &b, sizeof b);
  const Mask bits = (mask & ia) | (~mask & ib);
  std::memcpy(&out, &bits, sizeof out);
}

/// The fixed data of the chain, as the kernels read them.
struct Chain {
  const double* fixed;  ///< PoseBatch::fixed_
  const char* revolute;
  int n;
  const double* p_last;  ///< 3 values
  const double* R_last;  ///< column-major 3x3
};

/// x, y of a 3-vector turned about z by the angle of cosine c and sine s.
template <typename V>
MCWS_KERNEL_INLINE void turn(const V& c, const V& s, V* v) {
  const V x = v[0];
  v[0] = c * x - s * v[1];
  v[1] = s * x + c * v[1];
}

/// The fixed transform E (12 elements, kSplat copies each) times v, plus E's translation for a
/// point (for a direction + 0.0, as the kernel always did: the same bits, -0.0 included).
/// Element i of a fixed transform (kSplat copies).
template <typename V>
MCWS_KERNEL_INLINE const typename Loose<V>::type& element(const double* E, int i) {
  return *reinterpret_cast<const typename Loose<V>::type*>(E + kSplat * i);
}

template <bool kPoint, typename V>
MCWS_KERNEL_INLINE void transform(const double* E, V* v) {
  V zero;
  splat(0.0, zero);
  const V x = v[0], y = v[1], z = v[2];
  v[0] = element<V>(E, 0) * x + element<V>(E, 1) * y + element<V>(E, 2) * z +
         (kPoint ? V(element<V>(E, 3)) : zero);
  v[1] = element<V>(E, 4) * x + element<V>(E, 5) * y + element<V>(E, 6) * z +
         (kPoint ? V(element<V>(E, 7)) : zero);
  v[2] = element<V>(E, 8) * x + element<V>(E, 9) * y + element<V>(E, 10) * z +
         (kPoint ? V(element<V>(E, 11)) : zero);
}

/// Product of the diagonal of the Cholesky factor of the M x M Gram matrices G[k] of K lane
/// groups (lower triangle, G[k][a][b] for b <= a, overwritten); 0 for a lane whose matrix is not
/// positive definite. The groups go step by step together: each step's square root and division
/// of one group wait for the step before, so the other groups' fill that latency.
template <int M, int K, typename V>
MCWS_KERNEL_INLINE void choleskyDiagonalProducts(V (*G)[8][8], V* out) {
  using Mask = decltype(V{} > V{});
  V zero, one;
  splat(0.0, zero);
  splat(1.0, one);
  V product[K];
  Mask singular[K];
  for (int k = 0; k < K; ++k) {
    product[k] = one;
    singular[k] = zero > one;  // all false
  }
  for (int j = 0; j < M; ++j) {
    V inverse[K];
    for (int k = 0; k < K; ++k) {
      V d = G[k][j][j];
      for (int r = 0; r < j; ++r) d = d - G[k][j][r] * G[k][j][r];
      const Mask positive = d > zero;
      singular[k] = singular[k] | ~positive;
      V root;
      select(positive, d, one, root);
      for (int i = 0; i < kWidth<V>; ++i) root[i] = std::sqrt(root[i]);
      product[k] = product[k] * root;
      inverse[k] = one / root;
    }
    for (int i = j + 1; i < M; ++i) {
      for (int k = 0; k < K; ++k) {
        V v = G[k][i][j];
        for (int r = 0; r < j; ++r) v = v - G[k][i][r] * G[k][j][r];
        G[k][i][j] = v * inverse[k];
      }
    }
  }
  for (int k = 0; k < K; ++k) select(singular[k], zero, product[k], out[k]);
}

/// The Gram matrix G (lower triangle) of the lanes' Jacobians J[column][row] (n columns, the
/// tool frame) that mcws::manipulability() factors with `quality`: the rows the task measures,
/// velocity rows scaled by 1 / L for the full twist (in place), then J^T J or J J^T, each sum
/// accumulated from 0 in row (column) order. Returns its size, min(rows, n).
template <typename V>
MCWS_KERNEL_INLINE int gramOf(V (*J)[6], int n, const QualityOptions& quality, V (*G)[8]) {
  const int rows = quality.task == QualityTask::kPosition ? 3 : 6;
  if (rows == 6) {
    V scale;
    splat(1.0 / quality.characteristic_length, scale);
    for (int j = 0; j < n; ++j) {
      for (int r = 0; r < 3; ++r) J[j][r] = J[j][r] * scale;
    }
  }
  const int m = std::min(rows, n);
  V zero;
  splat(0.0, zero);
  if (n == 6 && rows == 6) {  // the six-joint arm's square Jacobian: column a in registers
    for (int a = 0; a < 6; ++a) {
      const V c0 = J[a][0], c1 = J[a][1], c2 = J[a][2], c3 = J[a][3], c4 = J[a][4], c5 = J[a][5];
      for (int b = 0; b <= a; ++b) {
        const V* o = J[b];
        G[a][b] = zero + c0 * o[0] + c1 * o[1] + c2 * o[2] + c3 * o[3] + c4 * o[4] + c5 * o[5];
      }
    }
    return m;
  }
  for (int a = 0; a < m; ++a) {
    for (int b = 0; b <= a; ++b) {
      V g = zero;
      if (n <= rows) {  // J^T J: columns a and b
        for (int r = 0; r < rows; ++r) g = g + J[a][r] * J[b][r];
      } else {  // J J^T: rows a and b
        for (int j = 0; j < n; ++j) g = g + J[j][a] * J[j][b];
      }
      G[a][b] = g;
    }
  }
  return m;
}

/// The manipulability of K lane groups from their Gram matrices of size m (1 to 6).
template <int K, typename V>
MCWS_KERNEL_INLINE void manipulabilities(V (*G)[8][8], int m, V* w) {
  switch (m) {
    case 1:
      return choleskyDiagonalProducts<1, K>(G, w);
    case 2:
      return choleskyDiagonalProducts<2, K>(G, w);
    case 3:
      return choleskyDiagonalProducts<3, K>(G, w);
    case 4:
      return choleskyDiagonalProducts<4, K>(G, w);
    case 5:
      return choleskyDiagonalProducts<5, K>(G, w);
    default:
      return choleskyDiagonalProducts<6, K>(G, w);  // m = min(rows, n) <= 6
  }
}

/// The kernel for the lanes [lane, lane + width) of the batch's arrays: the tool point, the axes
/// it needs (the approach; the x axis with kXAxis; all three with kQuality) and, with kQuality,
/// the Jacobian's columns and their Gram matrix G (returns its size).
template <typename V, bool kQuality, bool kXAxis>
MCWS_KERNEL_INLINE int lanes(const Chain& chain, const double* q, const double* c, const double* s,
                             int lane, double* p, double* approach, double* x_axis,
                             const QualityOptions* quality, V (*G)[8]) {
  constexpr bool kAxis0 = kQuality || kXAxis, kAxis1 = kQuality;  // the approach always
  const int n = chain.n;
  V P[3], R[3][3];  // the tool point; R[c][a]: component a of the tool's axis c
  V J[8][6];        // column j, row r: the Jacobian in the tool frame
  for (int a = 0; a < 3; ++a) {
    splat(chain.p_last[a], P[a]);
    for (int axis = 0; axis < 3; ++axis) splat(chain.R_last[3 * axis + a], R[axis][a]);
  }
  for (int i = n - 1; i >= 0; --i) {
    if (chain.revolute[i]) {
      V ci, si;
      load(c + i * L + lane, ci);
      load(s + i * L + lane, si);
      turn(ci, si, P);
      if (kAxis0) turn(ci, si, R[0]);
      if (kAxis1) turn(ci, si, R[1]);
      turn(ci, si, R[2]);
      if (kQuality) {
        // z x p = (-p_y, p_x, 0); in the tool frame R^T (z x p), and z is R^T z (row 2 of R).
        for (int a = 0; a < 3; ++a) {
          J[i][a] = -P[1] * R[a][0] + P[0] * R[a][1];
          J[i][3 + a] = R[a][2];
        }
      }
    } else {
      V qi;
      load(q + i * L + lane, qi);
      P[2] = P[2] + qi;
      if (kQuality) {
        for (int a = 0; a < 3; ++a) {
          J[i][a] = R[a][2];
          splat(0.0, J[i][3 + a]);
        }
      }
    }
    const double* E = chain.fixed + 12 * kSplat * i;
    transform<true>(E, P);
    if (kAxis0) transform<false>(E, R[0]);
    if (kAxis1) transform<false>(E, R[1]);
    transform<false>(E, R[2]);
  }
  for (int a = 0; a < 3; ++a) {
    store(p + a * L + lane, P[a]);
    store(approach + a * L + lane, R[2][a]);
    if (kXAxis) store(x_axis + a * L + lane, R[0][a]);
  }
  return kQuality ? gramOf(J, n, *quality, G) : 0;
}

/// Every lane of the batch, kWidth<V> at a time, then the manipulability of all at once.
template <typename V>
MCWS_KERNEL_INLINE void allLanes(const Chain& chain, const double* q, const double* c,
                                 const double* s, double* p, double* approach, double* x_axis,
                                 const QualityOptions* quality, double* manipulability) {
  constexpr int K = L / kWidth<V>;
  V G[K][8][8];
  int m = 0;
  for (int k = 0; k < K; ++k) {
    const int lane = k * kWidth<V>;
    if (quality && x_axis) {
      m = lanes<V, true, true>(chain, q, c, s, lane, p, approach, x_axis, quality, G[k]);
    } else if (quality) {
      m = lanes<V, true, false>(chain, q, c, s, lane, p, approach, x_axis, quality, G[k]);
    } else if (x_axis) {
      lanes<V, false, true>(chain, q, c, s, lane, p, approach, x_axis, quality, G[k]);
    } else {
      lanes<V, false, false>(chain, q, c, s, lane, p, approach, x_axis, quality, G[k]);
    }
  }
  if (!quality) return;
  V w[K];
  manipulabilities<K>(G, m, w);
  for (int k = 0; k < K; ++k) store(manipulability + k * kWidth<V>, w[k]);
}

void narrowKernel(const Chain& chain, const double* q, const double* c, const double* s, double* p,
                  double* approach, double* x_axis, const QualityOptions* quality,
                  double* manipulability) {
  allLanes<V2>(chain, q, c, s, p, approach, x_axis, quality, manipulability);
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
__attribute__((target("avx"))) void wideKernel(const Chain& chain, const double* q, const double* c,
                                               const double* s, double* p, double* approach,
                                               double* x_axis, const QualityOptions* quality,
                                               double* manipulability) {
  allLanes<V4>(chain, q, c, s, p, approach, x_axis, quality, manipulability);
}

bool processorHasAvx() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx");
}
#else
void wideKernel(const Chain& chain, const double* q, const double* c, const double* s, double* p,
                double* approach, double* x_axis, const QualityOptions* quality,
                double* manipulability) {
  narrowKernel(chain, q, c, s, p, approach, x_axis, quality, manipulability);
}

bool processorHasAvx() { return false; }
#endif

}  // namespace

PoseBatch::PoseBatch(const Robot& robot, bool wide) : wide_(wide && processorHasAvx()) {
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
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) fixed_.insert(fixed_.end(), kSplat, E.matrix()(r, c));
    }
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

void PoseBatch::cosinesAndSines(const double* angles, double* c, double* s) {
  // Separate loops: together GCC would fuse them into a scalar sincos call first.
#pragma omp simd
  for (int k = 0; k < L; ++k) c[k] = std::cos(angles[k]);
#pragma omp simd
  for (int k = 0; k < L; ++k) s[k] = std::sin(angles[k]);
}

void PoseBatch::poses(const double* q, double* p, double* approach, double* x_axis,
                      const QualityOptions* quality, double* manipulability) const {
  const int n = dof();
  // Every joint's cosine and sine, 8 lanes at a time (libmvec's vector functions).
  double c[8 * L], s[8 * L];
  for (int i = 0; i < n; ++i) {
    if (revolute_[i]) cosinesAndSines(q + i * L, c + i * L, s + i * L);
  }
  const Chain chain{fixed_.data(), revolute_.data(), n, p_last_.data(), R_last_.data()};
  if (wide_) {
    wideKernel(chain, q, c, s, p, approach, x_axis, quality, manipulability);
  } else {
    narrowKernel(chain, q, c, s, p, approach, x_axis, quality, manipulability);
  }
}

}  // namespace mcws

#undef MCWS_KERNEL_INLINE
