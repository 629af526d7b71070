// AtomicFile's rules for what lies at the output path (devices, FIFOs, links, read-only files)
// and what a run leaves behind when it fails or is killed.
#include "mcws/io/atomic_file.h"

#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstring>
#include <filesystem>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "mcws/core/input_files.h"
#include "test_support.h"

namespace mcws {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

/// Names in a directory.
std::set<std::string> listing(const std::string& dir) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.insert(entry.path().filename());
  return names;
}

/// Writes `text` to `path` through an AtomicFile and commits.
void writeAtomically(const std::string& path, const std::string& text) {
  io::AtomicFile file(path);
  file.write(text.data(), text.size());
  file.commit();
}

/// The file type bits of what lies at `path` (without following a link).
mode_t typeOf(const std::string& path) {
  struct stat status {};
  EXPECT_EQ(::lstat(path.c_str(), &status), 0) << path;
  return status.st_mode & S_IFMT;
}

TEST(AtomicFile, WritesThroughDevNullWhichStaysACharacterDevice) {
  writeAtomically("/dev/null", "discarded\n");
  EXPECT_EQ(typeOf("/dev/null"), static_cast<mode_t>(S_IFCHR));
}

TEST(AtomicFile, WritesThroughADeviceNodeOfItsOwn) {
  // The same rule on a device node in a directory of the test's own (where renaming over it
  // would succeed even without root).
  test::TempDir dir;
  const std::string node = dir.file("null");
  if (::mknod(node.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0) {
    GTEST_SKIP() << "mknod not permitted here";
  }
  const int probe = ::open(node.c_str(), O_WRONLY);
  if (probe < 0) GTEST_SKIP() << "devices not usable here (a nodev mount)";
  ::close(probe);
  writeAtomically(node, "discarded\n");
  EXPECT_EQ(typeOf(node), static_cast<mode_t>(S_IFCHR));
  EXPECT_EQ(listing(dir.file("")), std::set<std::string>{"null"});
}

TEST(AtomicFile, WritesThroughAFifoWithAReader) {
  test::TempDir dir;
  const std::string fifo = dir.file("pipe");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0666), 0);
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(reader, 0);
  writeAtomically(fifo, "through the pipe\n");  // less than a pipe's buffer: no reader needed yet
  char buffer[64] = {};
  const ssize_t got = ::read(reader, buffer, sizeof(buffer));
  ::close(reader);
  EXPECT_EQ(std::string(buffer, got > 0 ? got : 0), "through the pipe\n");
  EXPECT_EQ(typeOf(fifo), static_cast<mode_t>(S_IFIFO));
}

TEST(AtomicFile, RefusesAFifoWithoutAReaderInsteadOfWaiting) {
  test::TempDir dir;
  const std::string fifo = dir.file("pipe");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0666), 0);
  EXPECT_EQ(test::errorOf([&] { io::AtomicFile file(fifo); }),
            "cannot write '" + fifo + "': no reader");
}

TEST(AtomicFile, ReplacesTheTargetOfAChainOfLinksWhichStayLinks) {
  // first -> second -> sub/target.txt, both links relative to their own directory.
  test::TempDir dir;
  fs::create_directory(dir.file("sub"));
  test::writeFile(dir.file("sub/target.txt"), "old\n");
  fs::create_symlink("sub/target.txt", dir.file("second"));
  fs::create_symlink("second", dir.file("first"));
  writeAtomically(dir.file("first"), "new\n");
  EXPECT_TRUE(fs::is_symlink(dir.file("first")));
  EXPECT_TRUE(fs::is_symlink(dir.file("second")));
  EXPECT_EQ(test::readFile(dir.file("sub/target.txt")), "new\n");
  EXPECT_EQ(listing(dir.file("")), (std::set<std::string>{"first", "second", "sub"}));
  EXPECT_EQ(listing(dir.file("sub")), std::set<std::string>{"target.txt"});
}

TEST(AtomicFile, ADanglingLinkCreatesItsTarget) {
  test::TempDir dir;
  fs::create_symlink("made.txt", dir.file("link"));
  writeAtomically(dir.file("link"), "made\n");
  EXPECT_TRUE(fs::is_symlink(dir.file("link")));
  EXPECT_EQ(typeOf(dir.file("made.txt")), static_cast<mode_t>(S_IFREG));
  EXPECT_EQ(test::readFile(dir.file("made.txt")), "made\n");
}

