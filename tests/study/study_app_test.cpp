// mcws_study through its command line: the report's numbers against the tools run one by one on
// the same inputs and seeds (mcws_measure, mcws_envelope, mcws_place, mcws_plan), the same report
// for 1 and 2 threads, bad study files (one line naming file:line and field), and a failed run
// that leaves the output directory as it was.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "study/study_files.h"
#include "test_support.h"

namespace mcws {
namespace {

using test::kPlanner;
using test::StudyFiles;

using ::testing::ElementsAre;
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

/// The names in `dir`, sorted.
std::vector<std::string> entries(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
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

TEST_F(StudyRunTest, ReportIsMarkedAsAStudysReport) {
  EXPECT_EQ((*report_)["format"], "mcws_study report");
}

TEST_F(StudyRunTest, ReplacesTheOutputOfAnEarlierBuildWhoseReportHasNoFormat) {
  // What scripts/run_main.sh does after an update: out/study of a build before the marker.
  const test::TempDir dir;
  const std::string old = dir.file("old");
  std::filesystem::copy(files_->file("out"), old, std::filesystem::copy_options::recursive);
  Json report = Json::parse(test::readFile(old + "/report.json"));
  report.erase("format");
  report["study"] = "earlier";
  test::writeFile(old + "/report.json", report.dump());
  const std::string command =
      kStudyExe + " --study " + files_->file("study.yaml") + " --output " + old;
  const test::RunResult r = test::run(command);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Json::parse(test::readFile(old + "/report.json"))["format"], "mcws_study report");
  // Without one of a study report's members it is no study's report: refused, kept.
  report.erase("stages");
  test::writeFile(old + "/report.json", report.dump());
  const test::RunResult partial = test::run(command);
  EXPECT_EQ(partial.exit_code, 2) << partial.err;
  EXPECT_THAT(partial.err, HasSubstr("its report.json has no \"format\""));
  EXPECT_EQ(Json::parse(test::readFile(old + "/report.json")), report);
}

TEST_F(StudyRunTest, RefusesAFormerOutputHoldingFilesAStudyDoesNotWriteNamingTheFirst) {
  const test::TempDir dir;
  const std::string proj = dir.file("proj");
  std::filesystem::copy(files_->file("out"), proj, std::filesystem::copy_options::recursive);
  std::filesystem::create_directory(proj + "/data");
  test::writeFile(proj + "/data/thesis.tex", "precious\n");
  test::writeFile(proj + "/notes.txt", "mine");
  const std::string command =
      kStudyExe + " --study " + files_->file("study.yaml") + " --output " + proj;
  const test::RunResult data = test::run(command);
  EXPECT_EQ(data.exit_code, 2) << data.err;
  EXPECT_EQ(test::lineCount(data.err), 1) << data.err;
  // "data" is the first in name order: boundary.pcd, data, drawing.png, ...
  EXPECT_THAT(data.err, HasSubstr("--output " + proj +
                                  ": neither empty nor a former study's "
                                  "output (it holds data, which a study does not write)"));
  EXPECT_EQ(test::readFile(proj + "/data/thesis.tex"), "precious\n");
  EXPECT_EQ(test::readFile(proj + "/notes.txt"), "mine");
  // A path file the report does not name is no study's either.
  std::filesystem::remove_all(proj + "/data");
  std::filesystem::remove(proj + "/notes.txt");
  test::writeFile(proj + "/path_other.csv", "mine");
  const test::RunResult path = test::run(command);
  EXPECT_EQ(path.exit_code, 2) << path.err;
  EXPECT_THAT(path.err, HasSubstr("it holds path_other.csv, which a study does not write"));
  EXPECT_EQ(test::readFile(proj + "/path_other.csv"), "mine");
  EXPECT_THAT(entries(dir.file("")), ElementsAre("proj"));  // nothing left beside it
}

TEST_F(StudyRunTest, ReplacesAFormerOutputNamedWithATrailingSlash) {
  const test::TempDir dir;
  const std::string sc1 = dir.file("sc1");
  std::filesystem::copy(files_->file("out"), sc1, std::filesystem::copy_options::recursive);
  Json old = Json::parse(test::readFile(sc1 + "/report.json"));
  old["study"] = "old study";
  test::writeFile(sc1 + "/report.json", old.dump());
  std::filesystem::remove(sc1 + "/drawing.png");
  // The cache's folder shares the name's first letters, not its folder: it is not inside.
  const test::RunResult r = test::run(kStudyExe + " --study " + files_->file("study.yaml") +
                                      " --output " + sc1 + "/ --map-cache " + sc1 + "-cache");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Json::parse(test::readFile(sc1 + "/report.json"))["study"], "test study");
  EXPECT_TRUE(std::filesystem::exists(sc1 + "/drawing.png"));
  EXPECT_THAT(entries(dir.file("")), ElementsAre("sc1", "sc1-cache"));
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

/// A former output's report.json, as far as the refusal of other folders reads it.
const std::string kOldReport = R"({"format": "mcws_study report", "study": "old"})";

/// The test study whose stops reach no target: it fails in the placement stage.
std::string unreachingStudy() {
  std::string study = defaultStudy();
  test::replaceAll(study, "from: 20 cm, to: 40 cm", "from: 400 cm, to: 420 cm");
  return study;
}

TEST(StudyApp, NoStopReachingAnyTargetNamesTheTargetsAndLeavesOutputAlone) {
  const StudyFiles files(unreachingStudy());
  std::filesystem::create_directory(files.file("out"));
  test::writeFile(files.file("out/report.json"), kOldReport);
  const test::RunResult r = test::run(kStudyExe + " --study " + files.file("study.yaml") +
                                      " --output " + files.file("out"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("stops: no stop from 400 to 420 cm reaches any target "
                               "(targets t_1, t_2, t_3, t_4)"));
  EXPECT_EQ(test::readFile(files.file("out/report.json")), kOldReport);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(files.file("out")),
                          std::filesystem::directory_iterator()),
            1);
  // Nothing left beside it: the robot, targets and study files only, and the directory.
  EXPECT_EQ(files.dir.fileCount(), 4u);
}

/// mcws_study run in `files`' folder with --output `output`, ended by SIGTERM as soon as the
/// directory the study writes into has appeared in that folder: its stdout says how many such
/// directories were seen ("1\n") and the run's status ("status 143": ended by the signal).
test::RunResult stoppedBySignal(const StudyFiles& files, const std::string& output) {
  return test::run("cd " + files.file("") + " && (" + kStudyExe + " --study study.yaml --output " +
                   output +
                   " 2>/dev/null & pid=$!; for i in $(seq 500); do "
                   "ls -a | grep -q mcws-study && break; sleep 0.01; done; "
                   "ls -a | grep -c mcws-study; kill -TERM $pid; wait $pid; echo \"status $?\")");
}

TEST(StudyApp, RunStoppedBySignalLeavesNothingBesideTheOutputAndTheOutputAsItWas) {
  const StudyFiles files;
  std::filesystem::create_directory(files.file("out"));
  test::writeFile(files.file("out/report.json"), kOldReport);
  const test::RunResult r = stoppedBySignal(files, "out");
  EXPECT_THAT(r.out, StartsWith("1\n")) << "the study's directory was not seen: " << r.out;
  EXPECT_THAT(r.out, HasSubstr("status 143"));  // 128 + SIGTERM: ended by the signal
  EXPECT_EQ(test::readFile(files.file("out/report.json")), kOldReport);
  EXPECT_EQ(files.dir.fileCount(), 4u);  // robot, targets, study and out/: nothing beside them
}

TEST(StudyApp, RunToANewNestedOutputStoppedBySignalLeavesNothing) {
  const StudyFiles files;
  // The study's directory is made in the nearest existing folder, here the study's own.
  const test::RunResult r = stoppedBySignal(files, "new/deeper/out");
  EXPECT_THAT(r.out, StartsWith("1\n")) << "the study's directory was not seen: " << r.out;
  EXPECT_THAT(r.out, HasSubstr("status 143"));
  EXPECT_THAT(entries(files.file("")), ElementsAre("robot.yaml", "study.yaml", "targets.csv"));
}

TEST(StudyApp, MakesANewOutputNamedWithATrailingSlash) {
  const StudyFiles files;
  const test::RunResult r = test::run("cd " + files.file("") + " && " + kStudyExe +
                                      " --study study.yaml --output newdir/");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Json::parse(test::readFile(files.file("newdir/report.json")))["study"], "test study");
  EXPECT_THAT(entries(files.file("")),
              ElementsAre("newdir", "robot.yaml", "study.yaml", "targets.csv"));
}

