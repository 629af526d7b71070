#pragma once
/// \file
/// \brief The orthant boundary test of one point, its parameters resolved: which searches to ask
/// for, in which order, and what decides.

#include <pcl/types.h>

#include <cmath>
#include <optional>
#include <vector>

#include "mcws/filters/orthant/empty_orthant.h"
#include "mcws/filters/orthant/empty_sector.h"
#include "mcws/filters/orthant/frames.h"
#include "mcws/filters/orthant/hull_depth.h"
#include "mcws/search/neighbour_search.h"

namespace mcws::orthant {

/// \brief A per-point radius r_i = scale * (distance to the k-th nearest neighbour).
struct AdaptiveRadius {
  int k;
  double scale;
};

/// \brief The test's parameters, resolved for one cloud.
struct PointTestSettings {
  int dimensions{3};
  OrthantFrames frames;                    ///< resolved (resolveFrames)
  SectorGap gap{};                         ///< 2-D any rotation: the empty sector looked for
  std::optional<AdaptiveRadius> adaptive;  ///< per-point radius; without it, `radius`
  double radius{0.0};                      ///< the fixed radius [length unit]
  double outer{0.0};  ///< second-stage radius R [length unit] (0: none); a factor when adaptive

  /// True when more neighbours can only fill the orthants (no frame is built from the
  /// neighbourhood), so that a subset of the neighbours without an empty one decides.
  bool monotone() const {
    return (dimensions == 2 && frames.has(OrthantFrame::kAnyRotation)) ||
           frames == OrthantFrame::kAxis;
  }
  /// The second-stage radius for a point whose radius is r.
  double outerRadius(double r) const { return outer > 0.0 ? (adaptive ? outer * r : outer) : r; }
};

/// \brief The answer for one point.
struct PointDecision {
  bool boundary{false};
  /// With an adaptive radius, the point's r_i [length unit], unless the point was decided
  /// interior from the neighbours proved to lie within r_i before r_i itself was searched.
  std::optional<float> radius;
};

/// \brief Scratch space of one thread.
struct PointScratch {
  std::vector<Neighbour> neighbours;
  std::vector<Direction> directions;
  HullScratch hull;
};

/// \brief The test on one neighbour list: an empty sector (2-D any rotation) or an empty orthant
/// (the axis and outward frames).
inline bool isBoundaryPoint(const std::vector<Neighbour>& neighbours, const PointTestSettings& test,
                            std::vector<Direction>& directions) {
  if (test.dimensions == 2 && test.frames.has(OrthantFrame::kAnyRotation)) {
    return hasEmptySector(neighbours, test.gap, directions);
  }
  return hasEmptyOrthant(neighbours, test.dimensions, test.frames);
}

/// \brief A first search at this fraction of the radius, which decides almost every interior point
/// (why: filters/README.md, "A subset decides"). Exact when the test is monotone.
constexpr double kPrefilterRadius = 0.65;

/// \brief Decides point i with `search`; nothing when the search declined a query (ask another
/// search). With a monotone test, a neighbourhood subset (the points proved to lie within r_i,
/// the k nearest, or those within kPrefilterRadius of the radius) is tried first: if it leaves
/// no orthant empty, the point is interior. A point whose neighbours are all copies of it (r_i =
/// 0) is alone, hence boundary. With an outer radius, a point found at r is tested again at R.
inline std::optional<PointDecision> testPoint(const PointTestSettings& test,
                                              NeighbourSearch& search, pcl::index_t i,
                                              PointScratch& s) {
  const bool monotone = test.monotone();
  double r = test.radius;
  bool prefiltered = false;
  if (test.adaptive) {
    const auto [k, scale] = *test.adaptive;
    const bool subset = monotone && scale > 1.001;  // the k nearest then lie within r_i
    if (subset && search.adaptiveSubset(i, k + 1, static_cast<float>(scale), s.neighbours) &&
        !isBoundaryPoint(s.neighbours, test, s.directions)) {
      return PointDecision{false, std::nullopt};
    }
    const std::optional<float> d2k =
        search.kthDistance2(i, k + 1, subset ? &s.neighbours : nullptr);
    if (!d2k) return std::nullopt;
    const float rk = static_cast<float>(scale) * std::sqrt(*d2k);
    if (!(rk > 0.0f)) return PointDecision{true, rk};
    r = rk;
    if (subset) {
      if (!isBoundaryPoint(s.neighbours, test, s.directions)) return PointDecision{false, rk};
      prefiltered = true;
    }
  }
  const std::optional<float> own_radius =
      test.adaptive ? std::optional<float>(static_cast<float>(r)) : std::nullopt;
  const double R = test.outerRadius(r);
  if (monotone && !prefiltered) {
    if (!search.radius(i, kPrefilterRadius * R, s.neighbours)) return std::nullopt;
    if (!isBoundaryPoint(s.neighbours, test, s.directions)) return PointDecision{false, own_radius};
  }
  if (!search.radius(i, r, s.neighbours)) return std::nullopt;
  bool boundary = isBoundaryPoint(s.neighbours, test, s.directions);
  if (boundary && test.outer > 0.0) {
    if (!search.radius(i, R, s.neighbours)) return std::nullopt;
    boundary = isBoundaryPoint(s.neighbours, test, s.directions);
  }
  return PointDecision{boundary, own_radius};
}

}  // namespace mcws::orthant
