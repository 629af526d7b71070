#include "mcws/collision/collision_checker.h"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "mcws/collision/mesh_bounds.h"
#include "mcws/collision/mesh_witness.h"
#include "mcws/collision/segment_distance.h"
#include "mcws/core/error.h"
#include "mcws/kinematics/forward_kinematics.h"

namespace mcws {

struct CollisionChecker::Shape {
  ShapeType type{ShapeType::kSphere};
  bool swept{false};  ///< capsule or sphere: tested by segment distance
  /// p_from, p_to and radius bound the shape (a line-swept sphere, the LSS of
  /// Fu, Hu, Chen & Pan 2016): the shape itself when swept, a bounding capsule of a mesh's vertices
  /// otherwise.
  bool lss{false};
  Eigen::Vector3d p_from{Eigen::Vector3d::Zero()}, p_to{Eigen::Vector3d::Zero()};
  double radius{0.0};
  Eigen::Isometry3d T_body_shape{Eigen::Isometry3d::Identity()};
  std::shared_ptr<fcl::CollisionGeometry<double>> geometry;
  /// A mesh's search tree over `geometry`'s hierarchy (findIntersectingTriangles()).
  std::shared_ptr<const MeshSearchTree> search_tree;
  Eigen::Vector3d center{Eigen::Vector3d::Zero()};  ///< bounding sphere in the body frame
  double bound{0.0};
  int index{0};  ///< among all shapes of the checker
};

struct CollisionChecker::Body {
  std::string name;
  std::vector<Shape> shapes;
  Eigen::Vector3d center{Eigen::Vector3d::Zero()};  ///< bounding sphere in the body frame
  double bound{0.0};
};

struct CollisionChecker::Scratch::Data {
  std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> T_world_body;
  /// World endpoints of swept shapes, valid when stamp[shape] == sample.
  std::vector<Eigen::Vector3d> p_from, p_to;
  std::vector<std::uint64_t> stamp;
  /// World centres of the bounding spheres of bodies and shapes, valid when their stamp is sample.
  std::vector<Eigen::Vector3d> body_center, shape_center;
  std::vector<std::uint64_t> body_stamp, shape_stamp;
  std::uint64_t sample{0};
  fcl::CollisionRequest<double> request;
  fcl::CollisionResult<double> result;
};

CollisionChecker::Scratch::Scratch() : data_(std::make_unique<Data>()) {}
CollisionChecker::Scratch::~Scratch() = default;
CollisionChecker::Scratch::Scratch(Scratch&&) noexcept = default;

namespace {

/// T * p, computed once a sample: points[i] is valid when stamp[i] == sample.
const Eigen::Vector3d& placedOnce(std::vector<Eigen::Vector3d>& points,
                                  std::vector<std::uint64_t>& stamp, std::size_t i,
                                  std::uint64_t sample, const Eigen::Isometry3d& T,
                                  const Eigen::Vector3d& p) {
  if (stamp[i] != sample) {
    stamp[i] = sample;
    points[i] = T * p;
  }
  return points[i];
}

/// Sphere tests the intersecting-triangle search may spend on a mesh pair before fcl::collide
/// decides it.
constexpr int kTriangleSearchBudget = 400;

std::shared_ptr<fcl::BVHModel<fcl::OBBRSS<double>>> meshGeometry(const TriangleMesh& mesh) {
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>();
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(mesh.vertices.size()));
  model->addSubModel(mesh.vertices, triangles);
  model->endModel();
  model->computeLocalAABB();
  return model;
}

}  // namespace

CollisionChecker::CollisionChecker(const Robot& robot, const CollisionModel& model,
                                   const CollisionCheckerOptions& options)
    : robot_(robot), options_(options), tool_body_(robot.dof() + 1) {
  if (model.links.size() != robot.joints.size() + 1) {
    throw Error("collision model has " + std::to_string(model.links.size()) + " links; robot '" +
                robot.name + "' has " + std::to_string(robot.joints.size() + 1) +
                " (base and one per joint)");
  }
  // Bodies in the order of their indices: the links (base first), the tool, the environment.
  for (const BodySpec& link : model.links) bodies_.push_back(makeBody(link));
  bodies_.push_back(makeBody(model.tool));
  for (const BodySpec& object : model.environment) bodies_.push_back(makeBody(object));
  listPairs(allowedPairs(model));
}

