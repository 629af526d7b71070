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
/// Point i is exposed at r exactly when the farthest position of its Voronoi cell is at least r
/// from it: a position x on the sphere of radius r around i is the centre of an empty ball when
/// its nearest point is r away, so i is covered when every position the closed ball of radius r
/// around it reaches (the sphere's positions among them) is nearer than r to some point, which
/// then is not i. The proof bounds, on a grid of cubes (squares in 2-D) of edge about r / 2, how
/// far any position of a cell may be from the nearest point: a nearest-point transform (exact
/// along the first axis, then carried along the others, Felzenszwalb and Huttenlocher's lower
/// envelopes with the points' own coordinates) gives each cell a point, and the distance from it
/// to the cell's farthest corner is the bound (whichever point a cell carries, it is a bound).
/// A cell is full when its bound is below r. Point i is covered when every coarse cell (2^D
/// cells) that the ball may meet from anywhere in i's own is full (an erosion by a box, then
/// crosses, in separable passes); else, exactly: every cell the ball around i itself meets is
/// full, or the parts of it (halved up to three times) that the ball meets are nearer than r to
/// the point of the cell or of a face neighbour (the parts' slack: an eighth of a cell, r / 16).
/// On a uniform ball of 10^6 points at 3 local spacings, 45 255 points are exposed: 34 800
/// within a spacing of the surface (the triangulation's exposed points: 20 600) and the 1 %
/// below the smallest class, scattered; on uniform clouds of 10^5 points, 1.9 (ball) and 1.5
/// (disk) times the triangulation's count (exposed_points_oracle_test.cpp). The radii are rounded
/// down to classes (ratio 1.25 from the smallest radius but 1 %; a smaller radius is a stronger
/// claim; the 1 % below stay exposed); four classes share a grid with cells of half their
/// smallest radius, over their points' balls, so a cloud whose spacing varies by orders of
/// magnitude (refined clouds) gets cells to match; a grid for fewer than 2 % of the points is
/// skipped (they stay exposed). A grid holds at most 16 cells per point in its box (5 bytes a
/// cell, and 16 bytes a point: about 30 MB for a ball of 10^6 points, 100 MB at most). The
/// distances are rounded up and the radii down (a relative 10^-6, and the coordinates' float
/// rounding), so exposed is never wrong, only cautious: a point of the convex hull is always
/// exposed.
///
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
