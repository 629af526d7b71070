// The 3-D scene of the study report: the line, the workspace at the chosen stop, the reach map,
// the targets, the robot's collision bodies and the planned paths as animations.
#include <algorithm>
#include <cmath>

#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/reach/reach_map.h"
#include "mcws/study/detail/study_stages.h"

namespace mcws::detail {

namespace {

constexpr int kAround = 16;  ///< vertices around a tessellated circle
constexpr int kRings = 4;    ///< latitude rings of a half sphere
constexpr int kFrames = 60;  ///< frames of a path's animation

using Positions = std::vector<float>;
using Triangles = std::vector<std::uint32_t>;

void addVertex(Positions& positions, const Eigen::Vector3d& p) {
  for (int k = 0; k < 3; ++k) positions.push_back(static_cast<float>(p[k]));
}

std::uint32_t vertexCount(const Positions& positions) {
  return static_cast<std::uint32_t>(positions.size() / 3);
}

/// Rings of `kAround` vertices joined into a band (ring r to ring r + 1), closed at both ends by
/// the first and last ring's fans around their centres.
void addRings(const std::vector<std::vector<Eigen::Vector3d>>& rings, const Eigen::Vector3d& first,
              const Eigen::Vector3d& last, Positions& positions, Triangles& triangles) {
  const std::uint32_t base = vertexCount(positions);
  for (const auto& ring : rings)
    for (const Eigen::Vector3d& p : ring) addVertex(positions, p);
  const auto at = [&](std::size_t r, int k) {
    return base + static_cast<std::uint32_t>(r * kAround + static_cast<std::size_t>(k % kAround));
  };
  for (std::size_t r = 0; r + 1 < rings.size(); ++r) {
    for (int k = 0; k < kAround; ++k) {
      triangles.insert(triangles.end(), {at(r, k), at(r, k + 1), at(r + 1, k + 1)});
      triangles.insert(triangles.end(), {at(r, k), at(r + 1, k + 1), at(r + 1, k)});
    }
  }
  const std::uint32_t a = vertexCount(positions);
  addVertex(positions, first);
  addVertex(positions, last);
  for (int k = 0; k < kAround; ++k) {
    triangles.insert(triangles.end(), {a, at(0, k + 1), at(0, k)});
    triangles.insert(triangles.end(),
                     {a + 1, at(rings.size() - 1, k), at(rings.size() - 1, k + 1)});
  }
}

/// A capsule from a to b of radius r (a sphere when a == b), in the frame T.
void addCapsule(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double r,
                const Eigen::Isometry3d& T, Positions& positions, Triangles& triangles) {
  Eigen::Vector3d axis = b - a;
  const double length = axis.norm();
  axis = length > 0.0 ? Eigen::Vector3d(axis / length) : Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d u = axis.unitOrthogonal(), v = axis.cross(u);
  std::vector<std::vector<Eigen::Vector3d>> rings;
  for (int i = -kRings + 1; i <= kRings - 1; ++i) {
    const double lat = M_PI / 2 * i / kRings;
    const Eigen::Vector3d centre = (i <= 0 ? a : b) + axis * r * std::sin(lat);
    for (int copy = 0; copy < (i == 0 ? 2 : 1); ++copy) {
      std::vector<Eigen::Vector3d> ring;
      const Eigen::Vector3d c = copy == 1 ? Eigen::Vector3d(b) : centre;
      for (int k = 0; k < kAround; ++k) {
        const double phi = 2 * M_PI * k / kAround;
        ring.push_back(T * (c + r * std::cos(lat) * (std::cos(phi) * u + std::sin(phi) * v)));
      }
      rings.push_back(ring);
    }
  }
  addRings(rings, T * (a - axis * r), T * (b + axis * r), positions, triangles);
}

void addBox(const Eigen::Vector3d& size, const Eigen::Isometry3d& T, Positions& positions,
            Triangles& triangles) {
  const std::uint32_t base = vertexCount(positions);
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d corner((k & 1 ? 0.5 : -0.5) * size.x(), (k & 2 ? 0.5 : -0.5) * size.y(),
                                 (k & 4 ? 0.5 : -0.5) * size.z());
    addVertex(positions, T * corner);
  }
  const std::uint32_t faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6},
                                      {0, 1, 4}, {1, 5, 4}, {2, 6, 3}, {3, 6, 7},
                                      {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& face : faces)
    for (std::uint32_t k : face) triangles.push_back(base + k);
}

