#pragma once
/// \file
/// \brief Self-collision, tool-vs-arm and environment checks of one joint vector
/// (Fu, Hu, Chen & Pan 2016, section 2), with FCL (the Flexible Collision Library) underneath.

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "mcws/collision/collision_model.h"
#include "mcws/kinematics/robot.h"
#include "mcws/points/point_types.h"

namespace fcl {
template <typename S>
class CollisionGeometry;
}

namespace mcws {

/// \brief A pair of bodies the checker tests, with the label a collision of the pair gives.
struct CollisionPair {
  int body_a{0}, body_b{0};  ///< CollisionChecker::bodyName() indices
  std::uint32_t label{kLabelLinkLink};
};

/// \brief Clearance of one pair of bodies at one joint vector.
struct PairReport {
  std::string body_a, body_b;
  std::uint32_t label{kLabelLinkLink};  ///< the label a collision of this pair gives
  bool colliding{false};
  /// Smallest distance between the two bodies' shapes [length unit] when apart; when colliding,
  /// minus the penetration depth if `depth_known`, else 0 (FCL gives no depth for meshes).
  double distance{0.0};
  bool depth_known{true};
};

/// \brief Switches for measuring what each part of CollisionChecker saves (bench/).
struct CollisionCheckerOptions {
  /// Capsule and sphere pairs by exact segment distance; false sends them to fcl::collide too.
  bool exact_capsules{true};
  /// Reject body and shape pairs whose bounding spheres, and mesh pairs whose bounding capsules,
  /// are apart before any exact test.
  bool bounding_spheres{true};
  /// Before fcl::collide of two meshes, a short search for one pair of intersecting triangles
  /// (findIntersectingTriangles()), which proves a collision; false sends every mesh pair
  /// straight to fcl::collide.
  bool triangle_search{true};
};

/// \brief Tests joint vectors of a robot against its collision model.
///
/// Pairs checked, in this order (each collision gives the pair's label, and label() returns the
/// lowest label of any colliding pair):
/// 1. kLabelLinkLink: every two links (base included) that are not adjacent in the chain
///    (link i and i+1, the base and link 1 are adjacent) and not in the allowed list;
/// 2. kLabelToolLink: the tool against every link except the last one, which carries it;
/// 3. kLabelEnvironment: each moving link and the tool against each environment object (the
///    base does not move, so it is not checked against the environment).
/// Bodies without shapes take part in no pair. Capsule and sphere pairs are tested with an exact
/// segment-segment distance (Ericson 2005); every other pair goes to fcl::collide, whose
/// `fcl::BVHModel<fcl::OBBRSSd>` meshes are the OBB/RSS (swept-sphere) hierarchy of
/// Fu, Hu, Chen & Pan 2016. A broad phase first rejects body and shape pairs whose bounding spheres
/// are apart, and mesh pairs whose bounding capsules (line-swept spheres on the mesh's principal
/// axis, the top level of the paper's hierarchy) are apart. Two meshes whose bounds overlap are
/// first searched for one pair of intersecting triangles (findIntersectingTriangles(), FCL's own
/// triangle test over FCL's own trees, a few hundred node pairs at most), which proves the
/// collision; fcl::collide decides when the search gives up. Labels are those of fcl::collide on
/// every pair (tests/collision/mesh_broad_phase_test.cpp checks it sample by sample).
///
/// The checker is immutable after construction and may be shared between threads; each thread
/// passes its own Scratch (poses and FCL request/result objects), so no lock is taken. The FCL
/// geometry (including the BVH trees) is shared and only read.
class CollisionChecker {
 public:
  /// \throws mcws::Error when the model does not fit the robot (link count).
  CollisionChecker(const Robot& robot, const CollisionModel& model,
                   const CollisionCheckerOptions& options = {});
  ~CollisionChecker();

  /// \brief Per-thread working memory for label().
  class Scratch {
   public:
    Scratch();
    ~Scratch();
    Scratch(Scratch&&) noexcept;

   private:
    friend class CollisionChecker;
    struct Data;
    std::unique_ptr<Data> data_;
  };

  /// \brief Label of the joint vector q[0 .. dof) [rad | length unit]: kLabelFree or the lowest
  /// label of a colliding pair. Limits are not checked.
  std::uint32_t label(const double* q, Scratch& scratch) const;
  /// \brief label() with a scratch of its own (slower: for single checks).
  std::uint32_t label(const Eigen::VectorXd& q) const;
  /// \brief label() with the robot's base at T_world_base instead of the model's base pose:
  /// every robot body moves with the base, the environment stays (the swaying base of the
  /// maintenance-arm patent).
  std::uint32_t label(const double* q, const Eigen::Isometry3d& T_world_base,
                      Scratch& scratch) const;

