// The study file's reader: its behaviour model loaded and checked with the study (a bad model
// fails before any stage runs, "study.yaml:LINE: behaviour: model: ..."), the ranges of its
// counts stated in their messages, and `workspace: refine: 0` (no refinement).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "mcws/behavior/behavior_model.h"
#include "mcws/core/error.h"
#include "mcws/study/detail/study_stages.h"
#include "mcws/study/study.h"
#include "study/study_files.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

const std::string kReaderStudyExe = MCWS_STUDY_EXE;

// The line of the test study's `behaviour:` (after the planner's lines and an empty one).
constexpr int kBehaviourLineNumber = 26;

/// The shipped behaviour model with its robot named by its full path (the copy lies elsewhere),
/// `from` replaced by `to`.
std::string shippedModel(const std::string& from = "", const std::string& to = "") {
  std::string model =
      test::readFile(std::string(MCWS_ROBOTS_DIR) + "/insulator_cleaner_behaviors.yaml");
  model = test::replaceOnce(model, "robot: insulator_cleaner.yaml",
                            "robot: " + std::string(MCWS_ROBOTS_DIR) + "/insulator_cleaner.yaml");
  return from.empty() ? model : test::replaceOnce(model, from, to);
}

/// The test study (its files in `files`) naming the behaviour model `model` (as written).
std::string studyNamingModel(const std::string& model) {
  return test::replaceOnce(test::replaceOnce(test::kStudy, "@PLANNER@", test::kPlanner),
                           "@ROBOTS@/insulator_cleaner_behaviors.yaml", model);
}

/// The error of reading the test study with `from` replaced by `to`.
std::string readerError(const std::string& from, const std::string& to) {
  const test::StudyFiles files;
  const std::string text = test::replaceOnce(test::defaultStudyText(), from, to);
  return test::errorOf([&] { parseStudy(text, files.file("study.yaml")); });
}

/// What the study's reader says of the model `model_text` (written beside the study as
/// `name`), and, independently, what loading and validating it alone says.
struct ModelErrors {
  std::string study, model;
};
ModelErrors modelErrors(const std::string& name, const std::string& model_text) {
  const test::StudyFiles files(studyNamingModel(name));
  test::writeFile(files.file(name), model_text);
  ModelErrors errors;
  errors.study = test::errorOf([&] { loadStudy(files.file("study.yaml")); });
  try {
    validateBehaviorModel(loadBehaviorModel(files.file(name)));
  } catch (const Error& e) {
    errors.model = e.what();
  }
  return errors;
}

std::string atBehaviour(const test::StudyFiles& files) {
  return files.file("study.yaml") + ":" + std::to_string(kBehaviourLineNumber) +
         ": behaviour: model: ";
}

TEST(StudyBehaviourModel, MissingModelNamesTheStudysLineAndTheModel) {
  const test::StudyFiles files(studyNamingModel("nope.yaml"));
  EXPECT_EQ(test::errorOf([&] { loadStudy(files.file("study.yaml")); }),
            atBehaviour(files) + files.file("nope.yaml") +
                ": behaviour model file does not exist or is not a regular file");
}

TEST(StudyBehaviourModel, EmptyModelNamesTheStudysLineAndTheModel) {
  const ModelErrors errors = modelErrors("emptymodel.yaml", "");
  EXPECT_THAT(errors.model, HasSubstr("the document must be a map of behaviour model fields"));
  EXPECT_THAT(errors.study,
              HasSubstr(":" + std::to_string(kBehaviourLineNumber) + ": behaviour: model: "));
  // The model's own message, whole, after the study's place.
  EXPECT_THAT(errors.study, HasSubstr("study.yaml:26: behaviour: model: " + errors.model));
}

TEST(StudyBehaviourModel, ModelFailingValidationIsRefusedWithTheStudy) {
  // CB1's initial state q7 is not one of its states: parsed, refused by the validation.
  const ModelErrors errors = modelErrors("badq0.yaml", shippedModel("initial: q1", "initial: q7"));
  ASSERT_FALSE(errors.model.empty()) << "the changed model should fail validateBehaviorModel()";
  EXPECT_THAT(errors.study, HasSubstr("study.yaml:26: behaviour: model: " + errors.model));
}

TEST(StudyBehaviourModel, ModelTheJobCannotRunIsRefusedWithTheStudy) {
  // A valid model without CB3: the task plan (move down, clean, move up) cannot run.
  const ModelErrors errors = modelErrors("nocb3.yaml", shippedModel("name: CB3", "name: CB4"));
  EXPECT_EQ(errors.model, "") << "the changed model should pass validateBehaviorModel()";
  EXPECT_THAT(errors.study, HasSubstr("study.yaml:26: behaviour: model: "));
  EXPECT_THAT(errors.study, HasSubstr("nocb3.yaml: the task plan needs a combined behaviour CB3"));
}

