#include "mcws/search/cell_grid.h"

#include "mcws/search/cell_kernels.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace mcws {
double cellGridEdge(const Eigen::Vector3d& extent, int dimensions, double cell,
                    std::size_t points) {
  const double max_cells = 4.0 * static_cast<double>(points) + 16.0;
  for (;;) {
    double cells = 1.0;
    for (int k = 0; k < dimensions; ++k) cells *= std::floor(extent[k] / cell) + 1.0;
    if (cells <= max_cells) return cell;
    cell *= std::max(1.01, std::pow(cells / max_cells, 1.0 / dimensions));
  }
}

CellGrid::CellGrid(const pcl::PointCloud<pcl::PointXYZ>& cloud, int dimensions, double cell,
                   int threads)
    : dimensions_(dimensions), cell_(cell) {
  const auto n = static_cast<std::int64_t>(cloud.size());
  Eigen::Vector3d min = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector3d max = -min;
#pragma omp parallel num_threads(threads)
  {
    // Each thread's box, then their union: the same box in any order.
    // (from the constants, not min and max: another thread may already be writing those)
    Eigen::Vector3d own_min = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
    Eigen::Vector3d own_max = -own_min;
#pragma omp for schedule(static) nowait
    for (std::int64_t i = 0; i < n; ++i) {
      own_min = own_min.cwiseMin(cloud[i].getVector3fMap().cast<double>());
      own_max = own_max.cwiseMax(cloud[i].getVector3fMap().cast<double>());
    }
#pragma omp critical
    {
      min = min.cwiseMin(own_min);
      max = max.cwiseMax(own_max);
    }
  }
  origin_ = n > 0 ? min : Eigen::Vector3d::Zero();
  const Eigen::Vector3d extent = n > 0 ? Eigen::Vector3d(max - min) : Eigen::Vector3d::Zero();
  const double largest = extent.head(dimensions).maxCoeff();
  if (!(cell_ > 0.0) || !std::isfinite(cell_)) cell_ = largest > 0.0 ? largest : 1.0;
  cell_ = cellGridEdge(extent, dimensions, cell_, static_cast<std::size_t>(n));
  inverse_cell_ = 1.0 / cell_;
  std::int64_t total = 1;
  for (int k = 0; k < dimensions; ++k) {
    counts_[k] = static_cast<std::int64_t>(std::floor(extent[k] / cell_)) + 1;
    total *= counts_[k];
  }

  // Counting sort of the points by cell.
  std::vector<std::uint32_t> cell_of(static_cast<std::size_t>(n));
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    std::int64_t c = 0;
    for (int k = dimensions - 1; k >= 0; --k) c = c * counts_[k] + cellOf(cloud[i], k);
    cell_of[i] = static_cast<std::uint32_t>(c);
  }
  start_.assign(static_cast<std::size_t>(total) + 1, 0);
  for (const std::uint32_t c : cell_of) ++start_[c + 1];
  for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
  // Padded (zeros) for rowDistances(), which may read past the last row.
  x_.resize(cell_of.size() + detail::kKernelSlack);
  y_.resize(cell_of.size() + detail::kKernelSlack);
  z_.resize(cell_of.size() + detail::kKernelSlack);
  index_.resize(cell_of.size());
  std::vector<std::uint32_t> next(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < cell_of.size(); ++i) {
    const std::uint32_t slot = next[cell_of[i]]++;
    x_[slot] = cloud[i].x;
    y_[slot] = cloud[i].y;
    z_[slot] = dimensions == 3 ? cloud[i].z : 0.0f;
    index_[slot] = static_cast<pcl::index_t>(i);
  }
}

std::int64_t CellGrid::cellOf(const pcl::PointXYZ& p, int axis) const {
  const double c = std::floor((static_cast<double>(p.data[axis]) - origin_[axis]) / cell_);
  return std::clamp<std::int64_t>(static_cast<std::int64_t>(std::max(c, -1.0)), 0,
                                  counts_[axis] - 1);
}

std::size_t CellGrid::population(const pcl::PointXYZ& p) const {
  std::int64_t c = 0;
  for (int k = dimensions_ - 1; k >= 0; --k) c = c * counts_[k] + cellOf(p, k);
  return start_[c + 1] - start_[c];
}

namespace {

/// The candidates a k-nearest search keeps for the radius search after it: those with d^2 below
/// this many times the previous point's k-th d^2. An adaptive radius of s d_k (s = 2: 4 d_k^2)
/// then lies within them unless d_k^2 doubled from the previous point (which happens near the
/// boundary, where neighbours in cell order lie at other depths; filtering a longer list of near
/// ones costs less than a pass over every candidate).
constexpr float kNearHint = 8.0f;
/// The k-th smallest is first selected among the candidates with d^2 below this many times the
/// previous answer, then below twice it, then among all: selecting among few is most of a
/// k-nearest search's time.
constexpr float kFirstHint = 1.3f;

}  // namespace

