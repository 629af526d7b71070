#pragma once
/// \file
/// \brief The whole power-line study (mcws_study): workspace, reachability and reach study, base
/// placement along the line, planning under sway at the chosen stop; its report (JSON, with the
/// "view" the report page shows) and its 3-D scene.

#include <functional>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>

#include "mcws/report/report_page.h"
#include "mcws/study/study.h"

namespace mcws {

/// \brief Settings of runStudy().
struct StudyRunOptions {
  int threads{0};  ///< 0: all cores; the report does not depend on it (apart from seconds)
  /// Called as a stage's work goes on: (stage, done, total); may be empty.
  std::function<void(const std::string&, std::size_t, std::size_t)> progress;
  /// The reach-map cache's folder (ReachMapCache, mcws_place's): the reach stage's map is read
  /// from it when it holds the map of the same inputs, else built and stored there; empty: no
  /// cache. The report is the same either way.
  std::string map_cache;
  /// Where the cache's lines go ("mcws_study: reusing the cached map ..."); nullptr: nowhere.
  std::ostream* log{nullptr};
};

/// \brief What runStudy() made.
struct StudyRun {
  nlohmann::json report;  ///< report.json (with its "view")
  report::Scene scene;
};

/// \brief Runs every stage of the study, writing its files (samples.pcd, boundary.pcd,
/// refined.pcd with a refine count, envelope.ply, drawing.png, path_<target>.csv) into
/// `directory` (which must exist; the caller makes it appear whole).
///
/// Stages, each calling the library functions the stage tools call, so its numbers are theirs:
/// (1) workspace: writeSamples() of a RobotSampler (mcws_sample), OrthantBoundary with its
/// recommended settings (mcws_boundary), workspaceEnvelope() whose measure is delaunayMeasure()
/// (mcws_measure, mcws_envelope), envelopeDrawing(); (2) buildReachMap() counting samples free of
/// self-collision (mcws_place's own map) and the reach study of the targets at stop 0 (mcws_reach
/// --targets, the line as environment); (3) placeBase() over the stops, every stop confirmed by IK
/// (mcws_place --confirm all), then the reach study at every stop; (4) at the best stop, for each
/// target reached there (up to plan_targets), the IK solution as goal and SwayPlanner::plan()
/// from `start` with the validation (mcws_plan), the robot's base and the sway pivot moved by the
/// stop; (5) when the study names a behaviour model, the rehearsal of its cleaning job
/// (runCleaningJob(), as mcws_behave --json) with its timeline.
/// \throws mcws::Error naming the targets when no stop reaches any target, and for the stages'
///   own failures.
StudyRun runStudy(const Study& study, const std::string& directory,
                  const StudyRunOptions& options = {});

/// \brief Base64 of `bytes` (RFC 4648, with padding), for pictures embedded in the report.
std::string base64(const std::string& bytes);

}  // namespace mcws
