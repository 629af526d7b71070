// buildReachMap's dense box of voxels (mcws::reach_map_build::VoxelBox) against the hash tables
// it replaces where the reach fits in memory: the same map, byte for byte, on the planar arm and
// the inspection arm, with any thread count, records swept sorted or as they come, and with
// samples outside a box made too small on purpose; the box's indices (of keys and of scaled
// points) against brute force; the index of a map built by threads finding every voxel, also
// when it is built by the first of several threads to look (and in a copy); the voxels a part
// counts in each block against its records; a part's 8-byte samples (box index and bin in one
// code) against the plain recording, and the hash tables where the codes do not fit; a part's
// recorded batches handed back empty with their memory.
#include "mcws/reach/voxel_box.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <thread>

#include "mcws/kinematics/robot_yaml.h"
#include "mcws/reach/reach_map.h"
#include "reach/planar2.h"
#include "reach/reach_map_fixture.h"
#include "test_support.h"

namespace mcws {
namespace {

using reach_map_build::BoxPart;
using reach_map_build::BoxSample;
using reach_map_build::PendingSample;
using reach_map_build::VoxelBox;

/// A part that keeps the samples it records, in order.
class ListPart : public reach_map_build::Part<PendingSample> {
 public:
  std::vector<PendingSample> recorded;

