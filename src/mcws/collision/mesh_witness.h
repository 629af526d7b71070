#pragma once
/// \file
/// \brief A quick search for one pair of intersecting triangles of two meshes: a proof that two
/// meshes collide that is far cheaper than FCL's whole traversal when they overlap deeply
/// (CollisionChecker's shortcut before fcl::collide).

#include <Eigen/Core>
#include <Eigen/StdVector>
#include <vector>

namespace fcl {
class Triangle;
template <typename S>
class OBBRSS;
template <typename BV>
class BVHModel;
}  // namespace fcl

namespace mcws {

/// \brief A bounding sphere per node of a mesh's FCL hierarchy (`fcl::BVHModel<OBBRSS>`, same
/// node numbers, same children), for findIntersectingTriangles().
///
/// A node keeps its OBB and a sphere centred on the OBB's centre that holds every vertex of the
/// triangles below it (a cheap first test). The tree keeps a pointer to the model's vertices and
/// triangles: the model must outlive it.
class MeshSphereTree {
 public:
  /// \param model a built model (endModel() called).
  explicit MeshSphereTree(const fcl::BVHModel<fcl::OBBRSS<double>>& model);

  /// \brief Number of nodes (those of the model).
  int size() const { return static_cast<int>(nodes_.size()); }
  /// \brief Centre of node i's sphere, in the mesh's frame [length unit].
  const Eigen::Vector3d& center(int i) const { return nodes_[i].center; }
  /// \brief Radius of node i's sphere [length unit].
  double radius(int i) const { return nodes_[i].radius; }

  /// \brief Node i's ancestor `levels` levels up (the root when i is not that deep).
  int ancestor(int i, int levels) const;

  /// \brief One node: its OBB (as FCL's) and its sphere.
  struct Node {
    Eigen::Vector3d center{Eigen::Vector3d::Zero()};    ///< of the OBB and of the sphere
    Eigen::Matrix3d axes{Eigen::Matrix3d::Identity()};  ///< the OBB's axes (columns)
    Eigen::Vector3d extent{Eigen::Vector3d::Zero()};    ///< the OBB's half sizes
    double radius{0.0};
    int first_child{0};  ///< as fcl::BVNodeBase: children first_child and first_child + 1;
                         ///< a leaf holds triangle -(first_child + 1)
  };
  const Node& node(int i) const { return nodes_[i]; }
  /// \brief Vertex i of the model [length unit].
  const Eigen::Vector3d& vertex(int i) const;
  /// \brief Triangle i of the model (vertex indices).
  const fcl::Triangle& triangle(int i) const;

 private:
  /// Fills the radius of node i and those below it; appends the triangles below i to `below`.
  void fitRadius(int i, std::vector<int>& below);

  const fcl::BVHModel<fcl::OBBRSS<double>>& model_;
  std::vector<Node, Eigen::aligned_allocator<Node>> nodes_;
  std::vector<int> parents_;  ///< -1 for the root
};

/// \brief Where findIntersectingTriangles() looks first for a pair of meshes: the subtrees
/// (node_a, node_b) that held the last pair it found, a few levels up; -1 for none. A per-pair,
/// per-thread cache: the contact between two links tends to recur in the same region.
struct TriangleSearchHint {
  int node_a{-1}, node_b{-1};
};

/// \brief Looks for a triangle of mesh a and a triangle of mesh b that intersect, by
/// `fcl::detail::Intersect<double>::intersect_Triangle` (the test fcl::collide applies to the
/// triangle pairs its traversal reaches), descending both sphere trees depth first.
///
/// True means the meshes collide: fcl::collide, whose traversal reaches every triangle pair whose
/// bounding volumes overlap, finds a pair too. False means nothing: the search gives up after
/// `budget` node pairs, so a pair may have been missed (the caller then asks FCL).
/// \param R_a_b, \param p_a_b mesh b's frame in mesh a's (as FCL's relative transform: the
///   rotation R_a^T R_b and R_a^T (t_b - t_a)) [length unit].
/// \param budget node pairs tested at most.
/// \param hint where to look first (a few node pairs), updated when a pair is found; may be null.
bool findIntersectingTriangles(const MeshSphereTree& a, const MeshSphereTree& b,
                               const Eigen::Matrix3d& R_a_b, const Eigen::Vector3d& p_a_b,
                               int budget, TriangleSearchHint* hint = nullptr);

}  // namespace mcws