CollisionChecker::Body CollisionChecker::makeBody(const BodySpec& spec) {
  Body body;
  body.name = spec.name;
  std::vector<Eigen::Vector3d> extreme;  // points whose bounding sphere bounds the body
  for (const ShapeSpec& in : spec.shapes) {
    Shape shape = makeShape(in);
    // Six points of the shape's bounding sphere bound the body's sphere from below; take the
    // sphere's axis extremes so that the body sphere contains every shape sphere.
    for (int k = 0; k < 3; ++k) {
      extreme.push_back(shape.center + shape.bound * Eigen::Vector3d::Unit(k));
      extreme.push_back(shape.center - shape.bound * Eigen::Vector3d::Unit(k));
    }
    body.shapes.push_back(std::move(shape));
  }
  if (!body.shapes.empty()) {
    body.center = boundingSphere(extreme).center;
    for (const Shape& shape : body.shapes)
      body.bound = std::max(body.bound, (shape.center - body.center).norm() + shape.bound);
  }
  return body;
}

CollisionChecker::Shape CollisionChecker::makeShape(const ShapeSpec& in) {
  Shape shape;
  shape.type = in.type;
  shape.T_body_shape = in.T_body_shape;
  shape.radius = in.radius;
  shape.index = shape_count_++;
  switch (in.type) {
    case ShapeType::kCapsule:
    case ShapeType::kSphere: {
      shape.swept = shape.lss = options_.exact_capsules;
      shape.p_from = in.p_from;
      shape.p_to = in.p_to;
      const Eigen::Vector3d axis = in.p_to - in.p_from;
      const double length = axis.norm();
      shape.T_body_shape = Eigen::Isometry3d::Identity();
      shape.T_body_shape.translation() = 0.5 * (in.p_from + in.p_to);
      if (length > 0.0) {
        shape.T_body_shape.linear() =
            Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis / length)
                .toRotationMatrix();
        shape.geometry = std::make_shared<fcl::Capsule<double>>(in.radius, length);
      } else {
        shape.geometry = std::make_shared<fcl::Sphere<double>>(in.radius);
      }
      shape.center = 0.5 * (in.p_from + in.p_to);
      shape.bound = 0.5 * length + in.radius;
      break;
    }
    case ShapeType::kBox: {
      shape.geometry = std::make_shared<fcl::Box<double>>(in.size);
      shape.center = in.T_body_shape.translation();
      shape.bound = 0.5 * in.size.norm();
      // Bounding capsule: the longest axis, radius the half-diagonal of the other two.
      int longest = 0;
      in.size.maxCoeff(&longest);
      const Eigen::Vector3d half = 0.5 * in.size;
      const Eigen::Vector3d axis = half[longest] * Eigen::Vector3d::Unit(longest);
      shape.p_from = in.T_body_shape * (-axis);
      shape.p_to = in.T_body_shape * axis;
      shape.radius = std::sqrt(half.squaredNorm() - half[longest] * half[longest]) * (1.0 + 1e-12);
      shape.lss = options_.bounding_spheres;
      break;
    }
    case ShapeType::kCylinder: {
      shape.geometry = std::make_shared<fcl::Cylinder<double>>(in.radius, in.length);
      shape.center = in.T_body_shape.translation();
      shape.bound = std::hypot(in.radius, 0.5 * in.length);
      // Bounding capsule: the axis, same radius (it adds only the two end caps).
      const Eigen::Vector3d axis(0, 0, 0.5 * in.length);
      shape.p_from = in.T_body_shape * (-axis);
      shape.p_to = in.T_body_shape * axis;
      shape.radius = in.radius * (1.0 + 1e-12);
      shape.lss = options_.bounding_spheres;
      break;
    }
    case ShapeType::kMesh: {
      auto model = meshGeometry(*in.mesh);
      if (options_.triangle_search) shape.search_tree = std::make_shared<MeshSearchTree>(*model);
      shape.geometry = std::move(model);
      std::vector<Eigen::Vector3d> vertices;
      vertices.reserve(in.mesh->vertices.size());
      for (const auto& v : in.mesh->vertices) vertices.push_back(in.T_body_shape * v);
      const BoundingSphere sphere = boundingSphere(vertices);
      const BoundingCapsule capsule = boundingCapsule(vertices);
      shape.center = sphere.center;
      shape.bound = sphere.radius;
      shape.p_from = capsule.p_from;
      shape.p_to = capsule.p_to;
      shape.radius = capsule.radius;
      shape.lss = options_.bounding_spheres;
      break;
    }
  }
  return shape;
}