  /// \brief Places every body for the joint vector q [rad | length unit] with the base at
  /// T_world_base, for clearance() and bodyPose().
  void place(const double* q, const Eigen::Isometry3d& T_world_base, Scratch& scratch) const;
  /// \brief Distance between the two bodies of pairs()[pair] as last placed [length unit],
  /// capped: a value of `cap` or more comes back as `cap` (pairs whose bounding spheres are that
  /// far apart get no exact query); 0 when they collide. Capsule and sphere pairs by the exact
  /// segment distance, others by fcl::distance less a tolerance of 1e-6 length units (FCL's
  /// GJK distance is accurate to about that), so the value is a lower bound of the true one.
  double clearance(std::size_t pair, double cap, Scratch& scratch) const;
  /// \brief Whether the two bodies of pairs()[pair] collide as last placed (as label() tests).
  bool collides(std::size_t pair, Scratch& scratch) const;
  /// \brief World pose of body i as last placed.
  const Eigen::Isometry3d& bodyPose(int body, const Scratch& scratch) const;
  /// \brief A sphere holding every shape of body i, in the body's frame (radius 0 for a body
  /// without shapes).
  struct BodySphere {
    Eigen::Vector3d center{Eigen::Vector3d::Zero()};  ///< body frame [length unit]
    double radius{0.0};                               ///< [length unit]
  };
  BodySphere bodySphere(int body) const;
  /// \brief Index of the tool body (dof + 1); environment objects follow it.
  int toolBody() const { return tool_body_; }

  /// \brief Every pair at q, with its clearance or penetration (slow: FCL distance queries).
  std::vector<PairReport> report(const Eigen::VectorXd& q) const;

  /// \brief The pairs label() tests, in order.
  const std::vector<CollisionPair>& pairs() const { return pairs_; }
  /// \brief Name of body i: "base", a joint name (its link), "tool", or an environment object.
  const std::string& bodyName(int i) const;
  /// \brief Number of bodies (links, tool, environment objects).
  int bodyCount() const;

 private:
  struct Shape;
  struct Body;
  /// The checker's body for a body of the model: its shapes, its bounding sphere.
  Body makeBody(const BodySpec& spec);
  /// The checker's shape for a shape of the model: FCL geometry, bounding sphere and capsule;
  /// numbers it among all shapes.
  Shape makeShape(const ShapeSpec& in);
  /// The model's allowed pairs as body indices (lower first). \throws mcws::Error for a name
  /// that is not a body.
  std::set<std::pair<int, int>> allowedPairs(const CollisionModel& model) const;
  /// Fills pairs_ in the order label() tests them (see the class comment), less `allowed`.
  void listPairs(const std::set<std::pair<int, int>>& allowed);
  void computePoses(const double* q, const Eigen::Isometry3d& T_world_base,
                    Scratch::Data& data) const;
  double shapeClearance(const Shape& a, const Shape& b, double cap, Scratch::Data& data, int body_a,
                        int body_b) const;
  bool bodiesCollide(const CollisionPair& pair, Scratch::Data& data) const;
  bool shapesCollide(const Shape& a, const Shape& b, Scratch::Data& data, int body_a,
                     int body_b) const;
  /// The exact test of two shapes placed in the world (a search for intersecting triangles of
  /// two meshes, then fcl::collide); kept out of line so that the broad phase stays small.
  [[gnu::noinline]] bool exactlyCollide(const Shape& a, const Shape& b,
                                        const Eigen::Isometry3d& T_world_a,
                                        const Eigen::Isometry3d& T_world_b,
                                        Scratch::Data& data) const;

  const Robot robot_;
  CollisionCheckerOptions options_;
  std::vector<Body> bodies_;
  std::vector<CollisionPair> pairs_;
  int tool_body_{0};
  int shape_count_{0};
};

/// \brief Name of a label: "free", "link-link", "tool-link", "environment".
const char* labelName(std::uint32_t label);

/// \brief The label of the joint values CollisionChecker::report() gave `pairs` for, as label()
/// gives it: the lowest label of a colliding pair, kLabelFree when none collides.
std::uint32_t reportedLabel(const std::vector<PairReport>& pairs);

/// \brief The pairs of a report worth showing, nearest first (by PairReport::distance): every
/// pair with `all`, else the colliding ones or, when none collides, the pair of least clearance.
std::vector<PairReport> pairsToShow(std::vector<PairReport> pairs, bool all);

}  // namespace mcws
