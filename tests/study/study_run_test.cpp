// The study library: the study file's reader (its errors name file:line and field) and the scene
// runStudy() makes (the robot's bodies, the path animation ending at the target).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <string>

#include "mcws/core/error.h"
#include "mcws/study/study.h"
#include "mcws/study/study_run.h"
#include "study/study_files.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

// IK's position tolerance is 1e-6 of the robot's length unit; the poses are floats (7 digits of
// an arm some 80 cm long).
constexpr double kToolPointTol = 1e-3;  // [cm]

/// The error of parsing the test study with `from` replaced by `to`.
std::string studyError(const std::string& from, const std::string& to) {
  const test::StudyFiles files;
  const std::string text = test::replaceOnce(test::defaultStudyText(), from, to);
  return test::errorOf([&] { parseStudy(text, files.file("study.yaml")); });
}

TEST(StudyReader, ConductorNeedsTwoPoints) {
  EXPECT_THAT(
      studyError("[[-300 cm, 0 cm, 25 cm], [300 cm, 0 cm, 25 cm]]", "[[-300 cm, 0 cm, 25 cm]]"),
      HasSubstr("study.yaml:6: line: conductor 1: points: must list at least two points"));
}

TEST(StudyReader, UnknownFieldAndMissingTargetsFile) {
  EXPECT_THAT(studyError("seed: 3", "seeds: 3"),
              HasSubstr("study.yaml:3: study: unknown key 'seeds'"));
  EXPECT_THAT(studyError("file: targets.csv", "file: none.csv"),
              HasSubstr("study.yaml:10: targets[1]: file: "));
  EXPECT_THAT(studyError("name: spacer, type", "name: conductor_a, type"),
              HasSubstr("study.yaml:8: line: fittings: name 'conductor_a' is already used"));
}

TEST(StudyReader, ConductorSegmentsAreCapsulesAndReplaceTheRobotsScene) {
  const test::StudyFiles files;
  const Study study =
      parseStudy(test::replaceOnce(test::defaultStudyText(), "[300 cm, 0 cm, 25 cm]]",
                                   "[0 cm, 0 cm, 25 cm], [0.5 m, 0 cm, 250 mm]]"),
                 files.file("study.yaml"));
  ASSERT_EQ(study.problem.collision.environment.size(), 2u);  // conductor_a, spacer
  const BodySpec& conductor = study.problem.collision.environment[0];
  ASSERT_EQ(conductor.shapes.size(), 2u);
  EXPECT_EQ(conductor.shapes[1].type, ShapeType::kCapsule);
  EXPECT_TRUE(conductor.shapes[1].p_to.isApprox(Eigen::Vector3d(50, 0, 25)));
  EXPECT_DOUBLE_EQ(conductor.shapes[1].radius, 1.5);
  EXPECT_EQ(study.replaced_environment, 2u);
  EXPECT_EQ(study.stops, (std::vector<double>{20, 30, 40}));
  EXPECT_EQ(study.targets.size(), 4u);
}

TEST(StudyRun, SceneHasTheRobotsBodiesAndAPathEndingAtItsTarget) {
  const test::StudyFiles files;
  const Study study = loadStudy(files.file("study.yaml"));
  std::filesystem::create_directory(files.file("out"));
  const StudyRun run = runStudy(study, files.file("out"));
  const report::Scene& scene = run.scene;
  EXPECT_EQ(scene.length_unit, "cm");
  ASSERT_EQ(scene.bodies.size(), 6u);  // base, j1 .. j4, tool
  EXPECT_EQ(scene.bodies.back().name, "tool");
  ASSERT_EQ(scene.animations.size(), 1u);
  const report::Animation& path = scene.animations[0];
  ASSERT_GT(path.frames, 1u);
  ASSERT_EQ(path.poses.size(), path.frames * scene.bodies.size() * 16);
  // The gripper's tip, 10 cm along z of the flange frame (robots/maintenance4.yaml), lands on
  // the planned target, t_1 at (48, -29, -42) cm, at the last frame.
  const float* last = path.poses.data() + ((path.frames - 1) * scene.bodies.size() + 5) * 16;
  const Eigen::Matrix4d T = Eigen::Map<const Eigen::Matrix4f>(last).cast<double>();
  const Eigen::Vector3d tip = (T * Eigen::Vector4d(0, 0, 10, 1)).head<3>();
  EXPECT_NEAR((tip - Eigen::Vector3d(48, -29, -42)).norm(), 0.0, kToolPointTol);
  // Targets coloured by the reach at the chosen stop: the one 3 m away is not reached.
  for (const report::Layer& layer : scene.layers) {
    if (layer.name == "targets") {
      EXPECT_EQ(layer.values, (std::vector<float>{1, 1, 1, 0}));
    }
  }
  EXPECT_EQ(run.report["planning"]["targets"][0]["target"], "t_1");
}

}  // namespace
}  // namespace mcws
