#include "mcws/workspace/exposed_points.h"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/workspace/detail/radius_classes.h"

namespace mcws {
namespace {

/// Cells of a grid per point in its box at most (a uniform ball's grid has about 1.5; a cloud
/// that fills little of its bounding box gets coarser cells, and more of its points stay exposed).
constexpr double kCellsPerPoint = 4.0;
/// Share of the points whose radius may lie below the smallest class (they stay exposed): the
/// smallest radius sets the cell edge, and a few unusually close neighbours should not make the
/// grid finer for all.
constexpr double kBelowSmallestClass = 0.01;
/// How many radius classes (ratio detail::kClassRatio) share a grid (their radii span a factor
/// 2.4).
constexpr int kClassesPerGrid = 4;
using detail::kClassRatio;
using detail::RadiusClasses;
/// Share of the points below which a grid's classes are not proven (they stay exposed).
constexpr double kFewestOnAGrid = 0.02;
/// Cells per smallest radius: finer cells bound the distance to the nearest point more tightly,
/// but then a point's block of cells (kBlock) reaches less far; at 2 a uniform cloud's cell holds
/// about 0.9 points.
constexpr double kCellsPerRadius = 2.0;
/// Relative margin on the cover radii, for the rounding of coordinates and distances.
constexpr double kMargin = 1e-6;

/// The grid: cells per axis (the third is 1 in 2-D), the cell edge and the low corner.
struct Grid {
  std::array<std::int64_t, 3> n{1, 1, 1};
  double cell{0.0};
  std::array<double, 3> lo{0.0, 0.0, 0.0};
  std::size_t size() const { return static_cast<std::size_t>(n[0] * n[1] * n[2]); }
  std::array<std::int64_t, 3> stride() const { return {1, n[0], n[0] * n[1]}; }
  /// Index along axis `a` of the cell that holds p (clamped to the grid).
  std::int64_t along(const pcl::PointXYZ& p, int a) const {
    return std::clamp<std::int64_t>(
        static_cast<std::int64_t>(std::floor((p.data[a] - lo[a]) / cell)), 0, n[a] - 1);
  }
};

/// Replaces every cell by 1 when every cell of its line along `axis` within [a, b] of it is
/// non-zero and within the grid, else by 0 (an erosion by a segment). Lines run on all threads.
void erodeAlong(const Grid& grid, int axis, std::int64_t a, std::int64_t b,
                std::vector<std::uint8_t>& values, int threads) {
  const std::int64_t n = grid.n[axis], step = grid.stride()[axis];
  const std::int64_t lines = static_cast<std::int64_t>(grid.size()) / n;
#pragma omp parallel num_threads(threads)
  {
    std::vector<std::int32_t> zeros(n + 1);  // zeros before each cell of the line
#pragma omp for schedule(static)
    for (std::int64_t line = 0; line < lines; ++line) {
      // The line's first cell: `line` enumerates the other axes' indices.
      const std::int64_t first = line % step + (line / step) * step * n;
      zeros[0] = 0;
      for (std::int64_t t = 0; t < n; ++t)
        zeros[t + 1] = zeros[t] + (values[first + t * step] == 0);
      for (std::int64_t t = 0; t < n; ++t) {
        const std::int64_t from = t + a, to = t + b;  // inclusive
        values[first + t * step] = from >= 0 && to < n && zeros[to + 1] == zeros[from];
      }
    }
  }
}

/// Erodes by the cross of 2 D + 1 cells (a cell and its face neighbours): a cell stays non-zero
/// when it and its face neighbours, all within the grid, are. `scratch` is working memory.
template <int D>
void erodeCross(const Grid& grid, std::vector<std::uint8_t>& values,
                std::vector<std::uint8_t>& scratch, int threads) {
  scratch = values;
  const auto stride = grid.stride();
  const std::int64_t planes = grid.n[2] * grid.n[1];
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t plane = 0; plane < planes; ++plane) {
    const std::int64_t y = plane % grid.n[1], z = plane / grid.n[1];
    for (std::int64_t x = 0; x < grid.n[0]; ++x) {
      const std::int64_t c = x * stride[0] + y * stride[1] + z * stride[2];
      if (!scratch[c]) continue;
      const std::array<std::int64_t, 3> at{x, y, z};
      bool full = true;
      for (int a = 0; a < D && full; ++a) {
        full =
            at[a] > 0 && at[a] + 1 < grid.n[a] && scratch[c - stride[a]] && scratch[c + stride[a]];
      }
      values[c] = full;
    }
  }
}

/// The cells a point's test must find full, as offsets from its own cell: a box of half-width
/// `box` cells followed by `cross` erosions by the cross (erodeCross), which together reach
/// every cell that may meet a ball of radius rho cells around any position in the own cell and
/// overreach a box of the ball's width in the diagonal directions by far less (the box alone
/// reaches sqrt(D) times as far there).
struct Element {
  std::int64_t box{0};
  int cross{0};
};

template <int D>
Element elementFor(double rho) {
  // Cell t + o may meet the ball when the gap between the cells, max(|o_i| - 1, 0) per axis, is
  // shorter than rho: u below. A box of half-width A + 1 then a cross of B cover o when the
  // part of u beyond A, summed over the axes, is at most B; of the (A, B) that cover every u,
  // the one with the fewest offsets.
  const auto top = static_cast<std::int64_t>(std::ceil(rho));
  Element best;
  double best_size = std::numeric_limits<double>::infinity();
  for (std::int64_t box = 0; box <= top; ++box) {
    std::int64_t cross = 0;
    const std::int64_t uz = D == 3 ? top : 0;
    for (std::int64_t u0 = 0; u0 <= top; ++u0)
      for (std::int64_t u1 = 0; u1 <= top; ++u1)
        for (std::int64_t u2 = 0; u2 <= uz; ++u2) {
          if (static_cast<double>(u0 * u0 + u1 * u1 + u2 * u2) >= rho * rho) continue;
          cross = std::max(cross, std::max<std::int64_t>(u0 - box, 0) +
                                      std::max<std::int64_t>(u1 - box, 0) +
                                      std::max<std::int64_t>(u2 - box, 0));
        }
    // The offsets o of the box of half-width box + 1 grown by a cross of `cross`.
    const std::int64_t reach = box + 1 + cross, oz = D == 3 ? reach : 0;
    double size = 0.0;
    for (std::int64_t o0 = -reach; o0 <= reach; ++o0)
      for (std::int64_t o1 = -reach; o1 <= reach; ++o1)
        for (std::int64_t o2 = -oz; o2 <= oz; ++o2) {
          const std::int64_t beyond = std::max<std::int64_t>(std::abs(o0) - box - 1, 0) +
                                      std::max<std::int64_t>(std::abs(o1) - box - 1, 0) +
                                      std::max<std::int64_t>(std::abs(o2) - box - 1, 0);
          size += beyond <= cross;
        }
    if (size < best_size) {
      best_size = size;
      best = {box + 1, static_cast<int>(cross)};
    }
  }
  return best;
}

/// The grid of cells of edge `cell` over the cloud's bounding box [lo, hi], coarsened until it
/// has at most `cap` cells.
template <int D>
Grid gridOver(const std::array<double, 3>& lo, const std::array<double, 3>& hi, double cell,
              double cap) {
  Grid grid;
  grid.lo = lo;
  grid.cell = cell;
  for (;;) {
    double cells = 1.0;
    for (int a = 0; a < D; ++a) cells *= std::floor((hi[a] - lo[a]) / grid.cell) + 1.0;
    if (cells <= cap) break;
    grid.cell *= std::max(std::pow(cells / cap, 1.0 / D), 1.0 + 1e-3);
  }
  for (int a = 0; a < D; ++a) {
    grid.n[a] = static_cast<std::int64_t>(std::floor((hi[a] - lo[a]) / grid.cell)) + 1;
  }
  return grid;
}

/// Index of the cell that holds position p (clamped to the grid).
template <int D>
std::int64_t cellOf(const Grid& grid, const pcl::PointXYZ& p) {
  const auto stride = grid.stride();
  std::int64_t index = 0;
  for (int a = 0; a < D; ++a) index += grid.along(p, a) * stride[a];
  return index;
}

/// Half-width of the block of cells each point bounds (2-D: 5 x 5; 3-D: 3 x 3 x 3): a block of a
/// uniform cloud holds about 20 points, so it is empty once in millions.
template <int D>
constexpr int kBlock = D == 2 ? 2 : 1;

/// For every cell, a bound on how far its positions may be from the nearest point, squared: the
/// least, over the points in its block of cells (kBlock), of the squared distance from the point
/// to the cell's farthest corner (infinite where the block is empty). Rounded up, so a bound
/// still.
template <int D>
std::vector<float> coverRadius(const pcl::PointCloud<pcl::PointXYZ>& cloud,
                               const std::vector<std::uint32_t>& points, const Grid& grid,
                               int threads) {
  constexpr int m = kBlock<D>;
  std::vector<float> cover(grid.size(), std::numeric_limits<float>::infinity());
  const auto stride = grid.stride();
  auto bound = [&](const pcl::PointXYZ& p) {
    std::array<std::int64_t, 3> k{0, 0, 0};
    for (int a = 0; a < D; ++a) k[a] = grid.along(p, a);
    // Per axis and neighbour offset: the squared distance to the cell's farther face.
    std::array<std::array<double, 2 * m + 1>, 3> far2{};
    for (int a = 0; a < D; ++a) {
      for (int o = -m; o <= m; ++o) {
        const double low = grid.lo[a] + static_cast<double>(k[a] + o) * grid.cell;
        const double d = std::max(std::abs(p.data[a] - low), std::abs(low + grid.cell - p.data[a]));
        far2[a][o + m] = d * d;
      }
    }
    constexpr int mz = D == 3 ? m : 0;
    // Away from the grid's faces no cell of the block needs a check (the loops then unroll).
    bool inner = true;
    for (int a = 0; a < D; ++a) inner = inner && k[a] >= m && k[a] + m < grid.n[a];
    const auto update = [&](auto checked) {
      for (int dz = -mz; dz <= mz; ++dz) {
        if (checked && (k[2] + dz < 0 || k[2] + dz >= grid.n[2])) continue;
        for (int dy = -m; dy <= m; ++dy) {
          if (checked && (k[1] + dy < 0 || k[1] + dy >= grid.n[1])) continue;
          for (int dx = -m; dx <= m; ++dx) {
            if (checked && (k[0] + dx < 0 || k[0] + dx >= grid.n[0])) continue;
            const double d2 = far2[0][dx + m] + far2[1][dy + m] + (D == 3 ? far2[2][dz + m] : 0.0);
            const auto b = static_cast<float>(d2 * (1.0 + 2.0 * kMargin));
            float& c =
                cover[(k[0] + dx) * stride[0] + (k[1] + dy) * stride[1] + (k[2] + dz) * stride[2]];
            c = std::min(c, b);
          }
        }
      }
    };
    if (inner) {
      update(std::false_type{});
    } else {
      update(std::true_type{});
    }
  };
  // The points by slab of cells along the last axis, slabs at least 2 m + 1 cells thick: a point
  // changes cells of its own slab and the two next to it, so the even slabs run side by side,
  // then the odd ones (a minimum does not depend on the order it is taken in).
  const int axis = D - 1;
  const std::int64_t thick =
      std::max<std::int64_t>(2 * m + 1, (grid.n[axis] + 4 * threads - 1) / (4 * threads));
  const std::int64_t slabs = (grid.n[axis] + thick - 1) / thick;
  std::vector<std::uint32_t> start(slabs + 1, 0), order(points.size());
  std::vector<std::uint32_t> slab_of(points.size());
  for (std::size_t j = 0; j < points.size(); ++j) {
    slab_of[j] = static_cast<std::uint32_t>(grid.along(cloud[points[j]], axis) / thick);
    ++start[slab_of[j] + 1];
  }
  for (std::int64_t k = 0; k < slabs; ++k) start[k + 1] += start[k];
  {
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for (std::size_t j = 0; j < points.size(); ++j) order[next[slab_of[j]]++] = points[j];
  }
  for (const std::int64_t parity : {0, 1}) {
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
    for (std::int64_t k = parity; k < slabs; k += 2) {
      for (std::uint32_t j = start[k]; j < start[k + 1]; ++j) bound(cloud[order[j]]);
    }
  }
  return cover;
}

/// The radius of the smallest class: of the finite positive radii, the one with a share
/// kBelowSmallestClass of them below it; none when no radius is finite and positive.
std::optional<double> smallestClassRadius(const std::vector<double>& radius) {
  std::vector<double> finite;
  finite.reserve(radius.size());
  for (const double r : radius) {
    if (r > 0.0 && std::isfinite(r)) finite.push_back(r);
  }
  if (finite.empty()) return std::nullopt;
  const std::size_t rank = static_cast<std::size_t>(kBelowSmallestClass * (finite.size() - 1));
  std::nth_element(finite.begin(), finite.begin() + rank, finite.end());
  return finite[rank];
}

/// The box that spans the balls of radius `high` around the points `members` (lo, hi; the third
/// axis 0 in 2-D).
template <int D>
std::pair<std::array<double, 3>, std::array<double, 3>> spanOfBalls(
    const pcl::PointCloud<pcl::PointXYZ>& cloud, const std::vector<std::uint32_t>& members,
    double high) {
  std::array<double, 3> lo{0.0, 0.0, 0.0}, hi{0.0, 0.0, 0.0};
  for (int a = 0; a < D; ++a) {
    lo[a] = std::numeric_limits<double>::infinity();
    hi[a] = -lo[a];
  }
  for (const std::uint32_t i : members) {
    for (int a = 0; a < D; ++a) {
      lo[a] = std::min<double>(lo[a], cloud[i].data[a] - high);
      hi[a] = std::max<double>(hi[a], cloud[i].data[a] + high);
    }
  }
  return {lo, hi};
}

/// The points of the cloud in the box [lo, hi], in index order.
template <int D>
std::vector<std::uint32_t> pointsInBox(const pcl::PointCloud<pcl::PointXYZ>& cloud,
                                       const std::array<double, 3>& lo,
                                       const std::array<double, 3>& hi) {
  std::vector<std::uint32_t> nearby;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    bool in = true;
    for (int a = 0; a < D; ++a) in = in && cloud[i].data[a] >= lo[a] && cloud[i].data[a] <= hi[a];
    if (in) nearby.push_back(static_cast<std::uint32_t>(i));
  }
  return nearby;
}

