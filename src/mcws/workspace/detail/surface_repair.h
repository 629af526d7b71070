#pragma once
/// \file
/// \brief The surface repair of delaunayMeasure() (MeasureOptions::surface): the kept
/// tetrahedra's region made one whose boundary is a closed 2-manifold, and that boundary as
/// triangles. Private to mcws_workspace (namespace mcws::detail); compiled for the sequential and
/// the parallel 3-D triangulation of alpha_triangulation.h.

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <functional>
#include <vector>

#include "mcws/workspace/measure.h"

namespace mcws::detail {

/// Makes the kept tetrahedra's boundary a closed 2-manifold, round by round, changing as little
/// volume as it can: cavities (dropped cells no path of dropped cells connects to the infinite
/// ones) are kept (info 2, fillCavities()); around an edge where the kept region touches itself
/// (several runs of kept cells) every run of dropped cells but the heaviest (the one open to the
/// outside, else the largest) is kept; around a vertex with several groups of dropped cells
/// likewise, and where several groups of kept cells meet at a vertex across one group of dropped
/// ones, every kept group but the largest is dropped. Each round decides from the flags as they
/// were at its start, so the result does not depend on the order the cells are listed in; a cell
/// one round fills is not dropped again. \return false when singularities remain after
/// kFillRounds rounds. `cancel_check` (when set) is called between pieces of the rounds.
/// `changed` (when set) is called after each round that changed flags, with the cells it filled
/// or dropped (a cell may come more than once), before the next round looks at the flags: the
/// shell triangulation (MeasureOptions::shell) completes the stars of their vertices there.
template <typename Delaunay>
bool fillForSurface(
    Delaunay& dt, const CancelCheck& cancel_check,
    const std::function<void(const std::vector<typename Delaunay::Cell_handle>&)>& changed = {});

/// The facets between kept and dropped tetrahedra (info 1 and 0; infinite cells are dropped),
/// each oriented away from its kept tetrahedron (exact orientation test), over the points of
/// `points` they use. Canonical order, whatever order the triangulation lists its cells in:
/// vertices by point index, each triangle rotated to start at its smallest vertex, triangles
/// sorted. `cancel_check` (when set) is called between pieces of the pass over the cells.
template <typename Delaunay>
TriangleSurface keptSurface(const Delaunay& dt, const pcl::PointCloud<pcl::PointXYZ>& points,
                            const CancelCheck& cancel_check);

}  // namespace mcws::detail