std::set<std::pair<int, int>> CollisionChecker::allowedPairs(const CollisionModel& model) const {
  auto index = [&](const std::string& name) {
    for (std::size_t i = 0; i < bodies_.size(); ++i)
      if (bodies_[i].name == name) return static_cast<int>(i);
    throw Error("collision model: allowed pair names unknown body '" + name + "'");
  };
  std::set<std::pair<int, int>> allowed;
  for (const auto& [a, b] : model.allowed) {
    const int i = index(a), j = index(b);
    allowed.insert({std::min(i, j), std::max(i, j)});
  }
  return allowed;
}

void CollisionChecker::listPairs(const std::set<std::pair<int, int>>& allowed) {
  auto add = [&](int a, int b, std::uint32_t label) {
    if (bodies_[a].shapes.empty() || bodies_[b].shapes.empty()) return;
    if (allowed.count({std::min(a, b), std::max(a, b)})) return;
    pairs_.push_back({a, b, label});
  };
  const int links = robot_.dof() + 1;
  for (int a = 0; a < links; ++a)
    for (int b = a + 2; b < links; ++b) add(a, b, kLabelLinkLink);
  for (int a = 0; a < links - 1; ++a) add(a, tool_body_, kLabelToolLink);
  for (int e = tool_body_ + 1; e < bodyCount(); ++e) {
    for (int a = 1; a <= tool_body_; ++a) add(a, e, kLabelEnvironment);
  }
}

CollisionChecker::~CollisionChecker() = default;

const std::string& CollisionChecker::bodyName(int i) const { return bodies_.at(i).name; }

int CollisionChecker::bodyCount() const { return static_cast<int>(bodies_.size()); }

void CollisionChecker::computePoses(const double* q, const Eigen::Isometry3d& T_world_base,
                                    Scratch::Data& data) const {
  if (data.T_world_body.size() != bodies_.size()) {
    data.T_world_body.assign(bodies_.size(), Eigen::Isometry3d::Identity());
    data.p_from.resize(shape_count_);
    data.p_to.resize(shape_count_);
    data.stamp.assign(shape_count_, 0);
    data.body_center.resize(bodies_.size());
    data.body_stamp.assign(bodies_.size(), 0);
    data.shape_center.resize(shape_count_);
    data.shape_stamp.assign(shape_count_, 0);
    data.request.num_max_contacts = 1;
  }
  ++data.sample;
  Eigen::Isometry3d T = T_world_base;
  data.T_world_body[0] = T;
  for (int i = 0; i < robot_.dof(); ++i) {
    const Joint& joint = robot_.joints[i];
    applyMimicJoints(robot_, i, q, T);
    T = T * joint.T_parent_joint;
    if (joint.type == JointType::kRevolute && joint.axis == Eigen::Vector3d::UnitZ()) {
      const double c = std::cos(q[i]), s = std::sin(q[i]);
      const Eigen::Vector3d x = T.linear().col(0), y = T.linear().col(1);
      T.linear().col(0) = c * x + s * y;
      T.linear().col(1) = c * y - s * x;
    } else {
      T = T * jointMotion(joint, q[i]);
    }
    data.T_world_body[i + 1] = T;
  }
  applyMimicJoints(robot_, robot_.dof(), q, T);
  data.T_world_body[tool_body_] = T * robot_.T_last_flange;
}

