#include "mcws/distributed/tiled_boundary.h"

#include <pcl/common/point_tests.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include "mcws/core/error.h"
#include "mcws/filters/orthant/cloud_stages.h"
#include "mcws/points/unique_positions.h"
#include "mcws/search/grid_then_tree_search.h"

namespace mcws::distributed {

using io::PcdPointReader;
using io::WorkspaceCloud;

namespace {

/// Room a reach must leave to a loaded slab's wall, as a share of the slab axis's extent: covers
/// the rounding of float coordinates and of the radius comparison d^2 < float(r^2).
constexpr double kWallMargin = 1e-6;

/// Points whose radius makes the median: about this many, spread through the file.
constexpr std::uint64_t kRadiusSamples = 1000;

/// The slabs: `tiles` of equal width along `axis` from `low`.
struct Slabs {
  int axis{0};
  int tiles{1};
  double low{0.0}, high{0.0}, width{0.0};

  int tileOf(float v) const {
    if (!(width > 0.0)) return 0;
    const double t = std::floor((static_cast<double>(v) - low) / width);
    return static_cast<int>(std::clamp(t, 0.0, static_cast<double>(tiles - 1)));
  }
  /// The slab's walls; the outermost slabs reach to infinity.
  double lower(int t) const {
    return t == 0 ? -std::numeric_limits<double>::infinity() : low + t * width;
  }
  double upper(int t) const {
    return t == tiles - 1 ? std::numeric_limits<double>::infinity() : low + (t + 1) * width;
  }
};

/// The points of tile t and its halo, with their indices in the file and which are its own.
struct LoadedTile {
  WorkspaceCloud cloud;
  std::vector<std::uint64_t> index;
  std::vector<char> own;
  double from{0.0}, to{0.0};  ///< the loaded slab [length unit]; infinite where nothing lies beyond
};

LoadedTile loadTile(PcdPointReader& reader, const Slabs& slabs, int t, double halo) {
  LoadedTile tile;
  tile.from = slabs.lower(t) - halo;
  tile.to = slabs.upper(t) + halo;
  if (tile.from <= slabs.low) tile.from = -std::numeric_limits<double>::infinity();
  if (tile.to >= slabs.high) tile.to = std::numeric_limits<double>::infinity();
  WorkspaceCloud piece;
  std::vector<std::uint64_t> index;
  const std::size_t piece_points = reader.piecePoints();
  for (std::uint64_t first = 0; first < reader.size(); first += piece_points) {
    reader.readWithin(first, std::min<std::uint64_t>(piece_points, reader.size() - first),
                      slabs.axis, tile.from, tile.to, piece, index);
    tile.cloud.insert(tile.cloud.end(), piece.begin(), piece.end());
    tile.index.insert(tile.index.end(), index.begin(), index.end());
    for (const WorkspacePoint& p : piece) tile.own.push_back(slabs.tileOf(p.data[slabs.axis]) == t);
  }
  return tile;
}

/// The test's settings as the filter resolves them for a fixed or adaptive radius.
orthant::PointTestSettings reachSettings(const OrthantBoundary<WorkspacePoint>& filter) {
  orthant::PointTestSettings test;
  test.dimensions = boundaryDimensions(filter.getPlane());
  if (filter.getRadiusMode() == RadiusMode::kAdaptive) {
    test.adaptive =
        orthant::AdaptiveRadius{filter.getAdaptiveNeighbours(), filter.getAdaptiveScale()};
  }
  test.radius = filter.getRadiusSearch();
  test.outer = filter.getOuterRadius();
  return test;
}

/// Per point of the tile: its reach measured among the loaded points [length unit] (its radius
/// r_i in `radius` when adaptive), or infinity when fewer than k other positions are loaded. The
/// k-th distances come from the filter's own search (GridThenTreeSearch), on `threads` threads.
std::vector<double> reaches(const LoadedTile& tile, BoundaryPlane plane,
                            const orthant::PointTestSettings& test, int threads,
                            std::vector<float>& radius) {
  const std::size_t n = tile.cloud.size();
  std::vector<double> reach(n, test.outerRadius(test.radius));
  radius.assign(n, static_cast<float>(test.radius));
  if (!test.adaptive) return reach;
  pcl::Indices all(n), source;
  for (std::size_t i = 0; i < n; ++i) all[i] = static_cast<pcl::index_t>(i);
  pcl::PointCloud<pcl::PointXYZ> projected;
  projectToPlane(tile.cloud, all, plane, projected, source);
  std::vector<pcl::index_t> position_of;
  pcl::PointCloud<pcl::PointXYZ> positions = uniquePositions(projected, position_of);
  const int count = test.adaptive->k + 1;  // the point itself first, as nearestKSearch counts
  const std::size_t m = positions.size();
  std::vector<float> d2(m, std::numeric_limits<float>::infinity());
  if (m >= static_cast<std::size_t>(count)) {
    const double spacing = meanSpacing(positions, test.dimensions);
    GridThenTreeSearch search(std::move(positions), position_of, test.dimensions,
                              orthant::typicalOuterRadius(test, spacing), spacing, true);
    std::vector<char> wanted(m, 0);
    for (std::size_t k = 0; k < source.size(); ++k) {
      if (tile.own[static_cast<std::size_t>(source[k])]) wanted[position_of[k]] = 1;
    }
    std::vector<pcl::index_t> points;
    for (std::size_t i = 0; i < m; ++i) {
      if (wanted[i]) points.push_back(static_cast<pcl::index_t>(i));
    }
    search.forEachPoint<char>(points, threads, [&](NeighbourSearch& s, pcl::index_t i, char&) {
      const std::optional<float> kth = s.kthDistance2(i, count, nullptr);
      if (kth) d2[static_cast<std::size_t>(i)] = *kth;
      return kth.has_value();
    });
  }
  for (std::size_t k = 0; k < source.size(); ++k) {
    const auto i = static_cast<std::size_t>(source[k]);
    if (!tile.own[i]) continue;
    const float kth = d2[static_cast<std::size_t>(position_of[k])];
    radius[i] = static_cast<float>(test.adaptive->scale * std::sqrt(kth));
    reach[i] = test.outerRadius(radius[i]);
  }
  return reach;
}

/// 0 when every own point's reach ends inside the loaded slab (with a margin for rounding), else
/// the halo that holds the reach of every one measured here (which only shrinks as more points
/// are loaded), or infinity when some reach is unknown.
double haloNeeded(const LoadedTile& tile, const Slabs& slabs, int t,
                  const std::vector<double>& reach) {
  if (std::isinf(tile.from) && std::isinf(tile.to)) return 0.0;  // the whole cloud is loaded
  const double margin = kWallMargin * std::max(slabs.high - slabs.low, 1e-30);
  double needed = 0.0;
  bool short_of = false;
  for (std::size_t i = 0; i < tile.cloud.size(); ++i) {
    if (!tile.own[i]) continue;
    const double v = tile.cloud[i].data[slabs.axis];
    const double want = reach[i] * (1.0 + 1e-6) + margin;
    if (want < std::min(v - tile.from, tile.to - v)) continue;
    short_of = true;
    needed = std::max({needed, want - (v - slabs.lower(t)), want - (slabs.upper(t) - v)});
  }
  return short_of ? needed : 0.0;
}

/// The points kept by one process, and the radii of its sample points, as bytes.
struct Found {
  std::vector<std::uint64_t> kept;
  std::vector<double> radii;

