#include "mcws/sampling/sampler.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fcntl.h>
#include <pcl/common/common.h>
#include <pcl/io/pcd_io.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/robot_urdf.h"
#include "mcws/kinematics/robot_yaml.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

bool sameBytes(const pcl::PointCloud<WorkspacePoint>& a, const pcl::PointCloud<WorkspacePoint>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].x != b[i].x || a[i].y != b[i].y || a[i].z != b[i].z || a[i].label != b[i].label ||
        std::memcmp(a[i].q, b[i].q, sizeof a[i].q) != 0) {
      return false;
    }
  }
  return true;
}

TEST(CounterRng, IsUniformAndDependsOnlyOnSeedIndexAndStream) {
  const CounterRng rng(42);
  double sum = 0.0, sum2 = 0.0;
  constexpr int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double u = rng.uniform(i, 3);
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    sum2 += u * u;
  }
  // Mean 1/2 and variance 1/12; the mean's standard error is sqrt(1/12/n) = 6.5e-4: 5 sigma.
  EXPECT_NEAR(sum / n, 0.5, 5 * 6.5e-4);
  EXPECT_NEAR(sum2 / n - (sum / n) * (sum / n), 1.0 / 12.0, 2e-3);
  EXPECT_EQ(CounterRng(42).uniform(12345, 2), rng.uniform(12345, 2));
  EXPECT_NE(CounterRng(43).uniform(12345, 2), rng.uniform(12345, 2));
  EXPECT_NE(rng.uniform(12345, 1), rng.uniform(12345, 2));
}

TEST(RobotSampler, SameCloudForAnyThreadCountAndAnySplit) {
  const Robot robot = loadRobot(test::robotPath("ta1400"));
  const RobotSampler sampler(robot, {});
  const auto one = sampleCloud(sampler, 50001, 1);
  EXPECT_TRUE(sameBytes(one, sampleCloud(sampler, 50001, 2)));
  EXPECT_TRUE(sameBytes(one, sampleCloud(sampler, 50001, 3)));
  // Sample i does not depend on where a batch starts: generate [7, 1007) on its own.
  std::vector<WorkspacePoint, Eigen::aligned_allocator<WorkspacePoint>> part(1000);
  sampler.generate(7, part.size(), part.data());
  for (std::size_t k = 0; k < part.size(); ++k) {
    ASSERT_EQ(part[k].x, one[7 + k].x);
    ASSERT_EQ(part[k].z, one[7 + k].z);
    ASSERT_EQ(part[k].q6, one[7 + k].q6);
  }
}

TEST(RobotSampler, DifferentSeedsGiveDifferentClouds) {
  const Robot robot = loadRobot(test::robotPath("deicing"));
  RobotSamplerOptions options;
  options.seed = 2;
  EXPECT_FALSE(sameBytes(sampleCloud(RobotSampler(robot, {}), 100, 1),
                         sampleCloud(RobotSampler(robot, options), 100, 1)));
}

TEST(RobotSampler, PointsAreTheForwardKinematicsOfTheirJointValues) {
  for (const char* name :
       {"deicing", "ta1400", "inspection6", "maintenance4", "insulator_cleaner"}) {
    SCOPED_TRACE(name);
    const Robot robot = loadRobot(test::robotPath(name));
    for (SamplePoint which : {SamplePoint::kTool, SamplePoint::kFlange}) {
      RobotSamplerOptions options;
      options.point = which;
      const auto cloud = sampleCloud(RobotSampler(robot, options), 2000, 2);
      for (const WorkspacePoint& p : cloud) {
        Eigen::VectorXd q(robot.dof());
        for (int j = 0; j < robot.dof(); ++j) {
          q[j] = p.q[j];
          ASSERT_GE(q[j], robot.joints[j].lower - 1e-6);
          ASSERT_LE(q[j], robot.joints[j].upper + 1e-6);
        }
        for (int j = robot.dof(); j < kMaxJoints; ++j) ASSERT_EQ(p.q[j], 0.0f);
        ASSERT_EQ(p.label, kLabelFree);
        const Eigen::Isometry3d T =
            which == SamplePoint::kTool ? toolPose(robot, q) : flangePose(robot, q);
        // q was rounded to float when stored: positions agree to a few float ulps of the reach.
        const double tolerance = 1e-5 * (1.0 + T.translation().norm()) + 1e-4;
        ASSERT_NEAR(p.x, T.translation().x(), tolerance);
        ASSERT_NEAR(p.y, T.translation().y(), tolerance);
        ASSERT_NEAR(p.z, T.translation().z(), tolerance);
      }
    }
  }
}

