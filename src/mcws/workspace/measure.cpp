#include "mcws/workspace/measure.h"

#include <omp.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "mcws/core/decimal.h"
#include "mcws/core/error.h"
#include "mcws/points/unique_positions.h"
#include "mcws/workspace/detail/alpha_triangulation.h"
#include "mcws/workspace/detail/measure_shell.h"
#include "mcws/workspace/detail/measure_steps.h"
#include "mcws/workspace/detail/surface_repair.h"
#include "mcws/workspace/nearest_neighbours.h"

namespace mcws {
namespace detail {

constexpr int kNeighbour = 8;
/// More points outside the others' region than this share: the cloud is too small to estimate
/// the band it misses (a uniform cloud of 100 points in a disk has about 15 %).
constexpr double kLargestMissingShare = 0.5;

std::vector<double> localSpacing(const pcl::PointCloud<pcl::PointXYZ>& cloud, int dimensions,
                                 int threads, const CancelCheck& cancel_check) {
  const double scale =
      dimensions == 2 ? std::sqrt(kNeighbour / M_PI) : std::cbrt(3.0 * kNeighbour / (4.0 * M_PI));
  const std::vector<float> d2 =
      kthNeighbourSquaredDistance(cloud, dimensions, kNeighbour, threads, cancel_check);
  std::vector<double> spacing(d2.size());
  for (std::size_t i = 0; i < d2.size(); ++i) {
    spacing[i] = std::sqrt(static_cast<double>(d2[i])) / scale;
  }
  return spacing;
}

pcl::PointCloud<pcl::PointXYZ> checkedPositions(const pcl::PointCloud<pcl::PointXYZ>& points,
                                                int dimensions, double alpha_factor,
                                                std::vector<pcl::index_t>& position_of) {
  if (dimensions != 2 && dimensions != 3) throw Error("dimensions must be 2 or 3");
  if (!(alpha_factor > 0.0 && std::isfinite(alpha_factor))) {
    std::ostringstream msg;
    msg << "alpha factor " << alpha_factor << " must be a positive number";
    throw Error(msg.str());
  }
  if (points.size() < static_cast<std::size_t>(dimensions + 1)) {
    throw Error("a region needs at least " + std::to_string(dimensions + 1) + " points, got " +
                std::to_string(points.size()));
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || (dimensions == 3 && !std::isfinite(p.z))) {
      throw Error("point " + std::to_string(i) + " has a non-finite coordinate");
    }
  }
  // One position per set of copies (CGAL would merge them anyway), so copies neither shrink the
  // local spacing nor count as points.
  if (dimensions == 3) return uniquePositions(points, position_of);
  pcl::PointCloud<pcl::PointXYZ> projected = points;
  for (auto& p : projected) p.z = 0.0f;
  return uniquePositions(projected, position_of);
}

void startPhase(const MeasureOptions& options, const char* name) {
  if (options.phase) options.phase(name);
  if (options.cancel_check) options.cancel_check();
}

void checkKeptAndMissing(const RegionMeasure& result, int dimensions,
                         const MeasureOptions& options) {
  if (!(result.uncorrected > 0.0)) {
    throw Error(std::string("no ") + (dimensions == 2 ? "triangle" : "tetrahedron") +
                " passes the alpha limit: the points are (nearly) " +
                (dimensions == 2 ? "collinear" : "coplanar") + " or too sparse for alpha " +
                formatNumber(options.alpha_factor));
  }
  if (!options.edge_correction) return;
  if (static_cast<double>(result.outside) / result.points > kLargestMissingShare) {
    throw Error("too few points for the edge correction: " + std::to_string(result.outside) +
                " of " + std::to_string(result.points) + " lie outside the region of the others");
  }
}

namespace {

/// Leave one out by removal (LeaveOneOut::kRemoveAndReinsert): each boundary vertex is removed
/// from the triangulation, its point located among the others, and put back (one thread).
template <int D, typename Delaunay>
std::size_t outsideByRemoval(Delaunay& dt,
                             const std::vector<typename Delaunay::Vertex_handle>& boundary,
                             const std::vector<double>& spacing, double alpha_factor) {
  std::size_t outside = 0;
  for (const auto v : boundary) {
    const typename Delaunay::Point p = v->point();
    const std::uint32_t index = v->info();
    dt.remove(v);
    outside += !inRegion<D>(dt, p, spacing, alpha_factor);
    dt.insert(p)->info() = index;
  }
  return outside;
}

/// The area (D = 2) or volume (D = 3) of the region, on a triangulation built on all threads
/// (3-D with `Concurrency` = CGAL::Parallel_tag, TBB) or on one (CGAL::Sequential_tag, which the
/// remove-and-reinsert leave-one-out needs). CGAL breaks ties between cospherical points by a
/// symbolic perturbation, so the Delaunay triangulation is the same whatever the insertion order
/// and thread count, degenerate input included; what is summed over it does not depend on the
/// order its simplices are listed in.
template <int D, typename Concurrency = CGAL::Sequential_tag>
RegionMeasure measureRegion(const pcl::PointCloud<pcl::PointXYZ>& points,
                            const std::vector<double>& spacing, const MeasureOptions& options) {
  using Delaunay = typename Simplices<D, Concurrency>::Delaunay;
  const double alpha_factor = options.alpha_factor;
  startPhase(options, "triangulation");
  Delaunay dt;
  triangulate<D, Concurrency>(dt, points, {}, options.cancel_check);

  startPhase(options, "alpha test");
  RegionMeasure result;
  result.uncorrected = keepWithinAlpha<D>(dt, points, spacing, alpha_factor, options.cancel_check);
  const auto boundary = boundaryVertices<D>(dt, points.size());
  result.points = result.triangulated = dt.number_of_vertices();
  result.boundary_vertices = boundary.size();
  if (options.edge_correction) {
    startPhase(options, "edge correction");
    // A boundary vertex counts when its point lies outside the region of the others.
    result.outside = options.leave_one_out == LeaveOneOut::kStar
                         ? outsideByStar<D>(dt, boundary, spacing, alpha_factor, options.threads,
                                            nullptr, options.cancel_check)
                         : outsideByRemoval<D>(dt, boundary, spacing, alpha_factor);
  }
  if constexpr (D == 3) {
    if (options.surface) {
      startPhase(options, "surface");
      // last: it changes the kept flags
      result.surface_is_manifold = fillForSurface(dt, options.cancel_check);
      result.surface = keptSurface(dt, points, options.cancel_check);
    }
  }
  return result;
}

}  // namespace
}  // namespace detail

