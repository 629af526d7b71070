// The small study the study tests run (a few seconds): a copy of the maintenance4 robot whose
// scene is the study's line, targets on a spacer's clamp, three stops.
#pragma once

#include <string>

#include "test_support.h"

namespace mcws::test {

// The line of the test study, also written as the environment of a copy of the maintenance4
// robot file, so that mcws_place and mcws_plan see the very scene the study builds.
inline const char* const kRobotEnvironment = R"(  environment:
    - {name: conductor_a, type: capsule, from: [-300, 0, 25], to: [300, 0, 25], radius: 1.5}
    - {name: spacer, type: box, size: [6, 4, 20], xyz: [50, -35, -38]}
)";

// Three targets 4 cm off the spacer's face (normal +y) and one 3 m away that no stop reaches.
inline const char* const kTargets = R"(x,y,z,normal_x,normal_y,normal_z
48,-29,-42,0,1,0
50,-29,-40,0,1,0
52,-29,-38,0,1,0
300,-29,-40,0,1,0
)";

inline const char* const kStudy = R"(name: test study
robot: robot.yaml
seed: 3
line:
  conductors:
    - {name: conductor_a, radius: 1.5 cm, points: [[-300 cm, 0 cm, 25 cm], [300 cm, 0 cm, 25 cm]]}
  fittings:
    - {name: spacer, type: box, size: [6, 4, 20], xyz: [50, -35, -38]}
targets:
  - {file: targets.csv, name: t}
stops: {from: 20 cm, to: 40 cm, step: 10 cm}
start: [0 rad, 0 cm, 0 rad, 0 cm]
sway: {pivot: [0 cm, 0 cm, 25 cm], line: [1, 0, 0], swing: 2 deg, slide: 1 cm, poses: 40, seed: 2}
@PLANNER@
validation: {poses: 200}
workspace: {samples: 3000}
reach: {resolution: 4 cm, samples: 40000, orientations: 50, approach_tolerance: 10 deg, plan_targets: 1}
behaviour: {model: @ROBOTS@/insulator_cleaner_behaviors.yaml, insulators: 2}
)";

inline const char* const kPlanner = R"(planner:
  candidates: 3
  roadmap_nodes: 150
  max_roadmap_nodes: 600
  roadmap_seed: 4
  weight: 0.01
  base_step: 0 cm
  base_range: 0 cm
)";

inline std::string defaultStudyText() {
  return replaceOnce(replaceOnce(kStudy, "@PLANNER@", kPlanner), "@ROBOTS@", MCWS_ROBOTS_DIR);
}

/// A directory with the test robot, targets and study (`study` replacing the default).
struct StudyFiles {
  TempDir dir;
  explicit StudyFiles(const std::string& study = "") {
    std::string robot = readFile(robotPath("maintenance4"));
    const auto from = robot.find("  environment:"), to = robot.find("  allowed:");
    robot.replace(from, to - from, kRobotEnvironment);
    writeFile(dir.file("robot.yaml"), robot);
    writeFile(dir.file("targets.csv"), kTargets);
    writeFile(dir.file("study.yaml"), study.empty() ? defaultStudyText() : study);
  }
  std::string file(const std::string& name) const { return dir.file(name); }
};

}  // namespace mcws::test
