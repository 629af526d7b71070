// Mesh collision (FCL's OBBRSS trees) against a brute-force test of every triangle pair, over
// 2000 random TA1400 configurations: zero disagreements.
#include <gtest/gtest.h>

#include <fstream>

#include "mcws/collision/collision_checker.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/robot_yaml.h"
#include "mcws/sampling/sampler.h"
#include "test_support.h"

namespace mcws {
namespace {

using Triangle = std::array<Eigen::Vector3d, 3>;

/// Does segment [p, q] cross triangle t? Moeller and Trumbore (1997) for a segment; a segment in
/// the triangle's plane counts as missing it (coplanar contacts have probability zero here).
bool segmentHitsTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Triangle& t) {
  const Eigen::Vector3d d = q - p, e1 = t[1] - t[0], e2 = t[2] - t[0];
  const Eigen::Vector3d h = d.cross(e2);
  const double det = e1.dot(h);
  if (std::abs(det) < 1e-300) return false;
  const Eigen::Vector3d s = p - t[0];
  const double u = s.dot(h) / det;
  if (u < 0.0 || u > 1.0) return false;
  const Eigen::Vector3d k = s.cross(e1);
  const double v = d.dot(k) / det;
  if (v < 0.0 || u + v > 1.0) return false;
  const double along = e2.dot(k) / det;
  return along >= 0.0 && along <= 1.0;
}

/// Two triangles in general position intersect exactly when an edge of one crosses the other.
bool trianglesIntersect(const Triangle& a, const Triangle& b) {
  for (int i = 0; i < 3; ++i) {
    if (segmentHitsTriangle(a[i], a[(i + 1) % 3], b)) return true;
    if (segmentHitsTriangle(b[i], b[(i + 1) % 3], a)) return true;
  }
  return false;
}

/// A capsule mesh along z from 0 to `length` (as scripts/make_capsule_mesh.py), ASCII STL.
void writeCapsuleStl(const std::string& path, double radius, double length, int segments,
                     int rings) {
  std::vector<std::pair<double, double>> rows;  // (z, r)
  for (int k = 0; k <= rings; ++k) {
    const double a = -M_PI / 2 + M_PI / 2 * k / rings;
    rows.emplace_back(radius * std::sin(a), radius * std::cos(a));
  }
  rows.emplace_back(length, radius);
  for (int k = 1; k <= rings; ++k) {
    const double a = M_PI / 2 * k / rings;
    rows.emplace_back(length + radius * std::sin(a), radius * std::cos(a));
  }
  auto at = [&](std::size_t row, int j) {
    const double angle = 2 * M_PI * j / segments;
    return Eigen::Vector3d(rows[row].second * std::cos(angle), rows[row].second * std::sin(angle),
                           rows[row].first);
  };
  std::ofstream out(path);
  out.precision(17);
  out << "solid capsule\n";
  auto facet = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    out << "facet normal 0 0 0\nouter loop\n";
    for (const auto* v : {&a, &b, &c})
      out << "vertex " << v->x() << " " << v->y() << " " << v->z() << "\n";
    out << "endloop\nendfacet\n";
  };
  for (std::size_t r = 0; r + 1 < rows.size(); ++r) {
    for (int j = 0; j < segments; ++j) {
      const int n = (j + 1) % segments;
      if (rows[r].second > 1e-12)
        facet(at(r, j), at(r, n), at(r + 1, rows[r + 1].second > 1e-12 ? n : 0));
      if (rows[r + 1].second > 1e-12)
        facet(at(r, rows[r].second > 1e-12 ? j : 0), at(r + 1, n), at(r + 1, j));
    }
  }
  out << "endsolid capsule\n";
}