void CellGrid::collect(const pcl::PointXYZ& p, double reach, float near_bound,
                       Candidates& out) const {
  out.size = 0;
  out.near_size = 0;
  out.near_bound = near_bound;
  // The ball, widened for rounding, against the cells' extents [origin + c cell, + cell).
  // The margin also covers multiplying by 1 / cell where the points' cells were found dividing
  // by cell (relative errors of 1e-16 on at most a few million cells).
  const double r = reach * (1.0 + 1e-6) + cell_ * 1e-6;
  const Eigen::Vector3d q(p.x, p.y, dimensions_ == 3 ? p.z : 0.0f);
  const double inverse = inverse_cell_;
  const double last[3] = {static_cast<double>(counts_[0] - 1), static_cast<double>(counts_[1] - 1),
                          static_cast<double>(counts_[2] - 1)};
  auto cellAt = [&](double v, int axis) {
    // Clamped to [0, last cell] in double (minsd, maxsd: no branches), then truncated, which is
    // floor at and above 0: the same cell without std::floor, which the x86-64 baseline (no
    // SSE4.1) computes in a dozen instructions.
    const double c = std::min(std::max((v - origin_[axis]) * inverse, 0.0), last[axis]);
    return static_cast<std::int64_t>(c);
  };
  auto gapTo = [&](std::int64_t c, int axis) {  // distance from q to cell c's slab
    const double lo = origin_[axis] + c * cell_, hi = lo + cell_;
    // (without branches; only its square is used, so a -0 is as good as 0)
    return std::max(std::max(lo - q[axis], q[axis] - hi), 0.0);
  };
  std::int64_t lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (int k = 0; k < dimensions_; ++k) {
    lo[k] = cellAt(q[k] - r, k);
    hi[k] = cellAt(q[k] + r, k);
  }
  // The rows of cells that meet the ball, then their points in one pass.
  const auto most = static_cast<std::size_t>((hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1));
  if (out.rows.size() < most) out.rows.resize(2 * most);
  detail::RowSpan* rows = out.rows.data();
  std::size_t row_count = 0, total = 0;
  for (std::int64_t cz = lo[2]; cz <= hi[2]; ++cz) {
    const double gz = dimensions_ == 3 ? gapTo(cz, 2) : 0.0;
    const double slab = r * r - gz * gz;
    for (std::int64_t cy = lo[1]; cy <= hi[1]; ++cy) {
      const double gy = gapTo(cy, 1);
      const double left = slab - gy * gy;
      if (left < 0.0) continue;  // this row of cells misses the ball
      const double w = std::sqrt(left);
      const std::int64_t x0 = cellAt(q.x() - w, 0), x1 = cellAt(q.x() + w, 0);
      const std::int64_t row = (cz * counts_[1] + cy) * counts_[0];
      const std::uint32_t begin = start_[row + x0], end = start_[row + x1 + 1];
      total += end - begin;
      rows[row_count].begin = begin;
      rows[row_count].end = end;
      ++row_count;
    }
  }
  // Room for the rows and the entries the kernel may write past them.
  if (out.d2.size() < total + detail::kKernelSlack) {
    const std::size_t room = 2 * (total + detail::kKernelSlack);
    out.d2.resize(room);
    out.slot.resize(room);
    out.near_d2.resize(room);
    out.near_slot.resize(room);
  }
  out.size = total;
  // In 2-D, z is 0 - 0 and adds nothing to the squared distances.
  const float px = p.x, py = p.y, pz = dimensions_ == 3 ? p.z : 0.0f;
  out.near_size = detail::rowDistances(x_.data(), y_.data(), z_.data(), rows, row_count, px, py, pz,
                                       near_bound, out.d2.data(), out.slot.data(),
                                       out.near_d2.data(), out.near_slot.data());
}

bool CellGridSearch::gather(pcl::index_t i, double reach, float near_bound) {
  if (reach > max_reach_) return false;
  if (point_ != i || reach_ < reach) {
    grid_.collect(cloud_[i], reach, near_bound, candidates_);
    point_ = i;
    reach_ = reach;
  } else if (candidates_.near_bound < near_bound) {
    // The candidates kept from an earlier search of point i, their near ones anew.
    CellGrid::Candidates& c = candidates_;
    std::size_t m = 0;
    for (std::size_t k = 0; k < c.size; ++k) {
      c.near_d2[m] = c.d2[k];
      c.near_slot[m] = c.slot[k];
      m += c.d2[k] < near_bound;
    }
    c.near_size = m;
    c.near_bound = near_bound;
  }
  return true;
}