TEST(AtomicFile, RefusesAReadOnlyFileAndLeavesItAlone) {
  // By its mode bits, so also when the test runs as root.
  test::TempDir dir;
  const std::string file = dir.file("kept.txt");
  test::writeFile(file, "keep\n");
  fs::permissions(file, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  EXPECT_EQ(test::errorOf([&] { writeAtomically(file, "lost\n"); }),
            "cannot write '" + file + "': it is read-only");
  EXPECT_EQ(test::errorOf([&] { io::checkOutputPath(file); }),
            "cannot write '" + file + "': it is read-only");
  fs::create_symlink("kept.txt", dir.file("link"));
  EXPECT_EQ(test::errorOf([&] { writeAtomically(dir.file("link"), "lost\n"); }),
            "cannot write '" + dir.file("link") + "' (a link to '" + file + "'): it is read-only");
  EXPECT_EQ(test::readFile(file), "keep\n");
}

TEST(AtomicFile, LeavesNoEntryWhileWritingNorWhenDestroyedWithoutCommit) {
  test::TempDir dir;
  test::writeFile(dir.file("old.txt"), "old\n");
  const std::set<std::string> before = listing(dir.file(""));
  {
    io::AtomicFile file(dir.file("old.txt"));
    file.write("partial", 7);
    EXPECT_EQ(listing(dir.file("")), before);  // the file has no name until commit()
  }
  EXPECT_EQ(listing(dir.file("")), before);
  EXPECT_EQ(test::readFile(dir.file("old.txt")), "old\n");
}

TEST(AtomicFile, WritesA250CharacterNameWithTheUmasksMode) {
  test::TempDir dir;
  const std::string name = std::string(246, 'n') + ".pcd";
  ASSERT_EQ(name.size(), 250u);
  const mode_t old_umask = ::umask(027);
  writeAtomically(dir.file(name), "long\n");
  ::umask(old_umask);
  EXPECT_EQ(test::readFile(dir.file(name)), "long\n");
  EXPECT_EQ(listing(dir.file("")), std::set<std::string>{name});
  struct stat status {};
  ASSERT_EQ(::stat(dir.file(name).c_str(), &status), 0);
  EXPECT_EQ(status.st_mode & 0777, 0640u);  // 0666 & ~027
}

/// Forks a child that opens `path` with an AtomicFile, writes 1 MB and waits; kills it with
/// `signal_number` mid-write. \return the child's wait status. The child exits with 3 instead
/// when no handler is installed for the signal.
int killMidWrite(const std::string& path, int signal_number) {
  int ready[2];
  if (::pipe(ready) != 0) return -1;
  const pid_t child = ::fork();
  if (child == 0) {
    const rlimit no_core{0, 0};
    ::setrlimit(RLIMIT_CORE, &no_core);  // SIGQUIT and SIGXFSZ would dump core
    try {
      io::AtomicFile file(path);
      struct sigaction current {};
      ::sigaction(signal_number, nullptr, &current);
      if (signal_number != SIGKILL && current.sa_handler == SIG_DFL) ::_exit(3);
      const std::string megabyte(1 << 20, 'x');
      file.write(megabyte.data(), megabyte.size());
      if (::write(ready[1], "r", 1) != 1) ::_exit(4);
      for (;;) ::pause();
    } catch (...) {
      ::_exit(5);
    }
  }
  ::close(ready[1]);
  char byte = 0;
  const bool child_ready = ::read(ready[0], &byte, 1) == 1;
  ::close(ready[0]);
  if (child_ready) ::kill(child, signal_number);
  int status = 0;
  ::waitpid(child, &status, 0);
  return status;
}

TEST(AtomicFile, AChildKilledMidWriteLeavesNoEntry) {
  for (const int signal_number : {SIGKILL, SIGINT, SIGTERM, SIGHUP, SIGPIPE, SIGQUIT, SIGXFSZ,
                                  SIGUSR1, SIGUSR2, SIGALRM, SIGVTALRM, SIGPROF}) {
    struct sigaction inherited {};
    ::sigaction(signal_number, nullptr, &inherited);
    if (inherited.sa_handler == SIG_IGN) continue;  // ignored (nohup): AtomicFile keeps it so
    for (const char* name : {"old.txt", "new.txt"}) {
      test::TempDir dir;
      test::writeFile(dir.file("old.txt"), "old\n");
      const int status = killMidWrite(dir.file(name), signal_number);
      // Ended by the signal itself, as without a handler (an exit code of 3: no handler).
      EXPECT_EQ(WIFSIGNALED(status) ? WTERMSIG(status) : -WEXITSTATUS(status), signal_number)
          << strsignal(signal_number);
      EXPECT_EQ(listing(dir.file("")), std::set<std::string>{"old.txt"})
          << strsignal(signal_number) << ", " << name;
      EXPECT_EQ(test::readFile(dir.file("old.txt")), "old\n");
    }
  }
}

// --- OutputSet: the outputs of one run appear together or not at all (issue 31, section 1) ---

TEST(OutputSet, NothingIsRenamedUntilCommitAndAllAreThen) {
  test::TempDir dir;
  test::writeFile(dir.file("a.txt"), "old a\n");
  {
    io::OutputSet outputs;
    io::writeWholeFile(dir.file("a.txt"), "new a\n");
    io::writeWholeFile(dir.file("b.txt"), "new b\n");
    EXPECT_EQ(test::readFile(dir.file("a.txt")), "old a\n");
    EXPECT_EQ(listing(dir.file("")), std::set<std::string>{"a.txt"});
    outputs.commit();
  }
  EXPECT_EQ(test::readFile(dir.file("a.txt")), "new a\n");
  EXPECT_EQ(test::readFile(dir.file("b.txt")), "new b\n");
  EXPECT_EQ(listing(dir.file("")), (std::set<std::string>{"a.txt", "b.txt"}));
}

TEST(OutputSet, AFailureAfterTheFirstOutputLeavesEveryPathAsItWas) {
  // The old mcws_boundary committed --output, then removed it when --interior failed: the file
  // that lay there was lost. In a set, the first output is never renamed.
  test::TempDir dir;
  test::writeFile(dir.file("a.txt"), "old a\n");
  test::writeFile(dir.file("b.txt"), "old b\n");
  fs::permissions(dir.file("b.txt"), fs::perms::owner_read);
  EXPECT_EQ(test::errorOf([&] {
              io::OutputSet outputs;
              io::writeWholeFile(dir.file("a.txt"), "new a\n");
              io::writeWholeFile(dir.file("b.txt"), "new b\n");
              outputs.commit();
            }),
            "cannot write '" + dir.file("b.txt") + "': it is read-only");
  EXPECT_EQ(test::readFile(dir.file("a.txt")), "old a\n");
  EXPECT_EQ(test::readFile(dir.file("b.txt")), "old b\n");
  EXPECT_EQ(listing(dir.file("")), (std::set<std::string>{"a.txt", "b.txt"}));
}

TEST(OutputSet, ADeviceThatFailsOnCommitKeepsTheRegularOutputsUnwritten) {
  // /dev/full takes the open but fails every write with ENOSPC: the device's bytes are held
  // until the set's commit, which sends them before any regular output gets its name.
  test::TempDir dir;
  test::writeFile(dir.file("a.txt"), "old a\n");
  const std::string error = test::errorOf([&] {
    io::OutputSet outputs;
    io::writeWholeFile(dir.file("a.txt"), "new a\n");
    io::writeWholeFile("/dev/full", "to the device\n");
    outputs.commit();
  });
  EXPECT_THAT(error, HasSubstr("cannot write '/dev/full'"));
  EXPECT_EQ(test::readFile(dir.file("a.txt")), "old a\n");
  EXPECT_EQ(listing(dir.file("")), std::set<std::string>{"a.txt"});
  EXPECT_EQ(typeOf("/dev/full"), static_cast<mode_t>(S_IFCHR));
}

TEST(OutputSet, ADeviceGetsItsBytesOnlyOnCommit) {
  test::TempDir dir;
  const std::string fifo = dir.file("pipe");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0666), 0);
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(reader, 0);
  char buffer[64] = {};
  {
    io::OutputSet outputs;
    io::writeWholeFile(fifo, "held\n");
    EXPECT_LT(::read(reader, buffer, sizeof buffer), 1);  // nothing yet (EAGAIN)
    outputs.commit();
  }
  const ssize_t got = ::read(reader, buffer, sizeof buffer);
  ::close(reader);
  EXPECT_EQ(std::string(buffer, got > 0 ? got : 0), "held\n");
}