TEST(RobotSampler, FixedJointStaysAtItsValue) {
  const Robot robot = loadRobot(test::robotPath("deicing"));
  RobotSamplerOptions options;
  options.fixed = {{"theta3", 0.0}};
  const auto cloud = sampleCloud(RobotSampler(robot, options), 5000, 2);
  for (const WorkspacePoint& p : cloud) {
    ASSERT_EQ(p.q1, 0.0f);
    ASSERT_NEAR(p.y, 0.0f, 1e-5);  // the X-Z plane of Yin, Wang & Yu 2010
  }
}

TEST(RobotSampler, ReportsUnknownOrOutOfRangeFixedJoint) {
  const Robot robot = loadRobot(test::robotPath("deicing"));
  RobotSamplerOptions options;
  options.fixed = {{"theta9", 0.0}};
  try {
    RobotSampler sampler(robot, options);
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("robot 'deicing' has no joint 'theta9'"));
  }
  options.fixed = {{"a2", 80.0}};
  try {
    RobotSampler sampler(robot, options);
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "fixed value 80 of joint 'a2' is outside its limits [25, 70] cm");
  }
  options.fixed = {{"theta1", 1.0472}};  // pi/3 rounded up: outside, and the message shows why
  try {
    RobotSampler sampler(robot, options);
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "fixed value 1.0472 of joint 'theta1' is outside its limits [-0.7853981634, "
                 "0.7853981634] rad ([-45, 45] deg)");
  }
  options.fixed = {{"theta3", 0.0}, {"theta3", 0.5}};
  try {
    RobotSampler sampler(robot, options);
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "joint 'theta3' is fixed twice");
  }
}

TEST(RobotSampler, RefusesMoreJointsThanThePointRecords) {
  Robot robot = loadRobot(test::robotPath("ta1400"));
  robot.joints.insert(robot.joints.end(), robot.joints.begin(), robot.joints.begin() + 3);
  EXPECT_THROW(RobotSampler(robot, {}), Error);
}

// ---- validation shapes: the fraction of samples inside radius s must follow the region's
// measure; with n samples the binomial standard error is sqrt(p(1-p)/n), and we allow 5 sigma.

double fractionWithin(const pcl::PointCloud<WorkspacePoint>& cloud, double radius) {
  std::size_t inside = 0;
  for (const auto& p : cloud) inside += std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z) < radius;
  return static_cast<double>(inside) / cloud.size();
}

void expectFraction(double measured, double expected, std::size_t n) {
  EXPECT_NEAR(measured, expected, 5.0 * std::sqrt(expected * (1.0 - expected) / n));
}

TEST(ShapeSampler, DiskIsUniformInArea) {
  constexpr std::size_t n = 100000;
  const auto cloud = sampleCloud(ShapeSampler(Shape::kDisk, 1), n, 2);
  for (const auto& p : cloud) {
    ASSERT_EQ(p.z, 0.0f);
    ASSERT_LE(p.x * p.x + p.y * p.y, 1.0f + 1e-6f);
  }
  expectFraction(fractionWithin(cloud, 0.5), 0.25, n);
  std::size_t right = 0;
  for (const auto& p : cloud) right += p.x > 0;
  expectFraction(static_cast<double>(right) / n, 0.5, n);
}

TEST(ShapeSampler, AnnulusIsUniformInArea) {
  constexpr std::size_t n = 100000;
  const auto cloud = sampleCloud(ShapeSampler(Shape::kAnnulus, 1), n, 2);
  for (const auto& p : cloud) {
    const float r = std::sqrt(p.x * p.x + p.y * p.y);
    ASSERT_GE(r, 0.5f - 1e-6f);
    ASSERT_LE(r, 1.0f + 1e-6f);
  }
  expectFraction(fractionWithin(cloud, 0.75), (0.75 * 0.75 - 0.25) / 0.75, n);
}

TEST(ShapeSampler, BallIsUniformInVolume) {
  constexpr std::size_t n = 100000;
  const auto cloud = sampleCloud(ShapeSampler(Shape::kBall, 1), n, 2);
  EXPECT_EQ(fractionWithin(cloud, 1.0 + 1e-6), 1.0);  // every point inside the unit sphere
  expectFraction(fractionWithin(cloud, 0.5), 0.125, n);
  std::size_t top = 0;
  for (const auto& p : cloud) top += p.z > 0.5f;
  // Spherical cap above z = 0.5: volume pi h^2 (3 - h) / 3 with h = 0.5, over 4 pi / 3.
  expectFraction(static_cast<double>(top) / n, (M_PI * 0.25 * 2.5 / 3.0) / (4.0 * M_PI / 3.0), n);
}

