#pragma once
/// \file
/// \brief The radius classes of exposedPoints() (exposed_points.cpp): radii rounded down to
/// classes of ratio kClassRatio from the smallest. Private to mcws_workspace (namespace
/// mcws::detail).

#include <algorithm>
#include <cmath>
#include <vector>

namespace mcws::detail {

/// Ratio of consecutive radius classes.
constexpr double kClassRatio = 1.25;

/// The class of radius r (>= smallest): the largest j with smallest * kClassRatio^j <= r, but for
/// the rounding of the logarithm, which may put a radius just above a class's lower radius a class
/// lower (never higher).
inline int radiusClass(double r, double smallest) {
  int j = static_cast<int>(std::floor(std::log(r / smallest) / std::log(kClassRatio)));
  // The rounding of the logarithm must not put a radius in a class above it.
  while (j > 0 && smallest * std::pow(kClassRatio, j) > r) --j;
  return j;
}

/// radiusClass() for many radii, the same class for each: the classes' lower radii computed once
/// (as radiusClass() computes them) and each radius's class found among them by bisection;
/// radiusClass() itself answers the radii within a relative 1e-9 above a lower radius, where the
/// rounding of its logarithm may put them a class lower.
class RadiusClasses {
 public:
  /// \param smallest the lowest class's radius (> 0).
  /// \param largest the largest radius that will be asked about (finite, >= smallest).
  RadiusClasses(double smallest, double largest) : smallest_(smallest) {
    for (int j = 0; lower_.empty() || lower_.back() <= largest; ++j) {
      lower_.push_back(smallest * std::pow(kClassRatio, j));
    }
  }
  /// The class of r (smallest <= r <= largest).
  int operator()(double r) const {
    const auto above = std::upper_bound(lower_.begin(), lower_.end(), r);
    const int j = static_cast<int>(above - lower_.begin()) - 1;
    if (j < 0 || r < lower_[j] * (1.0 + 1e-9)) return radiusClass(r, smallest_);
    return j;
  }

 private:
  double smallest_;
  std::vector<double> lower_;  // class j's lower radius: smallest * kClassRatio^j
};

}  // namespace mcws::detail
