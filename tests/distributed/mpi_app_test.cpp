// mcws_sample and mcws_refine under mpirun (issue 18, section 1): the file of K processes is byte
// for byte the file of one, for any K and thread count; a process that fails or is killed ends
// the run with a non-zero exit code and leaves no output, not even a temporary file.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

const std::string kSample = MCWS_SAMPLE_EXE, kRefine = MCWS_REFINE_EXE,
                  kBoundary = MCWS_BOUNDARY_EXE, kReach = MCWS_REACH_EXE;

/// `mpirun -np K` with what this machine needs: more processes than cores, and root in a
/// container.
std::string mpirun(int processes) {
  return std::string(MCWS_MPIEXEC) + " -np " + std::to_string(processes) + " --oversubscribe" +
         (::geteuid() == 0 ? " --allow-run-as-root" : "");
}

/// Lines of `err` from the tool itself (the launcher adds its own banner of dashes and words).
int toolLines(const std::string& err, const std::string& tool) {
  int lines = 0;
  std::size_t at = 0;
  while ((at = err.find(tool + ": ", at)) != std::string::npos) {
    lines += at == 0 || err[at - 1] == '\n';
    at += tool.size();
  }
  return lines;
}

/// Two processes started from one command line but in two directories (two nodes' views of
/// "r.yaml"), each running `tool args`.
std::string twoDirectories(const std::string& first, const std::string& second,
                           const std::string& tool, const std::string& args) {
  return std::string(MCWS_MPIEXEC) + (::geteuid() == 0 ? " --allow-run-as-root" : "") +
         " --oversubscribe -np 1 --wdir " + first + " " + tool + args + " : -np 1 --wdir " +
         second + " " + tool + args;
}

