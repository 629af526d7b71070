#pragma once
/// \file
/// \brief The shell optimisation of delaunayMeasure() (MeasureOptions::shell): the measure from
/// the triangulation of the points near the region's edges only. Private to mcws_workspace
/// (namespace mcws::detail); compiled for 2-D and for the sequential and the parallel 3-D
/// triangulation.

#include <CGAL/tags.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <vector>

#include "mcws/workspace/measure.h"

namespace mcws::detail {

/// The area (D = 2) or volume (D = 3) of the region from the triangulation of the points an empty
/// ball of alpha radius may touch (MeasureOptions::shell). A simplex the alpha test drops has an
/// empty circumball wider than the alpha radius at each of its vertices, so all its vertices are
/// exposed (exposedPoints()), and it is a simplex of the shell's triangulation too. The shell's
/// triangulation covers the same hull, so the kept total is its finite simplices' total less the
/// dropped ones: the shell's simplices with a left-out point in their circumsphere fill in for the
/// whole triangulation's simplices there, all kept, whatever their size. The boundary vertices are
/// the same; the leave-one-out test needs each one's star, which is the whole triangulation's when
/// none of the star's simplices has a left-out point in its circumsphere. Where one has (a few
/// dozen points of 10^6, where the shell is thinnest), those left-out points are inserted and the
/// simplices around them tested again, until no star has one. With MeasureOptions::surface (3-D)
/// the same is done for the boundary vertices without the edge correction, and, after each round
/// of the surface repair (fillForSurface()), for the vertices of the cells it filled or dropped,
/// so that the repair and keptSurface() see only the whole triangulation's cells around the
/// surface: the same surface as triangulating every point.
/// \param spacing the local spacing at every point [length unit].
template <int D, typename Concurrency = CGAL::Sequential_tag>
RegionMeasure measureShell(const pcl::PointCloud<pcl::PointXYZ>& points,
                           const std::vector<double>& spacing, const MeasureOptions& options);

}  // namespace mcws::detail
