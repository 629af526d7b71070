#pragma once
/// \file
/// \brief Exact collision checking of straight joint-space motions of a robot whose base may be
/// displaced: no collision between two checked configurations is missed.

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "mcws/collision/collision_checker.h"
#include "mcws/kinematics/robot.h"

namespace mcws {

/// \brief Which pairs of CollisionChecker::pairs() a check takes.
enum class PairSet {
  kAll,          ///< self (link-link, tool-link) and environment pairs
  kEnvironment,  ///< environment pairs only: the ones a base displacement changes
};

/// \brief Settings of a MotionCertifier.
struct MotionCertifierOptions {
  /// Clearance every link and the tool must keep from environment objects [length unit]:
  /// 0 for plain collision checking; > 0 pads the obstacles (the usual answer to base sway in
  /// MoveIt-style planners, kept here for comparison).
  double environment_margin{0.0};
  /// A motion is split until its motion bound is below this [length unit]; a motion that still
  /// cannot be certified is reported as colliding (conservative: it grazes an obstacle within
  /// this distance).
  double resolution{1e-4};
};

/// \brief Certifies that the straight joint-space motion between two configurations is
/// collision-free, with the base at any pose.
///
/// The method is the adaptive, exact motion check of Schwarzer, Saha and Latombe ("Adaptive
/// dynamic collision checking for single and multiple articulated robots in complex
/// environments", IEEE T-RO 21(3), 2005): while the joints move from qa to qb along a line, no
/// point of body b travels farther than M_b = sum_i |qb_i - qa_i| R_ib, where R_ib bounds the
/// distance of b's points from joint i's axis (1 for a prismatic joint). If the clearances of a
/// pair at the two ends add up to more than M_a + M_b, the pair cannot touch in between; else
/// the motion is split in half and each half checked, down to `resolution`.
///
/// The bounds R_ib come from the chain: the fixed offsets between joints, the largest travel of
/// each prismatic joint and each body's bounding sphere (CollisionChecker::bodySphere).
/// Thread-safe: each thread passes its own CollisionChecker::Scratch.
class MotionCertifier {
 public:
  /// \param checker must outlive the certifier.
  MotionCertifier(const Robot& robot, const CollisionChecker& checker,
                  const MotionCertifierOptions& options = {});

  /// \brief Clearance of each pair of the set at q with the base at T_world_base, minus the
  /// pair's margin, capped at `cap` [length unit]; <= 0 means in collision (or within the
  /// margin). Values are in pairs() order of the set.
  void clearances(const Eigen::VectorXd& q, const Eigen::Isometry3d& T_world_base, PairSet set,
                  double cap, CollisionChecker::Scratch& scratch, std::vector<double>& out) const;

  /// \brief True when q is collision-free (environment clearance above the margin).
  bool configurationFree(const Eigen::VectorXd& q, const Eigen::Isometry3d& T_world_base,
                         CollisionChecker::Scratch& scratch) const;

  /// \brief True when every configuration on the line from qa to qb is collision-free with the
  /// base at T_world_base. \param set kEnvironment when the self pairs are known to be clear
  /// (they do not depend on the base).
  bool motionFree(const Eigen::VectorXd& qa, const Eigen::VectorXd& qb,
                  const Eigen::Isometry3d& T_world_base, PairSet set,
                  CollisionChecker::Scratch& scratch) const;

  /// \brief motionFree() with the ends' clearances known (from clearances() with `cap` at
  /// least the largest motion bound of the pair between qa and qb), so that no query is made
  /// at the ends.
  bool motionFree(const Eigen::VectorXd& qa, const std::vector<double>& clearance_a,
                  const Eigen::VectorXd& qb, const std::vector<double>& clearance_b,
                  const Eigen::Isometry3d& T_world_base, PairSet set,
                  CollisionChecker::Scratch& scratch) const;

  /// \brief Motion bound of each pair of the set between qa and qb [length unit].
  void motionBounds(const Eigen::VectorXd& qa, const Eigen::VectorXd& qb, PairSet set,
                    std::vector<double>& out) const;

  /// \brief Largest distance any point of pair p's moving body (the robot side) can move
  /// when the base is displaced by `displacement` (a rigid world motion) at q, given the
  /// body's world bounding sphere at q: 2 sin(angle / 2) |c - pivot| + |translation at pivot|
  /// + 2 sin(angle / 2) radius. Lets a nominal clearance bound the displaced one from below.
  struct DisplacementBound {
    double sin_term{0.0};  ///< 2 sin(angle / 2) of the displacement's rotation
    double shift{0.0};     ///< how far the displacement moves the pivot [length unit]
  };
  static DisplacementBound displacementBound(const Eigen::Isometry3d& displacement,
                                             const Eigen::Vector3d& pivot);

  /// \brief Indices into CollisionChecker::pairs() of a set.
  const std::vector<std::size_t>& pairs(PairSet set) const;
  /// \brief The robot body (link or tool index) of environment pair k of pairs(kEnvironment).
  int environmentBody(std::size_t k) const;
  const CollisionChecker& checker() const { return checker_; }
  const Robot& robot() const { return robot_; }
  const MotionCertifierOptions& options() const { return options_; }
  /// \brief R_ib: bound on the distance of body b's points from joint i's axis [length unit];
  /// 1 for a prismatic joint that moves b, 0 for a joint that does not move b.
  double reach(int joint, int body) const { return reach_(joint, body); }

 private:
  bool certify(const Eigen::VectorXd& qa, const std::vector<double>& da, const Eigen::VectorXd& qb,
               const std::vector<double>& db, const Eigen::Isometry3d& T_world_base, PairSet set,
               CollisionChecker::Scratch& scratch) const;

  Robot robot_;
  const CollisionChecker& checker_;
  MotionCertifierOptions options_;
  Eigen::MatrixXd reach_;  ///< dof x bodies
  std::vector<std::size_t> all_pairs_, environment_pairs_;
  std::vector<double> margin_;  ///< per checker pair
};

}  // namespace mcws
