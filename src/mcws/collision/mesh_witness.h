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

/// \brief The nodes of a mesh's FCL hierarchy (`fcl::BVHModel<OBBRSS>`: same node numbers, same
/// children), each with its OBB and a bounding sphere, laid out for findIntersectingTriangles().
///
/// A node's sphere is centred on its OBB's centre and holds every vertex of the triangles below
/// it. The tree reads the model's vertices and triangles: the model must outlive it.
class MeshSearchTree {
 public:
  /// \brief One node: its OBB (FCL's) and its sphere, in the mesh's frame [length unit].
  struct Node {
    Eigen::Vector3d center{Eigen::Vector3d::Zero()};    ///< of the OBB and of the sphere
    Eigen::Matrix3d axes{Eigen::Matrix3d::Identity()};  ///< the OBB's axes (columns)
    Eigen::Vector3d extent{Eigen::Vector3d::Zero()};    ///< the OBB's half sizes
    double radius{0.0};                                 ///< the sphere's
    int first_child{0};  ///< as fcl::BVNodeBase: children first_child and first_child + 1;
                         ///< a leaf holds triangle -(first_child + 1)
  };

  /// \param model a built model (endModel() called).
  explicit MeshSearchTree(const fcl::BVHModel<fcl::OBBRSS<double>>& model);

  /// \brief Number of nodes (those of the model); node 0 is the root.
  int size() const { return static_cast<int>(nodes_.size()); }
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
};

/// \brief Looks for a triangle of mesh a and a triangle of mesh b that intersect by
/// `fcl::detail::Intersect<double>::intersect_Triangle`, the test fcl::collide applies to the
/// triangle pairs its traversal reaches.
///
/// Depth first over node pairs, as FCL's traversal (the larger node is split), but a pair is
/// tested by its spheres, then its OBBs (the 15 separating axes of Gottschalk, Lin & Manocha
/// 1996), and of the two children the one whose centre is nearer the other node's is searched
/// first: when the meshes overlap deeply this reaches an intersecting pair in about a hundred node
/// pairs, where FCL's traversal costs several times more.
///
/// True means the meshes collide: fcl::collide, whose traversal reaches every triangle pair whose
/// bounding volumes overlap, finds a pair too. False means nothing: the search gives up after
/// `budget` node pairs, so a pair may have been missed (the caller then asks FCL).
/// \param R_a_b, \param p_a_b mesh b's frame in mesh a's (as FCL's relative transform: the
///   rotation R_a^T R_b and R_a^T (t_b - t_a)) [length unit].
/// \param budget node pairs tested at most.
bool findIntersectingTriangles(const MeshSearchTree& a, const MeshSearchTree& b,
                               const Eigen::Matrix3d& R_a_b, const Eigen::Vector3d& p_a_b,
                               int budget);

}  // namespace mcws
