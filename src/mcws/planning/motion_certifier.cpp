#include "mcws/planning/motion_certifier.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mcws/core/decimal.h"
#include "mcws/core/error.h"

namespace mcws {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// How far a joint's link frame origin can be from the previous one's: the fixed offset plus
/// the largest travel of a prismatic joint [length unit].
double linkOffsetBound(const Joint& joint) {
  const double travel = joint.type == JointType::kPrismatic
                            ? std::max(std::abs(joint.lower), std::abs(joint.upper))
                            : 0.0;
  return joint.T_parent_joint.translation().norm() + travel;
}

}  // namespace

MotionCertifier::MotionCertifier(const Robot& robot, const CollisionChecker& checker,
                                 const MotionCertifierOptions& options)
    : robot_(robot), checker_(checker), options_(options) {
  refuseMimicJoints(robot, "the motion certifier");
  if (!(options.environment_margin >= 0.0) || !std::isfinite(options.environment_margin)) {
    throw Error("motion check: environment margin " + formatNumber(options.environment_margin) +
                " must be >= 0");
  }
  if (!(options.resolution > 0.0) || !std::isfinite(options.resolution)) {
    throw Error("motion check: resolution " + formatNumber(options.resolution) + " must be > 0");
  }
  const int dof = robot.dof();
  const int tool = checker.toolBody();
  reach_ = Eigen::MatrixXd::Zero(dof, checker.bodyCount());
  for (int i = 0; i < dof; ++i) {
    // Bodies 1 .. dof are the links of joints 0 .. dof-1; the tool rides on the last link.
    for (int body = i + 1; body <= tool; ++body) {
      if (robot.joints[i].type == JointType::kPrismatic) {
        reach_(i, body) = 1.0;
        continue;
      }
      const int last_joint = body == tool ? dof - 1 : body - 1;
      double offset = 0.0;  // from joint i's axis (its link frame origin) to body's frame origin
      for (int k = i + 1; k <= last_joint; ++k) offset += linkOffsetBound(robot.joints[k]);
      if (body == tool) offset += robot.T_last_flange.translation().norm();
      const CollisionChecker::BodySphere sphere = checker.bodySphere(body);
      reach_(i, body) = offset + sphere.center.norm() + sphere.radius;
    }
  }
  margin_.assign(checker.pairs().size(), 0.0);
  for (std::size_t p = 0; p < checker.pairs().size(); ++p) {
    all_pairs_.push_back(p);
    if (checker.pairs()[p].label == kLabelEnvironment) {
      environment_pairs_.push_back(p);
      margin_[p] = options.environment_margin;
    }
  }
}

const std::vector<std::size_t>& MotionCertifier::pairs(PairSet set) const {
  return set == PairSet::kAll ? all_pairs_ : environment_pairs_;
}

int MotionCertifier::environmentBody(std::size_t k) const {
  return checker_.pairs().at(environment_pairs_.at(k)).body_a;
}

void MotionCertifier::clearances(const Eigen::VectorXd& q, const Eigen::Isometry3d& T_world_base,
                                 PairSet set, double cap, CollisionChecker::Scratch& scratch,
                                 std::vector<double>& out) const {
  checker_.place(q.data(), T_world_base, scratch);
  const std::vector<std::size_t>& indices = pairs(set);
  out.resize(indices.size());
  for (std::size_t k = 0; k < indices.size(); ++k) {
    const double margin = margin_[indices[k]];
    out[k] = checker_.clearance(indices[k], cap + margin, scratch) - margin;
  }
}

bool MotionCertifier::configurationFree(const Eigen::VectorXd& q,
                                        const Eigen::Isometry3d& T_world_base,
                                        CollisionChecker::Scratch& scratch) const {
  if (options_.environment_margin == 0.0)
    return checker_.label(q.data(), T_world_base, scratch) == kLabelFree;
  std::vector<double> d;
  clearances(q, T_world_base, PairSet::kAll, options_.resolution, scratch, d);
  return std::all_of(d.begin(), d.end(), [](double v) { return v > 0.0; });
}

