#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/workspace/detail/alpha_triangulation.h"
#include "mcws/workspace/detail/measure_steps.h"
#include "mcws/workspace/measure.h"

namespace mcws {
namespace detail {
namespace {

/// Fewest distinct subset points: the local spacing needs a point's 8 nearest neighbours.
constexpr std::size_t kFewestSubsetPoints = 9;

/// The whole cloud's kept simplices (info 1) and its edge correction on `dt`, as measureRegion()
/// in measure.cpp; `outside` flags the points outside the region of the others, `edge` the
/// boundary vertices.
template <int D, typename Delaunay>
RegionMeasure measureWhole(Delaunay& dt, const pcl::PointCloud<pcl::PointXYZ>& points,
                           const std::vector<double>& spacing, const MeasureOptions& options,
                           std::vector<char>& outside, std::vector<char>& edge) {
  startPhase(options, "triangulation");
  triangulate<D, CGAL::Sequential_tag>(dt, points, {});
  startPhase(options, "alpha test");
  RegionMeasure all;
  all.uncorrected = keepWithinAlpha<D>(dt, points, spacing, options.alpha_factor);
  const auto boundary = boundaryVertices<D>(dt, points.size());
  all.points = all.triangulated = dt.number_of_vertices();
  all.boundary_vertices = boundary.size();
  all.alpha_factor = options.alpha_factor;
  edge.assign(points.size(), 0);
  for (const auto v : boundary) edge[v->info()] = 1;
  outside.assign(points.size(), 0);
  if (options.edge_correction) {
    startPhase(options, "edge correction");
    all.outside =
        outsideByStar<D>(dt, boundary, spacing, options.alpha_factor, options.threads, &outside);
  }
  checkKeptAndMissing(all, D, options);
  return all;
}

/// The region that decides where the subset reaches: the Delaunay triangulation of the subset's
/// points and the whole cloud's boundary vertices next to them (`edge`: so that a subset thinner
/// than the whole reaches the whole's edge, not only its own points' edge), its alpha test at
/// their own local spacing. Vertex info: the index in `points`.
template <int D, typename Delaunay>
struct SubsetRegion {
  SubsetRegion(const pcl::PointCloud<pcl::PointXYZ>& points, const std::vector<char>& in_subset,
               const std::vector<char>& edge, const MeasureOptions& options) {
    std::size_t members = 0;
    pcl::PointCloud<pcl::PointXYZ> cloud;
    std::vector<std::uint32_t> index_of;
    for (std::size_t i = 0; i < points.size(); ++i) {
      members += in_subset[i] != 0;
      if (!in_subset[i] && !edge[i]) continue;
      cloud.push_back(points[i]);
      index_of.push_back(static_cast<std::uint32_t>(i));
    }
    if (members < kFewestSubsetPoints) {
      throw Error("the subset has " + std::to_string(members) +
                  " distinct points, too few to measure (at least " +
                  std::to_string(kFewestSubsetPoints) + ")");
    }
    const std::vector<double> local = localSpacing(cloud, D, options.threads);
    spacing.assign(points.size(), 0.0);
    for (std::size_t k = 0; k < cloud.size(); ++k) spacing[index_of[k]] = local[k];
    std::vector<char> take(points.size(), 0);
    for (const std::uint32_t i : index_of) take[i] = 1;
    try {
      triangulate<D, CGAL::Sequential_tag>(dt, points, take);
    } catch (const Error& e) {
      throw Error(std::string("the subset: ") + e.what());
    }
    vertex_of.resize(points.size());
    for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
      vertex_of[v->info()] = v;
    }
  }
  Delaunay dt;
  std::vector<double> spacing;                              ///< by index in `points`
  std::vector<typename Delaunay::Vertex_handle> vertex_of;  ///< by index in `points`
};

/// The subset's part of the whole cloud's kept simplices (delaunayMeasureSubset() says which),
/// summed as the whole's (the same bound, so no term or total exceeds the whole's), and the
/// whole's outside points counted for the subset, each weighted by the subset's share of the kept
/// simplices around it (at most 1).
template <int D, typename Delaunay>
std::pair<double, double> subsetPart(const Delaunay& dt,
                                     const pcl::PointCloud<pcl::PointXYZ>& points,
                                     const std::vector<char>& in_subset,
                                     const std::vector<char>& outside,
                                     const std::vector<char>& edge, const MeasureOptions& options) {
  // The whole's boundary vertices next to a subset point (in a kept simplex with one): those the
  // subset reaches out to. Those far from it (the far side of a cut) are left out.
  std::vector<char> near_edge(points.size(), 0);
  for (const auto s : finiteSimplices<D>(dt)) {
    if (!s->info()) continue;
    bool member = false;
    for (int k = 0; k <= D; ++k) member = member || in_subset[s->vertex(k)->info()];
    if (!member) continue;
    for (int k = 0; k <= D; ++k) {
      const std::uint32_t i = s->vertex(k)->info();
      if (edge[i]) near_edge[i] = 1;
    }
  }
  const SubsetRegion<D, Delaunay> region(points, in_subset, near_edge, options);
  OrderFreeSum part(boundingMeasure(points, D));
  std::vector<double> share(points.size(), 0.0), around(points.size(), 0.0);
  using Point = typename Delaunay::Point;
  decltype(region.dt.locate(Point())) hint{};
  for (const auto s : finiteSimplices<D>(dt)) {
    if (!s->info()) continue;
    int members = 0;
    std::uint32_t start = UINT32_MAX;  // the lowest index in the region: where the walk starts
    for (int k = 0; k <= D; ++k) {
      const std::uint32_t i = s->vertex(k)->info();
      members += in_subset[i] != 0;
      if (in_subset[i] || near_edge[i]) start = std::min(start, i);
    }
    const double measure = simplexMeasure<D>(s);
    double counted = measure;
    if (members < D + 1) {
      const auto p = canonicalPoints<D>(s);
      Point centre;
      if constexpr (D == 2) {
        centre = CGAL::centroid(p[0], p[1], p[2]);
        if (start != UINT32_MAX) hint = region.vertex_of[start]->face();
      } else {
        centre = CGAL::centroid(p[0], p[1], p[2], p[3]);
        if (start != UINT32_MAX) hint = region.vertex_of[start]->cell();
      }
      const auto holder = region.dt.locate(centre, hint);
      const bool inside = !region.dt.is_infinite(holder) &&
                          withinAlpha<D>(holder, region.spacing, options.alpha_factor);
      if (!region.dt.is_infinite(holder)) hint = holder;
      if (!inside) counted = measure * members / (D + 1);
    }
    part.add(counted);
    for (int k = 0; k <= D; ++k) {
      const std::uint32_t i = s->vertex(k)->info();
      if (!outside[i]) continue;
      share[i] += counted;
      around[i] += measure;
    }
  }
  double outside_share = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (around[i] > 0.0) outside_share += share[i] / around[i];
  }
  return {part.value(), outside_share};
}

template <int D>
SubsetMeasure measureSubset(const pcl::PointCloud<pcl::PointXYZ>& points,
                            const std::vector<char>& in_subset, const std::vector<double>& spacing,
                            const MeasureOptions& options) {
  using Delaunay = typename Simplices<D>::Delaunay;
  Delaunay dt;
  std::vector<char> outside, edge;
  SubsetMeasure result;
  result.all = measureWhole<D>(dt, points, spacing, options, outside, edge);
  startPhase(options, "subset");
  std::tie(result.uncorrected, result.outside) =
      subsetPart<D>(dt, points, in_subset, outside, edge, options);
  for (std::size_t i = 0; i < points.size(); ++i) result.points += in_subset[i] != 0;
  RegionMeasure& all = result.all;
  // Both corrected by one formula, uncorrected + outside * unit_share, which rounding keeps
  // monotonic in both: the subset's terms being at most the whole's, so is its measure.
  if (options.edge_correction) {
    result.unit_share = all.uncorrected / static_cast<double>(all.points - all.outside);
  }
  all.measure = all.uncorrected + static_cast<double>(all.outside) * result.unit_share;
  result.measure = result.uncorrected + result.outside * result.unit_share;
  return result;
}

}  // namespace
}  // namespace detail

SubsetMeasure delaunayMeasureSubset(const pcl::PointCloud<pcl::PointXYZ>& points,
                                    const std::vector<char>& in_subset, int dimensions,
                                    const MeasureOptions& options) {
  if (in_subset.size() != points.size()) {
    throw Error("subset flags: " + std::to_string(in_subset.size()) + " for " +
                std::to_string(points.size()) + " points");
  }
  std::vector<pcl::index_t> position_of;
  const pcl::PointCloud<pcl::PointXYZ> flat =
      detail::checkedPositions(points, dimensions, options.alpha_factor, position_of);
  std::vector<char> flat_subset(flat.size(), 0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (in_subset[i]) flat_subset[static_cast<std::size_t>(position_of[i])] = 1;
  }
  MeasureOptions resolved = options;
  resolved.threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  detail::startPhase(options, "local spacing");
  const std::vector<double> spacing = detail::localSpacing(flat, dimensions, resolved.threads);
  return dimensions == 2 ? detail::measureSubset<2>(flat, flat_subset, spacing, resolved)
                         : detail::measureSubset<3>(flat, flat_subset, spacing, resolved);
}

}  // namespace mcws