bool CollisionChecker::shapesCollide(const Shape& a, const Shape& b, Scratch::Data& data,
                                     int body_a, int body_b) const {
  const Eigen::Isometry3d& T_a = data.T_world_body[body_a];
  const Eigen::Isometry3d& T_b = data.T_world_body[body_b];
  const double reach = a.bound + b.bound;
  if (options_.bounding_spheres &&
      (placedOnce(data.shape_center, data.shape_stamp, a.index, data.sample, T_a, a.center) -
       placedOnce(data.shape_center, data.shape_stamp, b.index, data.sample, T_b, b.center))
              .squaredNorm() >= reach * reach) {
    return false;
  }
  if (a.lss && b.lss) {
    for (const auto* shape : {&a, &b}) {
      const Eigen::Isometry3d& T = shape == &a ? T_a : T_b;
      if (data.stamp[shape->index] != data.sample) {
        data.stamp[shape->index] = data.sample;
        data.p_from[shape->index] = T * shape->p_from;
        data.p_to[shape->index] = T * shape->p_to;
      }
    }
    const double touch = a.radius + b.radius;
    const bool overlap =
        segmentDistanceSquared(data.p_from[a.index], data.p_to[a.index], data.p_from[b.index],
                               data.p_to[b.index]) < touch * touch;
    // Exact for two capsules; for a mesh, only a bounding capsule: apart means apart.
    if (!overlap || (a.swept && b.swept)) return overlap;
  }
  return exactlyCollide(a, b, T_a * a.T_body_shape, T_b * b.T_body_shape, data);
}

bool CollisionChecker::exactlyCollide(const Shape& a, const Shape& b,
                                      const Eigen::Isometry3d& T_world_a,
                                      const Eigen::Isometry3d& T_world_b,
                                      Scratch::Data& data) const {
  if (a.search_tree && b.search_tree) {
    // FCL's relative transform (fcl::relativeTransform): mesh b's frame in mesh a's.
    const Eigen::Matrix3d R_a_b = T_world_a.linear().transpose() * T_world_b.linear();
    const Eigen::Vector3d p_a_b =
        T_world_a.linear().transpose() * (T_world_b.translation() - T_world_a.translation());
    if (findIntersectingTriangles(*a.search_tree, *b.search_tree, R_a_b, p_a_b,
                                  kTriangleSearchBudget)) {
      return true;
    }
  }
  data.result.clear();
  return fcl::collide(a.geometry.get(), T_world_a, b.geometry.get(), T_world_b, data.request,
                      data.result) > 0;
}

bool CollisionChecker::bodiesCollide(const CollisionPair& pair, Scratch::Data& data) const {
  const Body& a = bodies_[pair.body_a];
  const Body& b = bodies_[pair.body_b];
  const Eigen::Isometry3d& T_a = data.T_world_body[pair.body_a];
  const Eigen::Isometry3d& T_b = data.T_world_body[pair.body_b];
  const double reach = a.bound + b.bound;
  if (options_.bounding_spheres &&
      (placedOnce(data.body_center, data.body_stamp, pair.body_a, data.sample, T_a, a.center) -
       placedOnce(data.body_center, data.body_stamp, pair.body_b, data.sample, T_b, b.center))
              .squaredNorm() >= reach * reach) {
    return false;
  }
  for (const Shape& shape_a : a.shapes) {
    for (const Shape& shape_b : b.shapes) {
      if (shapesCollide(shape_a, shape_b, data, pair.body_a, pair.body_b)) return true;
    }
  }
  return false;
}

bool CollisionChecker::collides(std::size_t pair, Scratch& scratch) const {
  return bodiesCollide(pairs_.at(pair), *scratch.data_);
}