TEST(ShapeSampler, BoxIsTheCentredUnitCube) {
  constexpr std::size_t n = 100000;
  const auto cloud = sampleCloud(ShapeSampler(Shape::kBox, 1), n, 1);
  std::size_t corner = 0;
  for (const auto& p : cloud) {
    ASSERT_LE(std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}), 0.5f);
    corner += p.x > 0 && p.y > 0 && p.z > 0;
  }
  expectFraction(static_cast<double>(corner) / n, 0.125, n);
}

TEST(ShapeSampler, NamesAndMeasures) {
  EXPECT_EQ(parseShape("annulus"), Shape::kAnnulus);
  EXPECT_DOUBLE_EQ(shapeMeasure(Shape::kDisk), M_PI);
  EXPECT_DOUBLE_EQ(shapeMeasure(Shape::kBall), 4.0 * M_PI / 3.0);
  try {
    parseShape("torus");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "unknown shape 'torus' (known: disk, annulus, ball, box)");
  }
}

TEST(GenerateInChunks, EqualsTheCloudInMemoryAndReportsEachChunk) {
  const ShapeSampler sampler(Shape::kBall, 5);
  constexpr std::size_t n = (1u << 18) + 4099;  // one whole chunk and a part, not a block multiple
  std::vector<WorkspacePoint, Eigen::aligned_allocator<WorkspacePoint>> out(n);
  std::vector<std::pair<std::size_t, std::size_t>> reports;
  generateInChunks(sampler, n, out.data(), 2,
                   [&](std::size_t done, std::size_t total) { reports.emplace_back(done, total); });
  const auto cloud = sampleCloud(sampler, n, 1);
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_EQ(std::memcmp(out[i].data, cloud[i].data, 3 * sizeof(float)), 0) << i;
  }
  using Report = std::pair<std::size_t, std::size_t>;
  EXPECT_EQ(reports, (std::vector<Report>{{1u << 18, n}, {n, n}}));
}

TEST(GenerateFromJointValues, PadsAPartialBatchWithoutChangingItsSamples) {
  const Robot robot = loadRobot(test::robotPath("inspection6"));
  const PointKinematics kinematics = samplePointKinematics(robot, SamplePoint::kTool);
  // Joint values from the index alone; every count from 1 to 2 batches, started anywhere.
  const auto draw = [&](std::uint64_t index, double* q) {
    for (int j = 0; j < robot.dof(); ++j) q[j] = 0.01 * static_cast<double>(index) - 0.1 * j;
  };
  constexpr int kLanes = PointKinematics::kLanes;
  std::vector<WorkspacePoint, Eigen::aligned_allocator<WorkspacePoint>> whole(2 * kLanes + 3);
  generateFromJointValues(kinematics, 0, whole.size(), whole.data(), draw);
  for (std::size_t first = 0; first < 3; ++first) {
    for (std::size_t count = 1; count + first <= whole.size(); ++count) {
      std::vector<WorkspacePoint, Eigen::aligned_allocator<WorkspacePoint>> part(count);
      generateFromJointValues(kinematics, first, count, part.data(), draw);
      for (std::size_t k = 0; k < count; ++k) {
        ASSERT_EQ(std::memcmp(part[k].data, whole[first + k].data, 3 * sizeof(float)), 0);
        ASSERT_EQ(std::memcmp(part[k].q, whole[first + k].q, sizeof part[k].q), 0);
        ASSERT_EQ(part[k].label, 0u);
      }
    }
  }
  double q[kMaxJoints];
  draw(5, q);
  EXPECT_FLOAT_EQ(whole[5].q[2], static_cast<float>(q[2]));
  EXPECT_EQ(whole[5].q[robot.dof()], 0.0f);  // joints the robot lacks stay zero
}

