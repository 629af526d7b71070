#pragma once
/// \file
/// \brief Reachability maps of very many samples built in pieces, the map so far saved after each
/// piece, so that an interrupted run continues from its last completed piece.

#include <cstdint>
#include <functional>
#include <string>

#include "mcws/reach/reach_map.h"

namespace mcws {

/// \brief Where and how often buildReachMapInPieces() saves its progress.
struct ReachCheckpoint {
  std::string path;        ///< the file of the progress (written whole or not at all)
  std::uint64_t every{0};  ///< samples per piece (> 0)
  std::string run;         ///< a compact JSON object naming the run: a file of another is refused
};

/// \brief buildReachMap() of `sampling`'s samples in pieces of `checkpoint.every` samples: after
/// each piece the map so far and the number of samples done are written to `checkpoint.path`
/// (the binary map format of docs/reach_map.md, with header members "checkpoint_run" and
/// "samples_done"). When that file exists and names the same run, the map starts from it and
/// the samples it has done are skipped. Merging maps is exact (counts add, bins unite, the best
/// manipulability is the larger), so the map is the one buildReachMap() gives, in its order,
/// however often the run was interrupted and resumed.
/// \param progress called with (samples done, sampling.samples), counting resumed samples.
/// \param resumed if not null, receives the samples taken from the file (0: none).
/// \throws mcws::Error naming the file when it cannot be read or written, or holds another run.
ReachMap buildReachMapInPieces(
    const Robot& robot, const ReachGrid& grid, const ReachSampling& sampling,
    const ReachCheckpoint& checkpoint,
    const std::function<void(std::uint64_t, std::uint64_t)>& progress = {},
    std::uint64_t* resumed = nullptr);

}  // namespace mcws