std::uint32_t CollisionChecker::label(const double* q, Scratch& scratch) const {
  return label(q, robot_.T_world_base, scratch);
}

std::uint32_t CollisionChecker::label(const double* q, const Eigen::Isometry3d& T_world_base,
                                      Scratch& scratch) const {
  Scratch::Data& data = *scratch.data_;
  computePoses(q, T_world_base, data);
  for (const CollisionPair& pair : pairs_) {
    if (bodiesCollide(pair, data)) return pair.label;  // pairs_ is ordered by label
  }
  return kLabelFree;
}

std::uint32_t CollisionChecker::label(const Eigen::VectorXd& q) const {
  robot_.checkSize(q);
  Scratch scratch;
  return label(q.data(), scratch);
}

std::vector<PairReport> CollisionChecker::report(const Eigen::VectorXd& q) const {
  robot_.checkSize(q);
  Scratch scratch;
  Scratch::Data& data = *scratch.data_;
  computePoses(q.data(), robot_.T_world_base, data);
  std::vector<PairReport> reports;
  for (const CollisionPair& pair : pairs_) {
    PairReport report;
    report.body_a = bodies_[pair.body_a].name;
    report.body_b = bodies_[pair.body_b].name;
    report.label = pair.label;
    report.distance = std::numeric_limits<double>::infinity();
    const Eigen::Isometry3d& T_a = data.T_world_body[pair.body_a];
    const Eigen::Isometry3d& T_b = data.T_world_body[pair.body_b];
    for (const Shape& a : bodies_[pair.body_a].shapes) {
      for (const Shape& b : bodies_[pair.body_b].shapes) {
        // The same decision as label(); the distance is for the reader.
        const bool colliding = shapesCollide(a, b, data, pair.body_a, pair.body_b);
        report.colliding = report.colliding || colliding;
        double distance = 0.0;
        bool depth_known = true;
        if (a.swept && b.swept) {
          distance = std::sqrt(segmentDistanceSquared(T_a * a.p_from, T_a * a.p_to, T_b * b.p_from,
                                                      T_b * b.p_to)) -
                     a.radius - b.radius;
        } else if (colliding) {
          fcl::CollisionRequest<double> request(100, true);
          fcl::CollisionResult<double> result;
          fcl::collide(a.geometry.get(), T_a * a.T_body_shape, b.geometry.get(),
                       T_b * b.T_body_shape, request, result);
          double depth = 0.0;
          for (std::size_t k = 0; k < result.numContacts(); ++k)
            depth = std::max(depth, result.getContact(k).penetration_depth);
          depth_known = a.type != ShapeType::kMesh && b.type != ShapeType::kMesh;
          distance = depth_known ? -depth : 0.0;
        } else {
          fcl::DistanceRequest<double> request;
          request.gjk_solver_type = fcl::GST_INDEP;  // as clearance(): see shapeClearance()
          fcl::DistanceResult<double> result;
          distance =
              std::max(0.0, fcl::distance(a.geometry.get(), T_a * a.T_body_shape, b.geometry.get(),
                                          T_b * b.T_body_shape, request, result));
        }
        if (distance < report.distance) {
          report.distance = distance;
          report.depth_known = depth_known;
        }
      }
    }
    reports.push_back(report);
  }
  return reports;
}

void CollisionChecker::place(const double* q, const Eigen::Isometry3d& T_world_base,
                             Scratch& scratch) const {
  computePoses(q, T_world_base, *scratch.data_);
}

const Eigen::Isometry3d& CollisionChecker::bodyPose(int body, const Scratch& scratch) const {
  return scratch.data_->T_world_body.at(body);
}

CollisionChecker::BodySphere CollisionChecker::bodySphere(int body) const {
  const Body& b = bodies_.at(body);
  return {b.center, b.bound};
}

