// The reach map's pose kernel (mcws::PoseBatch) against a straightforward reference: each sample
// on its own, in scalar doubles, with the formulas of the kernel before it was vectorised in pairs
// of lanes (the point and the tool's axes turned and transformed joint by joint, the Jacobian's
// columns in the tool frame, its Gram matrix summed from 0, the Cholesky factor's diagonal). The
// kernel must give the same bits, so the maps it fills are the same files byte for byte.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "kinematics/random_joints.h"
#include "kinematics/test_chains.h"
#include "mcws/kinematics/robot_yaml.h"
#include "mcws/reach/orientation_bins.h"
#include "mcws/reach/pose_batch.h"
#include "mcws/reach/quality.h"
#include "test_support.h"

namespace mcws {
namespace {

constexpr int kBatch = PoseBatch::kLanes;

/// One sample's tool point, axes and manipulability, computed alone.
struct ReferencePose {
  double p[3];
  double R[3][3];  ///< R[c][a]: component a of the tool's axis c
  double manipulability{0.0};
};

/// The reference kernel: PoseBatch's fixed transforms (the same construction), then one sample.
class ReferenceKernel {
 public:
  explicit ReferenceKernel(const Robot& robot) : n_(robot.dof()) {
    Eigen::Matrix3d A_previous_inverse = Eigen::Matrix3d::Identity();
    for (int i = 0; i < n_; ++i) {
      const Joint& joint = robot.joints[i];
      const Eigen::Matrix3d A =
          Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), joint.axis.normalized())
              .toRotationMatrix();
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
    const Eigen::Isometry3d T =
        (n_ == 0 ? robot.T_world_base : E_last) * robot.T_last_flange * robot.T_flange_tool;
    for (int a = 0; a < 3; ++a) {
      p_last_[a] = T.translation()[a];
      for (int c = 0; c < 3; ++c) R_last_[c][a] = T.linear()(a, c);
    }
  }

  /// q: the sample's joint values; c, s: their cosines and sines (PoseBatch::cosinesAndSines()).
  ReferencePose pose(const double* q, const double* cosines, const double* sines,
                     const QualityOptions* quality) const {
    ReferencePose out;
    double* p = out.p;
    auto& R = out.R;
    double J[8][6];
    std::copy_n(p_last_, 3, p);
    for (int c = 0; c < 3; ++c) std::copy_n(R_last_[c], 3, R[c]);
    for (int i = n_ - 1; i >= 0; --i) {
      if (revolute_[i]) {
        const double c = cosines[i], s = sines[i];
        turn(c, s, p);
        for (auto& axis : R) turn(c, s, axis);
        for (int a = 0; a < 3; ++a) {
          J[i][a] = -p[1] * R[a][0] + p[0] * R[a][1];
          J[i][3 + a] = R[a][2];
        }
      } else {
        p[2] += q[i];
        for (int a = 0; a < 3; ++a) {
          J[i][a] = R[a][2];
          J[i][3 + a] = 0.0;
        }
      }
      transform(fixed_[i].data(), p, true);
      for (auto& axis : R) transform(fixed_[i].data(), axis, false);
    }
    if (quality) out.manipulability = manipulabilityOf(J, *quality);
    return out;
  }

 private:
  static void turn(double c, double s, double* v) {
    const double x = v[0];
    v[0] = c * x - s * v[1];
    v[1] = s * x + c * v[1];
  }
  static void transform(const double* E, double* v, bool point) {
    const double x = v[0], y = v[1], z = v[2];
    v[0] = E[0] * x + E[1] * y + E[2] * z + (point ? E[3] : 0.0);
    v[1] = E[4] * x + E[5] * y + E[6] * z + (point ? E[7] : 0.0);
    v[2] = E[8] * x + E[9] * y + E[10] * z + (point ? E[11] : 0.0);
  }
  double manipulabilityOf(double (*J)[6], const QualityOptions& quality) const {
    const int rows = quality.task == QualityTask::kPosition ? 3 : 6;
    if (rows == 6) {
      const double scale = 1.0 / quality.characteristic_length;
      for (int j = 0; j < n_; ++j) {
        for (int r = 0; r < 3; ++r) J[j][r] *= scale;
      }
    }
    const int m = std::min(rows, n_);
    double G[8][8];
    for (int a = 0; a < m; ++a) {
      for (int b = 0; b <= a; ++b) {
        double g = 0.0;
        if (n_ <= rows) {
          for (int r = 0; r < rows; ++r) g += J[a][r] * J[b][r];
        } else {
          for (int j = 0; j < n_; ++j) g += J[j][a] * J[j][b];
        }
        G[a][b] = g;
      }
    }
    double product = 1.0;
    bool singular = false;
    for (int j = 0; j < m; ++j) {
      double d = G[j][j];
      for (int r = 0; r < j; ++r) d -= G[j][r] * G[j][r];
      singular = singular || !(d > 0.0);
      const double root = std::sqrt(d > 0.0 ? d : 1.0);
      product *= root;
      for (int i = j + 1; i < m; ++i) {
        double v = G[i][j];
        for (int r = 0; r < j; ++r) v -= G[i][r] * G[j][r];
        G[i][j] = v * (1.0 / root);
      }
    }
    return singular ? 0.0 : product;
  }

