#pragma once
/// \file
/// \brief ReachMap.query: which voxels hold given points and whether given tool orientations were
/// reached there.

#include "bindings.h"
#include "mcws/reach/reach_map.h"

namespace mcws::python {

/// \brief For points (N, 3) [length unit]: "voxel" (int64, the voxel's index in the map, -1
/// where no sample fell or the point is not finite), "reachability" [1] (float64),
/// "manipulability" (float32) and "count" (uint64), 0 where voxel is -1; with directions (N, 3)
/// (approach directions, the tool's z axis, any length) or (N, 3, 3) (tool rotations), also
/// "reached" (bool): whether the map holds a sample in the point's voxel and the orientation's
/// bin (any roll bin of the approach's region for directions).
/// \throws UsageError for other shapes, non-finite or zero directions.
py::dict queryMap(const ReachMap& map, const py::handle& points, const py::handle& directions);

}  // namespace mcws::python