TEST(StudyBehaviourModel, StudyFailsBeforeAnyStageAndWritesNothing) {
  const test::StudyFiles files(studyNamingModel("nope.yaml"));
  const test::RunResult r = test::run(kReaderStudyExe + " --study " + files.file("study.yaml") +
                                      " --output " + files.file("out"));
  EXPECT_EQ(r.exit_code, 1);
  // One line: no stage's progress before it.
  EXPECT_EQ(r.err, "mcws_study: " + atBehaviour(files) + files.file("nope.yaml") +
                       ": behaviour model file does not exist or is not a regular file\n");
  EXPECT_FALSE(std::filesystem::exists(files.file("out")));
  EXPECT_EQ(files.dir.fileCount(), 3u);  // robot, targets, study
}

TEST(StudyBehaviourModel, StageRehearsesTheModelReadWithTheStudy) {
  const test::StudyFiles files(studyNamingModel("model.yaml"));
  test::writeFile(files.file("model.yaml"), shippedModel());
  const Study study = loadStudy(files.file("study.yaml"));
  ASSERT_TRUE(study.behaviour.loaded.has_value());
  EXPECT_EQ(study.behaviour.loaded->name, "insulator_cleaner_behaviors");
  EXPECT_EQ(study.behaviour.insulators, 2);
  // The model and its robot are inputs of the run.
  EXPECT_THAT(study.inputs, ::testing::Contains(files.file("model.yaml")));
  EXPECT_THAT(study.inputs,
              ::testing::Contains(std::string(MCWS_ROBOTS_DIR) + "/insulator_cleaner.yaml"));
  // The stage runs the model read with the study: it does not read the file again.
  std::filesystem::remove(files.file("model.yaml"));
  detail::StudyState state;
  state.study = &study;
  detail::runBehaviour(state);
  EXPECT_EQ(state.report["behaviour"]["run"], true);
  EXPECT_EQ(state.report["behaviour"]["model"], files.file("model.yaml"));
}

/// "study.yaml:LINE: FIELD: VALUE must be a whole number from LOW to HIGH", the reader's words.
std::string outOfRange(int line, const std::string& field_value, const std::string& low = "1",
                       const std::string& high = "1000000000") {
  return "study.yaml:" + std::to_string(line) + ": " + field_value +
         " must be a whole number from " + low + " to " + high;
}

/// The test study with each `from` replaced by its `to` refused with the message `message`.
struct RefusedEdit {
  std::string from, to, message;
};
void expectRefused(const std::vector<RefusedEdit>& edits) {
  for (const RefusedEdit& edit : edits) {
    EXPECT_THAT(readerError(edit.from, edit.to), HasSubstr(edit.message)) << edit.to;
  }
}

/// The test study with `from` replaced by `to`, read.
Study studyWith(const std::string& from, const std::string& to) {
  const test::StudyFiles files;
  return parseStudy(test::replaceOnce(test::defaultStudyText(), from, to),
                    files.file("study.yaml"));
}

TEST(StudyCounts, CountsAboveTheirLimitNameTheLimit) {
  expectRefused({
      {"orientations: 50", "orientations: 4294967297",
       outOfRange(25, "reach: orientations: 4294967297")},
      {"{samples: 3000}", "{samples: 2000000000}",
       outOfRange(24, "workspace: samples: 2000000000")},
      {"{poses: 200}", "{poses: 0}", outOfRange(23, "validation: poses: 0")},
      // mcws_place takes --ik-starts from 1 to 1000.
      {"orientations: 50", "orientations: 50, ik_starts: 1001",
       outOfRange(25, "reach: ik_starts: 1001", "1", "1000")},
  });
}

TEST(StudyCounts, MapSamplesAsManyAsMcwsPlaceTakes) {
  // mcws_place --samples 2000000000 builds its map; so does the study.
  EXPECT_EQ(studyWith("samples: 40000", "samples: 2000000000").reach.samples, 2000000000u);
  const std::string most = "9007199254740992";
  expectRefused({
      {"samples: 40000", "samples: 10000000000000000",
       outOfRange(25, "reach: samples: 10000000000000000", "1", most)},
      {"samples: 40000", "samples: 0", outOfRange(25, "reach: samples: 0", "1", most)},
  });
}

TEST(StudyRefine, ZeroMeansNoRefinement) {
  EXPECT_EQ(studyWith("{samples: 3000}", "{samples: 3000, refine: 0}").workspace.refine, 0u);
  expectRefused({
      {"{samples: 3000}", "{samples: 3000, refine: -1}",
       outOfRange(24, "workspace: refine: -1", "0")},
      {"{samples: 3000}", "{samples: 3000, refine: 2.5}",
       outOfRange(24, "workspace: refine: 2.5", "0")},
  });
}

}  // namespace
}  // namespace mcws
