#pragma once
/// \file
/// \brief The local frames in which the orthant boundary test looks for an empty orthant.

namespace mcws {

/// \brief A frame of the orthant test around a point p (see OrthantBoundary).
enum class OrthantFrame : unsigned {
  kAxis = 1u,         ///< the coordinate axes (Yin, Wang & Yu 2010's own rule)
  kOutward = 2u,      ///< turned so that one orthant is centred on the outward direction
  kAnyRotation = 4u,  ///< 2-D only: every rotation, i.e. an empty sector of the minimum gap
};

/// \brief A set of OrthantFrame values; empty means "the default for the plane".
class OrthantFrames {
 public:
  constexpr OrthantFrames() = default;
  constexpr OrthantFrames(OrthantFrame frame) : bits_(static_cast<unsigned>(frame)) {}  // NOLINT

  constexpr bool empty() const { return bits_ == 0; }
  /// The set as bits: kAxis 1, kOutward 2, kAnyRotation 4.
  constexpr unsigned bits() const { return bits_; }
  constexpr bool has(OrthantFrame frame) const {
    return (bits_ & static_cast<unsigned>(frame)) != 0;
  }
  constexpr bool operator==(OrthantFrames other) const { return bits_ == other.bits_; }
  constexpr bool operator!=(OrthantFrames other) const { return bits_ != other.bits_; }
  constexpr OrthantFrames operator|(OrthantFrames other) const {
    return fromBits(bits_ | other.bits_);
  }
  constexpr OrthantFrames without(OrthantFrame frame) const {
    return fromBits(bits_ & ~static_cast<unsigned>(frame));
  }

 private:
  static constexpr OrthantFrames fromBits(unsigned bits) {
    OrthantFrames frames;
    frames.bits_ = bits;
    return frames;
  }
  unsigned bits_{0};
};

constexpr OrthantFrames operator|(OrthantFrame a, OrthantFrame b) {
  return OrthantFrames(a) | OrthantFrames(b);
}

/// \brief The frames tested for `frames` in `dimensions` (2 or 3): the default when empty (any
/// rotation in 2-D; axis and outward in 3-D), and in 3-D any rotation replaced by axis and
/// outward.
constexpr OrthantFrames resolveFrames(OrthantFrames frames, int dimensions) {
  const OrthantFrames fixed = OrthantFrame::kAxis | OrthantFrame::kOutward;
  if (frames.empty()) return dimensions == 2 ? OrthantFrame::kAnyRotation : fixed;
  if (dimensions == 3 && frames.has(OrthantFrame::kAnyRotation)) {
    return frames.without(OrthantFrame::kAnyRotation) | fixed;
  }
  return frames;
}

}  // namespace mcws