/// Marks not exposed the points of class j among `members` (by `class_of`) that a ball of radius r
/// around them cannot reach out of the cloud: every cell of `grid` that may meet that ball is full
/// (its cover radius, `cover`, below r).
template <int D>
void markCovered(const pcl::PointCloud<pcl::PointXYZ>& cloud, const Grid& grid,
                 const std::vector<float>& cover, int j, double r,
                 const std::vector<std::uint32_t>& members, const std::vector<int>& class_of,
                 int threads, ExposedPoints& result) {
  // A cell is full when a ball of radius r centred anywhere in it holds a point: its cover
  // radius is below r (that point is not the one the ball's sphere passes through, at r).
  const auto r2 = static_cast<float>(r * r);
  std::vector<std::uint8_t> covered(grid.size()), scratch;
  for (std::size_t c = 0; c < covered.size(); ++c) covered[c] = cover[c] < r2;
  // A point is covered when every cell that may meet the ball of radius r around it is full.
  const Element element = elementFor<D>(r / grid.cell);
  for (int axis = 0; axis < D; ++axis) {
    erodeAlong(grid, axis, -element.box, element.box, covered, threads);
  }
  for (int k = 0; k < element.cross; ++k) erodeCross<D>(grid, covered, scratch, threads);
  std::size_t proven = 0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : proven)
  for (std::int64_t m = 0; m < static_cast<std::int64_t>(members.size()); ++m) {
    const std::uint32_t i = members[m];
    if (class_of[i] == j && covered[cellOf<D>(grid, cloud[i])]) {
      result.exposed[i] = 0;
      ++proven;
    }
  }
  result.count -= proven;
}