TEST(MeshCollision, AgreesWithBruteForceOverEveryTrianglePairIn2000Configurations) {
  // robots/ta1400_mesh.yaml with coarse meshes of the same capsules (13 to 14 segments around, so
  // brute force stays fast; sizes as in the mesh file names' capsules of ta1400.yaml).
  test::TempDir dir;
  const std::map<std::string, std::pair<double, double>> capsules{
      {"base", {180, 90}},         {"j1_turret", {150, 150}}, {"j1_shoulder", {100, 200}},
      {"j2_upper_arm", {90, 560}}, {"j3_elbow", {100, 180}},  {"j3_offset", {90, 130}},
      {"j3_forearm", {85, 320}},   {"j4_forearm", {70, 170}}, {"j5_wrist", {65, 120}},
      {"j6_flange", {45, 25}},     {"torch_body", {30, 110}}, {"torch_neck", {14, 119.897}}};
  for (const auto& [name, size] : capsules)
    writeCapsuleStl(dir.file(name + ".stl"), size.first, size.second, 13, 3);
  std::string text = test::readFile(test::robotPath("ta1400_mesh"));
  const std::string mesh_dir = "meshes/ta1400/", coarse_dir = dir.file("");
  for (auto at = text.find(mesh_dir); at != std::string::npos;
       at = text.find(mesh_dir, at + coarse_dir.size())) {
    text.replace(at, mesh_dir.size(), coarse_dir);
  }
  const std::string path = dir.file("ta1400_coarse.yaml");
  test::writeFile(path, text);
  const Robot robot = loadRobot(path);
  const CollisionModel model = loadCollisionModel(robot, path);
  const CollisionChecker checker(robot, model);

  // Every body's triangles in its own frame.
  std::vector<const BodySpec*> bodies;
  for (const BodySpec& link : model.links) bodies.push_back(&link);
  bodies.push_back(&model.tool);
  std::vector<std::vector<Triangle>> local(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    for (const ShapeSpec& shape : bodies[b]->shapes) {
      ASSERT_EQ(shape.type, ShapeType::kMesh);
      for (const auto& t : shape.mesh->triangles) {
        local[b].push_back({shape.T_body_shape * shape.mesh->vertices[t[0]],
                            shape.T_body_shape * shape.mesh->vertices[t[1]],
                            shape.T_body_shape * shape.mesh->vertices[t[2]]});
      }
    }
  }

  RobotSamplerOptions options;
  options.seed = 2026;
  const RobotSampler sampler(robot, options);
  CollisionChecker::Scratch scratch;
  int disagreements = 0, collisions = 0;
  for (int i = 0; i < 2000 / test::kSanitizerShrink; ++i) {  // 250 under the sanitizers
    Eigen::VectorXd q(6);
    sampler.jointValues(i, q.data());
    const ChainPoses poses = chainPoses(robot, q);
    std::vector<std::vector<Triangle>> world(bodies.size());
    std::vector<std::vector<Eigen::AlignedBox3d>> boxes(bodies.size());
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      const Eigen::Isometry3d T = b == 0                  ? robot.T_world_base
                                  : b + 1 < bodies.size() ? poses.T_world_link[b - 1]
                                                          : poses.T_world_flange;
      for (const Triangle& t : local[b]) {
        world[b].push_back({T * t[0], T * t[1], T * t[2]});
        Eigen::AlignedBox3d box(world[b].back()[0]);
        box.extend(world[b].back()[1]).extend(world[b].back()[2]);
        boxes[b].push_back(box);
      }
    }
    std::uint32_t expected = kLabelFree;
    for (const CollisionPair& pair : checker.pairs()) {
      if (expected != kLabelFree) break;  // pairs come in label order: the first hit is lowest
      const auto a = static_cast<std::size_t>(pair.body_a),
                 b = static_cast<std::size_t>(pair.body_b);
      bool hit = false;
      for (std::size_t s = 0; s < world[a].size() && !hit; ++s) {
        for (std::size_t t = 0; t < world[b].size() && !hit; ++t) {
          // A box test first only skips pairs that cannot meet; every other pair is tested.
          hit = boxes[a][s].intersects(boxes[b][t]) && trianglesIntersect(world[a][s], world[b][t]);
        }
      }
      if (hit) expected = pair.label;
    }
    const std::uint32_t got = checker.label(q.data(), scratch);
    disagreements += got != expected;
    collisions += expected != kLabelFree;
    EXPECT_EQ(got, expected) << "configuration " << i << ": " << q.transpose();
  }
  EXPECT_EQ(disagreements, 0);
  const int n = 2000 / test::kSanitizerShrink;
  EXPECT_GT(collisions, n / 10);  // both outcomes are well represented
  EXPECT_LT(collisions, n - n / 10);
}

}  // namespace
}  // namespace mcws
