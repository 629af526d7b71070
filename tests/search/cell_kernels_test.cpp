// The cell grid's inner loops (vector forms where the processor has AVX2) against their plain
// forms and against sorting: bit for bit, on lengths that leave every tail, with ties.
#include "mcws/search/cell_kernels.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

namespace mcws::detail {
namespace {

TEST(CellKernels, RowDistancesAreThePlainOnesBitForBit) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const std::uint32_t n = 200;
  std::vector<float> x(n + kKernelSlack), y(n + kKernelSlack), z(n + kKernelSlack);
  for (std::size_t k = 0; k < n; ++k) x[k] = u(rng), y[k] = u(rng), z[k] = rng() % 5 ? u(rng) : 0;
  int near_total = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    // Up to 6 rows of 0 to 30 points anywhere (the last ones reaching the end of the arrays).
    std::vector<RowSpan> rows(rng() % 7);
    std::vector<std::uint32_t> expected_slots;
    for (auto& row : rows) {
      const std::uint32_t length = rng() % 31;
      row.begin = trial % 5 == 0 ? n - length : static_cast<std::uint32_t>(rng() % (n - length));
      row.end = row.begin + length;
      for (std::uint32_t k = row.begin; k < row.end; ++k) expected_slots.push_back(k);
    }
    const std::size_t total = expected_slots.size();
    const float px = u(rng), py = u(rng), pz = rng() % 2 ? 0.0f : u(rng);
    std::vector<float> expected_d2;
    for (const std::uint32_t k : expected_slots) {
      const float dx = x[k] - px, dy = y[k] - py, dz = z[k] - pz;
      float d = dx * dx;
      d += dy * dy;
      d += dz * dz;
      expected_d2.push_back(d);
    }
    // A bound equal to one of the distances (a tie at the bound is not near), or 1.
    const float bound = total > 0 && trial % 2 ? expected_d2[total / 2] : 1.0f;
    std::vector<float> expected_near_d2;
    std::vector<std::uint32_t> expected_near_slot;
    for (std::size_t j = 0; j < total; ++j) {
      if (expected_d2[j] < bound) {
        expected_near_d2.push_back(expected_d2[j]);
        expected_near_slot.push_back(expected_slots[j]);
      }
    }
    for (auto kernel : {plain::rowDistances, rowDistances}) {
      std::vector<float> d2(total + kKernelSlack), near_d2(total + kKernelSlack);
      std::vector<std::uint32_t> slot(total + kKernelSlack), near_slot(total + kKernelSlack);
      const std::size_t near =
          kernel(x.data(), y.data(), z.data(), rows.data(), rows.size(), px, py, pz, bound,
                 d2.data(), slot.data(), near_d2.data(), near_slot.data());
      ASSERT_EQ(near, expected_near_d2.size()) << trial;
      // (bit for bit; memcmp only where there is something to compare: an empty vector's data
      // may be null)
      ASSERT_TRUE(total == 0 ||
                  std::memcmp(d2.data(), expected_d2.data(), total * sizeof(float)) == 0)
          << trial;
      ASSERT_EQ(std::vector<std::uint32_t>(slot.begin(), slot.begin() + total), expected_slots);
      ASSERT_TRUE(near == 0 ||
                  std::memcmp(near_d2.data(), expected_near_d2.data(), near * sizeof(float)) == 0);
      ASSERT_EQ(std::vector<std::uint32_t>(near_slot.begin(), near_slot.begin() + near),
                expected_near_slot);
    }
    near_total += static_cast<int>(expected_near_d2.size());
  }
  EXPECT_GT(near_total, 5000);
}

TEST(CellKernels, ValuesBelowKeepsTheOrderAndLeavesTies) {
  std::mt19937 rng(5);
  for (std::size_t n = 0; n < 70; ++n) {
    std::vector<float> v(n + kKernelSlack);
    for (auto& e : v) e = static_cast<float>(rng() % 20);
    const float bound = static_cast<float>(rng() % 22);
    std::vector<float> expected;
    for (std::size_t k = 0; k < n; ++k) {
      if (v[k] < bound) expected.push_back(v[k]);
    }
    for (auto kernel : {plain::valuesBelow, valuesBelow}) {
      std::vector<float> out(n + kKernelSlack);
      const std::size_t m = kernel(v.data(), n, bound, out.data());
      ASSERT_EQ(std::vector<float>(out.begin(), out.begin() + m), expected) << n;
    }
    for (auto kernel : {plain::placesBelow, placesBelow}) {
      std::vector<std::uint32_t> places(n + kKernelSlack);
      const std::size_t m = kernel(v.data(), n, bound, places.data());
      ASSERT_EQ(m, expected.size());
      for (std::size_t j = 0; j < m; ++j) {
        ASSERT_LT(places[j], n);
        ASSERT_TRUE(j == 0 || places[j] > places[j - 1]);
        ASSERT_EQ(v[places[j]], expected[j]);
      }
    }
  }
}

TEST(CellKernels, KthSmallestIsTheSortedListsEntry) {
  std::mt19937 rng(9);
  for (int trial = 0; trial < 3000; ++trial) {
    const std::size_t m = 1 + rng() % 80;
    // Few distinct values (many ties), or many.
    const unsigned spread = trial % 3 == 0 ? 4 : 1000;
    std::vector<float> v(m);
    for (auto& e : v) e = static_cast<float>(rng() % spread) * 0.25f;
    std::vector<float> sorted = v;
    std::sort(sorted.begin(), sorted.end());
    const int count = 1 + static_cast<int>(rng() % m);
    for (auto kernel : {plain::kthSmallest, kthSmallest}) {
      std::vector<float> w = v;
      w.resize(m + kKernelSlack, -7.0f);
      ASSERT_EQ(kernel(w.data(), m, count), sorted[count - 1]) << "m " << m << ", count " << count;
    }
  }
}

}  // namespace
}  // namespace mcws::detail
