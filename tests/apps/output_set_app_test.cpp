// Every tool with several outputs writes them as one set (io::OutputSet): when any one of them
// cannot be written, the run fails with one line and exit code 1, and nothing that lay at any
// output path is touched (contents, file type, the directory's other entries). Each output is
// failed in turn, in three ways: a read-only file, a FIFO without a reader and a file system that
// is full when the output is flushed (a small tmpfs, filled to the last page before the run).
// Also: two spellings of one new file are refused, /dev/stdout appends to a shell's `>> log`, and
// an output that is a file the run reads indirectly (a robot's collision mesh) is refused.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "apps/output_test_inputs.h"
#include "apps/tool_paths.h"
#include "test_support.h"

namespace mcws {
namespace {

namespace fs = std::filesystem;

/// A tool with several outputs: its flags but the outputs, and the output flags with a file name
/// each (the extension picks the format).
struct OutputSetCase {
  std::string name;
  std::string tool;
  std::string args;  ///< "{dir}" stands for a directory of the test's own (inputs made there)
  std::vector<std::pair<std::string, std::string>> outputs;  ///< (flag, file name)
};

void PrintTo(const OutputSetCase& c, std::ostream* out) { *out << c.name; }

/// A 3-D cloud for mcws_envelope: 3000 points of the unit ball, made once.
const std::string& ballCloud() {
  static test::TempDir dir;
  static const std::string path = [] {
    const std::string file = dir.file("ball.pcd");
    const test::RunResult r = test::run(std::string(MCWS_SAMPLE_EXE) +
                                        " --shape ball --samples 3000 --seed 1 --output " + file);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return file;
  }();
  return path;
}

/// The tool's command line but the outputs: "{dir}" is `dir`, "{ball}" ballCloud(), "{targets}"
/// two targets of the planar arm written into `dir`.
std::string commandOf(const OutputSetCase& c, const std::string& dir) {
  std::string command = c.tool + " " + c.args;
  if (command.find("{targets}") != std::string::npos) {
    test::writeFile(dir + "targets.csv",
                    "x,y,z,normal_x,normal_y,normal_z\n0,50,0,0,0,-1\n40,50,0,0,0,-1\n");
    test::replaceAll(command, "{targets}", dir + "targets.csv");
  }
  if (command.find("{ball}") != std::string::npos) test::replaceAll(command, "{ball}", ballCloud());
  test::replaceAll(command, "{dir}", dir);
  return command;
}

/// Names in a directory.
/// The type bits of what lies at `path` (a link not followed).
mode_t typeOf(const std::string& path) {
  struct stat status {};
  if (::lstat(path.c_str(), &status) != 0) return 0;
  return status.st_mode & S_IFMT;
}

/// A tmpfs of 256 KiB mounted on a directory of its own, unmounted when destroyed; fill() takes
/// every free page. Needs root (CI runs as root); unusable() says why not when it cannot mount.
class SmallFileSystem {
 public:
  SmallFileSystem() {
    if (::mount("tmpfs", dir_.file("").c_str(), "tmpfs", 0, "size=256k") != 0) {
      why_ = std::string("cannot mount a tmpfs here: ") + std::strerror(errno);
    }
  }
  ~SmallFileSystem() {
    if (why_.empty()) ::umount2(dir_.file("").c_str(), MNT_DETACH);
  }
  const std::string& unusable() const { return why_; }
  std::string file(const std::string& name) const { return dir_.file(name); }
  /// Writes a filler file until the file system is full.
  void fill() const {
    const int fd = ::open(file(".filler").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ASSERT_GE(fd, 0);
    const std::string block(4096, 'f');
    while (::write(fd, block.data(), block.size()) > 0) {
    }
    for (char byte = 'f'; ::write(fd, &byte, 1) == 1;) {
    }
    ::close(fd);
  }

 private:
  test::TempDir dir_;
  std::string why_;
};

enum class Failure { kReadOnly, kFifo, kFull };

const char* nameOf(Failure failure) {
  switch (failure) {
    case Failure::kReadOnly:
      return "a read-only file";
    case Failure::kFifo:
      return "a FIFO without a reader";
    default:
      return "a full file system";
  }
}

class OutputSetApp : public ::testing::TestWithParam<OutputSetCase> {
 protected:
  /// Runs the tool with output `failing` made to fail by `failure`; every other output path
  /// holds an old file. Checks that the run fails with one line and touches nothing.
  void expectNothingTouched(std::size_t failing, Failure failure) {
    const OutputSetCase& c = GetParam();
    SCOPED_TRACE(std::string("--") + c.outputs[failing].first + " is " + nameOf(failure));
    test::TempDir dir, inputs;
    std::unique_ptr<SmallFileSystem> small;
    if (failure == Failure::kFull) {
      small = std::make_unique<SmallFileSystem>();
      if (!small->unusable().empty()) GTEST_SKIP() << small->unusable();
    }
    std::string command = commandOf(c, inputs.file(""));
    const std::set<std::string> inputs_before = test::listing(inputs.file(""));
    std::map<std::string, std::string> before;  // path -> old content ("" for a FIFO)
    for (std::size_t k = 0; k < c.outputs.size(); ++k) {
      const auto& [flag, name] = c.outputs[k];
      const bool on_small = k == failing && failure == Failure::kFull;
      const std::string path = on_small ? small->file(name) : dir.file(name);
      if (k == failing && failure == Failure::kFifo) {
        ASSERT_EQ(::mkfifo(path.c_str(), 0644), 0);
        before[path] = "";
      } else {
        before[path] = "old " + flag + "\n";
        test::writeFile(path, before[path]);
        if (k == failing && failure == Failure::kReadOnly) ::chmod(path.c_str(), 0444);
      }
      command += " --" + flag + " " + path;
    }
    if (small) small->fill();
    const std::set<std::string> entries = test::listing(dir.file(""));

    const test::RunResult r = test::run(command);
    EXPECT_EQ(r.exit_code, 1) << command << "\n" << r.err;
    // One line says what failed, naming the output (mcws_behave prints its plan before).
    const std::string failed = c.outputs[failing].second;
    EXPECT_NE(r.err.rfind(failed), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\n', r.err.rfind(failed)), r.err.size() - 1) << r.err;
    EXPECT_EQ(test::listing(inputs.file("")), inputs_before) << "written beside the inputs (--dot)";
    for (const auto& [path, content] : before) {
      if (content.empty()) {
        EXPECT_EQ(typeOf(path), static_cast<mode_t>(S_IFIFO)) << path;
      } else {
        EXPECT_EQ(typeOf(path), static_cast<mode_t>(S_IFREG)) << path;
        EXPECT_EQ(test::readFile(path), content) << path << " was touched";
      }
    }
    EXPECT_EQ(test::listing(dir.file("")), entries) << "entries came or went";
    if (small) {
      EXPECT_EQ(test::listing(small->file("")),
                (std::set<std::string>{".filler", c.outputs[failing].second}));
    }
  }

  /// The same command with every output writable: it must succeed, or the failures above prove
  /// nothing.
  void expectSuccessWhenWritable() {
    const OutputSetCase& c = GetParam();
    test::TempDir dir, inputs;
    std::string command = commandOf(c, inputs.file(""));
    for (const auto& [flag, name] : c.outputs) command += " --" + flag + " " + dir.file(name);
    const test::RunResult r = test::run(command);
    ASSERT_EQ(r.exit_code, 0) << command << "\n" << r.err;
    for (const auto& [flag, name] : c.outputs) {
      EXPECT_GT(fs::file_size(dir.file(name)), 0u) << "--" << flag;
    }
  }
};

TEST_P(OutputSetApp, WritesEveryOutputWhenItCan) { expectSuccessWhenWritable(); }

TEST_P(OutputSetApp, AReadOnlyOutputLeavesEveryOutputPathAsItWas) {
  for (std::size_t k = 0; k < GetParam().outputs.size(); ++k) {
    expectNothingTouched(k, Failure::kReadOnly);
  }
}

TEST_P(OutputSetApp, AFifoWithoutReaderLeavesEveryOutputPathAsItWas) {
  for (std::size_t k = 0; k < GetParam().outputs.size(); ++k) {
    expectNothingTouched(k, Failure::kFifo);
  }
}

TEST_P(OutputSetApp, AFullFileSystemLeavesEveryOutputPathAsItWas) {
  for (std::size_t k = 0; k < GetParam().outputs.size(); ++k) {
    expectNothingTouched(k, Failure::kFull);
    if (IsSkipped()) return;
  }
}

const std::string kTrajRobotArgs = " --robot " + test::kPlanar2Robot +
                                   " --from '0 0' --to '0.1 0.2' --duration 1 "
                                   "--rate 10";

INSTANTIATE_TEST_SUITE_P(
    EveryToolWithSeveralOutputs, OutputSetApp,
    ::testing::Values(
        OutputSetCase{"Boundary",
                      MCWS_BOUNDARY_EXE,
                      "--input " + test::kAnnulusCloud + " --plane xy",
                      {{"output", "b.pcd"}, {"interior", "i.pcd"}}},
        OutputSetCase{"BoundaryTiled",
                      MCWS_BOUNDARY_EXE,
                      "--input {ball} --radius 0.3 --tiles 2",
                      {{"output", "b.pcd"}, {"interior", "i.pcd"}}},
        OutputSetCase{
            "Traj", MCWS_TRAJ_EXE, kTrajRobotArgs, {{"output", "t.csv"}, {"plot", "t.png"}}},
        OutputSetCase{"Envelope",
                      MCWS_ENVELOPE_EXE,
                      "--input {ball}",
                      {{"output", "e.ply"}, {"plot", "e.png"}, {"drawing", "d.svg"}}},
        OutputSetCase{
            "Reach",
            MCWS_REACH_EXE,
            "--robot " + test::kPlanar2Robot +
                " --resolution 10cm --samples 20000 --orientations 8",
            {{"output", "r.pcd"}, {"map", "r.bin"}, {"halfcut", "h.png"}, {"histogram", "g.png"}}},
        OutputSetCase{"Place",
                      MCWS_PLACE_EXE,
                      "--robot " + test::kPlanar2Robot + " --targets {targets}" +
                          " --along '0 10 5' --resolution 10cm --samples 20000 --orientations 8 "
                          "--no-collision --map-cache off",
                      {{"output", "p.pcd"}, {"plot", "p.png"}}},
        OutputSetCase{
            "Plan",
            MCWS_PLAN_EXE,
            "--scenario " + test::kPlanar2QuickScenario + " --validation-poses 0 --cells 16",
            {{"output", "path.csv"}, {"plot", "c.png"}, {"plot-offsets", "o.png"}}},
        OutputSetCase{"Behave",
                      MCWS_BEHAVE_EXE,
                      "--model " + test::kCleanerBehaviors + " --insulators 1 --dot {dir}",
                      {{"log", "log.jsonl"}, {"timeline", "t.csv"}, {"plot", "s.png"}}}),
    [](const ::testing::TestParamInfo<OutputSetCase>& info) { return info.param.name; });

// --- The same file under two spellings, an input read indirectly, a shell's `>> log` ---

TEST(OutputSpellings, TwoSpellingsOfOneNewOutputAreRefusedBeforeAnyWork) {
  test::TempDir dir;
  fs::create_directory(dir.file("real"));
  fs::create_directory_symlink("real", dir.file("linked"));
  const std::string cd = "cd " + dir.file("") + " && ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {std::string(MCWS_TRAJ_EXE) + kTrajRobotArgs + " --output t.csv --plot ./t.csv", "--plot"},
      {std::string(MCWS_TRAJ_EXE) + kTrajRobotArgs + " --output t.csv --plot " + dir.file("t.csv"),
       "--plot"},
      {std::string(MCWS_TRAJ_EXE) + kTrajRobotArgs + " --output real/t.csv --plot linked/t.csv",
       "--plot"},
      {std::string(MCWS_REACH_EXE) + " --robot " + test::kPlanar2Robot +
           " --resolution 10cm --samples 1000 --output m.pcd --checkpoint ./m.pcd",
       "--checkpoint"},
      {std::string(MCWS_BOUNDARY_EXE) + " --input " + test::kAnnulusCloud +
           " --plane xy --output real/b.pcd --interior linked/../real/b.pcd",
       "--interior"}};
  for (const auto& [command, flag] : cases) {
    const test::RunResult r = test::run(cd + command);
    EXPECT_EQ(r.exit_code, 2) << command << "\n" << r.err;
    EXPECT_NE(r.err.find(flag + ": must differ from --output"), std::string::npos) << r.err;
    EXPECT_EQ(test::lineCount(r.err), 1) << r.err;
  }
  EXPECT_EQ(test::listing(dir.file("")), (std::set<std::string>{"real", "linked"}));
  EXPECT_TRUE(test::listing(dir.file("real")).empty());
}

TEST(OutputSpellings, AFileTheRunReadsThroughTheRobotFileIsNeverReplaced) {
  // The robot's own collision mesh as --output of mcws_sample --collision: a copy of the robot
  // with its meshes, so that a failure of the check cannot damage the repository's.
  test::TempDir dir;
  fs::copy(std::string(MCWS_ROBOTS_DIR) + "/meshes", dir.file("meshes"),
           fs::copy_options::recursive);
  fs::copy_file(test::robotPath("ta1400_mesh"), dir.file("ta1400_mesh.yaml"));
  const std::string mesh = dir.file("meshes/ta1400/j6_flange.stl");
  const std::string original = test::readFile(mesh);
  for (const std::string& output : {mesh, dir.file("meshes/ta1400/../ta1400/j6_flange.stl")}) {
    const test::RunResult r =
        test::run(std::string(MCWS_SAMPLE_EXE) + " --robot " + dir.file("ta1400_mesh.yaml") +
                  " --collision --samples 200 --output " + output);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("it is the collision mesh"), std::string::npos) << r.err;
    EXPECT_EQ(test::lineCount(r.err), 1) << r.err;
    EXPECT_TRUE(test::readFile(mesh) == original) << "the mesh was overwritten";
  }
}

TEST(OutputSpellings, DevStdoutAppendsToTheShellsLog) {
  test::TempDir dir;
  const std::string log = dir.file("log");
  test::writeFile(log, "earlier run\n");
  // In a subshell: test::run() sends the command's own stdout elsewhere.
  const test::RunResult r = test::run("(" + std::string(MCWS_TRAJ_EXE) + kTrajRobotArgs +
                                      " --output /dev/stdout >> " + log + ")");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const std::string text = test::readFile(log);
  EXPECT_EQ(text.rfind("earlier run\nt_s,", 0), 0u) << text.substr(0, 80);
  EXPECT_EQ(test::lineCount(text), 1 + 1 + 11);  // the old line, the header, 11 samples
}

}  // namespace
}  // namespace mcws
