// mcws_study through its command line: the report's numbers against the tools run one by one on
// the same inputs and seeds (mcws_measure, mcws_envelope, mcws_place, mcws_plan), the same report
// for 1 and 2 threads, bad study files (one line naming file:line and field), and a failed run
// that leaves the output directory as it was.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "study/study_files.h"
#include "test_support.h"

namespace mcws {
namespace {

using test::kPlanner;
using test::StudyFiles;

using ::testing::HasSubstr;
using ::testing::StartsWith;
using Json = nlohmann::json;

const std::string kStudyExe = MCWS_STUDY_EXE;
const std::string kMeasureExe = MCWS_MEASURE_EXE;
const std::string kEnvelopeExe = MCWS_ENVELOPE_EXE;
const std::string kPlaceExe = MCWS_PLACE_EXE;
const std::string kPlanExe = MCWS_PLAN_EXE;
const std::string kBehaveExe = MCWS_BEHAVE_EXE;
const std::string kRefineExe = MCWS_REFINE_EXE;

// A goal and a pivot written as text with 17 digits and converted cm -> cm by the scenario reader
// (x * 0.01 / 0.01) may differ from the study's own by an ulp: numbers of the plan agree to this
// relative tolerance, counts exactly.
constexpr double kPlanTol = 1e-9;

/// The report with every "seconds" (and "*_seconds") member removed, and the view's table of
/// the stages' times.
Json withoutSeconds(Json json) {
  if (json.is_object() && json.contains("title") && json["title"] == "Time of each stage")
    return Json();
  if (json.is_object()) {
    Json out = Json::object();
    for (auto& [key, value] : json.items()) {
      if (key == "seconds" || (key.size() > 8 && key.compare(key.size() - 8, 8, "_seconds") == 0))
        continue;
      out[key] = withoutSeconds(value);
    }
    return out;
  }
  if (json.is_array()) {
    for (auto& item : json) item = withoutSeconds(item);
  }
  return json;
}

/// Numbers equal to kPlanTol (relative), everything else exactly; `where` names the member.
void expectClose(const Json& a, const Json& b, const std::string& where) {
  if (a.is_number_float() || b.is_number_float()) {
    ASSERT_TRUE(a.is_number() && b.is_number()) << where;
    const double x = a.get<double>(), y = b.get<double>();
    EXPECT_NEAR(x, y, kPlanTol * std::max(1.0, std::abs(y))) << where;
  } else if (a.is_object() && b.is_object()) {
    ASSERT_EQ(a.size(), b.size()) << where;
    for (auto& [key, value] : a.items()) {
      ASSERT_TRUE(b.contains(key)) << where << "/" << key;
      expectClose(value, b.at(key), where + "/" + key);
    }
  } else if (a.is_array() && b.is_array()) {
    ASSERT_EQ(a.size(), b.size()) << where;
    for (std::size_t k = 0; k < a.size(); ++k)
      expectClose(a[k], b[k], where + "/" + std::to_string(k));
  } else {
    EXPECT_EQ(a, b) << where;
  }
}

Json runStudy(const StudyFiles& files, const std::string& out, const std::string& flags) {
  const test::RunResult r = test::run(kStudyExe + " --study " + files.file("study.yaml") +
                                      " --output " + out + " --json " + flags);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.exit_code == 0 ? Json::parse(r.out) : Json();
}

/// One run of the test study shared by the comparisons (it takes a few seconds).
class StudyRunTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    files_ = new StudyFiles();
    report_ = new Json(runStudy(*files_, files_->file("out"), "--threads 2"));
  }
  static void TearDownTestSuite() {
    delete report_;
    delete files_;
  }
  static StudyFiles* files_;
  static Json* report_;
};
StudyFiles* StudyRunTest::files_ = nullptr;
Json* StudyRunTest::report_ = nullptr;

TEST_F(StudyRunTest, WritesTheReportAndItsFiles) {
  for (const char* name : {"report.json", "report.html", "samples.pcd", "boundary.pcd",
                           "envelope.ply", "drawing.png"}) {
    EXPECT_TRUE(std::filesystem::exists(files_->file("out/" + std::string(name)))) << name;
  }
  EXPECT_EQ(Json::parse(test::readFile(files_->file("out/report.json"))), *report_);
  // The target 3 m away is reported, and the study went on for the others.
  EXPECT_EQ((*report_)["placement"]["unreached_by_every_stop"], Json::array({"t_4"}));
  EXPECT_EQ((*report_)["planning"]["targets"].size(), 1u);
  // Every answer's source pointer holds the answer's value.
  for (const Json& answer : (*report_)["view"]["answers"]) {
    EXPECT_EQ(report_->at(Json::json_pointer(answer["source"].get<std::string>())), answer["value"])
        << answer["label"];
  }
}

