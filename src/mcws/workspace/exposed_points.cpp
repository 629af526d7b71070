#include "mcws/workspace/exposed_points.h"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/workspace/detail/nearest_point_field.h"
#include "mcws/workspace/detail/radius_classes.h"

namespace mcws {
namespace {

/// Cells of a grid per point in its box at most: the nearest-point transform keeps 4 bytes and
/// the cover bound 1 byte per cell (a uniform ball's grid, at kCellsPerRadius, has about 2).
constexpr double kCellsPerPoint = 16.0;
/// Cells per smallest radius of a grid: finer cells bound the distance from a position to the
/// nearest point more tightly (the test's own slack is about a cell, refined below it where a
/// ball may reach out of the cloud), coarser ones cost less.
constexpr double kCellsPerRadius = 2.0;
/// Fine cells per coarse cell along each axis (the coarse cells prune the exact test).
constexpr std::int64_t kCoarse = 2;
/// Levels of halving of a fine cell in the exact test (a cell whose cover bound reaches the
/// radius is split into 2^D parts, those that may meet the ball split again).
constexpr int kSplitLevels = 3;
using detail::candidatesOf;
using detail::Field;
using detail::Grid;
using detail::kClassRatio;
using detail::kCoverSteps;
using detail::kNone;
using detail::nearestPoints;
using detail::RadiusClasses;
/// Share of the points below which a grid's classes are not proven (they stay exposed).
constexpr double kFewestOnAGrid = 0.02;
/// Share of the points whose radius may lie below the smallest class (they stay exposed): the
/// smallest radius sets the cell edge, and a few unusually close neighbours should not make the
/// grid finer for all.
constexpr double kBelowSmallestClass = 0.01;
/// How many radius classes (ratio detail::kClassRatio) share a grid (their radii span a factor
/// 2.4).
constexpr int kClassesPerGrid = 4;
/// Relative margin on the radii, for the rounding of coordinates and distances.
constexpr double kMargin = 1e-6;

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

/// A class's radius in cells of the grid: how far a ball reaches (rounded up) and how far the
/// cover bounds must stay below (rounded down), and the cover bytes below which a cell is full.
struct ClassTest {
  double ball{0.0};
  double cover{0.0};
  int threshold{0};
  /// A squared distance from a point of `Field::at` below it is below `cover` with the slack
  /// and the rounding (-1 when none is).
  double within{-1.0};
};

/// The gap between position u and the interval [low, low + size] (0 inside).
inline double gapTo(double u, double low, double size) {
  return std::max({low - u, u - low - size, 0.0});
}

/// True when every position of the box [low, low + size]^D (cell units) that the ball of
/// `test.ball` around u reaches is nearer than `test.cover` to one of the points `candidates`
/// (the first `count`); parts whose bound fails are halved up to kSplitLevels times.
template <int D>
bool partsCovered(const Field& field, const std::array<std::uint32_t, 7>& candidates, int count,
                  const std::array<double, 3>& low, double size, const std::array<double, 3>& u,
                  const ClassTest& test, int level) {
  double gap2 = 0.0;
  for (int a = 0; a < D; ++a) gap2 += gapTo(u[a], low[a], size) * gapTo(u[a], low[a], size);
  if (gap2 > test.ball * test.ball) return true;
  // The first point near enough ends it (test.within: the squared bound, rounded down).
  for (int k = 0; k < count; ++k) {
    if (field.farthest2<D>(candidates[k], low, size) < test.within) return true;
  }
  if (level == kSplitLevels) return false;
  const double half = 0.5 * size;
  for (int part = 0; part < (1 << D); ++part) {
    std::array<double, 3> corner = low;
    for (int a = 0; a < D; ++a) corner[a] += ((part >> a) & 1) * half;
    if (!partsCovered<D>(field, candidates, count, corner, half, u, test, level + 1)) return false;
  }
  return true;
}

/// partsCovered() for cell c (at `at`), with the points carried by it and its face neighbours.
template <int D>
bool cellCovered(const Field& field, std::int64_t c, const std::array<std::int64_t, 3>& at,
                 const std::array<double, 3>& u, const ClassTest& test) {
  std::array<std::uint32_t, 7> candidates{};
  const int count = candidatesOf<D>(field, c, at, candidates);
  const std::array<double, 3> low{static_cast<double>(at[0]), static_cast<double>(at[1]),
                                  static_cast<double>(at[2])};
  return partsCovered<D>(field, candidates, count, low, 1.0, u, test, 0);
}

/// The exact test of a point at u (cell units): every cell that the closed ball of `test.ball`
/// around it meets is full or, split (cellCovered()), covered where the ball reaches; the coarse
/// cells whose fine cells are all full (`full`) are passed over whole.
template <int D>
bool provenCovered(const Field& field, const Grid& coarse, const std::vector<std::uint8_t>& full,
                   const std::array<double, 3>& u, const ClassTest& test) {
  const Grid& grid = field.grid;
  std::array<std::int64_t, 3> first{0, 0, 0}, last{0, 0, 0};
  std::array<double, 3> uc{0.0, 0.0, 0.0};
  const double rc = test.ball / kCoarse;
  for (int a = 0; a < D; ++a) {
    // A ball that leaves the grid reaches positions no bound is known for.
    if (std::floor(u[a] - test.ball) < 0.0 || std::floor(u[a] + test.ball) >= grid.n[a]) {
      return false;
    }
    uc[a] = u[a] / kCoarse;
    first[a] = std::max<std::int64_t>(static_cast<std::int64_t>(std::floor(uc[a] - rc)), 0);
    last[a] =
        std::min<std::int64_t>(static_cast<std::int64_t>(std::floor(uc[a] + rc)), coarse.n[a] - 1);
  }
  const auto cs = coarse.stride(), fs = grid.stride();
  for (std::int64_t z = first[2]; z <= last[2]; ++z) {
    const double gz = D == 3 ? gapTo(uc[2], static_cast<double>(z), 1.0) : 0.0;
    for (std::int64_t y = first[1]; y <= last[1]; ++y) {
      const double gy = gapTo(uc[1], static_cast<double>(y), 1.0);
      const double rest = rc * rc - gy * gy - gz * gz;
      if (rest < 0.0) continue;
      const double w = std::sqrt(rest);
      const std::int64_t x0 = std::max(first[0], static_cast<std::int64_t>(std::floor(uc[0] - w)));
      const std::int64_t x1 = std::min(last[0], static_cast<std::int64_t>(std::floor(uc[0] + w)));
      for (std::int64_t x = x0; x <= x1; ++x) {
        if (full[x + y * cs[1] + z * cs[2]]) continue;
        const std::int64_t zs = D == 3 ? kCoarse : 1;
        for (std::int64_t fz = z * zs; fz < std::min(z * zs + zs, grid.n[2]); ++fz)
          for (std::int64_t fy = y * kCoarse; fy < std::min(y * kCoarse + kCoarse, grid.n[1]); ++fy)
            for (std::int64_t fx = x * kCoarse; fx < std::min(x * kCoarse + kCoarse, grid.n[0]);
                 ++fx) {
              const std::int64_t c = fx + fy * fs[1] + fz * fs[2];
              if (field.cover[c] < test.threshold) continue;
              if (!cellCovered<D>(field, c, {fx, fy, fz}, u, test)) return false;
            }
      }
    }
  }
  return true;
}

/// The coarse grid (kCoarse fine cells a side) over the fine one.
template <int D>
Grid coarseOver(const Grid& grid) {
  Grid coarse = grid;
  coarse.cell = grid.cell * kCoarse;
  for (int a = 0; a < D; ++a) coarse.n[a] = (grid.n[a] + kCoarse - 1) / kCoarse;
  return coarse;
}

/// Per coarse cell: 1 when its fine cells are all within the grid and full (cover bytes below
/// `threshold`).
template <int D>
std::vector<std::uint8_t> coarseFull(const Field& field, const Grid& coarse, int threshold,
                                     int threads) {
  const Grid& grid = field.grid;
  std::vector<std::uint8_t> full(coarse.size(), 1);
  const std::int64_t planes = coarse.n[2] * coarse.n[1];
  const std::int64_t zs = D == 3 ? kCoarse : 1;
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t plane = 0; plane < planes; ++plane) {
    const std::int64_t y = plane % coarse.n[1], z = plane / coarse.n[1];
    std::uint8_t* row = full.data() + plane * coarse.n[0];
    if ((y + 1) * kCoarse > grid.n[1] || (z + 1) * zs > grid.n[2]) {
      std::fill(row, row + coarse.n[0], 0);
      continue;
    }
    if (coarse.n[0] * kCoarse > grid.n[0]) row[coarse.n[0] - 1] = 0;
    for (std::int64_t fz = z * zs; fz < z * zs + zs; ++fz)
      for (std::int64_t fy = y * kCoarse; fy < y * kCoarse + kCoarse; ++fy) {
        const std::uint8_t* cover = field.cover.data() + (fy + fz * grid.n[1]) * grid.n[0];
        for (std::int64_t fx = 0; fx < grid.n[0]; ++fx) {
          if (cover[fx] >= threshold) row[fx / kCoarse] = 0;
        }
      }
  }
  return full;
}

/// Marks not exposed the points of class j among `members` (by `class_of`) that no empty ball of
/// radius r touches: first those whose every coarse cell a ball may meet (the element, eroding
/// the coarse full cells) is full, then those the exact test (provenCovered()) proves.
template <int D>
void markCovered(const pcl::PointCloud<pcl::PointXYZ>& cloud, const Field& field, int j, double r,
                 const std::vector<std::uint32_t>& members, const std::vector<int>& class_of,
                 int threads, ExposedPoints& result) {
  const Grid& grid = field.grid;
  ClassTest test;
  test.ball = r * (1.0 + kMargin) / grid.cell;
  test.cover = r * (1.0 - kMargin) / grid.cell;
  test.threshold = static_cast<int>(std::min(std::ceil(test.cover * kCoverSteps), 255.0));
  const double reach = (test.cover - field.slack) / (1.0 + 1e-12);
  if (reach > 0.0) test.within = reach * reach * (1.0 - 1e-12);
  const Grid coarse = coarseOver<D>(grid);
  const std::vector<std::uint8_t> full = coarseFull<D>(field, coarse, test.threshold, threads);
  std::vector<std::uint8_t> covered = full, scratch;
  const Element element = elementFor<D>(test.ball / kCoarse);
  for (int axis = 0; axis < D; ++axis) {
    erodeAlong(coarse, axis, -element.box, element.box, covered, threads);
  }
  for (int k = 0; k < element.cross; ++k) erodeCross<D>(coarse, covered, scratch, threads);
  std::size_t proven = 0;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1024) reduction(+ : proven)
  for (std::int64_t m = 0; m < static_cast<std::int64_t>(members.size()); ++m) {
    const std::uint32_t i = members[m];
    if (class_of[i] != j) continue;
    bool sure = covered[cellOf<D>(coarse, cloud[i])];
    if (!sure) {
      std::array<double, 3> u{0.0, 0.0, 0.0};
      for (int a = 0; a < D; ++a) u[a] = (cloud[i].data[a] - grid.lo[a]) / grid.cell;
      sure = provenCovered<D>(field, coarse, full, u, test);
    }
    if (sure) {
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
    Field field;
    field.grid = gridOver<D>(lo, hi, low / kCellsPerRadius, cap);
    check();
    nearestPoints<D>(cloud, nearby, field, threads);
    for (int j = g * kClassesPerGrid; j < std::min(classes, (g + 1) * kClassesPerGrid); ++j) {
      check();
      markCovered<D>(cloud, field, j, smallest * std::pow(kClassRatio, j), members[g], class_of,
                     threads, result);
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
