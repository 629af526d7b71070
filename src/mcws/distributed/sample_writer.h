#pragma once
/// \file
/// \brief Monte Carlo sampling on several processes into one PCD file, byte for byte the file of
/// a single process (mcws::writeSamples()).

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "mcws/distributed/processes.h"
#include "mcws/io/provenance.h"
#include "mcws/sampling/sampler.h"

namespace mcws::distributed {

/// \brief Writes `prefix_size` given points followed by samples 0 .. n-1 of `generator` as one
/// binary PCD file, each process computing its block of sample indices (blockOf()) and writing
/// it at its offset (SharedFile).
///
/// A sample's random numbers depend only on the seed and its index, and every record has the
/// same length, so the file is byte for byte what writeSamples() (and, with a prefix,
/// app::saveCloud() of the prefix followed by the samples) writes on one process, for any number
/// of processes and threads. Collective: every process calls it with the same arguments but
/// `prefix`, which only rank 0 reads (`prefix_size` points; the others may pass nullptr).
/// \param threads threads per process (0: all cores).
/// \param progress called by rank 0 after each of its chunks with (its samples done, its block's
///   size); may be empty.
/// \param provenance the robot recorded in the header; without it, the thread's
///   io::ScopedProvenance, if any.
/// \return the summary of all n samples (the prefix not included), on every process.
/// \throws mcws::Error when the file cannot be written or holds more than 2^31-1 points.
template <typename PointT>
SampleSummary writeSamplesTogether(
    const Processes& processes, const BasicPointGenerator<PointT>& generator, std::size_t n,
    const std::string& path, int threads,
    const std::function<void(std::size_t, std::size_t)>& progress = {},
    const std::optional<io::CloudProvenance>& provenance = std::nullopt,
    const PointT* prefix = nullptr, std::uint64_t prefix_size = 0);

/// \brief The summaries of the processes' blocks combined (points and label counts added,
/// bounding boxes joined), on every process; with no points at all, a zero bounding box as
/// writeSamples() gives.
SampleSummary combineSummaries(const Processes& processes, const SampleSummary& own);

}  // namespace mcws::distributed
