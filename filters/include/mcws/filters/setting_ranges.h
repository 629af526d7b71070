#pragma once
/// \file
/// \brief The values the settings of the boundary methods may take for a given cloud, so that a
/// caller can refuse a value before the filter does and name its own setting (a tool's flag).

#include <optional>
#include <string>

#include "mcws/filters/boundary_geometry.h"

namespace mcws {

/// \brief The values one setting may take: [low, high], or (low, high] when `open_low`, in
/// `unit` ("[length unit]", "mean spacings", "neighbours", "times each point's radius"); `why`
/// says in words where the bounds come from (for a message).
struct SettingRange {
  double low{0.0};
  double high{0.0};
  bool open_low{false};
  std::string unit;
  std::string why;

  /// \brief Whether `value` lies in the range.
  bool contains(double value) const {
    return (open_low ? value > low : value >= low) && value <= high;
  }
};

/// \brief What the ranges of boundarySettingRanges() depend on besides the cloud.
struct BoundarySettings {
  /// GridBoundary or ExtremumBoundary (cell, gap), else OrthantBoundary (radius, auto-radius
  /// factor, outer radius, adaptive k).
  bool baseline{false};
  BoundaryPlane plane{BoundaryPlane::k3D};
  int adaptive_neighbours{0};    ///< orthant: the k of an adaptive radius
  double radius{0.0};            ///< orthant: a fixed radius [unit], 0 when none is set
  double auto_radius_factor{0};  ///< orthant: c of a radius c x mean spacing, 0 when none
};

/// \brief The range of each setting of a boundary method for one cloud. `adaptive` needs only
/// the count of distinct points; the lengths need the cloud summarised with its spacing
/// (SummaryDetail::kSpacing) and are set only then, and only for the method's own settings.
struct BoundarySettingRanges {
  SettingRange adaptive;  ///< orthant's adaptive k: 1 up to below the distinct points, at most 1000
  std::optional<SettingRange> cell;         ///< grid cell side, extremum column width [unit]
  std::optional<SettingRange> gap;          ///< extremum gap threshold [unit]
  std::optional<SettingRange> radius;       ///< orthant's fixed radius [unit]
  std::optional<SettingRange> auto_radius;  ///< orthant's c of c x mean spacing [mean spacings]
  /// orthant's outer radius: beyond the radius [unit] when it is fixed (`radius` or
  /// `auto_radius_factor`), else a factor beyond 1 of each point's adaptive radius
  std::optional<SettingRange> outer_radius;
};

/// \brief The ranges of the settings of a boundary method for `cloud` (CloudSummary): lengths
/// within parameterLengths() (a baseline's cell also coarse enough for the 21 bits an axis of
/// its cell keys), the adaptive k below the number of distinct points, the outer radius beyond
/// the radius and within the cloud's extent. A value outside is one the filter rejects or that
/// makes no boundary.
BoundarySettingRanges boundarySettingRanges(const CloudSummary& cloud,
                                            const BoundarySettings& settings);

}  // namespace mcws