TEST(StudyApp, MakesTheMissingParentFoldersOfANewOutput) {
  const StudyFiles files;
  const test::RunResult r = test::run("cd " + files.file("") + " && " + kStudyExe +
                                      " --study study.yaml --output out/study");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Json::parse(test::readFile(files.file("out/study/report.json")))["study"],
            "test study");
  EXPECT_THAT(entries(files.file("")),
              ElementsAre("out", "robot.yaml", "study.yaml", "targets.csv"));
  EXPECT_THAT(entries(files.file("out")), ElementsAre("study"));
}

TEST(StudyApp, FailedRunToANewNestedOutputMakesNoFolder) {
  const StudyFiles files(unreachingStudy());
  const test::RunResult r = test::run("cd " + files.file("") + " && " + kStudyExe +
                                      " --study study.yaml --output out/deeper/study");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("stops: no stop from 400 to 420 cm reaches any target"));
  EXPECT_THAT(entries(files.file("")), ElementsAre("robot.yaml", "study.yaml", "targets.csv"));
}

TEST(StudyApp, RefusesAMapCacheInsideTheOutput) {
  const StudyFiles files;
  const std::string study = "cd " + files.file("") + " && " + kStudyExe + " --study study.yaml ";
  const test::RunResult inside = test::run(study + "--output fo2 --map-cache fo2/cache");
  EXPECT_EQ(inside.exit_code, 2) << inside.err;
  EXPECT_EQ(test::lineCount(inside.err), 1) << inside.err;
  EXPECT_THAT(inside.err, HasSubstr("--map-cache fo2/cache: the folder is --output fo2 or inside "
                                    "it"));
  const test::RunResult same = test::run(study + "--output fo2/ --map-cache ./fo2");
  EXPECT_EQ(same.exit_code, 2) << same.err;
  EXPECT_THAT(same.err, HasSubstr("--map-cache ./fo2: the folder is --output fo2/ or inside it"));
  std::filesystem::create_directory(files.file("fo2"));
  const test::RunResult existing = test::run(study + "--output fo2 --map-cache fo2/a/b");
  EXPECT_EQ(existing.exit_code, 2) << existing.err;
  EXPECT_THAT(existing.err, HasSubstr("--map-cache fo2/a/b: the folder is --output fo2"));
  EXPECT_THAT(entries(files.file("")),
              ElementsAre("fo2", "robot.yaml", "study.yaml", "targets.csv"));
  EXPECT_TRUE(std::filesystem::is_empty(files.file("fo2")));
}