RegionMeasure delaunayMeasure(const pcl::PointCloud<pcl::PointXYZ>& points, int dimensions,
                              double alpha_factor) {
  MeasureOptions options;
  options.alpha_factor = alpha_factor;
  return delaunayMeasure(points, dimensions, options);
}

RegionMeasure delaunayMeasure(const pcl::PointCloud<pcl::PointXYZ>& points, int dimensions,
                              const MeasureOptions& options) {
  std::vector<pcl::index_t> position_of;
  auto flat = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>(
      detail::checkedPositions(points, dimensions, options.alpha_factor, position_of));
  position_of = {};
  detail::startPhase(options, "local spacing");
  MeasureOptions resolved = options;
  resolved.threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  const std::vector<double> spacing =
      detail::localSpacing(*flat, dimensions, resolved.threads, options.cancel_check);
  // CGAL's parallel triangulation runs on TBB's threads: at most as many as OpenMP's (TBB also
  // stops at the core count). The limit holds for the whole process while this call runs.
  const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism,
                                        static_cast<std::size_t>(resolved.threads));
  RegionMeasure result;
  const bool star = options.leave_one_out == LeaveOneOut::kStar;
  if (options.shell && star) {
    if (dimensions == 2) {
      result = detail::measureShell<2>(*flat, spacing, resolved);
    } else if (resolved.threads > 1) {
      result = detail::measureShell<3, CGAL::Parallel_tag>(*flat, spacing, resolved);
    } else {
      result = detail::measureShell<3, CGAL::Sequential_tag>(*flat, spacing, resolved);
    }
  } else if (dimensions == 2) {
    result = detail::measureRegion<2>(*flat, spacing, resolved);
  } else if (resolved.threads > 1 && star) {
    result = detail::measureRegion<3, CGAL::Parallel_tag>(*flat, spacing, resolved);
  } else {
    result = detail::measureRegion<3, CGAL::Sequential_tag>(*flat, spacing, resolved);
  }
  result.alpha_factor = options.alpha_factor;
  detail::checkKeptAndMissing(result, dimensions, options);
  if (!options.edge_correction) {
    result.measure = result.uncorrected;
    return result;
  }
  const double missing = static_cast<double>(result.outside) / result.points;
  result.measure = result.uncorrected / (1.0 - missing);
  return result;
}

}  // namespace mcws
