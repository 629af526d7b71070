// The mesh broad phase of CollisionChecker (bounding spheres and capsules, the search for one
// intersecting triangle pair before fcl::collide) against the plain FCL mesh-mesh check of every
// pair (CollisionCheckerOptions with both switched off), sample by sample; the bounds against the
// vertices they must contain, by closed-form distances; a hand-built two-box robot whose boxes
// overlap, nearly touch, are far apart or one inside the other.
#include <gtest/gtest.h>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>

#include <fstream>
#include <random>

#include "mcws/collision/collision_checker.h"
#include "mcws/collision/mesh_bounds.h"
#include "mcws/collision/mesh_witness.h"
#include "mcws/kinematics/robot_yaml.h"
#include "mcws/sampling/sampler.h"
#include "test_support.h"

namespace mcws {
namespace {

/// The checker without any broad phase or shortcut: every shape pair goes to fcl::collide.
CollisionCheckerOptions plainFcl() {
  CollisionCheckerOptions options;
  options.bounding_spheres = false;
  options.triangle_search = false;
  return options;
}

/// Distance from p to the segment [a, b], in closed form.
double pointSegmentDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double t =
      d.squaredNorm() > 0 ? std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
  return (p - (a + t * d)).norm();
}

/// A box of half sizes `half` centred at the origin, each face cut into n x n squares of two
/// triangles (12 n^2 triangles, so that the trees are deep), ASCII STL.
void writeGridBoxStl(const std::string& path, const Eigen::Vector3d& half, int n) {
  std::ofstream out(path);
  out.precision(17);
  out << "solid box\n";
  auto facet = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    out << "facet normal 0 0 0\nouter loop\n";
    for (const auto* v : {&a, &b, &c})
      out << "vertex " << v->x() << " " << v->y() << " " << v->z() << "\n";
    out << "endloop\nendfacet\n";
  };
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (double side : {-1.0, 1.0}) {
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          auto corner = [&](int di, int dj) {
            Eigen::Vector3d p;
            p[axis] = side * half[axis];
            p[u] = half[u] * (-1.0 + 2.0 * (i + di) / n);
            p[v] = half[v] * (-1.0 + 2.0 * (j + dj) / n);
            return p;
          };
          facet(corner(0, 0), corner(1, 0), corner(1, 1));
          facet(corner(0, 0), corner(1, 1), corner(0, 1));
        }
      }
    }
  }
  out << "endsolid box\n";
}

/// A robot turning about z (j1, no shapes) and sliding along z (j2, by d [mm]) through a fixed
/// base: the base is a box 300 x 300 x 300 mm from z = -450 to -150, link j2 a cube of side 100
/// centred on its frame (z = d). The base and j2 are not adjacent, so they are checked.
struct TwoBoxRobot {
  test::TempDir dir;
  Robot robot;
  CollisionModel model;
  TwoBoxRobot() {
    writeGridBoxStl(dir.file("base.stl"), Eigen::Vector3d(150, 150, 150), 8);
    writeGridBoxStl(dir.file("cube.stl"), Eigen::Vector3d(50, 50, 50), 8);
    const std::string path = dir.file("two_boxes.yaml");
    test::writeFile(path, R"(name: two_boxes
units: {length: mm, angle: deg}
convention: standard
joints:
  - {name: j1, type: revolute, a: 0, alpha: 0, d: 0, limits: [-180, 180]}
  - {name: j2, type: prismatic, a: 0, alpha: 0, d: 0, theta: 0, limits: [-500, 400]}
collision:
  links:
    base: [{type: mesh, file: base.stl, xyz: [0, 0, -300]}]
    j2: [{type: mesh, file: cube.stl}]
)");
    robot = loadRobot(path);
    model = loadCollisionModel(robot, path);
  }
};