TEST(OutputSet, TwoSpellingsOfOneNewFileAreRefused) {
  test::TempDir dir;
  fs::create_directory(dir.file("real"));
  fs::create_directory_symlink("real", dir.file("linked"));
  fs::create_symlink("real/new.txt", dir.file("dangling"));
  const std::string cwd = fs::current_path();
  fs::current_path(dir.file(""));
  const std::vector<std::pair<std::string, std::string>> same = {
      {"b.pcd", "./b.pcd"},       {"b.pcd", dir.file("b.pcd")}, {"real/b.pcd", "linked/b.pcd"},
      {"real/../b.pcd", "b.pcd"}, {"dangling", "real/new.txt"}, {"linked/new.txt", "dangling"}};
  for (const auto& [a, b] : same) {
    EXPECT_TRUE(io::sameOutputFile(a, b)) << a << " " << b;
    const std::string error = test::errorOf([&, a = a, b = b] {
      io::OutputSet outputs;
      io::writeWholeFile(a, "one\n");
      io::writeWholeFile(b, "two\n");
      outputs.commit();
    });
    EXPECT_THAT(error, HasSubstr("are the same file")) << a << " " << b;
  }
  EXPECT_FALSE(io::sameOutputFile("b.pcd", "c.pcd"));
  EXPECT_FALSE(io::sameOutputFile("real/b.pcd", "b.pcd"));
  EXPECT_FALSE(io::sameOutputFile("/dev/null", "/dev/null"));  // written through, replaces nothing
  EXPECT_EQ(listing(dir.file("")), (std::set<std::string>{"real", "linked", "dangling"}));
  EXPECT_TRUE(listing(dir.file("real")).empty());
  fs::current_path(cwd);
}