double CollisionChecker::shapeClearance(const Shape& a, const Shape& b, double cap,
                                        Scratch::Data& data, int body_a, int body_b) const {
  constexpr double kFclTolerance = 1e-6;  // FCL's GJK distance tolerance (DistanceRequest)
  const Eigen::Isometry3d& T_a = data.T_world_body[body_a];
  const Eigen::Isometry3d& T_b = data.T_world_body[body_b];
  const double apart = (T_a * a.center - T_b * b.center).norm() - a.bound - b.bound;
  if (apart >= cap) return cap;
  if (a.lss && b.lss) {  // exact for two capsules, a lower bound through bounding capsules
    double s = 0.0, t = 0.0;
    const double d = std::sqrt(segmentDistanceSquared(T_a * a.p_from, T_a * a.p_to, T_b * b.p_from,
                                                      T_b * b.p_to, s, t)) -
                     a.radius - b.radius;
    if (a.swept && b.swept) return std::clamp(d, 0.0, cap);
    if (d >= cap) return cap;
    // A capsule nearest to the side of a cylinder (not an end) is as far from the cylinder as
    // from its bounding capsule: the nearest axis point's offset is radial.
    constexpr double kInside = 1e-9;
    if (d > 0.0 &&
        ((a.swept && b.type == ShapeType::kCylinder && t > kInside && t < 1 - kInside) ||
         (b.swept && a.type == ShapeType::kCylinder && s > kInside && s < 1 - kInside))) {
      return std::min(d, cap);
    }
  }
  if (shapesCollide(a, b, data, body_a, body_b)) return 0.0;
  // FCL's own GJK (GST_INDEP): the default libccd solver over-estimates a capsule-box distance
  // by up to about 1e-3 of its size, which the tolerance below would not cover.
  fcl::DistanceRequest<double> request;
  request.gjk_solver_type = fcl::GST_INDEP;
  fcl::DistanceResult<double> result;
  const double d = fcl::distance(a.geometry.get(), T_a * a.T_body_shape, b.geometry.get(),
                                 T_b * b.T_body_shape, request, result);
  return std::clamp(d - kFclTolerance, 0.0, cap);
}

double CollisionChecker::clearance(std::size_t pair, double cap, Scratch& scratch) const {
  Scratch::Data& data = *scratch.data_;
  const CollisionPair& p = pairs_.at(pair);
  const Body& a = bodies_[p.body_a];
  const Body& b = bodies_[p.body_b];
  const Eigen::Isometry3d& T_a = data.T_world_body[p.body_a];
  const Eigen::Isometry3d& T_b = data.T_world_body[p.body_b];
  if ((T_a * a.center - T_b * b.center).norm() - a.bound - b.bound >= cap) return cap;
  double distance = cap;
  for (const Shape& shape_a : a.shapes) {
    for (const Shape& shape_b : b.shapes) {
      distance =
          std::min(distance, shapeClearance(shape_a, shape_b, distance, data, p.body_a, p.body_b));
      if (distance <= 0.0) return 0.0;
    }
  }
  return distance;
}

const char* labelName(std::uint32_t label) {
  switch (label) {
    case kLabelFree:
      return "free";
    case kLabelLinkLink:
      return "link-link";
    case kLabelToolLink:
      return "tool-link";
    case kLabelEnvironment:
      return "environment";
    default:
      return "unknown";
  }
}

std::uint32_t reportedLabel(const std::vector<PairReport>& pairs) {
  std::uint32_t label = kLabelFree;
  for (const PairReport& pair : pairs) {
    if (pair.colliding && (label == kLabelFree || pair.label < label)) label = pair.label;
  }
  return label;
}

std::vector<PairReport> pairsToShow(std::vector<PairReport> pairs, bool all) {
  std::sort(pairs.begin(), pairs.end(),
            [](const PairReport& a, const PairReport& b) { return a.distance < b.distance; });
  const bool free = reportedLabel(pairs) == kLabelFree;
  std::vector<PairReport> shown;
  for (const PairReport& pair : pairs) {
    if (all || pair.colliding || (free && shown.empty())) shown.push_back(pair);
  }
  return shown;
}

}  // namespace mcws
