#pragma once
/// \file
/// \brief The k-th nearest neighbour of every point of a cloud.

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <vector>

#include "mcws/core/cancel_check.h"

namespace mcws {

/// \brief Squared distance from every point to its k-th nearest other point.
///
/// Over x, y (`dimensions` = 2; z is ignored) or x, y, z (3), on all threads: the points sorted
/// into the cells of the boundary filter's grid (CellGrid's geometry), each cell's block of 3^D
/// (then 5^D) cells gathered once for the queries in it, exact where the block holds every point
/// that may be nearer; the few others by the grid search (CellGrid), exact; for a cloud crowded
/// into a small part of its bounding box, and for the few points the grid declines, a kd-tree
/// (nanoflann) queried in its leaf order, exact up to the float rounding of its pruning bound (a
/// neighbour within about one float step of the k-th may be passed over; brute force agrees to the
/// bit on the test clouds). Distances are computed in float, as PCL's `KdTreeFLANN` computes them.
/// Each result depends only on the cloud, not on the thread count. \param cloud the points; copies
/// of a position count as distinct points at distance 0. \param dimensions 2 or 3. \param k the
/// neighbour's rank among the other points (k >= 1); a cloud of at most k points
///   gives each point its farthest other point (0 for a single point).
/// \param threads worker threads; 0: OpenMP's default.
/// \param cancel_check called on the calling thread every few thousand of its queries (when set);
///   what it throws ends the search and is rethrown (CancelCheck).
/// \throws mcws::Error for a bad `dimensions` or `k`.
std::vector<float> kthNeighbourSquaredDistance(const pcl::PointCloud<pcl::PointXYZ>& cloud,
                                               int dimensions, int k, int threads = 0,
                                               const CancelCheck& cancel_check = {});

}  // namespace mcws
