#pragma once
/// \file
/// \brief Counter-based random numbers: what a sample draws depends on its index, not on the
/// thread or the order in which it is drawn.

#include <cstdint>

namespace mcws {

/// \brief Counter-based uniform random numbers: the value for (index, stream) depends only on
/// the seed and those two numbers, never on the order or thread in which it is drawn.
///
/// It is the SplitMix64 generator (Steele, Lea, Flood, "Fast splittable pseudorandom number
/// generators", OOPSLA 2014) evaluated at position index * kStreams + stream of the sequence
/// whose start is derived from the seed.
class CounterRng {
 public:
  /// \brief Random numbers one sample may draw.
  static constexpr std::uint64_t kStreams = 16;

  explicit CounterRng(std::uint64_t seed) : start_(mix(seed)) {}

  /// \brief Uniform number in [0, 1) with 53 random bits.
  double uniform(std::uint64_t index, std::uint64_t stream) const {
    const std::uint64_t bits = mix(start_ + (index * kStreams + stream) * kGolden);
    return static_cast<double>(bits >> 11) * 0x1.0p-53;
  }

 private:
  static constexpr std::uint64_t kGolden = 0x9E3779B97F4A7C15ULL;
  static std::uint64_t mix(std::uint64_t x) {
    x += kGolden;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    return x ^ (x >> 31);
  }
  std::uint64_t start_;
};

}  // namespace mcws