TEST(MeshBroadPhase, TwoBoxesOverlapTouchOrNotAsWorkedByHand) {
  const TwoBoxRobot boxes;
  const CollisionChecker checker(boxes.robot, boxes.model);
  const CollisionChecker plain(boxes.robot, boxes.model, plainFcl());
  ASSERT_EQ(checker.pairs().size(), 1u);  // base and j2
  // The cube spans z = d - 50 .. d + 50; the base's top face is z = -150, its bottom -450.
  struct Case {
    double q1_deg, d;
    std::uint32_t label;
    const char* what;
  };
  const Case cases[] = {
      {30, -110, kLabelLinkLink, "the cube 10 mm into the base's top face"},
      {0, -101, kLabelLinkLink, "1 mm in, faces parallel"},
      {45, -99.999, kLabelFree, "1 um above the top face"},
      {10, -50, kLabelFree, "50 mm above"},
      {0, 400, kLabelFree, "far"},
      // Wholly inside the base (|x|, |y| <= 71 < 150, z -350 .. -250): no surfaces cross, and a
      // mesh check tests surfaces (FCL's meshes are shells).
      {20, -300, kLabelFree, "inside the base"},
      {0, -440, kLabelLinkLink, "through the base's bottom face"},
  };
  for (const Case& c : cases) {
    const Eigen::Vector2d q(c.q1_deg * M_PI / 180.0, c.d);
    EXPECT_EQ(plain.label(q), c.label) << c.what;  // the hand-worked answer is FCL's
    EXPECT_EQ(checker.label(q), c.label) << c.what;
  }
}

/// Labels of `checker` and of the plain FCL check over n samples of `robot`: disagreements, and
/// the count of colliding samples.
std::pair<int, int> compareWithPlainFcl(const Robot& robot, const CollisionModel& model, int n) {
  const CollisionChecker checker(robot, model);
  const CollisionChecker plain(robot, model, plainFcl());
  RobotSamplerOptions options;
  options.seed = 37;
  const RobotSampler sampler(robot, options);
  CollisionChecker::Scratch scratch, plain_scratch;
  int disagreements = 0, collisions = 0;
  double q[kMaxJoints];
  for (int i = 0; i < n; ++i) {
    sampler.jointValues(i, q);
    const std::uint32_t expected = plain.label(q, plain_scratch);
    const std::uint32_t got = checker.label(q, scratch);
    EXPECT_EQ(got, expected) << "sample " << i;
    disagreements += got != expected;
    collisions += expected != kLabelFree;
  }
  return {disagreements, collisions};
}

TEST(MeshBroadPhase, LabelsEqualThePlainFclCheckSampleBySampleOnTwoBoxes) {
  // j2 slides over [-500, 400]: the cube is far, near, touching, inside and through the base;
  // it crosses the base's top face for d in (-200, -100), its bottom face for d in (-500, -400).
  const TwoBoxRobot boxes;
  const int n = 4000 / test::kSanitizerShrink;
  const auto [disagreements, collisions] = compareWithPlainFcl(boxes.robot, boxes.model, n);
  EXPECT_EQ(disagreements, 0);
  EXPECT_GT(collisions, n / 6);  // 200 of 900 mm: 22 %
  EXPECT_LT(collisions, n / 3);
}

TEST(MeshBroadPhase, LabelsEqualThePlainFclCheckSampleBySampleOnTheMeshTa1400) {
  const Robot robot = loadRobot(test::robotPath("ta1400_mesh"));
  const CollisionModel model = loadCollisionModel(robot, test::robotPath("ta1400_mesh"));
  const int n = 3000 / test::kSanitizerShrink;
  const auto [disagreements, collisions] = compareWithPlainFcl(robot, model, n);
  EXPECT_EQ(disagreements, 0);
  EXPECT_GT(collisions, n / 10);  // about a quarter of the TA1400's samples collide
  EXPECT_LT(collisions, n - n / 10);
}

