#pragma once
/// \file
/// \brief The orthant boundary test over a whole cloud: every point tested, the optional
/// hull-depth stage, and the radius to report.

#include <optional>
#include <vector>

#include "mcws/filters/orthant/point_test.h"
#include "mcws/search/grid_then_tree_search.h"

namespace mcws::orthant {

/// \brief Per point of the searched cloud (in its cell order): on the boundary or not, and its
/// adaptive radius r_i where known [length unit].
struct CloudDecisions {
  std::vector<char> boundary;
  std::vector<std::optional<float>> radius;
};

/// \brief The radius most points will search at, the outer one if set [length unit], for a
/// cloud of mean spacing `spacing`: with an adaptive radius, s times the expected distance to
/// the k-th neighbour in a uniform cloud (the radius of the disk or ball holding k + 1 points).
double typicalOuterRadius(const PointTestSettings& test, double spacing);

/// \brief testPoint() for every point of the searched cloud, on `threads` threads.
CloudDecisions testEveryPoint(GridThenTreeSearch& search, const PointTestSettings& test,
                              int threads);

/// \brief The hull-depth stage (OrthantBoundary::setHullDepth): of the points found and every
/// point within a quarter of its radius of one of them, keeps as boundary those less than
/// `depth` local spacings inside the convex hull of their neighbourhood (radius r_i, or R). Fills
/// in the radii it had to search.
void keepShallowPoints(GridThenTreeSearch& search, const PointTestSettings& test, double depth,
                       int threads, CloudDecisions& decisions);

/// \brief The median r_i [length unit] over about 1000 points spread through the cloud (those
/// whose radius the grid can find), 0 for an empty cloud. Fills in the radii it searched.
double medianRadius(const GridThenTreeSearch& search, const PointTestSettings& test,
                    CloudDecisions& decisions);

}  // namespace mcws::orthant
