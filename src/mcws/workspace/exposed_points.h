#pragma once
/// \file
/// \brief Which points of a cloud an empty ball of a given radius may touch (alpha-exposed points).

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstddef>
#include <vector>

#include "mcws/core/cancel_check.h"

namespace mcws {

/// \brief Result of exposedPoints().
struct ExposedPoints {
  /// 1: an empty open ball of radius `radius[i]` may touch point i (its sphere passes through the
  /// point and no point lies inside); 0: proven that none does.
  std::vector<char> exposed;
  std::size_t count{0};  ///< points flagged 1
};

/// \brief Flags every point that an empty ball of its radius may touch; the others are proven
/// covered: every open ball of radius `radius[i]` whose sphere passes through point i holds
/// another point of the cloud.
///
/// A vertex of a Delaunay simplex whose circumradius exceeds R lies on an empty ball of radius R
/// (the circumball), so a point proven covered at R is a vertex of no such simplex: an alpha
/// shape's dropped simplices (delaunayMeasure()) have only exposed vertices, and its kept ones
/// can be summed without triangulating the covered points (see MeasureOptions::shell).
///
/// The proof is a grid of cubes (squares in 2-D) of edge c with 2 sqrt(D) c < r: a cube whose
/// 3^D block of neighbours holds at least two points is "full" (every position x in it has a
/// point other than any given one within 2 sqrt(D) c < r, so a ball of radius r centred at x is
/// not empty); point i is covered when every cube that the box of half-edge r around it reaches
/// is full (the centres of the balls that touch it lie on the sphere of radius r around it), a
/// cell's cover radius being bounded by the points of the cells around it. The radii are rounded
/// down to classes (ratio 1.25 from the smallest radius but 1 %; a smaller radius is a stronger
/// claim; the 1 % below stay exposed); four classes share a grid with cells of half their
/// smallest radius, over their points' balls, so a cloud whose spacing varies by orders of
/// magnitude (refined clouds) gets cells to match; a grid for fewer than 2 % of the points is
/// skipped (they stay exposed). The full cells are eroded by the cells a ball may meet (a box,
/// then crosses) in separable passes: a few passes over each grid, not a search per point. A grid
/// holds at most 4 cells per point in its box. Exposed is never wrong, only cautious: a point of
/// the convex hull, or near any face of the region (2 to 4 radii deep), is always exposed.
/// \param cloud the points, distinct positions; for dimensions = 2 the x-y plane (z ignored).
/// \param dimensions 2 or 3.
/// \param radius the radius for each point [length unit]; non-positive or non-finite: exposed.
/// \param threads worker threads for the passes; 0: OpenMP's default. The flags do not depend on
///   it.
/// \param cancel_check called between the passes (when set); what it throws ends the call
///   (CancelCheck).
/// \throws mcws::Error for a bad `dimensions` or a `radius` of another size than the cloud.
ExposedPoints exposedPoints(const pcl::PointCloud<pcl::PointXYZ>& cloud, int dimensions,
                            const std::vector<double>& radius, int threads = 0,
                            const CancelCheck& cancel_check = {});

}  // namespace mcws
