#pragma once
/// \file
/// \brief The cleaning job decomposed into sub-tasks, each run by one combined behaviour
/// (Wang et al. 2018, section 2.3, Figure 8).

#include <string>
#include <vector>

namespace mcws {

/// \brief One sub-task of a cleaning job.
struct Subtask {
  std::string behavior;  ///< the combined behaviour that runs it: "CB1", "CB2" or "CB3"
  std::string action;    ///< "move down one disc", "clean disc", "move up one disc"
  int disc{0};           ///< the disc the robot works at after the sub-task (1 = tower end)
};

/// \brief The sequence of Wang et al. 2018 for a string of `discs` discs: from the tower end down
/// to the conductor end, (CB1, CB2) per disc, then CB3 per disc back to the start.
///
/// The worker mounts the robot at the tower end: the fixed (upper) clamp on the string's
/// tower-end fitting (position 0 of RobotSimulator's string), the moving clamp two pitches
/// below (robots/insulator_cleaner.yaml). Disc k is the one the cleaning platform faces after the
/// k-th CB1, so after k (CB1, CB2) pairs discs 1..k are clean; the mounting position is the
/// fitting, not a disc, so nothing there is cleaned, and every one of the `discs` discs is. Then
/// `discs` CB3 bring the robot back to where it was mounted, for the worker to take it off.
/// \throws mcws::Error for fewer than 1 or more than 200 discs.
std::vector<Subtask> planCleaningTask(int discs);

/// \brief The plan as text, one sub-task per line ("1 CB1 move down one disc -> disc 1"), for
/// the worker to confirm before the run.
std::string describePlan(const std::vector<Subtask>& plan);

}  // namespace mcws
