#include "mcws/collision/mesh_witness.h"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/detail/traversal/collision/intersect.h>

#include <algorithm>
#include <cmath>
#include <tuple>

namespace mcws {

MeshSearchTree::MeshSearchTree(const fcl::BVHModel<fcl::OBBRSS<double>>& model)
    : model_(model), nodes_(static_cast<std::size_t>(model.getNumBVs())) {
  for (int i = 0; i < size(); ++i) {
    const auto& obb = model.getBV(i).bv.obb;
    nodes_[i].center = obb.To;
    nodes_[i].axes = obb.axis;
    nodes_[i].extent = obb.extent;
    nodes_[i].first_child = model.getBV(i).first_child;
  }
  std::vector<int> below;
  if (!nodes_.empty()) fitRadius(0, below);
}

const Eigen::Vector3d& MeshSearchTree::vertex(int i) const { return model_.vertices[i]; }

const fcl::Triangle& MeshSearchTree::triangle(int i) const { return model_.tri_indices[i]; }

void MeshSearchTree::fitRadius(int i, std::vector<int>& below) {
  Node& node = nodes_[i];
  const std::size_t first = below.size();
  if (node.first_child < 0) {
    below.push_back(-(node.first_child + 1));
  } else {
    fitRadius(node.first_child, below);
    fitRadius(node.first_child + 1, below);
  }
  double squared = 0.0;
  for (std::size_t k = first; k < below.size(); ++k) {
    const fcl::Triangle& triangle = model_.tri_indices[below[k]];
    for (int c = 0; c < 3; ++c) {
      squared = std::max(squared, (model_.vertices[triangle[c]] - node.center).squaredNorm());
    }
  }
  node.radius = std::sqrt(squared);
}

namespace {

/// Whether two boxes are apart by one of the 15 separating axes of Gottschalk, Lin & Manocha
/// (1996): box b's axes are the columns of B and its centre is t, in box a's frame; a and b are
/// their half sizes. The absolute rotation is padded by 1e-6, as FCL's obbDisjoint, against
/// parallel axes.
bool boxesApart(const double (&B)[3][3], const double (&t)[3], const Eigen::Vector3d& a,
                const Eigen::Vector3d& b) {
  double Bf[3][3];
  for (int k = 0; k < 3; ++k) {
    for (int l = 0; l < 3; ++l) Bf[k][l] = std::abs(B[k][l]) + 1e-6;
  }
  for (int k = 0; k < 3; ++k) {
    if (std::abs(t[k]) > a[k] + Bf[k][0] * b[0] + Bf[k][1] * b[1] + Bf[k][2] * b[2]) return true;
  }
  for (int l = 0; l < 3; ++l) {
    if (std::abs(t[0] * B[0][l] + t[1] * B[1][l] + t[2] * B[2][l]) >
        b[l] + Bf[0][l] * a[0] + Bf[1][l] * a[1] + Bf[2][l] * a[2]) {
      return true;
    }
  }
  for (int k = 0; k < 3; ++k) {
    const int k1 = k == 2 ? 0 : k + 1, k2 = k == 0 ? 2 : k - 1;
    for (int l = 0; l < 3; ++l) {
      const int l1 = l == 2 ? 0 : l + 1, l2 = l == 0 ? 2 : l - 1;
      if (std::abs(t[k2] * B[k1][l] - t[k1] * B[k2][l]) >
          a[k1] * Bf[k2][l] + a[k2] * Bf[k1][l] + b[l1] * Bf[k][l2] + b[l2] * Bf[k][l1]) {
        return true;
      }
    }
  }
  return false;
}

/// Depth-first search from the node pair (i, j) for a pair of intersecting triangles, `budget`
/// node pairs at most.
bool searchFrom(const MeshSearchTree& a, const MeshSearchTree& b, const Eigen::Matrix3d& R_a_b,
                const Eigen::Vector3d& p_a_b, int i, int j, int budget) {
  // Each step replaces a pair by the two pairs of the larger sphere's children, so the stack
  // holds at most one pair per level of the two trees.
  constexpr int kStack = 256;
  std::pair<int, int> stack[kStack];
  int top = 0;
  stack[top++] = {i, j};
  // Node placed_j of b in a's frame: its centre and axes (columns), kept while the search splits
  // a's nodes against it.
  int placed_j = -1;
  Eigen::Vector3d c_b = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes_b = Eigen::Matrix3d::Zero();
  while (top > 0 && budget-- > 0) {
    std::tie(i, j) = stack[--top];
    const MeshSearchTree::Node& na = a.node(i);
    const MeshSearchTree::Node& nb = b.node(j);
    if (placed_j != j) {
      placed_j = j;
      c_b.noalias() = R_a_b * nb.center + p_a_b;
      axes_b.noalias() = R_a_b * nb.axes;
    }
    const Eigen::Vector3d d = c_b - na.center;
    const double reach = na.radius + nb.radius;
    if (d.squaredNorm() > reach * reach) continue;
    double B[3][3], t[3];
    for (int k = 0; k < 3; ++k) {
      t[k] = na.axes.col(k).dot(d);
      for (int l = 0; l < 3; ++l) B[k][l] = na.axes.col(k).dot(axes_b.col(l));
    }
    if (boxesApart(B, t, na.extent, nb.extent)) continue;
    const bool leaf_i = na.first_child < 0, leaf_j = nb.first_child < 0;
    if (leaf_i && leaf_j) {
      const fcl::Triangle& ta = a.triangle(-(na.first_child + 1));
      const fcl::Triangle& tb = b.triangle(-(nb.first_child + 1));
      if (fcl::detail::Intersect<double>::intersect_Triangle(
              a.vertex(ta[0]), a.vertex(ta[1]), a.vertex(ta[2]), b.vertex(tb[0]), b.vertex(tb[1]),
              b.vertex(tb[2]), R_a_b, p_a_b)) {
        return true;
      }
      continue;
    }
    if (top + 2 > kStack) return false;  // deeper than any tree FCL builds for a mesh
    // The child nearer the other node is searched first: it is likelier to reach the other
    // surface.
    if (leaf_j || (!leaf_i && na.radius >= nb.radius)) {
      const int first = na.first_child;
      const bool second_nearer =
          (a.node(first + 1).center - c_b).norm() - a.node(first + 1).radius <
          (a.node(first).center - c_b).norm() - a.node(first).radius;
      stack[top++] = {first + (second_nearer ? 0 : 1), j};
      stack[top++] = {first + (second_nearer ? 1 : 0), j};
    } else {
      const int first = nb.first_child;
      const Eigen::Vector3d c_a = R_a_b.transpose() * (na.center - p_a_b);  // in b's frame
      const bool second_nearer =
          (b.node(first + 1).center - c_a).norm() - b.node(first + 1).radius <
          (b.node(first).center - c_a).norm() - b.node(first).radius;
      stack[top++] = {i, first + (second_nearer ? 0 : 1)};
      stack[top++] = {i, first + (second_nearer ? 1 : 0)};
    }
  }
  return false;
}

}  // namespace

bool findIntersectingTriangles(const MeshSearchTree& a, const MeshSearchTree& b,
                               const Eigen::Matrix3d& R_a_b, const Eigen::Vector3d& p_a_b,
                               int budget) {
  if (a.size() == 0 || b.size() == 0) return false;
  return searchFrom(a, b, R_a_b, p_a_b, 0, 0, budget);
}

}  // namespace mcws
