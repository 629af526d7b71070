#pragma once
/// \file
/// \brief The object behind mcws.ReachMap: a reachability map and the header its file records.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "bindings.h"
#include "loaded_robot.h"
#include "mcws/reach/reach_map.h"

namespace mcws::python {

/// \brief A map and the header its file records (mapFileHeader(), without the grid's members,
/// which ReachMap::write() adds); a map built here also keeps its summary (mapSummary(), as
/// mcws_reach --json but for the files and seconds).
struct MapResult {
  ReachMap map;
  std::string header;   ///< compact JSON
  std::string summary;  ///< compact JSON, or "null" for a map read from a file
  std::string source;   ///< the file it was read from, or "reach_map()"
};

/// \brief How mcws.reach_map fills a map, as mcws_reach's flags.
struct MapArguments {
  double resolution;  ///< [length unit]
  std::int64_t samples, seed;
  int threads, orientations, rolls;
  bool manipulability;
  std::optional<std::string> quality_task;
  std::optional<double> length;
};

/// \brief The grid of `a`, checked. \throws UsageError naming a bad argument.
ReachGrid mapGrid(const MapArguments& a);

/// \brief The sampling of `a`, checked, counting the samples `checker` finds free (nullptr: all).
/// \throws UsageError naming a bad argument.
ReachSampling mapSampling(const Robot& robot, const MapArguments& a,
                          const CollisionChecker* checker);

/// \brief The map of `a`, as mcws_reach builds it, its file header and summary; `checker`: count
/// only the samples it finds free (nullptr: all). The GIL is released; `checkpoint` after each
/// chunk of samples (Ctrl-C, progress).
/// \throws UsageError naming a bad argument; mcws::Error when no sample counts.
std::unique_ptr<MapResult> buildMap(const LoadedRobot& loaded, const MapArguments& a,
                                    const CollisionChecker* checker, Checkpoint& checkpoint);

}  // namespace mcws::python
