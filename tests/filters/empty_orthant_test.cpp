// orthant::hasEmptyOrthant() (signs compared four lanes at a time, x and y summed side by side)
// against the plain per-coordinate form it replaced, on random neighbourhoods full of the cases
// the signs and the sums must get right: zeros of either sign, values on the axes, tiny offsets.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "mcws/filters/orthant/empty_orthant.h"

namespace mcws::orthant {
namespace {

/// The axis pass as it was written before, one neighbour at a time: the orthants occupied
/// (scalar sign codes), the three double sums in order and the largest squared distance.
struct ScalarAxisPass {
  unsigned mask{0};
  double sx{0.0}, sy{0.0}, sz{0.0};
  float size2{0.0f};
};

ScalarAxisPass scalarAxisPass(const std::vector<Neighbour>& neighbours, int dimensions) {
  const std::uint8_t* bits = orthantBits(dimensions);
  ScalarAxisPass pass;
  for (const auto& q : neighbours) {
    pass.mask |= bits[signCode(q.x, q.y, q.z)];
    pass.sx += q.x;
    pass.sy += q.y;
    pass.sz += q.z;
    pass.size2 = std::max(pass.size2, q.d2);
  }
  return pass;
}

/// hasEmptyOrthant() as it was written before (scalar sign codes, three double sums).
bool reference(const std::vector<Neighbour>& neighbours, int dimensions, OrthantFrames frames) {
  const unsigned full = dimensions == 2 ? 0xFu : 0xFFu;
  const auto [axis_mask, sx, sy, sz, size2] = scalarAxisPass(neighbours, dimensions);
  if (axis_mask == 0) return true;
  if (frames.has(OrthantFrame::kAxis) && axis_mask != full) return true;
  if (!frames.has(OrthantFrame::kOutward)) return false;
  const double count = static_cast<double>(neighbours.size());
  Eigen::Vector3f n(static_cast<float>(-sx / count), static_cast<float>(-sy / count),
                    static_cast<float>(-sz / count));
  if (dimensions == 2) n.z() = 0;
  const float length = n.norm();
  if (!(length > 1e-6f * std::sqrt(size2))) return false;
  n /= length;
  const Eigen::Matrix3f E = outwardFrame(n, dimensions);
  const std::uint8_t* bits = orthantBits(dimensions);
  unsigned outward_mask = 0;
  for (const auto& q : neighbours) {
    const Eigen::Vector3f w = E * Eigen::Vector3f(q.x, q.y, q.z);
    outward_mask |= bits[signCode(w.x(), w.y(), w.z())];
    if (outward_mask == full) return false;
  }
  return true;
}

/// A coordinate: mostly uniform in [-1, 1], now and then 0, -0, +-1 exactly or tiny.
float coordinate(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  switch (rng() % 12) {
    case 0:
      return 0.0f;
    case 1:
      return -0.0f;
    case 2:
      return rng() % 2 ? 1.0f : -1.0f;
    case 3:
      return u(rng) * 1e-30f;
    default:
      return u(rng);
  }
}

TEST(EmptyOrthant, SameAnswerAsThePerCoordinateForm) {
  std::mt19937 rng(7);
  const OrthantFrames frame_sets[] = {OrthantFrame::kAxis, OrthantFrame::kOutward,
                                      OrthantFrame::kAxis | OrthantFrame::kOutward};
  int boundary = 0, cases = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const int dimensions = 2 + trial % 2;
    std::vector<Neighbour> neighbours(rng() % 40);
    for (auto& q : neighbours) {
      const float x = coordinate(rng), y = coordinate(rng);
      const float z = dimensions == 3 ? coordinate(rng) : 0.0f;
      q = Neighbour(x, y, z, x * x + y * y + z * z, 0);
    }
    for (const OrthantFrames frames : frame_sets) {
      const bool expected = reference(neighbours, dimensions, frames);
      ASSERT_EQ(hasEmptyOrthant(neighbours, dimensions, frames), expected)
          << "trial " << trial << ", frames " << frames.bits();
      boundary += expected;
      ++cases;
    }
  }
  // Both answers occur often: the comparison means something.
  EXPECT_GT(boundary, cases / 10);
  EXPECT_LT(boundary, cases - cases / 10);
}

#if MCWS_ORTHANT_AVX2
TEST(EmptyOrthant, AxisPassAsOneByOne) {
  // The AVX2 first pass (eight neighbours at a time, the last group padded) against the same
  // quantities one neighbour at a time: the mask, the double sums bit for bit (their order
  // decides the outward frame), the largest d^2; lists of every length from 0 to 99.
  if (!axisPassHasAvx2()) GTEST_SKIP() << "no AVX2 on this processor";
  std::mt19937 rng(13);
  for (int trial = 0; trial < 20000; ++trial) {
    const int dimensions = 2 + trial % 2;
    std::vector<Neighbour> neighbours(static_cast<std::size_t>(trial / 2 % 100));
    for (auto& q : neighbours) {
      const float x = coordinate(rng), y = coordinate(rng);
      const float z = dimensions == 3 ? coordinate(rng) : 0.0f;
      q = Neighbour(x, y, z, x * x + y * y + z * z, 0);
    }
    const auto [mask, sx, sy, sz, size2] = scalarAxisPass(neighbours, dimensions);
    const AxisPass pass = axisPassAvx2(neighbours, dimensions);
    ASSERT_EQ(pass.mask, mask) << "trial " << trial;
    for (const auto& [got, expected] : {std::pair{pass.sx, sx}, {pass.sy, sy}, {pass.sz, sz}}) {
      ASSERT_EQ(got, expected) << "trial " << trial;
      ASSERT_EQ(std::signbit(got), std::signbit(expected)) << "trial " << trial;
    }
    ASSERT_EQ(pass.size2, size2) << "trial " << trial;
  }
}
#endif

#if defined(__SSE2__)
TEST(EmptyOrthant, FrameColumnsRoundAsEigensProduct) {
  // The outward frame applied four lanes at a time must give Eigen's E * v bit for bit: a sign
  // that flips at a last-bit difference would change an answer.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int differ_by_order = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    Eigen::Vector3f n(u(rng), u(rng), trial % 2 ? u(rng) : 0.0f);
    if (!(n.norm() > 1e-3f)) continue;
    n.normalize();
    const Eigen::Matrix3f E = outwardFrame(n, 2 + trial % 2);
    const FrameColumns columns(E);
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector3f v(coordinate(rng), coordinate(rng), coordinate(rng));
      const Eigen::Vector3f expected = E * v;
      alignas(16) float lanes[4];
      _mm_store_ps(lanes, columns.times(_mm_setr_ps(v.x(), v.y(), v.z(), 0.5f)));
      for (int axis = 0; axis < 3; ++axis) {
        ASSERT_EQ(std::signbit(lanes[axis]), std::signbit(expected[axis])) << trial;
        ASSERT_EQ(lanes[axis], expected[axis]) << "trial " << trial << ", axis " << axis;
        // The other order of the sum, (E(i,0) x + E(i,1) y) + E(i,2) z, often differs: the
        // comparison tells the orders apart.
        const float other = (E(axis, 0) * v.x() + E(axis, 1) * v.y()) + E(axis, 2) * v.z();
        differ_by_order += other != expected[axis];
      }
    }
  }
  EXPECT_GT(differ_by_order, 1000);
}
#endif

}  // namespace
}  // namespace mcws::orthant