void MotionCertifier::motionBounds(const Eigen::VectorXd& qa, const Eigen::VectorXd& qb,
                                   PairSet set, std::vector<double>& out) const {
  const std::vector<std::size_t>& indices = pairs(set);
  out.assign(indices.size(), 0.0);
  for (std::size_t k = 0; k < indices.size(); ++k) {
    const CollisionPair& pair = checker_.pairs()[indices[k]];
    double bound = 0.0;
    for (int i = 0; i < robot_.dof(); ++i) {
      // A joint that moves both bodies leaves their distance unchanged (a rigid motion of both).
      const bool moves_a = pair.body_a > i && pair.body_a <= checker_.toolBody();
      const bool moves_b = pair.body_b > i && pair.body_b <= checker_.toolBody();
      if (moves_a && moves_b) continue;
      bound += std::abs(qb[i] - qa[i]) * (reach_(i, pair.body_a) + reach_(i, pair.body_b));
    }
    out[k] = bound;
  }
}

bool MotionCertifier::motionFree(const Eigen::VectorXd& qa, const Eigen::VectorXd& qb,
                                 const Eigen::Isometry3d& T_world_base, PairSet set,
                                 CollisionChecker::Scratch& scratch) const {
  std::vector<double> bounds, da, db;
  motionBounds(qa, qb, set, bounds);
  const double cap = bounds.empty() ? 0.0 : *std::max_element(bounds.begin(), bounds.end());
  clearances(qa, T_world_base, set, cap + options_.resolution, scratch, da);
  if (std::any_of(da.begin(), da.end(), [](double v) { return v <= 0.0; })) return false;
  clearances(qb, T_world_base, set, cap + options_.resolution, scratch, db);
  return certify(qa, da, qb, db, T_world_base, set, scratch);
}

bool MotionCertifier::motionFree(const Eigen::VectorXd& qa, const std::vector<double>& clearance_a,
                                 const Eigen::VectorXd& qb, const std::vector<double>& clearance_b,
                                 const Eigen::Isometry3d& T_world_base, PairSet set,
                                 CollisionChecker::Scratch& scratch) const {
  return certify(qa, clearance_a, qb, clearance_b, T_world_base, set, scratch);
}

bool MotionCertifier::certify(const Eigen::VectorXd& qa, const std::vector<double>& da,
                              const Eigen::VectorXd& qb, const std::vector<double>& db,
                              const Eigen::Isometry3d& T_world_base, PairSet set,
                              CollisionChecker::Scratch& scratch) const {
  std::vector<double> bounds;
  motionBounds(qa, qb, set, bounds);
  double open = 0.0;  // the largest motion bound of a pair not yet certified
  for (std::size_t k = 0; k < bounds.size(); ++k) {
    if (da[k] <= 0.0 || db[k] <= 0.0) return false;
    if (da[k] + db[k] <= bounds[k]) open = std::max(open, bounds[k]);
  }
  if (open == 0.0) return true;
  if (open < options_.resolution) return false;  // grazing: cannot be told from a contact
  const Eigen::VectorXd qm = 0.5 * (qa + qb);
  checker_.place(qm.data(), T_world_base, scratch);
  const std::vector<std::size_t>& indices = pairs(set);
  std::vector<double> dm(bounds.size(), kInfinity);  // pairs certified over the whole motion
  const double cap = 0.5 * open + options_.resolution;
  for (std::size_t k = 0; k < bounds.size(); ++k) {
    if (da[k] + db[k] > bounds[k]) continue;
    const double margin = margin_[indices[k]];
    dm[k] = checker_.clearance(indices[k], cap + margin, scratch) - margin;
    if (dm[k] <= 0.0) return false;
  }
  return certify(qa, da, qm, dm, T_world_base, set, scratch) &&
         certify(qm, dm, qb, db, T_world_base, set, scratch);
}

MotionCertifier::DisplacementBound MotionCertifier::displacementBound(
    const Eigen::Isometry3d& displacement, const Eigen::Vector3d& pivot) {
  const double angle = Eigen::AngleAxisd(displacement.linear()).angle();
  return {2.0 * std::sin(0.5 * std::min(std::abs(angle), M_PI)),
          (displacement * pivot - pivot).norm()};
}

}  // namespace mcws
