#pragma once
/// \file
/// \brief The outputs of a tiled boundary run: the boundary points of a cloud larger than memory,
/// and the other finite points, streamed to binary PCD files.

#include <optional>
#include <string>

#include "mcws/distributed/tiled_boundary.h"
#include "mcws/io/provenance.h"

namespace mcws::distributed {

/// \brief Writes the points `found` flags as boundary points of the cloud `reader` reads to
/// `output` and, when `interior` is not empty, its other finite points to `interior`, in file
/// order, both binary PCD recording `provenance`. Both files appear together (io::OutputSet) or
/// not at all. Rank 0 only (it holds the flags).
/// \param interior_points the count of finite points minus `found.kept`.
/// \throws mcws::Error naming the file that cannot be written.
void writeTiledBoundary(io::PcdPointReader& reader, const TiledBoundary& found,
                        const std::string& output, const std::string& interior,
                        std::uint64_t interior_points,
                        const std::optional<io::CloudProvenance>& provenance);

}  // namespace mcws::distributed
