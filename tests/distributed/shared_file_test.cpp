// The pieces of a distributed run on one process (issue 18, section 1): how sample indices are
// shared among processes, the file written at offsets, and the sampler writing through it, which
// must give the bytes of the single-process writer.
#include <gtest/gtest.h>

#include "mcws/distributed/processes.h"
#include "mcws/distributed/sample_writer.h"
#include "mcws/sampling/sampler.h"
#include "test_support.h"

namespace mcws {
namespace {

using distributed::Block;
using distributed::blockOf;

TEST(Blocks, HandWorkedShares) {
  // 10 over 3: the first 10 % 3 = 1 process takes one more.
  EXPECT_EQ(blockOf(10, 0, 3).begin, 0u);
  EXPECT_EQ(blockOf(10, 0, 3).end, 4u);
  EXPECT_EQ(blockOf(10, 1, 3).begin, 4u);
  EXPECT_EQ(blockOf(10, 1, 3).end, 7u);
  EXPECT_EQ(blockOf(10, 2, 3).begin, 7u);
  EXPECT_EQ(blockOf(10, 2, 3).end, 10u);
  // Fewer items than processes: the last ones get none.
  EXPECT_EQ(blockOf(2, 2, 4).size(), 0u);
  EXPECT_EQ(blockOf(2, 1, 4).begin, 1u);
}

TEST(Blocks, EveryIndexOnceInOrderForAnyCount) {
  for (const std::uint64_t n : {0ull, 1ull, 7ull, 1000ull, 1000003ull}) {
    for (int size = 1; size <= 9; ++size) {
      std::uint64_t next = 0, smallest = n, largest = 0;
      for (int rank = 0; rank < size; ++rank) {
        const Block b = blockOf(n, rank, size);
        EXPECT_EQ(b.begin, next) << n << " " << size << " " << rank;
        next = b.end;
        smallest = std::min(smallest, b.size());
        largest = std::max(largest, b.size());
      }
      EXPECT_EQ(next, n);
      EXPECT_LE(largest - smallest, 1u);  // balanced
    }
  }
}

/// A Processes of this process alone (the test is not started by mpirun).
distributed::Processes& alone() {
  static int argc = 1;
  static char name[] = "test";
  static char* args[] = {name, nullptr};
  static char** argv = args;
  static distributed::Processes processes(argc, argv);
  return processes;
}

TEST(SharedFile, WritesAtOffsetsAndAppearsOnCommit) {
  ASSERT_FALSE(alone().distributed());
  test::TempDir dir;
  const std::string path = dir.file("out.bin");
  {
    distributed::SharedFile file(alone(), path);
    file.writeAt(6, "world", 5);
    file.writeAt(0, "hello ", 6);
    EXPECT_EQ(dir.fileCount(), 0u);  // nothing named before commit()
    file.commit();
  }
  EXPECT_EQ(test::readFile(path), "hello world");
}

TEST(SharedFile, LeavesNothingWithoutCommit) {
  test::TempDir dir;
  {
    distributed::SharedFile file(alone(), dir.file("out.bin"));
    file.writeAt(0, "partial", 7);
  }
  EXPECT_EQ(dir.fileCount(), 0u);
}

TEST(SharedFile, DoesNotReplaceTheTargetWithoutCommit) {
  test::TempDir dir;
  const std::string path = dir.file("out.bin");
  test::writeFile(path, "before");
  {
    distributed::SharedFile file(alone(), path);
    file.writeAt(0, "after", 5);
  }
  EXPECT_EQ(test::readFile(path), "before");
}

TEST(SampleWriter, SameBytesAsTheStreamingWriter) {
  // The oracle is writeSamples(), the single-process writer (PCL's header and packing).
  test::TempDir dir;
  const ShapeSampler ball(Shape::kBall, 7);
  const std::size_t n = 300001;  // two chunks and a bit
  writeSamples(ball, n, dir.file("one.pcd"), io::PcdFormat::kBinary, 2);
  const SampleSummary together =
      distributed::writeSamplesTogether(alone(), ball, n, dir.file("shared.pcd"), 2);
  EXPECT_EQ(test::readFile(dir.file("shared.pcd")), test::readFile(dir.file("one.pcd")));
  EXPECT_EQ(together.points, n);
  EXPECT_EQ(together.label_counts.at(0), n);
  EXPECT_LT(together.max.x(), 1.0);
  EXPECT_GT(together.max.x(), 0.99);  // 3e5 points in the unit ball reach near its rim
}

TEST(SampleWriter, PrefixThenSamplesAsOneCloud) {
  // The prefix of mcws_refine --cloud: the points come first, the samples after them.
  test::TempDir dir;
  const ShapeSampler disk(Shape::kDisk, 3);
  const pcl::PointCloud<WorkspacePoint> prefix = sampleCloud(disk, 1000, 1);
  const ShapeSampler ball(Shape::kBall, 5);
  const pcl::PointCloud<WorkspacePoint> samples = sampleCloud(ball, 2000, 1);
  distributed::writeSamplesTogether(alone(), ball, 2000, dir.file("joined.pcd"), 1, {},
                                    std::nullopt, prefix.data(), prefix.size());
  // Oracle: the streaming writer given the two clouds one after the other.
  io::PcdStreamWriter<WorkspacePoint> writer(dir.file("oracle.pcd"), 3000);
  writer.write(prefix.data(), prefix.size());
  writer.write(samples.data(), samples.size());
  writer.commit();
  EXPECT_EQ(test::readFile(dir.file("joined.pcd")), test::readFile(dir.file("oracle.pcd")));
}

TEST(SampleSummaries, OneProcessKeepsItsOwn) {
  SampleSummary own;
  own.points = 3;
  own.min = Eigen::Vector3d(-1, -2, -3);
  own.max = Eigen::Vector3d(1, 2, 3);
  own.label_counts = {{0, 2}, {7, 1}};
  const SampleSummary all = distributed::combineSummaries(alone(), own);
  EXPECT_EQ(all.points, 3u);
  EXPECT_EQ(all.min, own.min);
  EXPECT_EQ(all.max, own.max);
  EXPECT_EQ(all.label_counts, own.label_counts);
  const SampleSummary none = distributed::combineSummaries(alone(), SampleSummary{});
  EXPECT_EQ(none.min, Eigen::Vector3d::Zero());
}

}  // namespace
}  // namespace mcws