TEST(WriteSamples, StreamedFileEqualsTheCloudInMemory) {
  test::TempDir dir;
  const Robot robot = loadRobot(test::robotPath("inspection6"));
  const RobotSampler sampler(robot, {});
  constexpr std::size_t n = 600000;  // more than two chunks, and not a multiple of one
  const SampleSummary summary =
      writeSamples(sampler, n, dir.file("ws.pcd"), io::PcdFormat::kBinary, 2);
  const auto cloud = sampleCloud(sampler, n, 1);
  ASSERT_EQ(pcl::io::savePCDFileBinary(dir.file("pcl.pcd"), cloud), 0);
  EXPECT_EQ(test::readFile(dir.file("ws.pcd")), test::readFile(dir.file("pcl.pcd")));
  WorkspacePoint min, max;
  pcl::getMinMax3D(cloud, min, max);
  EXPECT_EQ(summary.points, n);
  EXPECT_FLOAT_EQ(summary.min.x(), min.x);
  EXPECT_FLOAT_EQ(summary.max.z(), max.z);
}

/// Samples whose x is 1 before sample `from` and +0 or -0 from it on, and whose z is -1 before it
/// and the same zero: the bounds tie between zeros of both signs, first met at sample `from`.
/// Labels cycle through 0..5 (the collision codes and two more). Throws for the samples from
/// `failing` on, naming the first of them.
class TieSampler : public PointGenerator {
 public:
  TieSampler(std::uint64_t from, bool negative_first, std::uint64_t failing = ~0ull)
      : from_(from), flip_(negative_first), failing_(failing) {}
  void generate(std::uint64_t first, std::size_t count, WorkspacePoint* out) const override {
    if (first + count > failing_) {
      throw Error("sample " + std::to_string(std::max(first, failing_)) + " failed");
    }
    for (std::size_t k = 0; k < count; ++k) {
      const std::uint64_t i = first + k;
      const bool negative = ((((i - from_) * 2654435761u) >> 7) & 1) == 0 ? flip_ : !flip_;
      out[k] = WorkspacePoint();
      out[k].x = i < from_ ? 1.0f : (negative ? -0.0f : 0.0f);
      out[k].y = static_cast<float>(i % 1000);
      out[k].z = i < from_ ? -1.0f : (negative ? -0.0f : 0.0f);
      out[k].label = static_cast<std::uint32_t>(i % 6);
    }
  }

 private:
  std::uint64_t from_;
  bool flip_;
  std::uint64_t failing_;
};

/// Writes nothing: streamSamples()'s summary only.
SampleSummary summaryOf(const PointGenerator& generator, std::uint64_t n, int threads) {
  return streamSamples<WorkspacePoint>(
      generator, 0, n, threads,
      [](const WorkspacePoint*, std::size_t, std::vector<char>& bytes) { bytes.clear(); },
      [](std::uint64_t, const char*, std::size_t, std::size_t) {}, SinkOrder::kAnyOrder);
}

TEST(StreamSamples, SummaryIsTheScanInOrderForAnyThreads) {
  // Oracle: the bounds as a scan of the samples in order finds them (Eigen's cwiseMin keeps the
  // first of equal values: +0 or -0, whichever comes first), the labels counted one by one.
  constexpr std::uint64_t n = 50001;  // 13 blocks of 4096, the last one partial
  for (const bool negative_first : {false, true}) {
    const TieSampler sampler(20000, negative_first);
    const auto cloud = sampleCloud(sampler, n, 1);
    Eigen::Vector3d min = Eigen::Vector3d::Constant(INFINITY), max = -min;
    std::map<std::uint32_t, std::size_t> labels;
    for (const WorkspacePoint& p : cloud) {
      const Eigen::Vector3d v(p.x, p.y, p.z);
      min = min.cwiseMin(v);
      max = max.cwiseMax(v);
      ++labels[p.label];
    }
    ASSERT_EQ(std::signbit(min.x()), negative_first);
    ASSERT_EQ(std::signbit(max.z()), negative_first);
    for (int threads = 1; threads <= 4; ++threads) {
      for (int repeat = 0; repeat < 5; ++repeat) {  // the blocks go to other threads each time
        const SampleSummary summary = summaryOf(sampler, n, threads);
        EXPECT_EQ(summary.points, n);
        EXPECT_EQ(std::memcmp(summary.min.data(), min.data(), sizeof(double) * 3), 0) << threads;
        EXPECT_EQ(std::memcmp(summary.max.data(), max.data(), sizeof(double) * 3), 0) << threads;
        EXPECT_EQ(summary.label_counts, labels);
      }
    }
  }
}