TEST(AtomicFile, AReservedSizeIsNotTheFilesSize) {
  // The place reserved for a file larger than what is written leaves it the bytes written.
  test::TempDir dir;
  {
    io::AtomicFile file(dir.file("short"));
    file.reserve(std::uint64_t{1} << 20);
    file.write("ten bytes\n", 10);
    file.commit();
  }
  EXPECT_EQ(test::readFile(dir.file("short")), "ten bytes\n");
  EXPECT_EQ(fs::file_size(dir.file("short")), 10u);
}

TEST(AtomicFile, WritesAtOffsetsFromSeveralThreadsAfterWhatWriteAppended) {
  // The header through write(), then 64 pieces at their offsets, from 4 threads in reverse
  // order: the file is the pieces in place, whoever wrote them when.
  test::TempDir dir;
  const std::string head = "header\n";
  std::string expected = head;
  for (int k = 0; k < 64; ++k) expected += std::string(1000, static_cast<char>('A' + k % 26));
  {
    io::AtomicFile file(dir.file("pieces"));
    ASSERT_TRUE(file.positional());
    file.write(head.data(), head.size());
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t) {
      threads.emplace_back([&, t] {
        for (int k = 63 - t; k >= 0; k -= 4) {
          const std::size_t at = head.size() + 1000 * static_cast<std::size_t>(k);
          file.writeAt(at, expected.data() + at, 1000);
        }
      });
    }
    for (std::thread& thread : threads) thread.join();
    file.commit();
  }
  EXPECT_EQ(test::readFile(dir.file("pieces")), expected);
}

TEST(AtomicFile, WritesAtOffsetsOnlyToAFileNotThroughToAFifo) {
  test::TempDir dir;
  const std::string fifo = dir.file("pipe");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0666), 0);
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(reader, 0);
  {
    io::AtomicFile through(fifo);
    EXPECT_FALSE(through.positional());
    EXPECT_EQ(test::errorOf([&] { through.writeAt(0, "x", 1); }),
              "cannot write '" + fifo + "' at an offset: it is not a regular file");
  }
  char buffer[64] = {};
  {
    // In an output set the FIFO's bytes wait in a file: that one is written at offsets.
    io::OutputSet outputs;
    io::AtomicFile held(fifo);
    EXPECT_TRUE(held.positional());
    held.write("ab", 2);
    held.writeAt(4, "ef", 2);
    held.writeAt(2, "cd", 2);
    held.commit();
    outputs.commit();
  }
  const ssize_t got = ::read(reader, buffer, sizeof buffer);
  ::close(reader);
  EXPECT_EQ(std::string(buffer, got > 0 ? got : 0), "abcdef");
}