  int n_;
  std::vector<std::array<double, 12>> fixed_;
  std::vector<bool> revolute_;
  double p_last_[3];
  double R_last_[3][3];
};

bool sameDoubleBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// Joint vectors: random within the limits, and the limits and zero, which meet singularities.
std::vector<Eigen::VectorXd> referenceJointVectors(const Robot& robot, int random) {
  std::mt19937_64 rng(17);
  std::vector<Eigen::VectorXd> qs;
  for (int i = 0; i < random; ++i) qs.push_back(test::randomJoints(robot, rng));
  qs.push_back(Eigen::VectorXd::Zero(robot.dof()));
  qs.push_back(robot.lowerLimits());
  qs.push_back(robot.upperLimits());
  while (qs.size() % kBatch != 0) qs.push_back(qs.front());
  return qs;
}

TEST(PoseBatch, EveryLaneHasTheBitsOfTheScalarReference) {
  std::vector<Robot> robots;
  for (const std::string& path : test::shippedRobotFiles()) robots.push_back(loadRobot(path));
  robots.push_back(test::tiltedAxesRobot());
  for (const Robot& robot : robots) {
    for (bool wide : {true, false}) {  // AVX where the processor has it; SSE2
      SCOPED_TRACE(robot.name + (wide ? " wide" : " narrow"));
      const PoseBatch batch(robot, wide);
      const ReferenceKernel reference(robot);
      QualityOptions position, full;
      position.task = QualityTask::kPosition;
      full.characteristic_length = chainLengthScale(robot);
      const std::vector<Eigen::VectorXd> qs = referenceJointVectors(robot, 2000);
      for (std::size_t first = 0; first < qs.size(); first += kBatch) {
        double q[8 * kBatch], c[8 * kBatch], s[8 * kBatch];
        for (int k = 0; k < kBatch; ++k) {
          for (int j = 0; j < robot.dof(); ++j) q[j * kBatch + k] = qs[first + k][j];
        }
        for (int j = 0; j < robot.dof(); ++j)
          PoseBatch::cosinesAndSines(q + j * kBatch, c + j * kBatch, s + j * kBatch);
        for (const QualityOptions* quality :
             {&position, &full, static_cast<QualityOptions*>(nullptr)}) {
          for (bool with_x : {true, false}) {
            double p[3 * kBatch], approach[3 * kBatch], x_axis[3 * kBatch], w[kBatch];
            batch.poses(q, p, approach, with_x ? x_axis : nullptr, quality, w);
            for (int k = 0; k < kBatch; ++k) {
              double qk[8], ck[8], sk[8];
              for (int j = 0; j < robot.dof(); ++j) {
                qk[j] = q[j * kBatch + k];
                ck[j] = c[j * kBatch + k];
                sk[j] = s[j * kBatch + k];
              }
              const ReferencePose expected = reference.pose(qk, ck, sk, quality);
              for (int a = 0; a < 3; ++a) {
                ASSERT_TRUE(sameDoubleBits(p[a * kBatch + k], expected.p[a]))
                    << qs[first + k].transpose();
                ASSERT_TRUE(sameDoubleBits(approach[a * kBatch + k], expected.R[2][a]))
                    << qs[first + k].transpose();
                if (with_x) {
                  ASSERT_TRUE(sameDoubleBits(x_axis[a * kBatch + k], expected.R[0][a]))
                      << qs[first + k].transpose();
                }
              }
              if (quality) {
                ASSERT_TRUE(sameDoubleBits(w[k], expected.manipulability))
                    << w[k] << " " << expected.manipulability << " " << qs[first + k].transpose();
              }
            }
          }
        }
      }
    }
  }
}

TEST(SpherePartition, ZoneTableFindsTheZonesOfTheRegionCounts) {
  // region() finds a direction's zone by a table of whole region counts; a linear search over
  // the zones' first regions (the definition) must agree, also at z exactly on a zone's edge and
  // just beside it, at the poles and beyond them (rounding).
  for (int regions : {1, 2, 3, 7, 200, 1000}) {
    SCOPED_TRACE(regions);
    const SpherePartition sphere(regions);
    std::vector<int> first;  // each zone's first region
    for (int r = 0; r < regions; ++r) {
      double t0, t1, p0, p1;
      sphere.bounds(r, t0, t1, p0, p1);
      if (p0 == 0.0) first.push_back(r);
    }
    first.push_back(regions);
    ASSERT_EQ(static_cast<int>(first.size()) - 1, sphere.zones());
    const auto expectedZone = [&](double z) {
      const double above = 0.5 * regions * (1.0 - z);
      int zone = 0;
      while (zone + 1 < sphere.zones() && above >= first[zone + 1]) ++zone;
      return zone;
    };
    std::vector<double> zs = {1.0, -1.0, 1.0 + 1e-15, -1.0 - 1e-15, 0.0, -0.0};
    for (int j = 0; j <= regions; ++j) {
      const double z = 1.0 - 2.0 * j / regions;
      zs.insert(zs.end(), {z, std::nextafter(z, 2.0), std::nextafter(z, -2.0)});
    }
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    for (int i = 0; i < 2000; ++i) zs.push_back(uniform(rng));
    for (double z : zs) {
      // A direction with that z and longitude 0, so the region is the zone's first.
      const Eigen::Vector3d d(std::sqrt(std::max(0.0, 1.0 - z * z)), 0.0, z);
      const int zone = expectedZone(d.z() / d.norm());
      EXPECT_EQ(sphere.region(d), first[zone]) << z;
    }
  }
}

}  // namespace
}  // namespace mcws
