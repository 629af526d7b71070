#pragma once
/// \file
/// \brief The grid of exposedPoints() (exposed_points.cpp): per cell a nearby point (a
/// nearest-point transform) and a bound on how far any position of the cell is from the nearest
/// point. Private to mcws_workspace (namespace mcws::detail).

#include <omp.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace mcws::detail {

/// The cover bound's unit: 1/kCoverSteps cell (a byte, rounded up; 255: unbounded).
constexpr double kCoverSteps = 16.0;
/// No point carried (the nearest-point transform).
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

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

/// Lower envelope of the parabolas (t - apex)^2 + height along a line of cells, for the cell
/// centres t + 0.5 (Felzenszwalb and Huttenlocher's distance transform, with apexes anywhere):
/// the parabolas are added in increasing order of apex.
class Envelope {
 public:
  /// Empties it for a line of up to n parabolas.
  void reset(std::int64_t n) {
    if (sites_.size() < static_cast<std::size_t>(n)) sites_.resize(n);
    size_ = 0;
  }
  void add(double apex, double height, std::uint32_t id) {
    const double key = height + apex * apex;
    double from = -std::numeric_limits<double>::infinity();
    while (size_ > 0) {
      const Site& top = sites_[size_ - 1];
      if (apex <= top.apex) {  // same apex (not expected): the lower parabola only
        if (key >= top.key) return;
        --size_;
        continue;
      }
      from = (key - top.key) / (2.0 * (apex - top.apex));
      if (from > top.from) break;
      --size_;
      from = -std::numeric_limits<double>::infinity();
    }
    sites_[size_++] = {apex, key, from, id};
  }
  /// Writes the lowest parabola's id of each of the n cells to out[t] (kNone: none).
  void fill(std::int64_t n, std::uint32_t* out) const {
    if (size_ == 0) {
      std::fill(out, out + n, kNone);
      return;
    }
    std::size_t k = 0;
    for (std::int64_t t = 0; t < n; ++t) {
      const double centre = static_cast<double>(t) + 0.5;
      while (k + 1 < size_ && sites_[k + 1].from <= centre) ++k;
      out[t] = sites_[k].id;
    }
  }

 private:
  struct Site {
    double apex, key, from;  // key: height + apex^2
    std::uint32_t id;
  };
  std::vector<Site> sites_;
  std::size_t size_{0};
};

/// The points of a grid in cell units and, per cell, a nearby point (nearly the nearest to its
/// centre) and a bound on the distance from any position in the cell to the nearest point.
struct Field {
  Grid grid;
  std::vector<std::array<float, 3>> at;  ///< the points, (p - lo) / cell, by line along axis 0
  std::vector<std::uint32_t> nearest;    ///< per cell: a point of `at` (kNone: none carried)
  /// Per cell: max over its positions of the distance to `nearest`, in 1/kCoverSteps cells,
  /// rounded up (255: none or farther).
  std::vector<std::uint8_t> cover;
  double slack{0.0};  ///< bound on the error of a distance computed from `at` [cells]
  /// Squared distance from `at[id]` to the farthest corner of the box [low, low + size]^D.
  template <int D>
  double farthest2(std::uint32_t id, const std::array<double, 3>& low, double size) const {
    double d2 = 0.0;
    for (int a = 0; a < D; ++a) {
      const double d = std::abs(static_cast<double>(at[id][a]) - (low[a] + 0.5 * size));
      d2 += (d + 0.5 * size) * (d + 0.5 * size);
    }
    return d2;
  }
};

/// The points of `points` in grid cell units, sorted by their line of cells along axis 0 (then
/// along it), and where each line starts.
template <int D>
void pointsByLine(const pcl::PointCloud<pcl::PointXYZ>& cloud,
                  const std::vector<std::uint32_t>& points, Field& field,
                  std::vector<std::uint32_t>& start) {
  const Grid& grid = field.grid;
  const std::int64_t lines = static_cast<std::int64_t>(grid.size()) / grid.n[0];
  std::vector<std::uint32_t> line_of(points.size());
  start.assign(lines + 1, 0);
  for (std::size_t j = 0; j < points.size(); ++j) {
    const auto& p = cloud[points[j]];
    line_of[j] =
        static_cast<std::uint32_t>(grid.along(p, 1) + (D == 3 ? grid.along(p, 2) : 0) * grid.n[1]);
    ++start[line_of[j] + 1];
  }
  for (std::int64_t k = 0; k < lines; ++k) start[k + 1] += start[k];
  field.at.assign(points.size(), {0.0f, 0.0f, 0.0f});
  std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
  for (std::size_t j = 0; j < points.size(); ++j) {
    auto& u = field.at[next[line_of[j]]++];
    for (int a = 0; a < D; ++a) {
      u[a] = static_cast<float>((cloud[points[j]].data[a] - grid.lo[a]) / grid.cell);
    }
  }
  for (std::int64_t k = 0; k < lines; ++k) {
    std::sort(field.at.begin() + start[k], field.at.begin() + start[k + 1],
              [](const auto& a, const auto& b) { return a[0] < b[0]; });
  }
}

