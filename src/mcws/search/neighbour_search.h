#pragma once
/// \file
/// \brief The neighbour searches the boundary tests ask for, behind one interface: a neighbour
/// as an offset from the query point, and a search that may decline a query it cannot answer
/// cheaply.

#include <pcl/types.h>

#include <optional>
#include <vector>

namespace mcws {

/// \brief A neighbour q of a query point p: its offset q - p [length unit] (z = 0 in a plane),
/// the squared distance [length unit^2] as pcl::KdTreeFLANN computes it, and q's index in the
/// searched cloud. A copy of p (or p itself) has offset (0, 0, 0).
struct Neighbour {
  Neighbour() {}  // uninitialised: buffers are resized, then written
  Neighbour(float x, float y, float z, float d2, pcl::index_t index)
      : x(x), y(y), z(z), d2(d2), index(index) {}
  float x, y, z;
  float d2;
  pcl::index_t index;
};

/// \brief The searches of the orthant boundary test around point i of a fixed cloud, for one
/// thread. Every answer is exactly pcl::KdTreeFLANN's: float squared distances, a radius search
/// returns the points with d^2 < float(r^2), i itself included. A search may decline (return
/// false or nothing) when it cannot answer cheaply; the caller then asks another one.
class NeighbourSearch {
 public:
  virtual ~NeighbourSearch() = default;

  /// \brief The squared distance [length unit^2] to the `count`-th nearest point of point i (i
  /// itself counted first, as nearestKSearch counts it), and those `count` points in `*nearest`
  /// unless it is null; nothing if declined.
  virtual std::optional<float> kthDistance2(pcl::index_t i, int count,
                                            std::vector<Neighbour>* nearest) = 0;

  /// \brief The points j with d^2(i, j) < float(radius^2) into `found`; false if declined.
  virtual bool radius(pcl::index_t i, double radius, std::vector<Neighbour>& found) = 0;

  /// \brief For an adaptive radius r_i = scale * sqrt(kthDistance2(i, count)): when it is cheap
  /// to prove that r_i reaches past some distance, the points within that distance (a subset of
  /// those within r_i) into `subset`, and true. False says nothing about r_i. The default proves
  /// nothing.
  virtual bool adaptiveSubset(pcl::index_t /*i*/, int /*count*/, float /*scale*/,
                              std::vector<Neighbour>& /*subset*/) {
    return false;
  }
};

}  // namespace mcws
