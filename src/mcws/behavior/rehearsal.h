#pragma once
/// \file
/// \brief A rehearsal of the cleaning job on the simulator with its records: the JSON-lines log,
/// the timeline CSV and the plot of the joint speeds.

#include <string>

#include "mcws/behavior/behavior_executor.h"
#include "mcws/behavior/behavior_model.h"

namespace mcws {

/// \brief What a rehearsal records and where; an empty path: not written.
struct RehearsalFiles {
  std::string model, faults;  ///< the inputs, named in the log's header
  std::string log;            ///< JSON lines: a header, then every log record as it comes
  std::string timeline;       ///< CSV, a row every `period`
  std::string plot;           ///< PNG of the joint speeds
  double period{0.1};         ///< between timeline rows [s]
  bool plot_all{false};       ///< the plot spans the whole run, not only the first disc
};

/// \brief Runs the job of `insulators` discs (runCleaningJob()), writing the log as it goes and
/// the timeline and plot at the end. Each file is written under a temporary name
/// (io::AtomicFile) and committed when the run ends, whatever its status: inside an
/// io::OutputSet it appears when the set commits.
/// \throws mcws::Error when a file cannot be written or the timeline's period does not fit the
///   simulator's step.
RunSummary rehearseCleaningJob(const BehaviorModel& model, const RunOptions& options,
                               int insulators, const RehearsalFiles& files);

}  // namespace mcws
