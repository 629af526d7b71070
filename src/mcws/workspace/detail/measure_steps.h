#pragma once
/// \file
/// \brief Steps of delaunayMeasure() (measure.cpp) that delaunayMeasureSubset()
/// (measure_subset.cpp) shares. Private to mcws_workspace (namespace mcws::detail).

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <vector>

#include "mcws/workspace/measure.h"

namespace mcws::detail {

/// The local spacing at every point [length unit]: its distance to the k-th nearest neighbour
/// (k = 8) over that distance's mean for a uniform cloud of mean spacing 1, sqrt(k / pi) in 2-D
/// and (3k / (4 pi))^(1/3) in 3-D. `cancel_check` as kthNeighbourSquaredDistance()'s.
std::vector<double> localSpacing(const pcl::PointCloud<pcl::PointXYZ>& cloud, int dimensions,
                                 int threads, const CancelCheck& cancel_check = {});

/// The distinct positions of `points` (projected onto z = 0 in 2-D), after checking the
/// dimensions, the alpha factor, the point count and that every coordinate is finite.
/// \param position_of on return, for each input point the index of its position.
/// \throws mcws::Error naming what is wrong.
pcl::PointCloud<pcl::PointXYZ> checkedPositions(const pcl::PointCloud<pcl::PointXYZ>& points,
                                                int dimensions, double alpha_factor,
                                                std::vector<pcl::index_t>& position_of);

/// Starts phase `name` of delaunayMeasure(): calls MeasureOptions::phase, then
/// MeasureOptions::cancel_check (on the calling thread: so that each phase checks at least once,
/// however its loops' items fall to the threads), each when set.
void startPhase(const MeasureOptions& options, const char* name);

/// \throws mcws::Error when no simplex passed the alpha test or (with the edge correction) more
/// than half the points lie outside the region of the others.
void checkKeptAndMissing(const RegionMeasure& result, int dimensions,
                         const MeasureOptions& options);

}  // namespace mcws::detail