void addCylinder(double radius, double length, const Eigen::Isometry3d& T, Positions& positions,
                 Triangles& triangles) {
  std::vector<std::vector<Eigen::Vector3d>> rings(2);
  for (int end = 0; end < 2; ++end) {
    for (int k = 0; k < kAround; ++k) {
      const double phi = 2 * M_PI * k / kAround;
      rings[end].push_back(T * Eigen::Vector3d(radius * std::cos(phi), radius * std::sin(phi),
                                               (end ? 0.5 : -0.5) * length));
    }
  }
  addRings(rings, T * Eigen::Vector3d(0, 0, -0.5 * length), T * Eigen::Vector3d(0, 0, 0.5 * length),
           positions, triangles);
}

/// The triangles of a collision shape placed by T (its body's frame to the mesh's).
void addShape(const ShapeSpec& shape, const Eigen::Isometry3d& T, Positions& positions,
              Triangles& triangles) {
  const Eigen::Isometry3d placed = T * shape.T_body_shape;
  switch (shape.type) {
    case ShapeType::kCapsule:
    case ShapeType::kSphere:
      addCapsule(shape.p_from, shape.p_to, shape.radius, T, positions, triangles);
      break;
    case ShapeType::kBox:
      addBox(shape.size, placed, positions, triangles);
      break;
    case ShapeType::kCylinder:
      addCylinder(shape.radius, shape.length, placed, positions, triangles);
      break;
    case ShapeType::kMesh: {
      const std::uint32_t base = vertexCount(positions);
      for (const auto& v : shape.mesh->vertices) addVertex(positions, placed * v);
      for (const auto& t : shape.mesh->triangles)
        for (int k = 0; k < 3; ++k) triangles.push_back(base + static_cast<std::uint32_t>(t[k]));
      break;
    }
  }
}

report::Layer pointsLayer(const std::string& name, const pcl::PointCloud<pcl::PointXYZ>& cloud,
                          const Eigen::Vector3d& move) {
  report::Layer layer;
  layer.name = name;
  layer.kind = report::Layer::Kind::kPoints;
  for (const auto& p : cloud) addVertex(layer.positions, p.getVector3fMap().cast<double>() + move);
  return layer;
}

/// Every body of the robot's collision model: base, links, tool.
std::vector<const BodySpec*> robotBodies(const CollisionModel& model) {
  std::vector<const BodySpec*> bodies;
  for (const BodySpec& link : model.links) bodies.push_back(&link);
  bodies.push_back(&model.tool);
  return bodies;
}

/// The body poses of the robot at q: base, links, tool (in the flange frame).
std::vector<Eigen::Isometry3d> bodyPoses(const Robot& robot, const Eigen::VectorXd& q) {
  const ChainPoses poses = chainPoses(robot, q);
  std::vector<Eigen::Isometry3d> out{robot.T_world_base};
  out.insert(out.end(), poses.T_world_link.begin(), poses.T_world_link.end());
  out.push_back(poses.T_world_flange);
  return out;
}

void addPoses(const std::vector<Eigen::Isometry3d>& poses, std::vector<float>& out) {
  for (const Eigen::Isometry3d& T : poses) {
    const Eigen::Matrix4d m = T.matrix();
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) out.push_back(static_cast<float>(m(r, c)));
  }
}

/// The chosen path of a planned target, interpolated in joint space at kFrames frames.
report::Animation pathAnimation(const StudyState& state, const PlannedTarget& planned) {
  report::Animation animation;
  animation.name = "path to " + state.study->targets[planned.target].name;
  const SwayPlanningResult& result = planned.result;
  const std::optional<std::size_t> round = result.accepted ? result.accepted : result.validated;
  if (!round || !result.rounds[*round].best) return animation;
  const PathSafety& path = *result.rounds[*round].best;
  const Robot& robot = planned.scenario.problem.robot;
  Robot moved = robot;
  moved.T_world_base.pretranslate(stopMove(*state.study, result.rounds[*round].base_offset));
  const Eigen::VectorXd& scale = planned.scenario.problem.roadmap.joint_scale;
  std::vector<double> along{0.0};
  for (std::size_t k = 1; k < path.waypoints.size(); ++k)
    along.push_back(
        along.back() +
        (scale.array() * (path.waypoints[k] - path.waypoints[k - 1]).array()).matrix().norm());
  std::size_t segment = 0;
  for (int f = 0; f < kFrames; ++f) {
    const double d = along.back() * f / (kFrames - 1);
    while (segment + 2 < along.size() && along[segment + 1] < d) ++segment;
    const std::size_t next = std::min(segment + 1, path.waypoints.size() - 1);
    const double span = along[next] - along[segment];
    const double t = span > 0.0 ? std::clamp((d - along[segment]) / span, 0.0, 1.0) : 0.0;
    const Eigen::VectorXd q =
        path.waypoints[segment] + t * (path.waypoints[next] - path.waypoints[segment]);
    addPoses(bodyPoses(moved, q), animation.poses);
    animation.parameter.push_back(static_cast<float>(d));
  }
  animation.frames = kFrames;
  animation.parameter_label = "path length D";
  animation.parameter_unit = "scaled joint distance";
  return animation;
}