/// One pass of the nearest-point transform along `axis` (1 or 2): each cell takes, of the
/// points its line's cells carry, the one nearest to its centre. The lines are taken kTile at a
/// time, side by side in memory, through a buffer (a line alone would touch a page per cell).
template <int D>
void carryAlong(Field& field, int axis, int threads) {
  constexpr std::int64_t kTile = 16;
  const Grid& grid = field.grid;
  const auto stride = grid.stride();
  const std::int64_t n = grid.n[axis], step = stride[axis];
  const std::int64_t blocks = static_cast<std::int64_t>(grid.size()) / (n * step);
  const std::int64_t per_block = (step + kTile - 1) / kTile;
#pragma omp parallel num_threads(threads)
  {
    Envelope envelope;
    std::vector<std::uint32_t> in(kTile * n), out(kTile * n);
#pragma omp for schedule(static)
    for (std::int64_t tile = 0; tile < blocks * per_block; ++tile) {
      const std::int64_t offset = (tile % per_block) * kTile;
      const std::int64_t width = std::min(kTile, step - offset);
      const std::int64_t base = offset + (tile / per_block) * step * n;
      for (std::int64_t t = 0; t < n; ++t) {
        const std::uint32_t* from = field.nearest.data() + base + t * step;
        for (std::int64_t l = 0; l < width; ++l) in[l * n + t] = from[l];
      }
      for (std::int64_t l = 0; l < width; ++l) {
        const std::int64_t first = base + l;
        std::array<double, 3> centre{0.0, 0.0, 0.0};
        for (int a = 0; a < D; ++a) {
          centre[a] = static_cast<double>((first / stride[a]) % grid.n[a]) + 0.5;
        }
        envelope.reset(n);
        for (std::int64_t t = 0; t < n; ++t) {
          const std::uint32_t id = in[l * n + t];
          if (id == kNone) continue;
          const auto& u = field.at[id];
          double height = 0.0;
          for (int a = 0; a < D; ++a) {
            if (a != axis) height += (centre[a] - u[a]) * (centre[a] - u[a]);
          }
          envelope.add(u[axis], height, id);
        }
        envelope.fill(n, out.data() + l * n);
      }
      for (std::int64_t t = 0; t < n; ++t) {
        std::uint32_t* to = field.nearest.data() + base + t * step;
        for (std::int64_t l = 0; l < width; ++l) to[l] = out[l * n + t];
      }
    }
  }
}

/// The points carried by cell c (at `at`) and by its face neighbours (none repeated in a row).
/// \return how many (at most 2 D + 1).
template <int D>
int candidatesOf(const Field& field, std::int64_t c, const std::array<std::int64_t, 3>& at,
                 std::array<std::uint32_t, 7>& candidates) {
  int count = 0;
  const auto stride = field.grid.stride();
  const auto take = [&](std::int64_t cell) {
    const std::uint32_t id = field.nearest[cell];
    if (id != kNone && (count == 0 || candidates[count - 1] != id)) candidates[count++] = id;
  };
  take(c);
  for (int a = 0; a < D; ++a) {
    if (at[a] > 0) take(c - stride[a]);
    if (at[a] + 1 < field.grid.n[a]) take(c + stride[a]);
  }
  return count;
}

/// The nearest-point transform of `field.at` on its grid: per cell a point nearly the nearest
/// to its centre (exact along axis 0, then one carried point per cell along the others; which
/// point is carried does not matter to the bound, only how far it is), then the cover bytes.
template <int D>
void nearestPoints(const pcl::PointCloud<pcl::PointXYZ>& cloud,
                   const std::vector<std::uint32_t>& points, Field& field, int threads) {
  const Grid& grid = field.grid;
  std::vector<std::uint32_t> start;
  pointsByLine<D>(cloud, points, field, start);
  field.nearest.assign(grid.size(), kNone);
  // The lines along axis 0 from the points of each (exact along it).
  {
    const std::int64_t n = grid.n[0], lines = static_cast<std::int64_t>(grid.size()) / n;
#pragma omp parallel num_threads(threads)
    {
      Envelope envelope;
#pragma omp for schedule(static)
      for (std::int64_t line = 0; line < lines; ++line) {
        const double y = static_cast<double>(line % grid.n[1]) + 0.5;
        const double z = static_cast<double>(line / grid.n[1]) + 0.5;
        envelope.reset(std::max<std::int64_t>(n, start[line + 1] - start[line]));
        for (std::uint32_t id = start[line]; id < start[line + 1]; ++id) {
          const auto& u = field.at[id];
          const double height = (y - u[1]) * (y - u[1]) + (D == 3 ? (z - u[2]) * (z - u[2]) : 0.0);
          envelope.add(u[0], height, id);
        }
        envelope.fill(n, field.nearest.data() + line * n);
      }
    }
  }
  for (int axis = 1; axis < D; ++axis) carryAlong<D>(field, axis, threads);
  // `at` rounds (p - lo) / cell to float: at most (n + 1) 2^-24 cells off per axis.
  const double largest = static_cast<double>(*std::max_element(grid.n.begin(), grid.n.end()));
  field.slack = 2.0 * std::sqrt(static_cast<double>(D)) * (largest + 1.0) * std::ldexp(1.0, -24);
  field.cover.assign(grid.size(), 255);
  const std::int64_t planes = grid.n[2] * grid.n[1];
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t plane = 0; plane < planes; ++plane) {
    const std::int64_t y = plane % grid.n[1], z = plane / grid.n[1];
    const std::array<double, 3> low{0.0, static_cast<double>(y), static_cast<double>(z)};
    for (std::int64_t x = 0; x < grid.n[0]; ++x) {
      const std::int64_t c = x + plane * grid.n[0];
      if (field.nearest[c] == kNone) continue;
      const std::array<double, 3> corner{static_cast<double>(x), low[1], low[2]};
      const double best = field.farthest2<D>(field.nearest[c], corner, 1.0);
      const double bound = (std::sqrt(best) + field.slack) * kCoverSteps;
      field.cover[c] = static_cast<std::uint8_t>(std::min(std::ceil(bound * (1.0 + 1e-12)), 255.0));
    }
  }
}

}  // namespace mcws::detail
