#pragma once
/// \file
/// \brief The parameters a boundary filter used on its last cloud, by name, for a report
/// (mcws_boundary --json): what it was given or what it chose for that cloud.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "mcws/filters/extremum_boundary.h"
#include "mcws/filters/grid_boundary.h"
#include "mcws/filters/orthant_boundary.h"

namespace mcws {

/// \brief Named lengths [the cloud's unit] and counts.
struct UsedParameters {
  std::vector<std::pair<std::string, double>> lengths;
  std::vector<std::pair<std::string, std::uint64_t>> counts;
};

/// \brief OrthantBoundary: "radius" (an adaptive radius's median over the points) and the mean
/// "spacing".
template <typename PointT>
UsedParameters usedParameters(const OrthantBoundary<PointT>& filter) {
  return {{{"radius", filter.usedRadius()}, {"spacing", filter.usedSpacing()}}, {}};
}

/// \brief GridBoundary: the "cell" side and the mean "spacing"; the "occupied_cells" and the
/// "boundary_cells".
template <typename PointT>
UsedParameters usedParameters(const GridBoundary<PointT>& filter) {
  return {{{"cell", filter.usedCellSize()}, {"spacing", filter.usedSpacing()}},
          {{"occupied_cells", filter.occupiedCells()}, {"boundary_cells", filter.boundaryCells()}}};
}

/// \brief ExtremumBoundary: the "cell" (column width), the "gap" threshold and the mean
/// "spacing"; the "columns".
template <typename PointT>
UsedParameters usedParameters(const ExtremumBoundary<PointT>& filter) {
  return {{{"cell", filter.usedColumnWidth()},
           {"gap", filter.usedGapThreshold()},
           {"spacing", filter.usedSpacing()}},
          {{"columns", filter.columns()}}};
}

}  // namespace mcws