TEST(StudyApp, RefusesAFolderWhoseReportJsonIsNoStudysAndKeepsItsFiles) {
  const StudyFiles files;
  std::filesystem::create_directories(files.file("proj/data"));
  test::writeFile(files.file("proj/report.json"), R"({"tool":"x"})");
  test::writeFile(files.file("proj/data/thesis.tex"), "precious\n");
  const test::RunResult r = test::run(kStudyExe + " --study " + files.file("study.yaml") +
                                      " --output " + files.file("proj"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(test::lineCount(r.err), 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("--output " + files.file("proj") +
                               ": neither empty nor a former study's output (its report.json "
                               "has no \"format\": \"mcws_study report\")"));
  EXPECT_EQ(test::readFile(files.file("proj/data/thesis.tex")), "precious\n");
  EXPECT_EQ(test::readFile(files.file("proj/report.json")), R"({"tool":"x"})");
  EXPECT_EQ(files.dir.fileCount(), 4u);  // robot, targets, study and proj/: nothing beside them
  // A study's report naming as a path file what is no path file (path_<target>.csv).
  std::filesystem::remove_all(files.file("proj/data"));
  test::writeFile(files.file("proj/report.json"),
                  R"({"format": "mcws_study report", "planning": {"targets": [)"
                  R"({"path_file": "thesis.tex"}]}})");
  test::writeFile(files.file("proj/thesis.tex"), "precious\n");
  const test::RunResult named = test::run(kStudyExe + " --study " + files.file("study.yaml") +
                                          " --output " + files.file("proj"));
  EXPECT_EQ(named.exit_code, 2) << named.err;
  EXPECT_THAT(named.err, HasSubstr("it holds thesis.tex, which a study does not write"));
  EXPECT_EQ(test::readFile(files.file("proj/thesis.tex")), "precious\n");
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
  EXPECT_THAT(help.out, HasSubstr("mcws_study --study STUDY.yaml --output DIR [--json] [--seed N] "
                                  "[--threads N] [--map-cache DIR|off]"));
  EXPECT_THAT(help.out, HasSubstr("output directory (made, with missing parent folders, or"));
}

}  // namespace
}  // namespace mcws