report::Layer lineLayer(const Study& study) {
  report::Layer line;
  line.name = "line";
  line.kind = report::Layer::Kind::kMesh;
  line.color = {0.35f, 0.35f, 0.4f};
  for (const BodySpec& body : lineBodies(study))
    for (const ShapeSpec& shape : body.shapes)
      addShape(shape, Eigen::Isometry3d::Identity(), line.positions, line.triangles);
  return line;
}

report::Layer reachLayer(const StudyState& state, const Eigen::Vector3d& move) {
  report::Layer reach;
  reach.name = "reach map";
  reach.kind = report::Layer::Kind::kVoxels;
  reach.size = static_cast<float>(state.study->reach.grid.resolution);
  reach.value_label = "reachability";
  reach.value_unit = "fraction";
  reach.visible = false;
  for (const ReachPoint& p : reachPoints(state.map)) {
    addVertex(reach.positions, p.getVector3fMap().cast<double>() + move);
    reach.values.push_back(p.reachability);
  }
  return reach;
}

}  // namespace

report::Scene studyScene(const StudyState& state) {
  const Study& study = *state.study;
  const std::size_t best = static_cast<std::size_t>(state.best);
  const Eigen::Vector3d move = stopMove(study, study.stops[best]);
  report::Scene scene;
  scene.length_unit = unitName(study.problem.robot.length_unit);
  scene.layers.push_back(lineLayer(study));
  report::Layer envelope;
  envelope.name = "envelope";
  envelope.kind = report::Layer::Kind::kMesh;
  envelope.opacity = 0.35f;
  envelope.color = {0.2f, 0.5f, 0.9f};
  for (const Eigen::Vector3d& v : state.envelope.mesh.vertices)
    addVertex(envelope.positions, v + move);
  for (const auto& t : state.envelope.mesh.triangles)
    envelope.triangles.insert(envelope.triangles.end(), t.begin(), t.end());
  scene.layers.push_back(envelope);
  scene.layers.push_back(pointsLayer("boundary points", state.boundary, move));
  scene.layers.back().visible = false;
  scene.layers.push_back(reachLayer(state, move));
  report::Layer targets;
  targets.name = "targets";
  targets.kind = report::Layer::Kind::kPoints;
  targets.value_label = "reached at the chosen stop";
  targets.value_unit = "1 yes, 0 no";
  targets.size = 2.0f * static_cast<float>(study.reach.grid.resolution);
  for (std::size_t t = 0; t < study.targets.size(); ++t) {
    addVertex(targets.positions, study.targets[t].target.pose.translation());
    targets.values.push_back(state.per_stop[best][t].reached ? 1.0f : 0.0f);
  }
  scene.layers.push_back(targets);
  for (const BodySpec* body : robotBodies(study.problem.collision)) {
    report::Body drawn;
    drawn.name = body->name;
    for (const ShapeSpec& shape : body->shapes)
      addShape(shape, Eigen::Isometry3d::Identity(), drawn.positions, drawn.triangles);
    scene.bodies.push_back(drawn);
  }
  for (const PlannedTarget& planned : state.planned) {
    report::Animation animation = pathAnimation(state, planned);
    if (animation.frames > 0) scene.animations.push_back(std::move(animation));
  }
  if (scene.animations.empty()) {  // the page places the bodies by an animation's frame 0
    Robot moved = study.problem.robot;
    moved.T_world_base.pretranslate(move);
    report::Animation still;
    still.name = "the robot at the chosen stop, start configuration";
    still.frames = 1;
    addPoses(bodyPoses(moved, study.problem.start), still.poses);
    scene.animations.push_back(std::move(still));
  }
  return scene;
}

}  // namespace mcws::detail