/// Runs `args` on one process without mpirun and under mpirun on 1, 2 and 3 processes (each with
/// its own thread count), and expects the same bytes every time.
void expectSameFileOnAnyProcessCount(const std::string& tool, const std::string& args) {
  test::TempDir dir;
  const std::string alone = dir.file("alone.pcd");
  const test::RunResult one = test::run(tool + " " + args + " --threads 1 --output " + alone);
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const std::string expected = test::readFile(alone);
  ASSERT_GT(expected.size(), 1000u);
  for (const int k : {1, 2, 3}) {
    const std::string out = dir.file("np" + std::to_string(k) + ".pcd");
    const test::RunResult r = test::run(mpirun(k) + " " + tool + " " + args + " --threads " +
                                        std::to_string(4 - k) + " --output " + out + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(test::readFile(out) == expected) << tool << " " << args << " on " << k;
    // One process (rank 0) reports, for the whole run.
    const auto summary = nlohmann::json::parse(r.out);
    EXPECT_EQ(summary["processes"], k);
  }
  EXPECT_EQ(dir.fileCount(), 4u);  // no temporary file left beside them
}

TEST(MpiSample, ShapeCloudIsTheSameOnAnyProcessCount) {
  expectSameFileOnAnyProcessCount(kSample, "--shape ball --samples 300001 --seed 4");
}

TEST(MpiSample, CollisionLabelledCloudIsTheSame) {
  expectSameFileOnAnyProcessCount(
      kSample, "--robot " + test::robotPath("ta1400") + " --collision --samples 20000");
}

TEST(MpiSample, QualityCloudIsTheSame) {
  expectSameFileOnAnyProcessCount(
      kSample, "--robot " + test::robotPath("inspection6") + " --quality --samples 20000");
}

TEST(MpiSample, SummaryCountsEveryProcessesSamples) {
  test::TempDir dir;
  const test::RunResult one =
      test::run(kSample + " --robot " + test::robotPath("ta1400") +
                " --collision --samples 30000 --json --output " + dir.file("a.pcd"));
  const test::RunResult three =
      test::run(mpirun(3) + " " + kSample + " --robot " + test::robotPath("ta1400") +
                " --collision --samples 30000 --json --output " + dir.file("b.pcd"));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  ASSERT_EQ(three.exit_code, 0) << three.err;
  auto a = nlohmann::json::parse(one.out), b = nlohmann::json::parse(three.out);
  // The labels are counted on each process and added; the box is joined.
  EXPECT_EQ(a["labels"], b["labels"]);
  EXPECT_EQ(a["bbox"], b["bbox"]);
  EXPECT_EQ(b["points"], 30000);
  EXPECT_GT(b["labels"]["link-link"]["count"].get<int>(), 0);
}

TEST(MpiRefine, RefinedCloudIsTheSameOnAnyProcessCount) {
  test::TempDir dir;
  const std::string robot = test::robotPath("deicing");
  const std::string cloud = dir.file("cloud.pcd"), rim = dir.file("rim.pcd");
  ASSERT_EQ(
      test::run(kSample + " --robot " + robot + " --samples 20000 --output " + cloud).exit_code, 0);
  ASSERT_EQ(test::run(kBoundary + " --input " + cloud + " --output " + rim).exit_code, 0);
  // With --cloud: rank 0 copies the cloud, every process its block of the new samples.
  expectSameFileOnAnyProcessCount(
      kRefine, "--robot " + robot + " --input " + rim + " --cloud " + cloud + " --samples 30001");
  expectSameFileOnAnyProcessCount(
      kRefine, "--robot " + robot + " --input " + rim + " --samples 30001 --spread 0.05 --seed 9");
}

TEST(MpiBoundary, TiledBoundaryIsTheSameOnAnyProcessCount) {
  // The slabs shared among the processes, their flags gathered on rank 0, which writes.
  test::TempDir dir;
  const std::string cloud = dir.file("arm.pcd");
  ASSERT_EQ(test::run(kSample + " --robot " + test::robotPath("inspection6") +
                      " --samples 30000 --output " + cloud)
                .exit_code,
            0);
  const std::string args = "--input " + cloud;
  const test::RunResult whole =
      test::run(kBoundary + " " + args + " --output " + dir.file("b.pcd"));
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  for (const int k : {1, 2, 3}) {
    const std::string out = dir.file("np" + std::to_string(k) + ".pcd");
    const test::RunResult r = test::run(mpirun(k) + " " + kBoundary + " " + args +
                                        " --tiles 5 --threads 1 --json --output " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(test::readFile(out) == test::readFile(dir.file("b.pcd"))) << k;
    EXPECT_EQ(nlohmann::json::parse(r.out)["processes"], k);
  }
  // Without --tiles the whole cloud is one process's work: refused on two, nothing written.
  const test::RunResult two =
      test::run(mpirun(2) + " " + kBoundary + " " + args + " --output " + dir.file("x.pcd"));
  EXPECT_EQ(two.exit_code, 2);
  EXPECT_EQ(toolLines(two.err, "mcws_boundary"), 1) << two.err;
  EXPECT_THAT(two.err, HasSubstr("share a boundary only with --tiles N"));
  EXPECT_EQ(dir.fileCount(), 5u);
}

/// mcws_reach on one process and on 2 and 3 under mpirun: the same map (PCD and binary map).
void expectSameMapOnAnyProcessCount(const std::string& args) {
  test::TempDir dir;
  const auto outputs = [&](const std::string& name) {
    return " --output " + dir.file(name + ".pcd") + " --map " + dir.file(name + ".bin");
  };
  const test::RunResult one = test::run(kReach + " " + args + " --threads 1" + outputs("one"));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  for (const int k : {2, 3}) {
    const std::string name = "np" + std::to_string(k);
    const test::RunResult r =
        test::run(mpirun(k) + " " + kReach + " " + args + outputs(name) + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(test::readFile(dir.file(name + ".pcd")) == test::readFile(dir.file("one.pcd")));
    EXPECT_TRUE(test::readFile(dir.file(name + ".bin")) == test::readFile(dir.file("one.bin")));
    EXPECT_EQ(nlohmann::json::parse(r.out)["processes"], k);
  }
  EXPECT_EQ(dir.fileCount(), 6u);
}

TEST(MpiReach, MapIsTheSameOnAnyProcessCount) {
  // Counts add, bins unite, the best manipulability is the larger: merged along the tree.
  expectSameMapOnAnyProcessCount("--robot " + test::robotPath("inspection6") +
                                 " --resolution 10cm --samples 1000003");
}

TEST(MpiReach, CollisionFreeMapIsTheSame) {
  expectSameMapOnAnyProcessCount(
      "--robot " + test::robotPath("ta1400") +
      " --collision --resolution 100 --orientations 50 --samples 200000");
}

TEST(MpiReach, KilledRunContinuesFromItsCheckpoints) {
  // The run is stopped (SIGTERM to mpirun) once both processes have saved a checkpoint; the same
  // command run again continues from them and gives the map of an uninterrupted run, and a run
  // of another seed refuses them.
  test::TempDir dir, scratch;
  const std::string args =
      " --robot " + test::robotPath("inspection6") + " --resolution 10cm --samples 60000000";
  const test::RunResult one =
      test::run(kReach + args + " --output " + dir.file("one.pcd") + " --map " +
                dir.file("one.bin") + " --checkpoint " + dir.file("solo"));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const std::string run = mpirun(2) + " " + kReach + args + " --output " + dir.file("two.pcd") +
                          " --checkpoint " + dir.file("ck"),
                    every = " --checkpoint-every 100000";
  test::writeFile(scratch.file("stop.sh"),
                  run + every + " &\nlauncher=$!\nfor i in $(seq 600); do\n  [ -e " +
                      dir.file("ck.0") + " ] && [ -e " + dir.file("ck.1") +
                      " ] && break; sleep 0.05\ndone\nkill -TERM $launcher\nwait $launcher\n");
  const test::RunResult stopped = test::run("bash " + scratch.file("stop.sh"));
  ASSERT_NE(stopped.exit_code, 0) << "the run ended before it was stopped: make it longer";
  EXPECT_FALSE(std::filesystem::exists(dir.file("two.pcd")));
  ASSERT_TRUE(std::filesystem::exists(dir.file("ck.0")));
  // Another run (another seed) does not take these checkpoints, and leaves them as they are.
  const std::string saved = test::readFile(dir.file("ck.1"));
  const test::RunResult other = test::run(run + every + " --seed 2");
  EXPECT_EQ(other.exit_code, 1);
  EXPECT_THAT(other.err, HasSubstr("is of another run"));
  EXPECT_FALSE(std::filesystem::exists(dir.file("two.pcd")));
  EXPECT_TRUE(test::readFile(dir.file("ck.1")) == saved);
  // Resumed with pieces of another size: the merge is exact, so the map is the same.
  const test::RunResult resumed =
      test::run(run + " --checkpoint-every 300000 --map " + dir.file("two.bin") + " --json");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_GT(nlohmann::json::parse(resumed.out)["resumed_samples"].get<std::uint64_t>(), 0u);
  EXPECT_TRUE(test::readFile(dir.file("two.pcd")) == test::readFile(dir.file("one.pcd")));
  EXPECT_TRUE(test::readFile(dir.file("two.bin")) == test::readFile(dir.file("one.bin")));
  EXPECT_EQ(dir.fileCount(), 4u);  // the checkpoints are gone
}

TEST(MpiFailure, DifferentArgumentsOnTheProcessesAreRefused) {
  test::TempDir dir;
  const std::string out = dir.file("x.pcd");
  const test::RunResult r =
      test::run(std::string(MCWS_MPIEXEC) + (::geteuid() == 0 ? " --allow-run-as-root" : "") +
                " --oversubscribe -np 1 " + kSample + " --shape ball --samples 1000 --output " +
                out + " : -np 1 " + kSample + " --shape ball --samples 2000 --output " + out);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("mcws_sample: the 2 processes were not all given the same"));
  EXPECT_EQ(toolLines(r.err, "mcws_sample"), 1) << r.err;  // both failed; the first reports
  EXPECT_EQ(dir.fileCount(), 0u);
}

TEST(MpiFailure, BadInputOnOneProcessLeavesNoOutput) {
  // The same command line, but process 1 runs in a directory whose robot file is broken (a node
  // with a stale copy): it fails in its set-up, and process 0, whose set-up went well, ends
  // with it at the set-up agreement, before any output is opened.
  test::TempDir good, bad, out;
  test::writeFile(good.file("r.yaml"), test::readFile(test::robotPath("deicing")));
  test::writeFile(bad.file("r.yaml"), "name: [broken\n");
  const test::RunResult r =
      test::run(twoDirectories(good.file(""), bad.file(""), kSample,
                               " --robot r.yaml --samples 2000000 --output " + out.file("x.pcd")));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("mcws_sample: --robot: r.yaml:2: YAML syntax"));
  EXPECT_EQ(toolLines(r.err, "mcws_sample"), 1) << r.err;
  EXPECT_EQ(out.fileCount(), 0u);
}

TEST(MpiFailure, AnotherRobotOnOneProcessIsRefused) {
  // Both robot files are good, but they differ: the blocks would mix two robots in one file.
  test::TempDir first, second, out;
  test::writeFile(first.file("r.yaml"), test::readFile(test::robotPath("deicing")));
  test::writeFile(second.file("r.yaml"), test::readFile(test::robotPath("planar2")));
  for (const std::string& tool : {kSample, kReach}) {
    const std::string name = tool == kSample ? "mcws_sample" : "mcws_reach";
    const std::string extra = tool == kReach ? " --resolution 5" : "";
    const test::RunResult r = test::run(
        twoDirectories(first.file(""), second.file(""), tool,
                       " --robot r.yaml --samples 1000 --output " + out.file("x.pcd") + extra));
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_THAT(r.err, HasSubstr(name + ": --robot: the processes did not all read the same"));
    EXPECT_EQ(toolLines(r.err, name), 1) << r.err;
    EXPECT_EQ(out.fileCount(), 0u);
  }
}

TEST(MpiFailure, FailureAfterSetUpEndsEveryProcessWithItsCode) {
  // The planar arm inside a solid cage: every sample collides, which rank 0 finds after the
  // merge, while rank 1 waits for it: the run ends with rank 0's code and one line, nothing left.
  test::TempDir dir, out;
  std::string caged = test::readFile(test::robotPath("planar2"));
  caged += "    - {name: cage, type: box, size: [500, 500, 500], xyz: [0, 0, 0]}\n";
  test::writeFile(dir.file("caged.yaml"), caged);
  const test::RunResult r =
      test::run(mpirun(2) + " " + kReach + " --robot " + dir.file("caged.yaml") +
                " --resolution 5 --collision" + " --samples 20000 --threads 1 --output " +
                out.file("m.pcd") + " --map " + out.file("m.bin"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("mcws_reach: no sample counted: every sample collides"));
  EXPECT_EQ(toolLines(r.err, "mcws_reach"), 1) << r.err;
  EXPECT_EQ(out.fileCount(), 0u);
}

TEST(MpiFailure, BadCloudThatRankZeroAloneReadsIsOneLine) {
  // mcws_refine --cloud is read by rank 0 alone; its failure is agreed on at the set-up.
  test::TempDir dir, out;
  const std::string robot = test::robotPath("deicing");
  const std::string rim = dir.file("rim.pcd");
  ASSERT_EQ(test::run(kSample + " --robot " + robot + " --samples 2000 --output " + rim).exit_code,
            0);
  test::writeFile(dir.file("bad.pcd"), "not a cloud\n");
  const test::RunResult r =
      test::run(mpirun(2) + " " + kRefine + " --robot " + robot + " --input " + rim + " --cloud " +
                dir.file("bad.pcd") + " --samples 1000 --output " + out.file("x.pcd"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("mcws_refine: " + dir.file("bad.pcd")));
  EXPECT_EQ(toolLines(r.err, "mcws_refine"), 1) << r.err;
  EXPECT_EQ(out.fileCount(), 0u);
}

TEST(MpiFailure, KilledProcessLeavesNoOutput) {
  // Process 1 is killed (SIGKILL) once the temporary file exists; the launcher ends process 0,
  // which removes it. Mesh collision checks keep the run going for seconds.
  test::TempDir out, scratch;
  const std::string script = scratch.file("kill.sh");
  test::writeFile(script, mpirun(2) + " " + kSample + " --robot " + test::robotPath("ta1400_mesh") +
                              " --collision --samples 4000000 --threads 1 --output " +
                              out.file("k.pcd") +
                              " &\n"
                              "run=$!\n"
                              "for i in $(seq 600); do\n"  // up to 30 s for the temporary file
                              "  [ -n \"$(ls -A " +
                              out.file("") +
                              ")\" ] && break; sleep 0.05\n"
                              "done\n"
                              "for p in $(pgrep -f " +
                              out.file("k.pcd") +
                              "); do\n"
                              "  tr '\\0' '\\n' < /proc/$p/environ 2>/dev/null |"
                              " grep -qx OMPI_COMM_WORLD_RANK=1 && kill -9 $p\n"
                              "done\n"
                              "wait $run\n");
  const test::RunResult r = test::run("bash " + script);
  EXPECT_NE(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("exited on signal 9"));
  EXPECT_EQ(out.fileCount(), 0u);
}

TEST(MpiFailure, AsciiIsRefusedOnSeveralProcesses) {
  test::TempDir dir;
  const test::RunResult r =
      test::run(mpirun(2) + " " + kSample + " --shape disk --samples 100 --ascii --output " +
                dir.file("a.pcd"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("mcws_sample: --ascii: several processes write binary PCD only"));
  EXPECT_EQ(toolLines(r.err, "mcws_sample"), 1) << r.err;
  EXPECT_EQ(dir.fileCount(), 0u);
}

}  // namespace
}  // namespace mcws