template <int D>
ExposedPoints exposed(const pcl::PointCloud<pcl::PointXYZ>& cloud,
                      const std::vector<double>& radius, int threads,
                      const CancelCheck& cancel_check) {
  const auto check = [&] {
    if (cancel_check) cancel_check();
  };
  const std::size_t points = cloud.size();
  ExposedPoints result;
  result.exposed.assign(points, 1);
  result.count = points;
  const std::optional<double> smallest_class = smallestClassRadius(radius);
  if (!smallest_class || points < 2) return result;
  const double smallest = *smallest_class;
  // Radius classes r_j = r_0 1.25^j from the smallest radius but 1 %, kClassesPerGrid to a
  // grid: a grid's cells are half its smallest class's radius (a cloud's density may vary by
  // orders of magnitude: refined clouds).
  std::vector<int> class_of(points, -1);
  double largest = smallest;
  for (const double r : radius) {
    if (std::isfinite(r)) largest = std::max(largest, r);
  }
  const RadiusClasses class_for(smallest, largest);
  int classes = 0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(max : classes)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(points); ++i) {
    const double r = radius[i];
    if (!(r >= smallest && std::isfinite(r))) continue;
    class_of[i] = class_for(r);
    classes = std::max(classes, class_of[i] + 1);
  }
  const int grids = (classes + kClassesPerGrid - 1) / kClassesPerGrid;
  std::vector<std::vector<std::uint32_t>> members(grids);
  for (std::size_t i = 0; i < points; ++i) {
    if (class_of[i] >= 0)
      members[class_of[i] / kClassesPerGrid].push_back(static_cast<std::uint32_t>(i));
  }
  for (int g = 0; g < grids; ++g) {
    // A grid whose points are a few scattered ones (the edge's, in a uniform cloud) is not worth
    // its pass over the cloud: they stay exposed.
    if (members[g].size() < kFewestOnAGrid * static_cast<double>(points)) continue;
    check();
    const double low = smallest * std::pow(kClassRatio, g * kClassesPerGrid);
    const double high = low * std::pow(kClassRatio, kClassesPerGrid);
    // The grid spans the members' balls; every point in it bounds the cover radii.
    const auto [lo, hi] = spanOfBalls<D>(cloud, members[g], high);
    const std::vector<std::uint32_t> nearby = pointsInBox<D>(cloud, lo, hi);
    const double cap = std::max(kCellsPerPoint * static_cast<double>(nearby.size()), 4096.0);
    const Grid grid = gridOver<D>(lo, hi, low / kCellsPerRadius, cap);
    check();
    const std::vector<float> cover = coverRadius<D>(cloud, nearby, grid, threads);
    for (int j = g * kClassesPerGrid; j < std::min(classes, (g + 1) * kClassesPerGrid); ++j) {
      check();
      markCovered<D>(cloud, grid, cover, j, smallest * std::pow(kClassRatio, j), members[g],
                     class_of, threads, result);
    }
  }
  return result;
}

}  // namespace

ExposedPoints exposedPoints(const pcl::PointCloud<pcl::PointXYZ>& cloud, int dimensions,
                            const std::vector<double>& radius, int threads,
                            const CancelCheck& cancel_check) {
  if (dimensions != 2 && dimensions != 3) {
    throw Error("dimensions must be 2 or 3, got " + std::to_string(dimensions));
  }
  if (radius.size() != cloud.size()) {
    throw Error("exposedPoints: " + std::to_string(radius.size()) + " radii for " +
                std::to_string(cloud.size()) + " points");
  }
  if (threads <= 0) threads = omp_get_max_threads();
  return dimensions == 2 ? exposed<2>(cloud, radius, threads, cancel_check)
                         : exposed<3>(cloud, radius, threads, cancel_check);
}

}  // namespace mcws
