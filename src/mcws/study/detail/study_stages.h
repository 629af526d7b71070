#pragma once
/// \file
/// \brief What the stages of runStudy() hand on to each other (study module only).

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "mcws/collision/collision_checker.h"
#include "mcws/planning/scenario.h"
#include "mcws/reach/base_placement.h"
#include "mcws/reach/reach_map.h"
#include "mcws/reach/reach_study.h"
#include "mcws/report/report_page.h"
#include "mcws/study/study.h"
#include "mcws/study/study_run.h"
#include "mcws/workspace/envelope.h"

namespace mcws::detail {

/// \brief One planned target at the chosen stop.
struct PlannedTarget {
  std::size_t target{0};  ///< index into Study::targets
  Scenario scenario;      ///< the equivalent scenario (base and pivot moved to the stop)
  SwayPlanningResult result;
};

/// \brief The study's intermediate results.
struct StudyState {
  const Study* study{nullptr};
  std::string directory;
  StudyRunOptions options;
  nlohmann::json report;
  // workspace (in the robot's place at stop 0)
  pcl::PointCloud<pcl::PointXYZ> samples, boundary;
  Envelope envelope;
  std::string drawing_png;
  // reach
  ReachMap map;
  std::unique_ptr<CollisionChecker> checker;  ///< robot and line
  std::vector<TargetReach> at_origin;         ///< reach study at stop 0
  // placement
  std::vector<BaseCandidate> candidates;
  int best{-1};
  std::vector<std::vector<TargetReach>> per_stop;  ///< [stop][target]
  // planning
  std::vector<PlannedTarget> planned;
  // behaviour
  nlohmann::json behaviour_timeline;  ///< the view's timeline section (null: no rehearsal)
};

/// \brief The world move of the robot at `stop` [length unit] along the sway's line.
Eigen::Vector3d stopMove(const Study& study, double stop);

/// \brief Stage (1): sampling, boundary, measure, envelope, drawing.
void runWorkspace(StudyState& state);
/// \brief Stage (2): the reachability map and the reach study at stop 0.
void runReach(StudyState& state);
/// \brief Stage (3): the placement over the stops, the reach study at each.
/// \throws mcws::Error when no stop reaches any target.
void runPlacement(StudyState& state);
/// \brief Stage (4): planning under sway at the chosen stop.
void runPlanning(StudyState& state);

/// \brief Stage (5): the behaviour rehearsal, when the study names a model.
void runBehaviour(StudyState& state);

/// \brief The report's "view" (answers, sections).
nlohmann::json studyView(const StudyState& state);
/// \brief The 3-D scene.
report::Scene studyScene(const StudyState& state);

}  // namespace mcws::detail
