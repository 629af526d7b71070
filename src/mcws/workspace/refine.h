#pragma once
/// \file
/// \brief Boundary refinement: more samples near the configurations that produced boundary
/// points (the improved Monte Carlo method of Liu et al. 2013).

#include <pcl/point_cloud.h>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mcws/kinematics/point_kinematics.h"
#include "mcws/kinematics/robot.h"
#include "mcws/points/point_types.h"
#include "mcws/sampling/sampler.h"

namespace mcws {

/// \brief Options of RefineSampler.
struct RefineOptions {
  std::uint64_t seed{1};
  SamplePoint point{SamplePoint::kTool};
  /// Half-width of each joint's neighbourhood, as a fraction of its range (0, 1]; the default
  /// is the de-icing arm's best (docs/performance-history.md, "The de-icing arm's pipeline,
  /// tighter").
  double spread{0.1};
  /// The joints pinned when the parents were sampled (mcws_sample --fix), by name [rad | length
  /// unit]: these, and only these, keep their value. Without it, joints with one value in every
  /// parent (of two or more) are taken as pinned.
  std::optional<std::vector<std::pair<std::string, double>>> fixed;
};

/// \brief Samples joint vectors in small neighbourhoods of given parent configurations: sample i
/// takes parent i mod P and moves each joint by spread * (range of the joint) * (2u - 1), u
/// uniform in [0, 1), clamped to the joint's limits. Clamping is deliberate: the joint limits map
/// onto much of the workspace boundary, which plain uniform sampling reaches with probability 0.
/// Joints pinned when the parents were sampled (RefineOptions::fixed, e.g. the de-icing arm's
/// theta3 = 0 for its X-Z plane) keep their value. Points carry x y z, q and label 0, like
/// RobotSampler's, and depend only on the seed and their index.
///
/// Joint-space sampling leaves the Cartesian edge of a workspace sparse where the forward map
/// stretches (near the tips of the region); refinement puts samples there.
class RefineSampler : public PointGenerator {
 public:
  /// \param parents the boundary points; their q fields are the configurations to refine.
  /// \throws mcws::Error for no parents, a spread outside (0, 1], a robot with more than
  ///   kMaxJoints joints, a parent whose joint values lie outside the robot's limits (the
  ///   cloud was not sampled from this robot), an unknown joint or a value outside its limits in
  ///   RefineOptions::fixed, or a parent whose value of a fixed joint is not the fixed value,
  ///   naming the point, the joint and the value.
  RefineSampler(const Robot& robot, const pcl::PointCloud<WorkspacePoint>& parents,
                const RefineOptions& options);

  void generate(std::uint64_t first, std::size_t count, WorkspacePoint* out) const override;
  /// \brief The joint values of sample `index`, exactly as generate() draws them, into
  /// q[0 .. dof) [rad | length unit].
  void jointValues(std::uint64_t index, double* q) const;

  /// \brief Names of the joints kept at their value.
  const std::vector<std::string>& pinnedJoints() const { return pinned_names_; }

 private:
  CounterRng rng_;
  PointKinematics kinematics_;
  int dof_;
  std::vector<double> parents_;           ///< dof_ values per parent
  Eigen::VectorXd lower_, upper_, step_;  ///< step 0 for a pinned joint
  std::vector<std::string> pinned_names_;
};

}  // namespace mcws
