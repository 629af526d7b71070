// mcws::buildReachMapInPieces (issue 18, section 2): a map built in pieces, saved after each, is
// the map buildReachMap() builds in one go; a run interrupted after some pieces continues from
// its checkpoint to the same map; a checkpoint of another run is refused.
#include "mcws/reach/reach_checkpoint.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "mcws/core/error.h"
#include "mcws/kinematics/robot_yaml.h"
#include "test_support.h"

namespace mcws {
namespace {

/// The planar 2R arm at 2 cm and 20 x 6 bins: a small map filled fast.
struct Planar {
  Robot robot = loadRobot(test::robotPath("planar2"));
  ReachGrid grid;
  ReachSampling sampling;
  Planar() {
    grid.resolution = 2.0;
    grid.directions = 20;
    grid.rolls = 6;
    sampling.samples = 100003;  // not a multiple of the pieces below
    sampling.first = 17;        // a block that does not start at sample 0, as under mpirun
    sampling.seed = 5;
    sampling.threads = 2;
  }
};

std::string checkpointBytes(const ReachMap& map) {
  std::ostringstream out;
  map.write(out, "{}");
  return out.str();
}

TEST(ReachCheckpoint, PiecesGiveTheMapOfOneGo) {
  const Planar p;
  test::TempDir dir;
  const ReachMap whole = buildReachMap(p.robot, p.grid, p.sampling);
  std::uint64_t resumed = 99;
  const ReachMap pieces = buildReachMapInPieces(
      p.robot, p.grid, p.sampling, {dir.file("ck"), 30000, R"({"run":1})"}, {}, &resumed);
  EXPECT_EQ(resumed, 0u);
  EXPECT_EQ(pieces.samples(), p.sampling.samples);
  EXPECT_EQ(checkpointBytes(pieces), checkpointBytes(whole));
  // The last piece's checkpoint is left for the caller to remove (after its outputs).
  EXPECT_TRUE(std::filesystem::exists(dir.file("ck")));
}

TEST(ReachCheckpoint, InterruptedRunContinuesToTheSameMap) {
  const Planar p;
  test::TempDir dir;
  const ReachCheckpoint checkpoint{dir.file("ck"), 20000, R"({"run":2})"};
  // Interrupted in its third piece: the progress callback throws, as a signal would end it.
  struct Interrupted {};
  EXPECT_THROW(buildReachMapInPieces(p.robot, p.grid, p.sampling, checkpoint,
                                     [](std::uint64_t done, std::uint64_t) {
                                       if (done > 45000) throw Interrupted{};
                                     }),
               Interrupted);
  ASSERT_TRUE(std::filesystem::exists(checkpoint.path));
  std::uint64_t resumed = 0, first_report = 0;
  bool reported = false;
  const ReachMap map = buildReachMapInPieces(
      p.robot, p.grid, p.sampling, checkpoint,
      [&](std::uint64_t done, std::uint64_t) {
        if (!reported) first_report = done;
        reported = true;
      },
      &resumed);
  EXPECT_EQ(resumed, 40000u);  // two whole pieces were saved
  EXPECT_EQ(first_report, 40000u);
  EXPECT_EQ(checkpointBytes(map), checkpointBytes(buildReachMap(p.robot, p.grid, p.sampling)));
}

TEST(ReachCheckpoint, CheckpointOfAnotherRunIsRefused) {
  const Planar p;
  test::TempDir dir;
  buildReachMapInPieces(p.robot, p.grid, p.sampling, {dir.file("ck"), 50000, R"({"seed":5})"});
  const std::string before = test::readFile(dir.file("ck"));
  const std::string message = test::errorOf([&] {
    buildReachMapInPieces(p.robot, p.grid, p.sampling, {dir.file("ck"), 50000, R"({"seed":6})"});
  });
  EXPECT_NE(message.find("checkpoint '" + dir.file("ck") + "' is of another run"),
            std::string::npos)
      << message;
  EXPECT_EQ(test::readFile(dir.file("ck")), before);  // left as it was
}

TEST(ReachCheckpoint, AMapIsNotACheckpoint) {
  const Planar p;
  test::TempDir dir;
  test::writeFile(dir.file("map.bin"), checkpointBytes(buildReachMap(p.robot, p.grid, p.sampling)));
  const std::string message = test::errorOf([&] {
    buildReachMapInPieces(p.robot, p.grid, p.sampling, {dir.file("map.bin"), 50000, "{}"});
  });
  EXPECT_NE(message.find("is a map, not a checkpoint"), std::string::npos) << message;
}

}  // namespace
}  // namespace mcws