/// Every vertex of every mesh of the mesh TA1400 and of the two boxes, placed in its body.
std::vector<std::vector<Eigen::Vector3d>> meshVertexSets() {
  std::vector<std::vector<Eigen::Vector3d>> sets;
  const Robot robot = loadRobot(test::robotPath("ta1400_mesh"));
  const TwoBoxRobot boxes;
  for (const CollisionModel& model :
       {loadCollisionModel(robot, test::robotPath("ta1400_mesh")), boxes.model}) {
    std::vector<const BodySpec*> bodies{&model.tool};
    for (const BodySpec& link : model.links) bodies.push_back(&link);
    for (const BodySpec* body : bodies) {
      for (const ShapeSpec& shape : body->shapes) {
        sets.emplace_back();
        for (const auto& v : shape.mesh->vertices) sets.back().push_back(shape.T_body_shape * v);
      }
    }
  }
  return sets;
}

TEST(MeshBroadPhase, BoundingCapsulesAndSpheresHoldEveryVertex) {
  const auto sets = meshVertexSets();
  ASSERT_EQ(sets.size(), 14u);  // 12 TA1400 meshes, 2 boxes
  std::mt19937 random(5);
  std::normal_distribution<double> normal;
  auto cloud = sets;
  for (int k = 0; k < 3; ++k) {  // random clouds too, one of them a single point
    cloud.emplace_back();
    for (int i = 0; i < (k == 0 ? 1 : 500); ++i)
      cloud.back().emplace_back(normal(random), 10 * normal(random), 0.1 * normal(random));
  }
  for (std::size_t s = 0; s < cloud.size(); ++s) {
    const BoundingCapsule capsule = boundingCapsule(cloud[s]);
    const BoundingSphere sphere = boundingSphere(cloud[s]);
    double largest = 0.0;
    for (const Eigen::Vector3d& p : cloud[s]) {
      const double d = pointSegmentDistance(p, capsule.p_from, capsule.p_to);
      largest = std::max(largest, d / capsule.radius);
      EXPECT_LE(d, capsule.radius) << "set " << s;
      EXPECT_LE((p - sphere.center).norm(), sphere.radius) << "set " << s;
    }
    // Tight: some point lies on the capsule's surface, to rounding.
    if (capsule.radius > 0) {
      EXPECT_GT(largest, 1 - 1e-9) << "set " << s;
    }
  }
}

TEST(MeshBroadPhase, EverySearchTreeSphereHoldsTheVerticesBelowIt) {
  for (const auto& vertices : meshVertexSets()) {
    // A model of the same triangles as the checker builds: a fan over the first vertex is enough
    // to test the tree's spheres against the vertices each node holds.
    auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSS<double>>>();
    std::vector<fcl::Triangle> triangles;
    for (std::size_t i = 1; i + 1 < vertices.size(); ++i) triangles.emplace_back(0, i, i + 1);
    model->beginModel();
    model->addSubModel(vertices, triangles);
    model->endModel();
    const MeshSearchTree tree(*model);
    ASSERT_EQ(tree.size(), model->getNumBVs());
    // The vertices below each node, gathered from the leaves up (children have larger indices
    // than their parent in FCL's layout, checked here).
    std::vector<std::vector<int>> below(tree.size());
    for (int i = tree.size() - 1; i >= 0; --i) {
      const int child = tree.node(i).first_child;
      if (child < 0) {
        const fcl::Triangle& t = tree.triangle(-(child + 1));
        below[i] = {int(t[0]), int(t[1]), int(t[2])};
      } else {
        ASSERT_GT(child, i);
        below[i] = below[child];
        below[i].insert(below[i].end(), below[child + 1].begin(), below[child + 1].end());
      }
      for (int v : below[i]) {
        EXPECT_LE((tree.vertex(v) - tree.node(i).center).norm(), tree.node(i).radius * (1 + 1e-12));
      }
    }
    EXPECT_EQ(below[0].size(), 3 * triangles.size());
  }
}

}  // namespace
}  // namespace mcws
