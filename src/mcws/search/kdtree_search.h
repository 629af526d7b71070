#pragma once
/// \file
/// \brief pcl::KdTreeFLANN behind the NeighbourSearch interface: the reference search, which
/// answers every query.

#include <pcl/kdtree/kdtree_flann.h>

#include <algorithm>
#include <optional>
#include <vector>

#include "mcws/search/neighbour_search.h"

namespace mcws {

/// \brief NeighbourSearch on a pcl::KdTreeFLANN built over `cloud`, for one thread (the tree is
/// shared read-only). Never declines; adaptiveSubset() proves nothing.
class KdTreeSearch : public NeighbourSearch {
 public:
  KdTreeSearch(const pcl::KdTreeFLANN<pcl::PointXYZ>& tree,
               const pcl::PointCloud<pcl::PointXYZ>& cloud)
      : tree_(tree), cloud_(cloud) {}

  std::optional<float> kthDistance2(pcl::index_t i, int count,
                                    std::vector<Neighbour>* nearest) override {
    const int found = tree_.nearestKSearch(cloud_[i], count, indices_, d2_);
    const float kth = found > 0 ? *std::max_element(d2_.begin(), d2_.begin() + found) : 0.0f;
    if (nearest) offsets(i, *nearest);
    return kth;
  }

  bool radius(pcl::index_t i, double radius, std::vector<Neighbour>& found) override {
    tree_.radiusSearch(cloud_[i], radius, indices_, d2_);
    offsets(i, found);
    return true;
  }

 private:
  void offsets(pcl::index_t i, std::vector<Neighbour>& out) const {
    const pcl::PointXYZ& p = cloud_[i];
    out.resize(indices_.size());
    for (std::size_t k = 0; k < indices_.size(); ++k) {
      const pcl::PointXYZ& q = cloud_[indices_[k]];
      out[k] = {q.x - p.x, q.y - p.y, q.z - p.z, d2_[k], indices_[k]};
    }
  }

  const pcl::KdTreeFLANN<pcl::PointXYZ>& tree_;
  const pcl::PointCloud<pcl::PointXYZ>& cloud_;
  pcl::Indices indices_;
  std::vector<float> d2_;
};

}  // namespace mcws