TEST(WriteSamples, SameBytesForAnyThreadsAtOffsetsInOrderAndAsAscii) {
  // Oracles: PCL's own binary writer, and for ASCII the writer given the whole cloud at once.
  test::TempDir dir;
  const Robot robot = loadRobot(test::robotPath("inspection6"));
  const RobotSampler sampler(robot, {});
  constexpr std::size_t n = 100003;
  const auto cloud = sampleCloud(sampler, n, 1);
  ASSERT_EQ(pcl::io::savePCDFileBinary(dir.file("pcl.pcd"), cloud), 0);
  const std::string binary = test::readFile(dir.file("pcl.pcd"));
  {
    io::PcdStreamWriter<WorkspacePoint> whole(dir.file("whole.pcd"), n, io::PcdFormat::kAscii);
    whole.write(cloud.data(), n);
    whole.commit();
  }
  const std::string ascii = test::readFile(dir.file("whole.pcd"));
  for (int threads = 1; threads <= 3; ++threads) {
    SCOPED_TRACE(threads);
    writeSamples(sampler, n, dir.file("b.pcd"), io::PcdFormat::kBinary, threads);
    EXPECT_EQ(test::readFile(dir.file("b.pcd")), binary);
    writeSamples(sampler, n, dir.file("a.pcd"), io::PcdFormat::kAscii, threads);
    EXPECT_EQ(test::readFile(dir.file("a.pcd")), ascii);
    // A FIFO takes the blocks in order (a second writer keeps the reader from an early EOF).
    const std::string fifo = dir.file("pipe");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0666), 0);
    const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
    const int keeper = ::open(fifo.c_str(), O_WRONLY);
    ASSERT_GE(reader, 0);
    ASSERT_GE(keeper, 0);
    ::fcntl(reader, F_SETFL, 0);
    std::string piped;
    std::thread drain([&] {
      char buffer[1 << 16];
      for (ssize_t got; (got = ::read(reader, buffer, sizeof buffer)) > 0;)
        piped.append(buffer, got);
    });
    writeSamples(sampler, n, fifo, io::PcdFormat::kBinary, threads);
    ::close(keeper);
    drain.join();
    ::close(reader);
    std::filesystem::remove(fifo);
    EXPECT_EQ(piped, binary);
  }
}

TEST(WriteSamples, AFailingSampleLeavesNoFileAndTheErrorOfTheLowestBlock) {
  constexpr std::uint64_t n = 60000, failing = 30000;  // later blocks fail too
  const TieSampler sampler(0, false, failing);
  for (const io::PcdFormat format : {io::PcdFormat::kBinary, io::PcdFormat::kAscii}) {
    for (int threads = 1; threads <= 4; ++threads) {
      test::TempDir dir;
      EXPECT_EQ(
          test::errorOf([&] { writeSamples(sampler, n, dir.file("ws.pcd"), format, threads); }),
          "sample 30000 failed");
      EXPECT_EQ(dir.fileCount(), 0u);
    }
  }
}

/// Samples at the origin; the block from sample `slow` waits 100 ms, every block from sample
/// `failing` on throws at once.
class SlowThenFailingSampler : public PointGenerator {
 public:
  SlowThenFailingSampler(std::uint64_t slow, std::uint64_t failing)
      : slow_(slow), failing_(failing) {}
  void generate(std::uint64_t first, std::size_t count, WorkspacePoint* out) const override {
    if (first >= failing_) throw Error("sample " + std::to_string(first) + " failed");
    if (first == slow_) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    std::fill(out, out + count, WorkspacePoint());
  }

 private:
  std::uint64_t slow_, failing_;
};

TEST(StreamSamples, InOrderTheSinksErrorBelowAFailingBlockIsReportedForAnyThreads) {
  // Block 2 is slow to draw and its sink fails; block 3 fails to draw at once. One thread meets
  // the sink's failure first; so must two or four, which draw block 3 while block 2 sleeps.
  constexpr std::uint64_t block = 4096;
  const SlowThenFailingSampler sampler(2 * block, 3 * block);
  for (int threads = 1; threads <= 4; ++threads) {
    std::vector<std::uint64_t> written;
    const std::string error = test::errorOf([&] {
      streamSamples<WorkspacePoint>(
          sampler, 0, 8 * block, threads,
          [](const WorkspacePoint*, std::size_t, std::vector<char>& bytes) { bytes.clear(); },
          [&](std::uint64_t first, const char*, std::size_t, std::size_t) {
            if (first == 2 * block) throw Error("the sink refused sample " + std::to_string(first));
            written.push_back(first);
          },
          SinkOrder::kInOrder);
    });
    EXPECT_EQ(error, "the sink refused sample 8192") << threads << " threads";
    EXPECT_EQ(written, (std::vector<std::uint64_t>{0, block})) << threads << " threads";
  }
}

