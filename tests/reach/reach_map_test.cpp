// mcws::ReachMap on hand-made maps: adding, merging and sorting voxels, their keys, the grid's
// checks, and the binary format and its errors (buildReachMap is in reach_map_build_test.cpp).
#include "mcws/reach/reach_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include "mcws/core/error.h"
#include "reach/reach_map_fixture.h"
#include "test_support.h"

namespace mcws {
namespace {

using test::bytesOf;
using test::contents;
using test::key;
using test::readBytes;
using test::Voxel;
using test::VoxelIndex;

// ---------------------------------------------------------------------------------------------
// Hand-made maps.

/// 0.5 voxels, 100 x 2 = 200 bins (four words, so bins 63/64 and 150/199 sit in different words).
ReachGrid handGrid() { return test::reachGrid(0.5, 100, 2); }

ReachMap handMapA() {
  ReachMap map(handGrid());
  map.add({0.1, 0.1, 0.1}, 3, 1.5f);     // voxel (0, 0, 0)
  map.add({0.2, 0.3, 0.4}, 150, 0.5f);   // voxel (0, 0, 0)
  map.add({-0.1, 0.0, 0.0}, 199, 2.0f);  // voxel (-1, 0, 0)
  map.add({1.0, -2.0, 3.0}, 64, 0.25f);  // voxel (2, -4, 6)
  return map;
}

ReachMap handMapB() {
  ReachMap map(handGrid());
  map.add({0.4, 0.4, 0.4}, 3, 3.0f);   // voxel (0, 0, 0), a bin A has, a better value
  map.add({0.3, 0.1, 0.2}, 63, 1.0f);  // voxel (0, 0, 0)
  map.add({5.0, 5.0, 5.0}, 0, 0.0f);   // voxel (10, 10, 10)
  return map;
}

/// A and B merged, by hand.
std::map<VoxelIndex, Voxel> handMerged() {
  return {{{0, 0, 0}, {4, 3.0f, {3, 63, 150}}},
          {{-1, 0, 0}, {1, 2.0f, {199}}},
          {{2, -4, 6}, {1, 0.25f, {64}}},
          {{10, 10, 10}, {1, 0.0f, {0}}}};
}

TEST(ReachMap, AddCountsSamplesAndKeepsBinsAndBestValue) {
  const ReachMap a = handMapA();
  EXPECT_EQ(a.size(), 3u);
  EXPECT_EQ(a.samples(), 4u);
  const std::map<VoxelIndex, Voxel> expected = {{{0, 0, 0}, {2, 1.5f, {3, 150}}},
                                                {{-1, 0, 0}, {1, 2.0f, {199}}},
                                                {{2, -4, 6}, {1, 0.25f, {64}}}};
  EXPECT_TRUE(contents(a) == expected);
  const long v = a.find({0.49, 0.01, 0.25});
  ASSERT_GE(v, 0);
  EXPECT_EQ(a.reachedBins(v), 2);
  EXPECT_DOUBLE_EQ(a.reachability(v), 2.0 / 200.0);
  EXPECT_EQ(a.find({0.5, 0.0, 0.0}), -1);      // voxel (1, 0, 0): empty
  EXPECT_EQ(a.find({-0.01, -0.01, 0.0}), -1);  // voxel (-1, -1, 0)
}

TEST(ReachMap, BinsOutOfRangeAreErrorsAndFindNeverThrows) {
  ReachMap map = handMapA();  // 100 directions x 2 rolls: bins 0 .. 199, four 64-bit words
  for (int bin : {-1, 200, 255, 256}) {
    EXPECT_NE(test::errorOf([&] {
                map.add({0.1, 0.1, 0.1}, bin, 1.0f);
              }).find("no orientation bin " + std::to_string(bin) + " of 200"),
              std::string::npos);
    EXPECT_NE(test::errorOf([&] { (void)map.reached(0, bin); }).find("no orientation bin"),
              std::string::npos);
  }
  EXPECT_EQ(map.samples(), 4u);  // nothing was recorded
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(map.find({nan, 0.0, 0.0}), -1);
  EXPECT_EQ(map.find({1e300, 0.0, 0.0}), -1);
  EXPECT_FALSE(map.reached(Eigen::Vector3d(1e300, 0.0, 0.0), Eigen::Matrix3d::Identity()));
  EXPECT_NE(test::errorOf([&] {
              map.add({1e300, 0.0, 0.0}, 0, 1.0f);
            }).find("beyond the grid"),
            std::string::npos);
}

TEST(ReachMap, MergeAddsCountsUnitesBinsAndKeepsTheMaximum) {
  ReachMap ab = handMapA();
  ab.merge(handMapB());
  ReachMap ba = handMapB();
  ba.merge(handMapA());
  EXPECT_TRUE(contents(ab) == handMerged());
  EXPECT_TRUE(contents(ba) == handMerged());
  EXPECT_EQ(ab.samples(), 7u);

  // One map of all the samples, added in yet another order.
  ReachMap one(handGrid());
  one.add({5.0, 5.0, 5.0}, 0, 0.0f);
  one.add({1.0, -2.0, 3.0}, 64, 0.25f);
  one.add({0.3, 0.1, 0.2}, 63, 1.0f);
  one.add({-0.1, 0.0, 0.0}, 199, 2.0f);
  one.add({0.4, 0.4, 0.4}, 3, 3.0f);
  one.add({0.2, 0.3, 0.4}, 150, 0.5f);
  one.add({0.1, 0.1, 0.1}, 3, 1.5f);

  // Unsorted, the voxel order is the order of arrival; sorted, every map writes the same bytes.
  EXPECT_NE(bytesOf(ab), bytesOf(ba));
  ab.sort();
  ba.sort();
  one.sort();
  EXPECT_EQ(bytesOf(ab), bytesOf(ba));
  EXPECT_EQ(bytesOf(ab), bytesOf(one));
  // Sorted by index, x slowest and z fastest.
  const std::vector<VoxelIndex> order = {{-1, 0, 0}, {0, 0, 0}, {2, -4, 6}, {10, 10, 10}};
  ASSERT_EQ(ab.size(), order.size());
  for (std::size_t v = 0; v < order.size(); ++v) EXPECT_EQ(key(ab.voxel(v)), order[v]) << v;
  // The index still finds every voxel after sorting.
  for (std::size_t v = 0; v < ab.size(); ++v) {
    EXPECT_EQ(ab.find(ab.voxelCentre(ab.voxel(v))), static_cast<long>(v));
  }
}

TEST(ReachMap, SortOrdersZFastestThenYThenX) {
  ReachMap map(handGrid());
  const std::vector<VoxelIndex> sorted = {{-3, 5, 5}, {-3, 6, -9}, {-3, 6, -8}, {0, -1, 7},
                                          {0, 0, -7}, {0, 0, 0},   {1, -9, -9}};
  for (auto it = sorted.rbegin(); it != sorted.rend(); ++it) {  // reversed on the way in
    map.add(map.voxelCentre({(*it)[0], (*it)[1], (*it)[2]}), 0, 0.f);
  }
  map.sort();
  ASSERT_EQ(map.size(), sorted.size());
  for (std::size_t v = 0; v < sorted.size(); ++v) EXPECT_EQ(key(map.voxel(v)), sorted[v]) << v;
}

TEST(ReachMap, MergeRejectsAnotherGrid) {
  ReachMap a = handMapA();
  for (int change = 0; change < 3; ++change) {
    ReachGrid grid = handGrid();
    if (change == 0) grid.resolution = 0.25;
    if (change == 1) grid.directions = 50;
    if (change == 2) grid.rolls = 4;
    const ReachMap other(grid);
    EXPECT_NE(test::errorOf([&] { a.merge(other); }).find("different grids"), std::string::npos);
  }
}

TEST(ReachMap, ManyVoxelsSurviveTheIndexGrowingAndSorting) {
  // Past several rebuilds of the open-addressing index (1024 slots, load at most one half).
  ReachGrid grid;
  grid.resolution = 1.0;
  grid.directions = 1;
  ReachMap map(grid);
  std::map<VoxelIndex, std::uint64_t> expected;
  for (int i = -20; i < 20; ++i) {
    for (int j = -20; j < 20; ++j) {
      for (int k = 0; k < 5; ++k) {
        const int repeats = 1 + ((i * 7 + j * 3 + k) % 3 + 3) % 3;  // 1 to 3
        for (int r = 0; r < repeats; ++r) map.add({i + 0.5, j + 0.25, k + 0.75}, 0, float(r));
        expected[{i, j, k}] = repeats;
      }
    }
  }
  ASSERT_EQ(map.size(), expected.size());
  map.sort();
  std::size_t v = 0;
  for (const auto& [index, count] : expected) {  // std::map: x, then y, then z ascending
    ASSERT_EQ(key(map.voxel(v)), index);
    ASSERT_EQ(map.count(v), count);
    ASSERT_EQ(map.bestManipulability(v), float(count - 1));
    ASSERT_EQ(map.find(Eigen::Vector3d(index[0] + 0.5, index[1] + 0.5, index[2] + 0.5)),
              static_cast<long>(v));
    ++v;
  }
}

TEST(ReachMap, VoxelOfIsTheFloorAlsoBelowZero) {
  ReachGrid grid;
  grid.resolution = 2.0;
  const ReachMap map(grid);
  struct Case {
    double x;
    int index;
  };
  // floor(x / 2): -0.5 * resolution is in voxel -1, not 0 (truncation would say 0).
  for (const Case& c :
       {Case{-1.0, -1}, Case{-1e-12, -1}, Case{-0.0, 0}, Case{0.0, 0}, Case{1.999, 0}, Case{2.0, 1},
        Case{-2.0, -1}, Case{-2.0001, -2}, Case{-3.0, -2}, Case{-4.0, -2}, Case{7.5, 3}}) {
    EXPECT_EQ(map.voxelOf({c.x, 0.0, 0.0}).x(), c.index) << c.x;
    EXPECT_EQ(map.voxelOf({0.0, c.x, 0.0}).y(), c.index) << c.x;
    EXPECT_EQ(map.voxelOf({0.0, 0.0, c.x}).z(), c.index) << c.x;
  }
  // The centre of voxel i is (i + 1/2) * resolution.
  EXPECT_EQ(map.voxelCentre({-1, 0, 3}), Eigen::Vector3d(-1.0, 1.0, 7.0));
  // The index range: -2^20 .. 2^20 - 1.
  const double limit = ReachMap::kIndexLimit * grid.resolution;
  EXPECT_EQ(map.voxelOf({-limit, 0.0, 0.0}).x(), -(1 << 20));
  EXPECT_EQ(map.voxelOf({limit - 1.0, 0.0, 0.0}).x(), (1 << 20) - 1);
  for (double x : {limit, -limit - 1.0, std::numeric_limits<double>::quiet_NaN(),
                   std::numeric_limits<double>::infinity()}) {
    const std::string message = test::errorOf([&] { map.voxelOf({0.0, x, 0.0}); });
    EXPECT_NE(message.find("beyond the grid's range"), std::string::npos) << x << ": " << message;
  }
}

TEST(ReachMap, ExtremeIndicesRoundTripThroughTheKey) {
  ReachGrid grid;
  grid.resolution = 1.0;
  ReachMap map(grid);
  const int lo = -(1 << 20), hi = (1 << 20) - 1;
  const std::vector<VoxelIndex> corners = {
      {lo, lo, lo}, {hi, hi, hi}, {lo, hi, 0}, {-1, -1, -1}, {0, lo, hi}};
  for (const VoxelIndex& i : corners) map.add({i[0] + 0.5, i[1] + 0.5, i[2] + 0.5}, 0, 0.f);
  ASSERT_EQ(map.size(), corners.size());
  for (std::size_t v = 0; v < corners.size(); ++v) EXPECT_EQ(key(map.voxel(v)), corners[v]);
  const ReachMap copy = readBytes(bytesOf(map), "corners");
  EXPECT_TRUE(contents(copy) == contents(map));
}

TEST(ReachMap, GridChecksNameTheBadValue) {
  ReachGrid grid = handGrid();
  EXPECT_NO_THROW(grid.check());
  for (double resolution : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                            std::numeric_limits<double>::infinity()}) {
    grid = handGrid();
    grid.resolution = resolution;
    EXPECT_NE(test::errorOf([&] { ReachMap{grid}; }).find("resolution"), std::string::npos);
  }
  grid = handGrid();
  grid.directions = 0;
  EXPECT_NE(test::errorOf([&] { grid.check(); }).find("not 0"), std::string::npos);
  grid = handGrid();
  grid.rolls = -2;
  EXPECT_NE(test::errorOf([&] { grid.check(); }).find("roll bin, not -2"), std::string::npos);
  grid = handGrid();
  grid.directions = 65536;
  grid.rolls = 1;
  EXPECT_NO_THROW(grid.check());  // exactly the limit
  grid.directions = 32769;
  grid.rolls = 2;
  EXPECT_NE(test::errorOf([&] { grid.check(); }).find("65538 orientation bins"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// The binary format.

TEST(ReachMap, WriteThenReadIsTheSameMap) {
  ReachMap map = handMapA();
  map.merge(handMapB());
  map.sort();
  const std::string bytes = bytesOf(map, R"({"robot":"hand","samples":7})");
  std::string header;
  const ReachMap copy = readBytes(bytes, "hand.map", &header);
  EXPECT_TRUE(contents(copy) == handMerged());
  EXPECT_EQ(copy.grid().resolution, 0.5);
  EXPECT_EQ(copy.grid().directions, 100);
  EXPECT_EQ(copy.grid().rolls, 2);
  EXPECT_EQ(bytesOf(copy, R"({"robot":"hand","samples":7})"), bytes);
  EXPECT_EQ(header, R"({"resolution":0.5,"directions":100,"rolls":2,"voxels":4,"words":4,)"
                    R"("robot":"hand","samples":7})");
  // The layout: the magic line, the header line, then per voxel 3 int32 indices, a uint64
  // count, a float and 4 uint64 words of bits: 56 bytes.
  const std::string first_line = "MCWS-REACH-MAP 1\n";
  ASSERT_EQ(bytes.compare(0, first_line.size(), first_line), 0);
  const std::size_t data = first_line.size() + header.size() + 1;
  ASSERT_EQ(bytes.size(), data + 4 * 56);
  // The second voxel in order is (0, 0, 0): count 4, best 3, bits 3 and 63 in word 0, 150 in
  // word 2.
  const char* v1 = bytes.data() + data + 56;
  std::int32_t index[3];
  std::uint64_t count, words[4];
  float best;
  std::memcpy(index, v1, 12);
  std::memcpy(&count, v1 + 12, 8);
  std::memcpy(&best, v1 + 20, 4);
  std::memcpy(words, v1 + 24, 32);
  EXPECT_EQ(index[0], 0);
  EXPECT_EQ(index[1], 0);
  EXPECT_EQ(index[2], 0);
  EXPECT_EQ(count, 4u);
  EXPECT_EQ(best, 3.0f);
  EXPECT_EQ(words[0], (std::uint64_t{1} << 3) | (std::uint64_t{1} << 63));
  EXPECT_EQ(words[1], 0u);
  EXPECT_EQ(words[2], std::uint64_t{1} << (150 - 128));
  EXPECT_EQ(words[3], 0u);
}

TEST(ReachMap, AnEmptyMapRoundTrips) {
  const ReachMap empty(handGrid());
  const std::string bytes = bytesOf(empty);
  const ReachMap copy = readBytes(bytes, "empty.map");
  EXPECT_EQ(copy.size(), 0u);
  EXPECT_EQ(copy.samples(), 0u);
  EXPECT_EQ(bytesOf(copy), bytes);
}

TEST(ReachMap, ReadRejectsTruncatedData) {
  ReachMap map = handMapA();
  map.sort();
  const std::string bytes = bytesOf(map, R"({"robot":"hand"})");
  // Every proper prefix fails, naming the source: no magic, no header line, a missing voxel,
  // a voxel cut in the middle.
  for (std::size_t size = 0; size < bytes.size(); ++size) {
    const std::string message = test::errorOf([&] { readBytes(bytes.substr(0, size), "cut.map"); });
    ASSERT_EQ(message.rfind("cut.map: ", 0), 0u) << size << ": " << message;
  }
  const std::size_t data = bytes.size() - 3 * 56;
  EXPECT_NE(test::errorOf([&] {
              readBytes(bytes.substr(0, data + 56 + 20), "cut.map");
            }).find("ends early"),
            std::string::npos);
}

TEST(ReachMap, ReadRejectsBadMagicAndTrailingBytes) {
  ReachMap map = handMapA();
  map.sort();
  const std::string bytes = bytesOf(map);
  std::string bad = bytes;
  bad[15] = '2';  // "MCWS-REACH-MAP 2"
  std::string message = test::errorOf([&] { readBytes(bad, "other.map"); });
  EXPECT_EQ(message.rfind("other.map: ", 0), 0u) << message;
  EXPECT_NE(message.find("not a reachability map"), std::string::npos) << message;
  EXPECT_NE(test::errorOf([&] {
              readBytes("# .PCD v0.7\nVERSION 0.7\n", "cloud.pcd");
            }).find("cloud.pcd: not a reachability map"),
            std::string::npos);

  message = test::errorOf([&] { readBytes(bytes + "x", "long.map"); });
  EXPECT_EQ(message.rfind("long.map: ", 0), 0u) << message;
  EXPECT_NE(message.find("data after the last voxel"), std::string::npos) << message;
}

TEST(ReachMap, ReadRejectsBadHeadersAndVoxels) {
  ReachMap map = handMapA();
  map.sort();
  const std::string bytes = bytesOf(map);
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string changed = bytes;
    const std::size_t at = changed.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return changed.replace(at, from.size(), to);
  };
  EXPECT_NE(test::errorOf([&] {
              readBytes(replaced("\"words\":4", "\"wordz\":4"), "h.map");
            }).find("h.map: header has no 'words'"),
            std::string::npos);
  EXPECT_NE(test::errorOf([&] {
              readBytes(replaced("\"words\":4", "\"words\":3"), "h.map");
            }).find("h.map: header 'words' does not match"),
            std::string::npos);
  EXPECT_NE(test::errorOf([&] {
              readBytes(replaced("\"rolls\":2", "\"rolls\":x"), "h.map");
            }).find("h.map: header field 'rolls' is not a number"),
            std::string::npos);
  EXPECT_NE(test::errorOf([&] {
              readBytes(replaced("\"directions\":100", "\"directions\":0"), "h.map");
            }).find("h.map: header has an impossible grid"),
            std::string::npos);
  EXPECT_NE(test::errorOf([&] {
              readBytes(replaced("\"resolution\":0.5", "\"resolution\":-0.5"), "h.map");
            }).find("h.map: reachability map: the resolution"),
            std::string::npos);
  // One more voxel announced than written: the data ends early.
  EXPECT_NE(test::errorOf([&] {
              readBytes(replaced("\"voxels\":3", "\"voxels\":4"), "h.map");
            }).find("h.map: the reachability map ends early"),
            std::string::npos);

  // The second voxel's index overwritten with the first's, and an index out of range.
  const std::size_t data = bytes.size() - 3 * 56;
  std::string twice = bytes;
  twice.replace(data + 56, 12, bytes.substr(data, 12));
  EXPECT_NE(test::errorOf([&] { readBytes(twice, "d.map"); }).find("d.map: a voxel appears twice"),
            std::string::npos);
  std::string far = bytes;
  const std::int32_t beyond = 1 << 20;
  std::memcpy(far.data() + data + 4, &beyond, 4);
  EXPECT_NE(test::errorOf([&] { readBytes(far, "f.map"); }).find("f.map: voxel index out of range"),
            std::string::npos);
}

TEST(ReachMap, WriteRejectsAHeaderThatIsNotAnObject) {
  const ReachMap map = handMapA();
  std::ostringstream out;
  const std::string wanted = "must be a JSON object on one line";
  EXPECT_NE(test::errorOf([&] { map.write(out, "robot"); }).find(wanted), std::string::npos);
  EXPECT_NE(test::errorOf([&] { map.write(out, ""); }).find(wanted), std::string::npos);
  EXPECT_NE(test::errorOf([&] { map.write(out, "{\n  \"robot\": \"a\"\n}"); }).find(wanted),
            std::string::npos);
  // Spaces around a one-line object are fine, and its members reach the header.
  std::ostringstream spaced;
  map.write(spaced, "  {\"robot\":\"a\"}  ");
  std::istringstream in(spaced.str());
  std::string header;
  ReachMap::read(in, "spaced", &header);
  EXPECT_NE(header.find("\"robot\":\"a\""), std::string::npos) << header;
}

}  // namespace
}  // namespace mcws