std::optional<float> CellGridSearch::kthDistance2(pcl::index_t i, int count,
                                                  std::vector<Neighbour>* nearest) {
  double reach = std::min(std::max(first_reach_, grid_.cellSize()), max_reach_);
  for (;; reach = std::min(2 * reach, max_reach_)) {
    // Every point whose float distance is below `limit` lies within reach, so it is a
    // candidate; if `count` of them are, the count-th smallest of all points is among them. The
    // previous query's answer, a little enlarged, usually leaves a short list to select from (a
    // hint only: the answer does not depend on it).
    const auto limit = static_cast<float>(reach * reach * (1.0 - 1e-5));
    // The near candidates: within a few times the previous answer, so that an adaptive radius of
    // twice the k-th distance likely lies within them.
    if (reach > max_reach_ || !gather(i, reach, std::min(limit, kNearHint * hint_))) {
      return std::nullopt;
    }
    const CellGrid::Candidates& c = candidates_;
    const std::size_t n = c.size;
    if (smallest_.size() < n + detail::kKernelSlack) smallest_.resize(2 * n + detail::kKernelSlack);
    // Of the near ones, those within 1.3 (then 2) times the previous answer to select from; then,
    // if too few, every candidate within the limit.
    std::size_t m = 0;
    for (const float factor : {kFirstHint, 2.0f}) {
      const float first = std::min(limit, factor * hint_);
      if (first > c.near_bound) break;
      m = detail::valuesBelow(c.near_d2.data(), c.near_size, first, smallest_.data());
      if (m >= static_cast<std::size_t>(count)) break;
    }
    if (m < static_cast<std::size_t>(count)) {
      m = detail::valuesBelow(c.d2.data(), n, limit, smallest_.data());
    }
    if (m < static_cast<std::size_t>(count)) {
      if (reach >= max_reach_) return std::nullopt;
      continue;
    }
    const float d2 = detail::kthSmallest(smallest_.data(), m, count);
    hint_ = d2;
    if (nearest) nearestOf(i, count, d2, *nearest);
    return d2;
  }
}

void CellGridSearch::nearestOf(pcl::index_t i, int count, float d2, std::vector<Neighbour>& out) {
  // Those strictly closer than d2, then ties at d2 up to `count`, each in the candidates' order;
  // from the near ones when they hold every candidate within d2.
  const CellGrid::Candidates& c = candidates_;
  const bool near = d2 < c.near_bound;
  const float* d2s = near ? c.near_d2.data() : c.d2.data();
  const std::uint32_t* slots = near ? c.near_slot.data() : c.slot.data();
  const std::size_t n = near ? c.near_size : c.size;
  out.clear();
  const pcl::PointXYZ& p = cloud_[i];
  for (std::size_t k = 0; k < n; ++k) {
    if (d2s[k] < d2) out.push_back(grid_.neighbour(slots[k], p, d2s[k]));
  }
  for (std::size_t k = 0; k < n && out.size() < static_cast<std::size_t>(count); ++k) {
    if (d2s[k] == d2) out.push_back(grid_.neighbour(slots[k], p, d2));
  }
}

bool CellGridSearch::adaptiveSubset(pcl::index_t i, int count, float scale,
                                    std::vector<Neighbour>& subset) {
  const double reach = grid_.cellSize();
  // If fewer than `count` points have d^2 < inner, then d^2 >= inner, r_i >= scale sqrt(inner)
  // (rounding is monotone) and every point with d^2 < float(r_min^2) lies within r_i.
  const auto inner = static_cast<float>(reach * reach / (static_cast<double>(scale) * scale));
  const float r_min = scale * std::sqrt(inner);
  const auto limit = std::min(static_cast<float>(static_cast<double>(r_min) * r_min),
                              static_cast<float>(reach * reach * (1.0 - 1e-5)));
  if (!gather(i, reach, std::max(limit, inner))) return false;
  return within(i, limit, subset, inner) < static_cast<std::size_t>(count);
}

bool CellGridSearch::radius(pcl::index_t i, double radius, std::vector<Neighbour>& found) {
  const auto limit = static_cast<float>(radius * radius);  // d^2 < float(r^2), as KdTreeFLANN
  if (!gather(i, radius, limit)) return false;
  within(i, limit, found);
  return true;
}

std::size_t CellGridSearch::within(pcl::index_t i, float limit, std::vector<Neighbour>& out,
                                   float count_below) {
  // The near candidates hold every one with d^2 < limit (and < count_below); the places of those
  // within first, then their offsets.
  const CellGrid::Candidates& c = candidates_;
  const std::size_t n = c.near_size;
  const float* d2s = c.near_d2.data();
  std::size_t m = n, below = 0;
  if (count_below > 0.0f) {
    for (std::size_t k = 0; k < n; ++k) below += d2s[k] < count_below;
  }
  if (limit < c.near_bound) {
    if (kept_.size() < n + detail::kKernelSlack) kept_.resize(2 * n + detail::kKernelSlack);
    m = detail::placesBelow(d2s, n, limit, kept_.data());
  }
  out.resize(m);
  const pcl::PointXYZ& p = cloud_[i];
  const std::uint32_t* slots = c.near_slot.data();
  if (m == n) {
    for (std::size_t k = 0; k < m; ++k) out[k] = grid_.neighbour(slots[k], p, d2s[k]);
  } else {
    for (std::size_t k = 0; k < m; ++k) {
      out[k] = grid_.neighbour(slots[kept_[k]], p, d2s[kept_[k]]);
    }
  }
  return below;
}

}  // namespace mcws