 private:
  void record(const std::vector<std::vector<PendingSample>>& batches) override {
    for (const auto& batch : batches) recorded.insert(recorded.end(), batch.begin(), batch.end());
  }
  bool cached() const override { return true; }
};

std::string boxMapBytes(const ReachMap& map) {
  std::ostringstream out(std::ios::binary);
  map.write(out, "{}");
  return out.str();
}

/// ReachMap's packed key of a voxel index, written out.
std::uint64_t boxTestKey(std::int64_t x, std::int64_t y, std::int64_t z) {
  const auto field = [](std::int64_t i) {
    return static_cast<std::uint64_t>(i + ReachMap::kIndexLimit);
  };
  return (field(x) << 42) | (field(y) << 21) | field(z);
}

TEST(VoxelBox, IndicesRunZFastestAndKeysRoundTrip) {
  const std::int64_t low[3] = {-3, 5, -1}, size[3] = {4, 3, 5};
  VoxelBox box(low, size, 3);
  ASSERT_EQ(box.voxels(), 60u);
  std::size_t expected = 0;
  for (std::int64_t x = -5; x < 3; ++x) {
    for (std::int64_t y = 3; y < 10; ++y) {
      for (std::int64_t z = -3; z < 6; ++z) {
        const bool inside = x >= -3 && x < 1 && y >= 5 && y < 8 && z >= -1 && z < 4;
        std::uint64_t index = 0;
        ASSERT_EQ(box.indexOf(boxTestKey(x, y, z), index), inside) << x << " " << y << " " << z;
        if (!inside) continue;
        ASSERT_EQ(index, expected++);
        ASSERT_EQ(box.keyOf(index), boxTestKey(x, y, z));
        for (int w = 0; w < 3; ++w) ASSERT_EQ(box.record(index)[w], 0u);  // zeroed memory
      }
    }
  }
  EXPECT_EQ(expected, 60u);
}

TEST(VoxelBox, TheReachBoxIsRefusedWhenTooLargeOrBeyondTheIndexRange) {
  const Robot robot = test::planar2();  // 70 cm of reach
  // 1 cm voxels: 143 per axis, 4 words each.
  ASSERT_NE(reach_map_build::reachBox(robot, 70.0, 1.0, 4, 100u << 20), nullptr);
  EXPECT_EQ(reach_map_build::reachBox(robot, 70.0, 1.0, 4, 1u << 20), nullptr);
  EXPECT_EQ(reach_map_build::reachBox(robot, 70.0, 1e-5, 4, ~std::uint64_t{0}), nullptr);
}

TEST(BuildReachMap, TheDenseBoxGivesTheHashTablesMap) {
  const Robot robot = test::planar2();
  // 2 cm: a 12 MB box swept in sorted order; 10 cm: one recorded as samples come.
  for (const double resolution : {2.0, 10.0}) {
    ReachSampling hash = test::reachSampling(robot, 150001, 3, 1);
    hash.dense_bytes = 0;
    const std::string expected =
        boxMapBytes(buildReachMap(robot, test::reachGrid(resolution, 20, 6), hash));
    for (const int threads : {1, 2, 3}) {
      EXPECT_EQ(boxMapBytes(buildReachMap(robot, test::reachGrid(resolution, 20, 6),
                                          test::reachSampling(robot, 150001, 3, threads))),
                expected)
          << resolution << " " << threads;
    }
  }
}

TEST(BuildReachMap, TheInspectionArmsDenseMapIsItsHashMapWithAndWithoutManipulability) {
  const Robot robot = loadRobot(test::robotPath("inspection6"));  // mm, 1655 mm of reach
  ASSERT_NE(reach_map_build::reachBox(robot, chainLengthScale(robot), 50.0, 6, 1u << 30), nullptr);
  for (const bool manipulability : {true, false}) {
    ReachSampling hash = test::reachSampling(robot, 200003, 3, 2);
    hash.manipulability = manipulability;
    ReachSampling dense = hash;
    hash.dense_bytes = 0;
    const ReachMap map = buildReachMap(robot, test::reachGrid(50.0, 200, 1), dense);
    EXPECT_EQ(boxMapBytes(map),
              boxMapBytes(buildReachMap(robot, test::reachGrid(50.0, 200, 1), hash)));
    EXPECT_GT(map.size(), 10000u);
  }
}

TEST(BuildReachMap, SamplesOutsideTheBoxCountAsInTheHashTables) {
  // A box for 30 cm or 0 cm of the planar arm's 70: most samples fall outside it.
  const Robot robot = test::planar2();
  ReachSampling hash = test::reachSampling(robot, 100003, 3, 1);
  hash.dense_bytes = 0;
  const std::string expected = boxMapBytes(buildReachMap(robot, test::reachGrid(2.0, 20, 6), hash));
  for (const double radius : {30.0, 0.0}) {
    for (const int threads : {1, 2}) {
      EXPECT_EQ(boxMapBytes(reach_map_build::buildReachMapInBox(
                    robot, test::reachGrid(2.0, 20, 6),
                    test::reachSampling(robot, 100003, 3, threads), radius)),
                expected)
          << radius << " " << threads;
    }
  }
}

TEST(BuildReachMap, TheIndexBuiltByThreadsFindsEveryVoxel) {
  // Over 65536 voxels: the index is built by both threads, for the box and the hash tables.
  const Robot robot = loadRobot(test::robotPath("inspection6"));
  for (const std::uint64_t dense_bytes : {std::uint64_t{1} << 30, std::uint64_t{0}}) {
    ReachSampling s = test::reachSampling(robot, 200003, 3, 2);
    s.manipulability = false;
    s.dense_bytes = dense_bytes;
    const ReachMap map = buildReachMap(robot, test::reachGrid(20.0, 20, 1), s);
    ASSERT_GT(map.size(), 65536u);
    for (std::size_t v = 0; v < map.size(); ++v) {
      ASSERT_EQ(map.find(map.voxelCentre(map.voxel(v))), static_cast<long>(v)) << v;
    }
    EXPECT_EQ(map.find(Eigen::Vector3d(1e5, 0.0, 0.0)), -1);
  }
}

TEST(VoxelBox, TheIndexOfAScaledPointIsThatOfItsFloorsKey) {
  // Scaled coordinates on, just beside and between the box's voxel edges, beyond it and NaN:
  // the index of the key of floor(s) (brute force), or false where that key is outside.
  const std::int64_t low[3] = {-3, 5, -1}, size[3] = {4, 3, 5};
  const VoxelBox box(low, size, 3);
  std::vector<double> values;
  for (int i = -6; i <= 10; ++i) {
    for (const double d : {0.0, 0.5, 1e-12, -1e-12}) values.push_back(i + d);
  }
  values.push_back(std::nextafter(-3.0, -4.0));
  values.push_back(std::nan(""));
  for (const double x : values) {
    for (const double y : values) {
      for (const double z : {-1.0, -0.5, 3.999, 4.0, std::nan("")}) {
        const double scaled[3] = {x, y, z};
        std::uint64_t index = 7, expected = 7;
        const bool inside = box.indexOfScaled(scaled, 1, index);
        const bool finite = std::isfinite(x) && std::isfinite(y) && std::isfinite(z);
        const bool key_inside =
            finite && box.indexOf(boxTestKey(static_cast<std::int64_t>(std::floor(x)),
                                             static_cast<std::int64_t>(std::floor(y)),
                                             static_cast<std::int64_t>(std::floor(z))),
                                  expected);
        ASSERT_EQ(inside, key_inside) << x << " " << y << " " << z;
        ASSERT_EQ(index, expected) << x << " " << y << " " << z;
      }
    }
  }
}

TEST(VoxelBox, APartCountsTheVoxelsItReachesInEachOfItsBlocks) {
  // 10^3 voxels of 3 words (cached, recorded as samples come) and 80^3 of 6 (24 MB: sorted):
  // the counts against the records' own, block by block, over both parts.
  for (const std::int64_t edge : {10, 80}) {
    const std::int64_t low[3] = {-4, 0, 7}, size[3] = {edge, edge, edge};
    const int stride = edge == 10 ? 3 : 6;
    VoxelBox box(low, size, stride);
    std::vector<std::unique_ptr<reach_map_build::BoxPart>> parts;
    const int bins = stride == 3 ? 64 : 200;
    for (int p = 0; p < 2; ++p) parts.push_back(std::make_unique<BoxPart>(box, 2, bins));
    std::mt19937_64 random(5);
    for (int round = 0; round < 3; ++round) {
      std::vector<reach_map_build::BoxBatch> batches(2);
      for (int i = 0; i < 200000; ++i) {
        // Squared: denser near the box's start, so some blocks stay empty.
        const double u = std::uniform_real_distribution<double>(0.0, 1.0)(random);
        const auto index = static_cast<std::uint64_t>(u * u * 0.7 * box.voxels());
        const int part = BoxPart::partOf(index, 2);
        batches[part].push_back({parts[part]->code(index, i % bins), 0.25f});
      }
      for (int p = 0; p < 2; ++p) {
        parts[p]->post(std::move(batches[p]));
        ASSERT_TRUE(parts[p]->tryRecord());
      }
    }
    std::size_t empty_blocks = 0;
    for (std::size_t b = 0; b < box.blocks(); ++b) {
      std::uint32_t reached = 0;
      for (std::size_t i = b * VoxelBox::kBlock;
           i < std::min(box.voxels(), (b + 1) * VoxelBox::kBlock); ++i) {
        reached += box.record(i)[0] != 0;
      }
      const int holder = reach_map_build::BoxPart::partOf(b * VoxelBox::kBlock, 2);
      ASSERT_EQ(parts[holder]->reached()[b], reached) << edge << " " << b;
      ASSERT_EQ(parts[1 - holder]->reached()[b], 0u) << edge << " " << b;
      empty_blocks += reached == 0;
    }
    if (edge == 80) {
      EXPECT_GT(empty_blocks, 0u);
    }
  }
}

TEST(VoxelBox, APartsEightByteSamplesRecordWhatTheSixteenByteOnesDid) {
  // Samples as 8-byte codes (index and bin) recorded by the box's parts, swept sorted or as they
  // come, against the same samples recorded one by one with recordSample (the plain path):
  // every word of every record the same. Bins of 1, 64, 200 and 65536 (0, 6, 8 and 16 bits),
  // the last box index and the last bin among them.
  struct Case {
    std::int64_t edge[3];
    int bins;
    int samples;
  };
  for (const Case& c : {Case{{10, 10, 10}, 64, 20000}, Case{{80, 80, 80}, 200, 300000},
                        Case{{40, 41, 43}, 1, 100000}, Case{{16, 64, 64}, 65536, 3000}}) {
    const std::int64_t low[3] = {-7, 2, 0};
    const int stride = 2 + (c.bins + 63) / 64;
    VoxelBox box(low, c.edge, stride);
    ASSERT_TRUE(BoxPart::fits(box.voxels(), c.bins));
    std::vector<std::uint64_t> plain(box.voxels() * stride, 0);
    std::vector<std::unique_ptr<BoxPart>> parts;
    for (int p = 0; p < 2; ++p) parts.push_back(std::make_unique<BoxPart>(box, 2, c.bins));
    std::mt19937_64 random(11);
    std::vector<std::size_t> touched;
    for (int round = 0; round < 2; ++round) {
      std::vector<reach_map_build::BoxBatch> batches(2);
      for (int i = 0; i < c.samples; ++i) {
        std::uint64_t index = random() % box.voxels();
        int bin = static_cast<int>(random() % static_cast<unsigned>(c.bins));
        if (i % 97 == 0) index = box.voxels() - 1;
        if (i % 89 == 0) bin = c.bins - 1;
        if (c.bins == 65536) index = i % 2 == 0 ? index % 64 : box.voxels() - 1 - index % 64;
        const float w = std::uniform_real_distribution<float>(0.0f, 2.0f)(random);
        reach_map_build::recordSample(plain.data() + index * stride, bin, w);
        touched.push_back(index);
        const int part = BoxPart::partOf(index, 2);
        const std::uint32_t code = parts[part]->code(index, bin);
        ASSERT_EQ(code >> BoxPart::binBits(c.bins), index);
        ASSERT_EQ(code & ((std::uint32_t{1} << BoxPart::binBits(c.bins)) - 1),
                  static_cast<std::uint32_t>(bin));
        batches[part].push_back({code, w});
      }
      for (int p = 0; p < 2; ++p) {
        parts[p]->post(std::move(batches[p]));
        ASSERT_TRUE(parts[p]->tryRecord());
      }
    }
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    std::size_t reached = 0;
    for (std::size_t b = 0; b < box.blocks(); ++b) {
      reached += parts[0]->reached()[b] + parts[1]->reached()[b];
    }
    EXPECT_EQ(reached, touched.size()) << c.bins;
    for (const std::size_t i : touched) {
      for (int w = 0; w < stride; ++w) {
        ASSERT_EQ(box.record(i)[w], plain[i * stride + w]) << c.bins << " " << i << " " << w;
      }
    }
  }
}

TEST(VoxelBox, ABoxFitsTheCodesOfItsIndicesAndBinsIn32Bits) {
  EXPECT_EQ(BoxPart::binBits(1), 0);
  EXPECT_EQ(BoxPart::binBits(2), 1);
  EXPECT_EQ(BoxPart::binBits(200), 8);
  EXPECT_EQ(BoxPart::binBits(256), 8);
  EXPECT_EQ(BoxPart::binBits(257), 9);
  EXPECT_EQ(BoxPart::binBits(65536), 16);
  EXPECT_TRUE(BoxPart::fits(std::size_t{1} << 24, 256));
  EXPECT_FALSE(BoxPart::fits((std::size_t{1} << 24) + 1, 256));
  EXPECT_FALSE(BoxPart::fits(std::size_t{1} << 24, 257));
  EXPECT_TRUE(BoxPart::fits(std::size_t{1} << 32, 1));
  EXPECT_TRUE(BoxPart::fits(65536, 65536));
  EXPECT_FALSE(BoxPart::fits(65537, 65536));
}

TEST(BuildReachMap, ABoxTooLargeForItsCodesGivesWayToTheHashTables) {
  // The planar arm at 3.5 cm (a box of 43^3 voxels, 652 MB at 65536 bins, within the default
  // 1 GiB) with 4096 directions x 16 rolls: 16 bits of bin leave 2^16 voxels, fewer than the
  // box's, so the hash tables record it; the map is theirs.
  const Robot robot = test::planar2();
  const auto box = reach_map_build::reachBox(robot, 70.0, 3.5, 2 + 1024, std::uint64_t{1} << 30);
  ASSERT_NE(box, nullptr);
  EXPECT_EQ(box->voxels(), 43u * 43u * 43u);
  EXPECT_FALSE(BoxPart::fits(box->voxels(), 4096 * 16));
  ReachSampling hash = test::reachSampling(robot, 20011, 3, 2);
  const ReachSampling dense = hash;
  hash.dense_bytes = 0;
  EXPECT_EQ(boxMapBytes(buildReachMap(robot, test::reachGrid(3.5, 4096, 16), dense)),
            boxMapBytes(buildReachMap(robot, test::reachGrid(3.5, 4096, 16), hash)));
}

TEST(BuildReachMap, ThreadsFindingVoxelsAtOnceInACopyOfAMapWithoutItsIndex) {
  // The built map's index is left to the first lookup: two threads look up every voxel at once
  // in the map and in a copy made before either looked (the copy builds its own).
  const Robot robot = loadRobot(test::robotPath("inspection6"));
  ReachSampling s = test::reachSampling(robot, 200003, 3, 2);
  s.manipulability = false;
  const ReachMap map = buildReachMap(robot, test::reachGrid(20.0, 20, 1), s);
  const ReachMap copy = map;  // NOLINT(performance-unnecessary-copy-initialization): the test
  ASSERT_GT(map.size(), 65536u);
  for (const ReachMap* m : {&map, &copy}) {
    std::vector<std::size_t> wrong(2, 0);
    std::vector<std::thread> threads;
    for (int t = 0; t < 2; ++t) {
      threads.emplace_back([&, t] {
        for (std::size_t v = 0; v < m->size(); ++v) {
          wrong[t] += m->find(m->voxelCentre(m->voxel(v))) != static_cast<long>(v);
        }
      });
    }
    for (auto& thread : threads) thread.join();
    EXPECT_EQ(wrong[0], 0u);
    EXPECT_EQ(wrong[1], 0u);
    EXPECT_EQ(m->find(Eigen::Vector3d(1e5, 0.0, 0.0)), -1);
  }
  // Its points made by two threads are those made by one.
  const auto points = reachPoints(map);
  std::vector<ReachPoint, Eigen::aligned_allocator<ReachPoint>> by_two(map.size());
  reachPoints(map, 0, map.size(), by_two.data(), 2);
  std::size_t differ = 0;
  for (std::size_t v = 0; v < map.size(); ++v) {
    const ReachPoint &a = points[v], &b = by_two[v];
    differ += a.x != b.x || a.y != b.y || a.z != b.z || a.reachability != b.reachability ||
              a.manipulability != b.manipulability || a.count != b.count;
  }
  EXPECT_EQ(differ, 0u);
  // Bytes are those of the hash tables' map, whose index was built as it filled.
  ReachSampling hash = s;
  hash.dense_bytes = 0;
  EXPECT_EQ(boxMapBytes(copy),
            boxMapBytes(buildReachMap(robot, test::reachGrid(20.0, 20, 1), hash)));
}

TEST(BuildReachMap, APartHandsBackTheBatchesItRecordedEmptyWithTheirMemory) {
  ListPart part;
  std::vector<PendingSample> first;
  first.reserve(100);
  for (int i = 0; i < 100; ++i) first.push_back({std::uint64_t(i), i % 7, 0.5f * i});
  const PendingSample* memory = first.data();
  // Nothing recorded yet: a new batch.
  std::vector<PendingSample> second = part.exchange(std::move(first), 100);
  EXPECT_TRUE(second.empty());
  EXPECT_GE(second.capacity(), 100u);
  EXPECT_NE(second.data(), memory);
  EXPECT_TRUE(part.due());
  ASSERT_TRUE(part.tryRecord());
  ASSERT_EQ(part.recorded.size(), 100u);
  for (int i = 0; i < 100; ++i) {
    EXPECT_EQ(part.recorded[i].key, std::uint64_t(i));
    EXPECT_EQ(part.recorded[i].bin, i % 7);
    EXPECT_EQ(part.recorded[i].manipulability, 0.5f * i);
  }
  // The first batch recorded: handed back empty, its memory kept.
  second.push_back({1000, 3, 2.0f});
  std::vector<PendingSample> third = part.exchange(std::move(second), 100);
  EXPECT_TRUE(third.empty());
  EXPECT_EQ(third.data(), memory);
  EXPECT_GE(third.capacity(), 100u);
  ASSERT_TRUE(part.tryRecord());
  ASSERT_EQ(part.recorded.size(), 101u);
  EXPECT_EQ(part.recorded.back().key, 1000u);
  // Spares dropped: a new batch again (not the one still waiting).
  part.dropSpares();
  third.push_back({1001, 4, 1.0f});
  const PendingSample* waiting = third.data();
  const std::vector<PendingSample> fourth = part.exchange(std::move(third), 10);
  EXPECT_TRUE(fourth.empty());
  EXPECT_GE(fourth.capacity(), 10u);
  EXPECT_NE(fourth.data(), waiting);
}

}  // namespace
}  // namespace mcws
