#pragma once
/// \file
/// \brief The orthant boundary of a binary PCD cloud larger than memory,
/// one slab of space (a tile) at a time, on one process or shared among MPI processes.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "mcws/distributed/processes.h"
#include "mcws/filters/boundary_geometry.h"
#include "mcws/filters/orthant_boundary.h"
#include "mcws/io/cloud_io.h"

namespace mcws::distributed {

/// \brief A cloud file seen in one pass (summarizeFile()).
struct FileSummary {
  CloudSummary cloud;         ///< counts and extents in the plane, as summarizeCloud() gives them
  io::CoordinateRange range;  ///< for the coordinate checks of io::readCloud()
  Eigen::Vector3d low{Eigen::Vector3d::Zero()};  ///< the finite points' lowest x, y, z
};

/// \brief What a tiled run found.
struct TiledBoundary {
  std::vector<char> boundary;       ///< per point of the file, on rank 0 only: 1 on the boundary
  std::uint64_t kept{0};            ///< boundary points (every rank)
  double median_radius{0.0};        ///< adaptive: median r_i over about 1000 points [length unit]
  double largest_halo{0.0};         ///< the widest halo a tile needed [length unit]
  std::uint64_t largest_tile{0};    ///< most points a process held at once (tile and halo)
  std::uint64_t reloaded_tiles{0};  ///< tiles loaded again with a wider halo
};

/// \brief The boundary of the cloud `reader` reads, by OrthantBoundary filters from `make`
/// (fixed or adaptive radius; no hull-depth stage), on `tiles` slabs of equal width along the
/// longest axis of the cloud in the filter's plane, each process taking a contiguous block of
/// them (blockOf()).
///
/// A tile's filter runs on its own points and a halo: the points within h of the slab. A point's
/// answer depends only on the points within its reach, max(r, R) (with an adaptive radius,
/// s d_k times the outer factor, d_k the distance to its k-th distinct neighbour), so it is the
/// whole cloud's answer when its reach, measured among the loaded points, ends inside them:
/// then no point beyond could be nearer than its k-th. Every own point is checked so; when one
/// is not, the tile is loaded again with the halo that holds the reaches measured (a reach
/// measured among more points is never longer, so one reload suffices unless a point had fewer
/// than k neighbours loaded: then the halo doubles; a whole-cloud halo always passes). The first
/// halo is 1.01 times the reach (fixed radius) or 1.5 times the typical reach of a uniform cloud
/// (orthant::typicalOuterRadius()). So the flags are exactly those of one filter on the whole
/// cloud, for any number of tiles and processes.
///
/// Every process reads the file; rank 0 gathers the flags. `progress` is called on rank 0 after
/// each of its tiles with (tiles done, its tiles): a progress line, or a check that ends the run
/// by throwing (Ctrl-C in the Python module).
TiledBoundary tiledBoundary(
    io::PcdPointReader& reader, const FileSummary& file, int tiles,
    const std::function<std::shared_ptr<OrthantBoundary<WorkspacePoint>>()>& make, int threads,
    const Processes& processes, const std::function<void(std::size_t, std::size_t)>& progress);

/// \brief The spacing of `cloud.finite` points spread evenly through its bounding box in its
/// plane (an extent below 1e-3 of the largest counts as that much) [length unit]: what a tiled
/// run knows of the spacing without the whole cloud's distinct positions.
double boundingBoxSpacing(const CloudSummary& cloud);

/// \brief Calls `visit(first, piece)` for the file's points in pieces
/// (io::PcdPointReader::piecePoints()), in order.
void forEachPiece(io::PcdPointReader& reader,
                  const std::function<void(std::uint64_t, const io::WorkspaceCloud&)>& visit);

/// \brief One pass over the file: the CloudSummary of its points in `plane` (counts, extents)
/// and the range of its coordinates, for the checks io::readCloud() and summarizeCloud() make.
FileSummary summarizeFile(io::PcdPointReader& reader, BoundaryPlane plane);

/// \brief What a process saw of the file `reader` reads in summarizeFile(): its point count, the
/// finite points, their lowest corner and extent (17 digits), for the processes of a run to check
/// that they all read the same file (Processes::setUpDone()).
std::string fileFingerprint(const io::PcdPointReader& reader, const FileSummary& file);

}  // namespace mcws::distributed