  std::string encode() const {
    std::string bytes(sizeof(std::uint64_t) + 8 * (kept.size() + radii.size()), '\0');
    const std::uint64_t n = kept.size();
    std::memcpy(bytes.data(), &n, sizeof n);
    if (!kept.empty()) std::memcpy(bytes.data() + 8, kept.data(), 8 * kept.size());
    if (!radii.empty())
      std::memcpy(bytes.data() + 8 * (1 + kept.size()), radii.data(), 8 * radii.size());
    return bytes;
  }
  void merge(const std::string& bytes) {
    std::uint64_t n = 0;
    std::memcpy(&n, bytes.data(), sizeof n);
    const std::size_t old_kept = kept.size(), old_radii = radii.size();
    const std::size_t more_radii = (bytes.size() - 8 * (1 + n)) / 8;
    kept.resize(old_kept + n);
    radii.resize(old_radii + more_radii);
    if (n > 0) std::memcpy(kept.data() + old_kept, bytes.data() + 8, 8 * n);
    if (more_radii > 0)
      std::memcpy(radii.data() + old_radii, bytes.data() + 8 * (1 + n), 8 * more_radii);
  }
};

}  // namespace

double boundingBoxSpacing(const CloudSummary& cloud) {
  double measure = 1.0;
  for (int axis = 0; axis < 3; ++axis) {
    const bool in_plane = cloud.plane == BoundaryPlane::k3D || axis == planeAxes(cloud.plane)[0] ||
                          axis == planeAxes(cloud.plane)[1];
    if (in_plane) measure *= std::max(cloud.extent[axis], 1e-3 * cloud.largest);
  }
  return std::pow(measure / static_cast<double>(std::max<std::size_t>(cloud.finite, 1)),
                  1.0 / boundaryDimensions(cloud.plane));
}

void forEachPiece(PcdPointReader& reader,
                  const std::function<void(std::uint64_t, const WorkspaceCloud&)>& visit) {
  WorkspaceCloud piece;
  const std::size_t piece_points = reader.piecePoints();
  for (std::uint64_t first = 0; first < reader.size(); first += piece_points) {
    reader.read(first, std::min<std::uint64_t>(piece_points, reader.size() - first), piece);
    visit(first, piece);
  }
}

FileSummary summarizeFile(PcdPointReader& reader, BoundaryPlane plane) {
  FileSummary file;
  CloudSummarizer summarizer(plane);
  forEachPiece(reader, [&](std::uint64_t, const WorkspaceCloud& piece) {
    file.range.add(piece);
    summarizer.add(piece);
  });
  file.cloud = summarizer.summary();
  file.low = summarizer.low();
  return file;
}

TiledBoundary tiledBoundary(
    PcdPointReader& reader, const FileSummary& file, int tiles,
    const std::function<std::shared_ptr<OrthantBoundary<WorkspacePoint>>()>& make, int threads,
    const Processes& processes, const std::function<void(std::size_t, std::size_t)>& progress) {
  const std::shared_ptr<OrthantBoundary<WorkspacePoint>> settings = make();
  const BoundaryPlane plane = settings->getPlane();
  if (settings->getRadiusMode() == RadiusMode::kAutomatic || settings->getHullDepth() > 0.0) {
    throw Error("tiledBoundary: a fixed or adaptive radius, without the hull-depth stage");
  }
  const orthant::PointTestSettings test = reachSettings(*settings);
  const CloudSummary& summary = file.cloud;
  if (threads <= 0) threads = omp_get_num_procs();  // as the filter resolves it

  Slabs slabs;
  slabs.tiles = tiles;
  // The longest axis in the plane: a slab across another axis would not bound the neighbours.
  slabs.axis = plane == BoundaryPlane::k3D ? 0 : planeAxes(plane)[0];
  for (int axis = 0; axis < 3; ++axis) {
    const bool in_plane =
        plane == BoundaryPlane::k3D || axis == planeAxes(plane)[0] || axis == planeAxes(plane)[1];
    if (in_plane && summary.extent[axis] > summary.extent[slabs.axis]) slabs.axis = axis;
  }
  slabs.low = file.low[slabs.axis];
  slabs.high = slabs.low + summary.extent[slabs.axis];
  slabs.width = summary.extent[slabs.axis] / tiles;

  // The first halo: the reach itself with the margin haloNeeded() asks for, or 1.5 times the
  // typical reach in a uniform cloud of the summary's bounding box.
  const double spacing = boundingBoxSpacing(summary);
  const double first_halo = test.adaptive ? 1.5 * orthant::typicalOuterRadius(test, spacing)
                                          : 1.01 * test.outerRadius(test.radius) +
                                                2.0 * kWallMargin * (slabs.high - slabs.low);

  const std::uint64_t stride = std::max<std::uint64_t>(1, summary.points / kRadiusSamples);
  Found found;
  TiledBoundary result;
  const Block mine = blockOf(static_cast<std::uint64_t>(tiles), processes.rank(), processes.size());
  for (auto t = static_cast<int>(mine.begin); t < static_cast<int>(mine.end); ++t) {
    for (double halo = first_halo;;) {
      LoadedTile tile = loadTile(reader, slabs, t, halo);
      if (tile.cloud.size() > static_cast<std::size_t>(std::numeric_limits<pcl::index_t>::max())) {
        throw Error("slab " + std::to_string(t + 1) + " holds " +
                    std::to_string(tile.cloud.size()) +
                    " points with its halo, more than a PCL index reaches (2^31 - 1): give more "
                    "--tiles");
      }
      result.largest_tile = std::max<std::uint64_t>(result.largest_tile, tile.cloud.size());
      std::vector<float> radius;
      const std::vector<double> reach = reaches(tile, plane, test, threads, radius);
      const double needed = haloNeeded(tile, slabs, t, reach);
      if (needed > 0.0) {
        ++result.reloaded_tiles;
        halo = std::isfinite(needed) ? std::max(1.01 * needed, 1.1 * halo) : 2.0 * halo;
        continue;
      }
      result.largest_halo = std::max(result.largest_halo, halo);
      const std::shared_ptr<OrthantBoundary<WorkspacePoint>> filter = make();
      filter->setInputCloud(std::make_shared<WorkspaceCloud>(std::move(tile.cloud)));
      pcl::Indices kept;
      filter->filter(kept);
      for (const pcl::index_t i : kept) {
        if (tile.own[static_cast<std::size_t>(i)]) found.kept.push_back(tile.index[i]);
      }
      if (test.adaptive) {
        for (std::size_t i = 0; i < tile.index.size(); ++i) {
          if (tile.own[i] && tile.index[i] % stride == 0) found.radii.push_back(radius[i]);
        }
      }
      break;
    }
    if (processes.rank() == 0)
      progress(static_cast<std::size_t>(t - mine.begin + 1), static_cast<std::size_t>(mine.size()));
  }

  std::vector<double> stats = {result.largest_halo, static_cast<double>(result.largest_tile),
                               static_cast<double>(result.reloaded_tiles)};
  processes.max(stats);
  result.largest_halo = stats[0];
  result.largest_tile = static_cast<std::uint64_t>(stats[1]);
  std::vector<std::uint64_t> reloaded = {result.reloaded_tiles};
  processes.sum(reloaded);
  result.reloaded_tiles = reloaded[0];
  reduceToFirst(
      processes, [&] { return found.encode(); },
      [&](const std::string& bytes) { found.merge(bytes); });
  std::vector<std::uint64_t> kept_count = {found.kept.size()};
  if (processes.rank() == 0) {
    result.boundary.assign(reader.size(), 0);
    for (const std::uint64_t i : found.kept) result.boundary[i] = 1;
    if (!found.radii.empty()) {
      auto middle = found.radii.begin() + static_cast<std::ptrdiff_t>(found.radii.size() / 2);
      std::nth_element(found.radii.begin(), middle, found.radii.end());
      result.median_radius = *middle;
    }
  } else {
    kept_count[0] = 0;
  }
  processes.sum(kept_count);
  result.kept = kept_count[0];
  return result;
}

std::string fileFingerprint(const io::PcdPointReader& reader, const FileSummary& file) {
  std::ostringstream seen;
  seen.precision(17);
  seen << reader.size() << " points, " << file.cloud.finite << " finite, low "
       << file.low.transpose() << ", extent " << file.cloud.extent.transpose();
  return seen.str();
}

}  // namespace mcws::distributed
