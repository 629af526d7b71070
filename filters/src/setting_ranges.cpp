#include "mcws/filters/setting_ranges.h"

#include <algorithm>

#include "mcws/core/decimal.h"
#include "mcws/filters/grid_boundary.h"
#include "mcws/filters/orthant/cloud_stages.h"
#include "mcws/filters/orthant_boundary.h"

namespace mcws {
namespace {

/// The orthant filter's ranges: its fixed or automatic radius and its outer radius.
void orthantRanges(const CloudSummary& cloud, const BoundarySettings& settings,
                   BoundarySettingRanges& ranges) {
  const LengthRange length = parameterLengths(cloud);
  const double h = *cloud.spacing;
  const std::string lengths =
      "a tenth of the cloud's mean spacing " + formatNumber(h) + " to its extent";
  ranges.radius = SettingRange{length.min, length.max, false, "[length unit]", lengths};
  ranges.auto_radius = SettingRange{
      length.min / h, length.max / h, false, "mean spacings",
      "the radius c x " + formatNumber(h) + " from a tenth of a spacing to the extent"};
  // As the filter computes it.
  const double radius = settings.radius > 0.0 ? settings.radius : settings.auto_radius_factor * h;
  if (radius > 0.0) {
    ranges.outer_radius = SettingRange{radius, length.max, true, "[length unit]",
                                       "beyond the radius, at most the cloud's extent"};
    return;
  }
  orthant::PointTestSettings test;
  test.dimensions = boundaryDimensions(settings.plane);
  test.adaptive = orthant::AdaptiveRadius{settings.adaptive_neighbours,
                                          OrthantBoundary<pcl::PointXYZ>::kRecommendedScale};
  const double typical = orthant::typicalOuterRadius(test, h);
  ranges.outer_radius =
      SettingRange{1.0, length.max / typical, true, "times each point's radius",
                   "a factor beyond 1 of the radius, about " + formatNumber(typical) +
                       ", that keeps it within the cloud's extent"};
}

}  // namespace

BoundarySettingRanges boundarySettingRanges(const CloudSummary& cloud,
                                            const BoundarySettings& settings) {
  BoundarySettingRanges ranges;
  ranges.adaptive =
      SettingRange{1.0, std::min<double>(1000.0, cloud.distinct - 1.0), false, "neighbours",
                   "fewer than the cloud's " + std::to_string(cloud.distinct) +
                       " distinct points, at most 1000"};
  if (!cloud.spacing) return ranges;
  if (!settings.baseline) {
    orthantRanges(cloud, settings, ranges);
    return ranges;
  }
  const LengthRange length = parameterLengths(cloud);
  const std::string lengths =
      "a tenth of the cloud's mean spacing " + formatNumber(*cloud.spacing) + " to its extent";
  // The grid packs 21 bits per axis: a cell may not be so small that the extent needs more.
  const double cells = cloud.largest / kMaxBaselineCellsPerAxis * (1.0 + 1e-6);
  ranges.cell =
      SettingRange{std::max(length.min, cells), length.max, false, "[length unit]", lengths};
  ranges.gap = SettingRange{length.min, length.max, false, "[length unit]", lengths};
  return ranges;
}

}  // namespace mcws