TEST(AtomicFile, ADescriptorOfTheProcessIsWrittenThroughAndAppendsToAnAppendingFile) {
  // /dev/stdout under the shell's `>> log` is a descriptor opened with O_APPEND on a regular
  // file: the log is appended to, its inode kept, never replaced.
  test::TempDir dir;
  const std::string log = dir.file("log");
  test::writeFile(log, "earlier line\n");
  struct stat before {};
  ASSERT_EQ(::stat(log.c_str(), &before), 0);
  const int fd = ::open(log.c_str(), O_WRONLY | O_APPEND);
  ASSERT_GE(fd, 0);
  writeAtomically("/proc/self/fd/" + std::to_string(fd), "appended\n");
  writeAtomically("/dev/fd/" + std::to_string(fd), "again\n");
  {
    io::OutputSet outputs;  // held, then sent on commit, still appended
    writeAtomically("/proc/self/fd/" + std::to_string(fd), "in a set\n");
    outputs.commit();
  }
  ::close(fd);
  struct stat after {};
  ASSERT_EQ(::stat(log.c_str(), &after), 0);
  EXPECT_EQ(before.st_ino, after.st_ino);
  EXPECT_EQ(test::readFile(log), "earlier line\nappended\nagain\nin a set\n");
  EXPECT_EQ(listing(dir.file("")), std::set<std::string>{"log"});
}

TEST(AtomicFile, AFileTheRunReadsIsNeverAnOutput) {
  // A robot file's collision mesh, read through the robot file, named as an output: refused
  // (mcws::UsageError, exit 2 in the tools) and left as it was, also when it is read after the
  // output was made.
  test::TempDir dir;
  const RunInputs run;
  test::writeFile(dir.file("mesh.stl"), "solid mesh\n");
  test::writeFile(dir.file("late.stl"), "solid late\n");
  requireInputFile(dir.file("mesh.stl"), "collision mesh");
  fs::create_symlink("mesh.stl", dir.file("link.stl"));
  for (const std::string& output :
       {dir.file("mesh.stl"), dir.file("link.stl"), dir.file("./mesh.stl")}) {
    try {
      writeAtomically(output, "overwritten\n");
      ADD_FAILURE() << output << " was written";
    } catch (const UsageError& e) {
      EXPECT_EQ(std::string(e.what()), "cannot write '" + output + "': it is the collision mesh '" +
                                           dir.file("mesh.stl") + "' this run reads");
    }
  }
  io::AtomicFile late(dir.file("late.stl"));
  late.write("overwritten\n", 12);
  requireInputFile(dir.file("late.stl"), "collision mesh");
  EXPECT_THROW(late.commit(), UsageError);
  EXPECT_EQ(test::readFile(dir.file("mesh.stl")), "solid mesh\n");
  EXPECT_EQ(test::readFile(dir.file("late.stl")), "solid late\n");
  EXPECT_EQ(listing(dir.file("")), (std::set<std::string>{"mesh.stl", "late.stl", "link.stl"}));
}

TEST(InputFiles, AFifoOrDeviceIsRefusedBeforeItIsOpened) {
  // Opening a FIFO that nobody writes would block for ever.
  test::TempDir dir;
  const std::string fifo = dir.file("pipe");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0666), 0);
  EXPECT_EQ(test::errorOf([&] { requireInputFile(fifo, "scenario file"); }),
            fifo + ": scenario file is not a regular file (a FIFO)");
  EXPECT_EQ(test::errorOf([&] { requireInputFile("/dev/zero", "map"); }),
            "/dev/zero: map is not a regular file (a character device)");
  EXPECT_EQ(test::errorOf([&] { requireInputFile(dir.file(""), "cloud file"); }),
            dir.file("") + ": cloud file is not a regular file (a directory)");
  EXPECT_EQ(test::errorOf([&] { requireInputFile(dir.file("none"), "robot file"); }),
            dir.file("none") + ": robot file does not exist");
}

}  // namespace
}  // namespace mcws