TEST(WriteSamples, ReportsProgressOnTheCallingThreadUpToTheEnd) {
  test::TempDir dir;
  const ShapeSampler ball(Shape::kBall, 3);
  constexpr std::size_t n = 700001;
  std::vector<std::size_t> done;
  const std::thread::id caller = std::this_thread::get_id();
  bool elsewhere = false;
  writeSamples(ball, n, dir.file("ws.pcd"), io::PcdFormat::kBinary, 3,
               [&](std::size_t points, std::size_t total) {
                 elsewhere |= std::this_thread::get_id() != caller || total != n;
                 done.push_back(points);
               });
  EXPECT_FALSE(elsewhere);
  ASSERT_FALSE(done.empty());
  EXPECT_TRUE(std::is_sorted(done.begin(), done.end()));
  EXPECT_EQ(done.back(), n);
}

TEST(WriteSamples, WhatProgressThrowsEndsTheRunWithoutAFile) {
  // A cancellation thrown by the progress callback, on the calling thread inside the loop.
  test::TempDir dir;
  const ShapeSampler ball(Shape::kBall, 3);
  for (int threads = 1; threads <= 3; ++threads) {
    int calls = 0;
    EXPECT_EQ(test::errorOf([&] {
                writeSamples(ball, 700001, dir.file("ws.pcd"), io::PcdFormat::kBinary, threads,
                             [&](std::size_t, std::size_t) {
                               ++calls;
                               throw Error("cancelled");
                             });
              }),
              "cancelled");
    EXPECT_EQ(calls, 1);
    EXPECT_EQ(dir.fileCount(), 0u);
  }
}

// A URDF with a continuous joint without limits (one turn, [-pi, pi)), one with limits [-1, 2),
// and a mimic joint between them (x 0.5 of the first, issue 33 item 2): the sampler draws the two
// free joints over those ranges, and each point is the FK of its joint values.
TEST(RobotSampler, ContinuousJointsAndAMimicJointOfAUrdf) {
  const Robot robot = parseRobotUrdf(R"(<robot name="c">
    <link name="a"/><link name="b"/><link name="c"/><link name="d"/><link name="tool"/>
    <joint name="j1" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint>
    <joint name="m" type="revolute"><parent link="b"/><child link="c"/><origin xyz="0.3 0 0"/>
      <axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/>
      <mimic joint="j1" multiplier="0.5"/></joint>
    <joint name="j2" type="continuous"><parent link="c"/><child link="d"/><origin xyz="0.2 0 0"/>
      <axis xyz="1 0 0"/><limit lower="-1" upper="2" effort="1" velocity="1"/></joint>
    <joint name="t" type="fixed"><parent link="d"/><child link="tool"/><origin xyz="0 0.1 0"/>
    </joint></robot>)",
                                     "c.urdf");
  ASSERT_EQ(robot.dof(), 2);
  const RobotSampler sampler(robot, {});
  constexpr int kCount = 4000;
  std::vector<WorkspacePoint> points(kCount);
  sampler.generate(0, kCount, points.data());
  double low[2] = {10, 10}, high[2] = {-10, -10};
  for (int i = 0; i < kCount; ++i) {
    double q[2];
    sampler.jointValues(i, q);
    for (int j = 0; j < 2; ++j) low[j] = std::min(low[j], q[j]), high[j] = std::max(high[j], q[j]);
    ASSERT_GE(q[0], -M_PI);
    ASSERT_LT(q[0], M_PI);
    ASSERT_GE(q[1], -1.0);
    ASSERT_LT(q[1], 2.0);
    const Eigen::Vector3d p = toolPose(robot, Eigen::Vector2d(q[0], q[1])).translation();
    // Float coordinates of points within 0.6 m [m].
    ASSERT_LT((p - Eigen::Vector3d(points[i].x, points[i].y, points[i].z)).norm(), 1e-6) << i;
  }
  // Uniform draws fill the ranges: 4000 of them leave gaps of about range / 4000 at the ends.
  EXPECT_LT(low[0], -M_PI + 0.02);
  EXPECT_GT(high[0], M_PI - 0.02);
  EXPECT_LT(low[1], -1.0 + 0.01);
  EXPECT_GT(high[1], 2.0 - 0.01);
}

}  // namespace
}  // namespace mcws
