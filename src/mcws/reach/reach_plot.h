#pragma once
/// \file
/// \brief Pictures of a reachability map, drawn by gnuplot: the half-cut view and the histogram
/// of the reachability index.

#include <string>

#include "mcws/reach/reach_map.h"

namespace mcws {

/// \brief The half-cut view (as ROS Reuleaux shows a map cut open): the voxels of the slab one
/// voxel thick through y = y_cut, seen along y, each a square coloured by its reachability
/// index D from 0 to 1 (a named colour bar), axes x and z in the robot's length unit.
/// \param title picture title (the robot's name, say).
/// \param unit length unit name for the axis labels.
/// \return the PNG's bytes. \throws mcws::Error when gnuplot fails or the slab is empty.
std::string renderHalfCutPng(const ReachMap& map, double y_cut, const std::string& title,
                             const std::string& unit);

/// \brief Histogram of D over the occupied voxels, 20 bins of width 0.05.
/// \return the PNG's bytes. \throws mcws::Error when gnuplot fails or the map is empty.
std::string renderReachabilityHistogramPng(const ReachMap& map, const std::string& title);

}  // namespace mcws
