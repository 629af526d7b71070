#pragma once
/// \file
/// \brief The record mcws_boundary writes into its outputs' headers (the point count and
/// SHA-256 of the cloud it read and the number of boundary points it wrote), and the check that
/// a boundary cloud is by it the whole boundary of a given cloud.

#include <cstdint>
#include <optional>
#include <string>

#include "mcws/io/provenance.h"

namespace mcws::io {

/// \brief The provenance a boundary of the cloud file `input` (of `points` points) records: the
/// input's own (its robot and sampling, when it records them; none otherwise) with the input's
/// identity, its point count and SHA-256, and `boundary_points`, the boundary's point count, so
/// that requireBoundaryOf() can tell the whole boundary of this cloud from that of a subset or an
/// older cloud, or from a part of it.
/// \throws mcws::Error when `input` cannot be read.
std::optional<CloudProvenance> boundaryProvenance(const std::string& input, std::uint64_t points,
                                                  std::uint64_t boundary_points);

/// \brief Checks that the boundary cloud `path` (--boundary, of `boundary_points` points) is the
/// boundary of the cloud `input` (--input, of `points` points) itself, not of a subset of it or
/// of an older cloud whose points it shares, nor a part of it: its record of the cloud it was
/// found in must give `input`'s point count and SHA-256 (or the boundary is `input`'s own bytes),
/// and its record of the points written must be `boundary_points`. A boundary without the record
/// is refused when `input` records its robot (mcws made it, so mcws_boundary would have recorded
/// it); clouds that record nothing (--shape samples, other tools) pass, to be checked point by
/// point by the caller.
/// \throws mcws::Error naming both files, what differs and how to re-make the boundary.
void requireBoundaryOf(const std::string& path, const std::string& input, std::uint64_t points,
                       std::uint64_t boundary_points);

}  // namespace mcws::io
