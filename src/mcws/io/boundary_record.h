#pragma once
/// \file
/// \brief The check that a boundary cloud is the whole boundary of a given cloud, by the record
/// mcws_boundary writes into its header (the point count and SHA-256 of the cloud it read and
/// the number of boundary points it wrote).

#include <cstdint>
#include <string>

namespace mcws::io {

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
