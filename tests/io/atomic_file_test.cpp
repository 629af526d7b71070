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

}  // namespace
}  // namespace mcws
