#include <algorithm>
#include <cmath>
#include <numeric>

#include "mcws/filters/orthant/cloud_stages.h"

namespace mcws::orthant {
namespace {

/// Expected distance to the k-th nearest neighbour in a uniform cloud [mean spacings]: the
/// radius of the disk (ball) holding k + 1 points.
double kthNeighbourDistance(int k, int dimensions) {
  return dimensions == 2 ? std::sqrt((k + 1) / M_PI) : std::cbrt(3.0 * (k + 1) / (4.0 * M_PI));
}

/// The radius of point i's neighbourhood in the hull stage, r_i (searched if not known yet) or
/// R; nothing if `search` declined.
std::optional<double> hullRadius(NeighbourSearch& search, const PointTestSettings& test,
                                 pcl::index_t i, std::optional<float>& radius) {
  if (test.adaptive && !radius) {
    const std::optional<float> d2k = search.kthDistance2(i, test.adaptive->k + 1, nullptr);
    if (!d2k) return std::nullopt;
    radius = static_cast<float>(test.adaptive->scale) * std::sqrt(*d2k);
  }
  return test.outerRadius(test.adaptive ? *radius : test.radius);
}

}  // namespace

double typicalOuterRadius(const PointTestSettings& test, double spacing) {
  const double radius =
      test.adaptive
          ? test.adaptive->scale * kthNeighbourDistance(test.adaptive->k, test.dimensions) * spacing
          : test.radius;
  return test.outerRadius(radius);
}

CloudDecisions testEveryPoint(GridThenTreeSearch& search, const PointTestSettings& test,
                              int threads) {
  const std::size_t n = search.size();
  CloudDecisions decisions{std::vector<char>(n, 0), std::vector<std::optional<float>>(n)};
  std::vector<pcl::index_t> every(n);
  std::iota(every.begin(), every.end(), 0);
  search.forEachPoint<PointScratch>(
      every, threads, [&](NeighbourSearch& s, pcl::index_t i, PointScratch& scratch) {
        const std::optional<PointDecision> decision = testPoint(test, s, i, scratch);
        if (!decision) return false;
        decisions.boundary[i] = decision->boundary;
        decisions.radius[i] = decision->radius;
        return true;
      });
  return decisions;
}

void keepShallowPoints(GridThenTreeSearch& search, const PointTestSettings& test, double depth,
                       int threads, CloudDecisions& decisions) {
  const std::size_t n = search.size();
  // Candidates: the points found and those within a quarter of their radius (the points the test
  // misses lie about a spacing from one it finds). One thread, as the task marks other points:
  // a few thousand searches.
  std::vector<pcl::index_t> found;
  for (std::size_t i = 0; i < n; ++i) {
    if (decisions.boundary[i]) found.push_back(static_cast<pcl::index_t>(i));
  }
  std::vector<char> candidate(n, 0);
  search.forEachPoint<PointScratch>(
      found, 1, [&](NeighbourSearch& s, pcl::index_t i, PointScratch& scratch) {
        const std::optional<double> r = hullRadius(s, test, i, decisions.radius[i]);
        if (!r || !s.radius(i, 0.25 * *r, scratch.neighbours)) return false;
        for (const auto& q : scratch.neighbours) candidate[q.index] = 1;
        return true;
      });
  std::vector<pcl::index_t> candidates;
  for (std::size_t i = 0; i < n; ++i) {
    if (candidate[i]) candidates.push_back(static_cast<pcl::index_t>(i));
  }
  std::vector<char> shallow(n, 0);
  search.forEachPoint<PointScratch>(
      candidates, threads, [&](NeighbourSearch& s, pcl::index_t i, PointScratch& scratch) {
        const std::optional<double> r = hullRadius(s, test, i, decisions.radius[i]);
        if (!r || !s.radius(i, *r, scratch.neighbours)) return false;
        shallow[i] = hullDepthInSpacings(scratch.neighbours, scratch.hull) < depth;
        return true;
      });
  decisions.boundary.swap(shallow);
}

double medianRadius(const GridThenTreeSearch& search, const PointTestSettings& test,
                    CloudDecisions& decisions) {
  const std::size_t n = search.size();
  CellGridSearch grid = search.gridSearch();
  std::vector<float> sample;
  for (std::size_t i = 0; i < n; i += std::max<std::size_t>(1, n / 1000)) {
    std::optional<float>& radius = decisions.radius[i];
    if (!radius) {
      const auto index = static_cast<pcl::index_t>(i);
      if (const auto d2k = grid.kthDistance2(index, test.adaptive->k + 1, nullptr)) {
        radius = static_cast<float>(test.adaptive->scale) * std::sqrt(*d2k);
      }
    }
    if (radius) sample.push_back(*radius);
  }
  if (sample.empty()) return 0.0;
  std::nth_element(sample.begin(), sample.begin() + sample.size() / 2, sample.end());
  return sample[sample.size() / 2];
}

}  // namespace mcws::orthant
