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
  const std::size_t n = 64;
  std::vector<float> x(n + kKernelSlack), y(n + kKernelSlack), z(n + kKernelSlack);
  for (std::size_t k = 0; k < n; ++k) x[k] = u(rng), y[k] = u(rng), z[k] = rng() % 5 ? u(rng) : 0;
  int near_total = 0;
  for (std::uint32_t offset = 0; offset < 9; ++offset) {
    for (std::uint32_t length = 0; offset + length <= n; ++length) {
      const float px = x[offset], py = u(rng), pz = rng() % 2 ? 0.0f : u(rng);
      // A bound equal to one of the distances (a tie at the bound is not near), or 1.
      float bound = 1.0f;
      if (length > 2 && offset % 2 == 0) {
        const std::uint32_t k = offset + length / 2;
        const float dx = x[k] - px, dy = y[k] - py, dz = z[k] - pz;
        bound = dx * dx;
        bound += dy * dy;
        bound += dz * dz;
      }
      std::vector<float> d2[2], near_d2[2];
      std::vector<std::uint32_t> slot[2], near_slot[2];
      std::size_t near[2];
      for (int form = 0; form < 2; ++form) {
        d2[form].assign(length + kKernelSlack, -1.0f);
        slot[form].assign(length + kKernelSlack, 0);
        near_d2[form].assign(length + kKernelSlack, -1.0f);
        near_slot[form].assign(length + kKernelSlack, 0);
        auto kernel = form == 0 ? plain::rowDistances : rowDistances;
        near[form] = kernel(x.data() + offset, y.data() + offset, z.data() + offset, length, px, py,
                            pz, 100 + offset, bound, d2[form].data(), slot[form].data(),
                            near_d2[form].data(), near_slot[form].data());
      }
      ASSERT_EQ(near[0], near[1]) << offset << " " << length;
      ASSERT_EQ(0, std::memcmp(d2[0].data(), d2[1].data(), length * sizeof(float)));
      for (std::uint32_t k = 0; k < length; ++k) {
        const float dx = x[offset + k] - px, dy = y[offset + k] - py, dz = z[offset + k] - pz;
        float d = dx * dx;
        d += dy * dy;
        d += dz * dz;
        ASSERT_EQ(d2[1][k], d);
        ASSERT_EQ(slot[1][k], 100 + offset + k);
      }
      ASSERT_EQ(0, std::memcmp(near_d2[0].data(), near_d2[1].data(), near[0] * sizeof(float)));
      ASSERT_EQ(0, std::memcmp(near_slot[0].data(), near_slot[1].data(),
                               near[0] * sizeof(std::uint32_t)));
      near_total += static_cast<int>(near[0]);
    }
  }
  EXPECT_GT(near_total, 1000);
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
    std::vector<std::uint32_t> places(n + kKernelSlack);
    const std::size_t m = placesBelow(v.data(), n, bound, places.data());
    ASSERT_EQ(m, expected.size());
    for (std::size_t j = 0; j < m; ++j) ASSERT_EQ(v[places[j]], expected[j]);
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
