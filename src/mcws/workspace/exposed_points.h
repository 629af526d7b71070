#pragma once
/// \file
/// \brief Which points of a cloud an empty ball of a given radius may touch (alpha-exposed points).

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cstddef>
#include <vector>

namespace mcws {

/// \brief Result of exposedPoints().
struct ExposedPoints {
  /// 1: an empty open ball of radius `radius[i]` may touch point i (its sphere passes through the
  /// point and no point lies inside); 0: proven that none does.
  std::vector<char> exposed;
  std::size_t count{0};  ///< points flagged 1
  double cell{0.0};      ///< edge of the grid's cells [length unit]
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
/// is full (the centres of the balls that touch it lie on the sphere of radius r around it). The
/// radii are rounded down to classes (ratio 1.25 from the smallest radius but 1 %; a smaller
/// radius is a stronger claim; the 1 % below stay exposed), each proven on a grid of its own with
/// cells as coarse as its radius allows, the full cubes eroded by the class's box in separable
/// passes: a few passes over each grid, not a search per point. A grid holds at most 32 cells per
/// point: a cloud much sparser than its radii in most of its bounding box gets coarser cells and
/// more exposed points. Exposed is never wrong, only cautious: a point of the convex hull, or
/// near any face of the region (3 to 5 radii deep), is always exposed.
/// \param cloud the points, distinct positions; for dimensions = 2 the x-y plane (z ignored).
/// \param dimensions 2 or 3.
/// \param radius the radius for each point [length unit]; non-positive or non-finite: exposed.
/// \param threads worker threads for the passes; 0: OpenMP's default. The flags do not depend on
///   it.
/// \throws mcws::Error for a bad `dimensions` or a `radius` of another size than the cloud.
ExposedPoints exposedPoints(const pcl::PointCloud<pcl::PointXYZ>& cloud, int dimensions,
                            const std::vector<double>& radius, int threads = 0);

}  // namespace mcws