TEST_F(StudyRunTest, VolumeIsMcwsMeasuresOnTheStudysSamples) {
  const test::RunResult r =
      test::run(kMeasureExe + " --input " + files_->file("out/samples.pcd") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json measure = Json::parse(r.out);
  EXPECT_EQ((*report_)["workspace"]["measure"]["volume"], measure["volume"]);
  EXPECT_EQ((*report_)["workspace"]["measure"]["outside"], measure["outside"]);
  EXPECT_EQ((*report_)["workspace"]["measure"]["units"]["volume"], "cm^3");
}

TEST_F(StudyRunTest, EnvelopeIsMcwsEnvelopesOnTheStudysSamples) {
  const test::RunResult r = test::run(kEnvelopeExe + " --input " + files_->file("out/samples.pcd") +
                                      " --drawing " + files_->file("drawing.png") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json envelope = Json::parse(r.out);
  for (const char* key : {"volume", "area", "offset", "triangles", "vertices"})
    EXPECT_EQ((*report_)["workspace"]["envelope"][key], envelope[key]) << key;
  EXPECT_EQ((*report_)["workspace"]["envelope"]["drawing"]["max_reach"],
            envelope["drawing"]["max_reach"]);
}

TEST_F(StudyRunTest, PlacementIsMcwsPlacesOverTheSameStops) {
  const test::RunResult r = test::run(
      kPlaceExe + " --robot " + files_->file("robot.yaml") + " --targets " +
      files_->file("targets.csv") +
      " --along '20 40 10' --resolution 4 --samples 40000 --orientations 50 --seed 3"
      " --approach-tolerance 10deg --confirm all --threads 1 --map-cache off --json --output " +
      files_->file("bases.pcd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json place = Json::parse(r.out);
  EXPECT_EQ((*report_)["placement"]["candidates"], place["candidates"]);
  EXPECT_EQ((*report_)["placement"]["best"], place["best"]);
  EXPECT_EQ((*report_)["placement"]["map"], place["map"]);
}

TEST_F(StudyRunTest, PlanIsMcwsPlansOnTheEquivalentScenario) {
  const Json& planned = (*report_)["planning"]["targets"][0];
  const double stop = planned["stop"].get<double>();
  std::ostringstream goal, scenario;
  goal.precision(17);
  const char* units[] = {" rad", " cm", " rad", " cm"};
  for (int j = 0; j < 4; ++j)
    goal << (j ? ", " : "") << planned["goal"][j].get<double>() << units[j];
  scenario.precision(17);
  scenario << "name: equivalent\nrobot: robot.yaml\nstart: [0 rad, 0 cm, 0 rad, 0 cm]\n"
           << "goal: [" << goal.str() << "]\n"
           << "base: {xyz: [" << stop << " cm, 0 cm, -20 cm], rpy: [180 deg, 0 deg, 0 deg]}\n"
           << "sway: {pivot: [" << stop << " cm, 0 cm, 25 cm], line: [1, 0, 0], swing: 2 deg, "
           << "slide: 1 cm, poses: 40, seed: 2}\n"
           << kPlanner << "validation: {poses: 200}\n";
  test::writeFile(files_->file("scenario.yaml"), scenario.str());
  const test::RunResult r = test::run(kPlanExe + " --scenario " + files_->file("scenario.yaml") +
                                      " --output " + files_->file("path.csv") + " --json");
  ASSERT_LE(r.exit_code, 1) << r.err;  // 1: no path accepted, still a report
  const Json plan = withoutSeconds(Json::parse(r.out));
  const Json study_plan = withoutSeconds(planned["plan"]);
  for (const char* key : {"status", "rounds", "validation"}) {
    ASSERT_TRUE(plan.contains(key)) << key;
    expectClose(study_plan[key], plan[key], key);
  }
}

TEST_F(StudyRunTest, BehaviourIsMcwsBehavesRehearsal) {
  const test::RunResult r = test::run(kBehaveExe + " --model " + MCWS_ROBOTS_DIR +
                                      "/insulator_cleaner_behaviors.yaml --insulators 2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Json study_behaviour = (*report_)["behaviour"];
  for (const char* key : {"run", "model", "failure"}) study_behaviour.erase(key);
  EXPECT_EQ(study_behaviour, Json::parse(r.out));
  bool timeline = false;
  for (const Json& section : (*report_)["view"]["sections"])
    timeline = timeline || (section["kind"] == "timeline" && !section["events"].empty());
  EXPECT_TRUE(timeline);
}

TEST(StudyApp, SameReportForOneAndTwoThreads) {
  const StudyFiles files;
  const Json one = runStudy(files, files.file("one"), "--threads 1 --seed 5");
  const Json two = runStudy(files, files.file("two"), "--threads 2 --seed 5");
  ASSERT_FALSE(one.is_null());
  EXPECT_EQ(withoutSeconds(one), withoutSeconds(two));
  EXPECT_EQ(one["seed"], 5);
}

/// The one-line error of a run of `study`, whose exit code must be `exit_code`.
std::string failure(const std::string& study, int exit_code = 1) {
  const StudyFiles files(study);
  const test::RunResult r = test::run(kStudyExe + " --study " + files.file("study.yaml") +
                                      " --output " + files.file("out"));
  EXPECT_EQ(r.exit_code, exit_code) << r.err;
  EXPECT_EQ(test::lineCount(r.err), 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(files.file("out")));
  return r.err;
}

std::string defaultStudy() { return test::defaultStudyText(); }

TEST(StudyApp, OffsetsScanPlansEachTargetAgainAtEveryShiftTheShiftZeroBeingThePlanItself) {
  const StudyFiles files(defaultStudy() + "offsets: {range: 4 cm, step: 2 cm}\n");
  const Json report = runStudy(files, files.file("out"), "");
  ASSERT_FALSE(report.is_null());
  std::size_t scanned = 0;
  for (const Json& target : report["planning"]["targets"]) {
    const Json& plan_round = target["plan"]["rounds"][0];
    ASSERT_TRUE(target.contains("offsets"));
    const Json& rows = target["offsets"];
    ASSERT_EQ(rows.size(), 5u);
    for (std::size_t k = 0; k < rows.size(); ++k)
      EXPECT_NEAR(rows[k]["base_offset"].get<double>(), -4.0 + 2.0 * k, 1e-12);
    if (!plan_round.contains("best")) continue;
    // The round at shift 0 is the planning of the chosen stop itself: the same best path.
    EXPECT_EQ(rows[2]["P"], plan_round["best"]["probability"]);
    EXPECT_EQ(rows[2]["whole_path_free_fraction"], plan_round["best"]["whole_path_free_fraction"]);
    ++scanned;
  }
  EXPECT_GT(scanned, 0u);
  bool charted = false;
  for (const Json& section : report["view"]["sections"])
    charted = charted || section["title"] == "P against the base offset from the chosen stop";
  EXPECT_TRUE(charted);
}

TEST(StudyApp, RefinedVolumeIsMcwsRefineThenMcwsMeasureOnTheStudysFiles) {
  const StudyFiles files(test::replaceOnce(defaultStudy(), "workspace: {samples: 3000}",
                                           "workspace: {samples: 3000, refine: 4000, alpha: 5}"));
  const Json report = runStudy(files, files.file("out"), "");
  ASSERT_FALSE(report.is_null());
  EXPECT_EQ(report["workspace"]["refine"]["points"], 7000);
  const std::string refined = files.file("r.pcd");
  const test::RunResult refine =
      test::run(kRefineExe + " --robot " + files.file("robot.yaml") + " --input " +
                files.file("out/boundary.pcd") + " --cloud " + files.file("out/samples.pcd") +
                " --samples 4000 --seed 3 --output " + refined);
  ASSERT_EQ(refine.exit_code, 0) << refine.err;
  const test::RunResult r =
      test::run(kMeasureExe + " --input " + refined + " --correction none --alpha 5 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json measure = Json::parse(r.out);
  EXPECT_EQ(report["workspace"]["measure"]["volume"], measure["volume"]);
  EXPECT_EQ(report["workspace"]["measure"]["outside"], measure["outside"]);
  EXPECT_EQ(report["workspace"]["measure"]["correction"], "none");
  EXPECT_EQ(measure["correction"], "none");
}

TEST(StudyApp, OffsetsOfNoStepAreRefused) {
  const std::string err = failure(defaultStudy() + "offsets: {range: 4 cm, step: 0 cm}\n");
  EXPECT_THAT(err, HasSubstr("offsets: step must be > 0"));
  EXPECT_THAT(err, HasSubstr("study.yaml:"));
}

TEST(StudyApp, UnknownFittingTypeNamesFileLineAndField) {
  const std::string err = failure(test::replaceOnce(defaultStudy(), "type: box", "type: cone"));
  EXPECT_THAT(err, HasSubstr("study.yaml:8: line: fitting 1 'spacer': type 'cone' is not "
                             "capsule, sphere, box, cylinder or mesh"));
}

TEST(StudyApp, EmptyStopRangeNamesFileLineAndField) {
  const std::string err = failure(
      test::replaceOnce(defaultStudy(), "from: 20 cm, to: 40 cm", "from: 40 cm, to: 20 cm"));
  EXPECT_THAT(err, HasSubstr("study.yaml:11: stops: the range is empty: to 20 cm is below "
                             "from 40 cm"));
}

TEST(StudyApp, RobotWithoutCollisionGeometryIsRefused) {
  const StudyFiles files(
      test::replaceOnce(defaultStudy(), "robot: robot.yaml", "robot: bare.yaml"));
  const std::string robot = test::readFile(files.file("robot.yaml"));
  test::writeFile(files.file("bare.yaml"), robot.substr(0, robot.find("\ncollision:") + 1));
  const test::RunResult r = test::run(kStudyExe + " --study " + files.file("study.yaml") +
                                      " --output " + files.file("out"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(test::lineCount(r.err), 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("study.yaml:2: robot: 'bare.yaml' has no collision geometry"));
}

TEST(StudyApp, NoStopReachingAnyTargetNamesTheTargetsAndLeavesOutputAlone) {
  std::string study = defaultStudy();
  test::replaceAll(study, "from: 20 cm, to: 40 cm", "from: 400 cm, to: 420 cm");
  const StudyFiles files(study);
  std::filesystem::create_directory(files.file("out"));
  test::writeFile(files.file("out/report.json"), "old report");
  const test::RunResult r = test::run(kStudyExe + " --study " + files.file("study.yaml") +
                                      " --output " + files.file("out"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("stops: no stop from 400 to 420 cm reaches any target "
                               "(targets t_1, t_2, t_3, t_4)"));
  EXPECT_EQ(test::readFile(files.file("out/report.json")), "old report");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(files.file("out")),
                          std::filesystem::directory_iterator()),
            1);
  // Nothing left beside it: the robot, targets and study files only, and the directory.
  EXPECT_EQ(files.dir.fileCount(), 4u);
}

TEST(StudyApp, RunStoppedBySignalLeavesNothingBesideTheOutputAndTheOutputAsItWas) {
  const StudyFiles files;
  std::filesystem::create_directory(files.file("out"));
  test::writeFile(files.file("out/report.json"), "old report");
  // SIGTERM as soon as the directory the study writes into has appeared beside out/.
  const test::RunResult r =
      test::run("cd " + files.file("") + " && (" + kStudyExe +
                " --study study.yaml --output out 2>/dev/null & pid=$!; for i in $(seq 500); do "
                "ls -a | grep -q mcws-study && break; sleep 0.01; done; "
                "ls -a | grep -c mcws-study; kill -TERM $pid; wait $pid; echo \"status $?\")");
  EXPECT_THAT(r.out, StartsWith("1\n")) << "the study's directory was not seen: " << r.out;
  EXPECT_THAT(r.out, HasSubstr("status 143"));  // 128 + SIGTERM: ended by the signal
  EXPECT_EQ(test::readFile(files.file("out/report.json")), "old report");
  EXPECT_EQ(files.dir.fileCount(), 4u);  // robot, targets, study and out/: nothing beside them
}

TEST(StudyApp, RefusesToReplaceADirectoryOfInputsOrOfOtherFiles) {
  const StudyFiles files;
  const test::RunResult inputs =
      test::run(kStudyExe + " --study " + files.file("study.yaml") + " --output " + files.file(""));
  EXPECT_EQ(inputs.exit_code, 2);
  EXPECT_THAT(inputs.err, HasSubstr("study.yaml, an input of the run"));
  std::filesystem::create_directory(files.file("other"));
  test::writeFile(files.file("other/notes.txt"), "mine");
  const test::RunResult other = test::run(kStudyExe + " --study " + files.file("study.yaml") +
                                          " --output " + files.file("other"));
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_THAT(other.err, HasSubstr("neither empty nor a former study's output"));
  EXPECT_EQ(test::readFile(files.file("other/notes.txt")), "mine");
}

TEST(StudyApp, UsageErrorsExitTwo) {
  const StudyFiles files;
  const test::RunResult no_output = test::run(kStudyExe + " --study " + files.file("study.yaml"));
  EXPECT_EQ(no_output.exit_code, 2);
  EXPECT_THAT(no_output.err, HasSubstr("--output"));
  const test::RunResult help = test::run(kStudyExe + " --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_THAT(help.out, HasSubstr("mcws_study --study STUDY.yaml --output DIR"));
}

}  // namespace
}  // namespace mcws
