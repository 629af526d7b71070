// Boundary methods side by side (issue 3, section 4) on the same uniform clouds from mcws's
// ShapeSampler (seed 1): the unit disk in 2-D and the unit ball in 3-D. For each method: time
// (including what it needs, e.g. normals or a kd-tree; median of 3 runs when a run takes under
// 5 s, else one run), points reported, precision (share of reported points within 2 mean
// spacings h of the true boundary), recall (share of the points within h / 2 of it that are
// reported) and, where the method gives one, the error of its area or volume.
// Usage: boundary_peers [N] [disk|ball|both] [THREADS] [ONLY] [BE_RADII]
//   defaults: 1000000 both 2, all methods, BoundaryEstimation at r = 4h. ONLY: run the methods
//   whose name contains this text; BE_RADII: BoundaryEstimation radii in h, e.g. "4,6,8".
#include <CGAL/Alpha_shape_2.h>
#include <CGAL/Alpha_shape_face_base_2.h>
#include <CGAL/Alpha_shape_vertex_base_2.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Fixed_alpha_shape_3.h>
#include <CGAL/Fixed_alpha_shape_cell_base_3.h>
#include <CGAL/Fixed_alpha_shape_vertex_base_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <omp.h>
#include <pcl/features/boundary.h>
#include <pcl/features/normal_3d_omp.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/surface/concave_hull.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "boundary_metrics.h"
#include "mcws/filters/extremum_boundary.h"
#include "mcws/filters/grid_boundary.h"
#include "mcws/filters/orthant_boundary.h"
#include "mcws/sampling/sampler.h"
#include "mcws/workspace/measure.h"

namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

/// What a method reports: boundary points (indices into the cloud) and, if it gives one, the
/// area or volume.
struct Outcome {
  pcl::Indices boundary;
  std::optional<double> measure;
};

struct Context {
  mcws::Shape shape;
  Cloud::Ptr cloud;
  double h;  ///< mean spacing (measure / N)^(1/d)
  int dimensions;
  int threads;
};

// A straightforward quadrant (2-D) or octant (3-D) test in the axis frame: the rule of
// Yin, Wang & Yu 2010 with one fixed radius, a kd-tree and nothing else.
Outcome axisOrthants(const Context& c, double radius) {
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  tree.setInputCloud(c.cloud);
  const std::size_t n = c.cloud->size();
  const unsigned full = c.dimensions == 2 ? 0xFu : 0xFFu;
  std::vector<char> boundary(n, 0);
#pragma omp parallel num_threads(c.threads)
  {
    pcl::Indices nn;
    std::vector<float> d2;
#pragma omp for schedule(dynamic, 1024)
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(n); ++i) {
      const pcl::PointXYZ& p = (*c.cloud)[i];
      tree.radiusSearch(p, radius, nn, d2);
      unsigned occupied = 0;
      for (const auto j : nn) {
        if (j == i) continue;
        const pcl::PointXYZ& q = (*c.cloud)[j];
        occupied |= 1u << ((q.x >= p.x ? 1 : 0) | (q.y >= p.y ? 2 : 0) |
                           (c.dimensions == 3 && q.z >= p.z ? 4 : 0));
      }
      boundary[i] = occupied != full;
    }
  }
  Outcome out;
  for (std::size_t i = 0; i < n; ++i) {
    if (boundary[i]) out.boundary.push_back(static_cast<pcl::index_t>(i));
  }
  return out;
}

Outcome boundaryEstimation(const Context& c, int normal_k, double radius) {
  pcl::NormalEstimationOMP<pcl::PointXYZ, pcl::Normal> normals_of(c.threads);
  auto normals = std::make_shared<pcl::PointCloud<pcl::Normal>>();
  auto tree = std::make_shared<pcl::search::KdTree<pcl::PointXYZ>>();
  normals_of.setInputCloud(c.cloud);
  normals_of.setSearchMethod(tree);
  normals_of.setKSearch(normal_k);
  normals_of.compute(*normals);
  pcl::BoundaryEstimation<pcl::PointXYZ, pcl::Normal, pcl::Boundary> estimation;
  estimation.setInputCloud(c.cloud);
  estimation.setInputNormals(normals);
  estimation.setSearchMethod(tree);
  estimation.setRadiusSearch(radius);
  pcl::PointCloud<pcl::Boundary> flags;
  estimation.compute(flags);
  Outcome out;
  for (std::size_t i = 0; i < flags.size(); ++i) {
    if (flags[i].boundary_point) out.boundary.push_back(static_cast<pcl::index_t>(i));
  }
  return out;
}

Outcome concaveHull(const Context& c, double alpha) {
  pcl::ConcaveHull<pcl::PointXYZ> hull;
  hull.setInputCloud(c.cloud);
  hull.setAlpha(alpha);
  hull.setDimension(c.dimensions);
  hull.setKeepInformation(true);
  Cloud points;
  std::vector<pcl::Vertices> polygons;
  hull.reconstruct(points, polygons);
  pcl::PointIndices indices;
  hull.getHullPointIndices(indices);
  Outcome out;
  out.boundary = indices.indices;
  std::sort(out.boundary.begin(), out.boundary.end());
  double measure = 0.0;
  for (const auto& polygon : polygons) {
    const auto& v = polygon.vertices;
    if (c.dimensions == 2) {  // shoelace, each polygon on its own
      double twice = 0.0;
      for (std::size_t k = 0; k < v.size(); ++k) {
        const auto& a = points[v[k]];
        const auto& b = points[v[(k + 1) % v.size()]];
        twice += static_cast<double>(a.x) * b.y - static_cast<double>(b.x) * a.y;
      }
      measure += std::abs(twice) / 2.0;
    } else if (v.size() == 3) {  // divergence theorem over the triangles as given
      const Eigen::Vector3d a = points[v[0]].getVector3fMap().cast<double>();
      const Eigen::Vector3d b = points[v[1]].getVector3fMap().cast<double>();
      const Eigen::Vector3d d = points[v[2]].getVector3fMap().cast<double>();
      measure += a.dot(b.cross(d)) / 6.0;
    }
  }
  out.measure = std::abs(measure);
  return out;
}

Outcome cgalAlphaShape2(const Context& c, double alpha) {
  using Vb =
      CGAL::Alpha_shape_vertex_base_2<K, CGAL::Triangulation_vertex_base_with_info_2<int, K>>;
  using Fb = CGAL::Alpha_shape_face_base_2<K>;
  using Delaunay = CGAL::Delaunay_triangulation_2<K, CGAL::Triangulation_data_structure_2<Vb, Fb>>;
  using AlphaShape = CGAL::Alpha_shape_2<Delaunay>;
  std::vector<std::pair<K::Point_2, int>> points;
  points.reserve(c.cloud->size());
  for (std::size_t i = 0; i < c.cloud->size(); ++i) {
    points.emplace_back(K::Point_2((*c.cloud)[i].x, (*c.cloud)[i].y), static_cast<int>(i));
  }
  Delaunay delaunay(points.begin(), points.end());
  AlphaShape shape(delaunay, alpha * alpha, AlphaShape::REGULARIZED);
  Outcome out;
  for (auto v = shape.finite_vertices_begin(); v != shape.finite_vertices_end(); ++v) {
    const auto type = shape.classify(v);
    if (type == AlphaShape::REGULAR || type == AlphaShape::SINGULAR)
      out.boundary.push_back(v->info());
  }
  std::sort(out.boundary.begin(), out.boundary.end());
  double area = 0.0;
  for (auto f = shape.finite_faces_begin(); f != shape.finite_faces_end(); ++f) {
    if (shape.classify(f) == AlphaShape::INTERIOR) area += shape.triangle(f).area();
  }
  out.measure = area;
  return out;
}

Outcome cgalFixedAlphaShape3(const Context& c, double alpha) {
  using Vb =
      CGAL::Fixed_alpha_shape_vertex_base_3<K, CGAL::Triangulation_vertex_base_with_info_3<int, K>>;
  using Cb = CGAL::Fixed_alpha_shape_cell_base_3<K>;
  using Delaunay = CGAL::Delaunay_triangulation_3<K, CGAL::Triangulation_data_structure_3<Vb, Cb>>;
  using AlphaShape = CGAL::Fixed_alpha_shape_3<Delaunay>;
  std::vector<std::pair<K::Point_3, int>> points;
  points.reserve(c.cloud->size());
  for (std::size_t i = 0; i < c.cloud->size(); ++i) {
    const auto& p = (*c.cloud)[i];
    points.emplace_back(K::Point_3(p.x, p.y, p.z), static_cast<int>(i));
  }
  Delaunay delaunay(points.begin(), points.end());
  AlphaShape shape(delaunay, alpha * alpha);
  Outcome out;
  for (auto v = shape.finite_vertices_begin(); v != shape.finite_vertices_end(); ++v) {
    const auto type = shape.classify(v);
    if (type == AlphaShape::REGULAR || type == AlphaShape::SINGULAR)
      out.boundary.push_back(v->info());
  }
  std::sort(out.boundary.begin(), out.boundary.end());
  double volume = 0.0;
  for (auto cell = shape.finite_cells_begin(); cell != shape.finite_cells_end(); ++cell) {
    if (shape.classify(cell) == AlphaShape::INTERIOR) volume += shape.tetrahedron(cell).volume();
  }
  out.measure = volume;
  return out;
}

// The filter's recommended settings (adaptive radius, k = 24 in 2-D and 16 in 3-D, 92-degree
// sector; in 2-D the hull depth, 1 unless given) and the area by the paper's column method over
// its points.
Outcome orthant(const Context& c, double hull_depth) {
  mcws::OrthantBoundary<pcl::PointXYZ> filter;
  filter.setInputCloud(c.cloud);
  filter.setPlane(c.dimensions == 2 ? mcws::BoundaryPlane::kXY : mcws::BoundaryPlane::k3D);
  filter.setHullDepth(hull_depth);
  filter.setNumberOfThreads(c.threads);
  Outcome out;
  filter.filter(out.boundary);
  if (c.dimensions == 2) {
    Cloud rim;
    pcl::copyPointCloud(*c.cloud, out.boundary, rim);
    out.measure = mcws::columnArea(rim).area;
  }
  return out;
}

Outcome grid(const Context& c) {
  mcws::GridBoundary<pcl::PointXYZ> filter;
  filter.setInputCloud(c.cloud);
  filter.setPlane(c.dimensions == 2 ? mcws::BoundaryPlane::kXY : mcws::BoundaryPlane::k3D);
  Outcome out;
  filter.filter(out.boundary);
  if (c.dimensions == 2) out.measure = mcws::columnArea(filter.cellMeans()).area;
  return out;
}

Outcome extremum(const Context& c) {
  mcws::ExtremumBoundary<pcl::PointXYZ> filter;
  filter.setInputCloud(c.cloud);
  filter.setPlane(mcws::BoundaryPlane::kXY);
  Outcome out;
  filter.filter(out.boundary);
  out.measure = mcws::bench::extremumColumnArea(*c.cloud, out.boundary, filter.usedColumnWidth());
  return out;
}

Outcome delaunay(const Context& c) {
  Outcome out;
  out.measure = mcws::delaunayMeasure(*c.cloud, c.dimensions).measure;
  return out;
}

/// Methods whose name contains this text run; empty: all.
std::string only;

void report(const Context& c, const std::string& method, const std::function<Outcome()>& run) {
  if (method.find(only) == std::string::npos) return;
  std::vector<double> seconds;
  Outcome outcome;
  for (int k = 0; k < 3; ++k) {
    const auto start = std::chrono::steady_clock::now();
    outcome = run();
    seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (seconds.front() >= 5.0) break;
  }
  std::sort(seconds.begin(), seconds.end());
  const double median = seconds[seconds.size() / 2];
  const std::string runs = seconds.size() == 1 ? "1 run" : "median of 3";
  std::string quality = "– | –";
  if (!outcome.boundary.empty() || !outcome.measure) {
    const auto q = mcws::bench::boundaryQuality(c.shape, *c.cloud, outcome.boundary, c.h);
    char text[64];
    std::snprintf(text, sizeof text, "%.4f | %.4f", q.precision, q.recall);
    quality = text;
  }
  std::string error = "–";
  if (outcome.measure) {
    char text[32];
    std::snprintf(text, sizeof text, "%+.3f %%",
                  100.0 * (*outcome.measure / mcws::shapeMeasure(c.shape) - 1.0));
    error = text;
  }
  std::printf("| %s | %s | %.2f s (%s) | %zu | %s | %s |\n", c.dimensions == 2 ? "disk" : "ball",
              method.c_str(), median, runs.c_str(), outcome.boundary.size(), quality.c_str(),
              error.c_str());
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t n = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1000000;
  const std::string which = argc > 2 ? argv[2] : "both";
  const int threads = argc > 3 ? std::atoi(argv[3]) : 2;
  only = argc > 4 ? argv[4] : "";
  std::vector<double> be_radii;
  for (std::string list = argc > 5 ? argv[5] : "4"; !list.empty();) {
    const std::size_t comma = list.find(',');
    be_radii.push_back(std::atof(list.substr(0, comma).c_str()));
    list = comma == std::string::npos ? "" : list.substr(comma + 1);
  }
  std::printf("| cloud | method | time | reported | precision | recall | area / volume error |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (const mcws::Shape shape : {mcws::Shape::kDisk, mcws::Shape::kBall}) {
    const bool planar = mcws::shapeIsPlanar(shape);
    if (which != "both" && which != (planar ? "disk" : "ball")) continue;
    Context c{shape, std::make_shared<Cloud>(), 0.0, planar ? 2 : 3, threads};
    pcl::copyPointCloud(mcws::sampleCloud(mcws::ShapeSampler(shape, 1), n, threads), *c.cloud);
    c.h = std::pow(mcws::shapeMeasure(shape) / n, 1.0 / c.dimensions);
    const double h = c.h;
    if (planar) {
      for (const double r : be_radii) {
        char name[96];
        std::snprintf(
            name, sizeof name,
            "pcl::NormalEstimationOMP (k = 10) + pcl::BoundaryEstimation (r = %gh, 90 deg)", r);
        report(c, name, [&] { return boundaryEstimation(c, 10, r * h); });
      }
      report(c, "pcl::ConcaveHull 2-D (alpha = 3h)", [&] { return concaveHull(c, 3 * h); });
      report(c, "CGAL Alpha_shape_2 (alpha = (3h)^2, regularized)",
             [&] { return cgalAlphaShape2(c, 3 * h); });
      report(c, "KdTreeFLANN quadrant test (axis frame, r = 8h)",
             [&] { return axisOrthants(c, 8 * h); });
      report(c, "mcws OrthantBoundary (mcws_boundary defaults, hull depth 1); area: column method",
             [&] { return orthant(c, 1.0); });
      report(c, "mcws OrthantBoundary, sector test alone (--hull-depth 0); area: column method",
             [&] { return orthant(c, 0.0); });
      report(c, "mcws GridBoundary (automatic cell); area: column method on cell means",
             [&] { return grid(c); });
      report(c, "mcws ExtremumBoundary (automatic); area: eq. (2) on its columns",
             [&] { return extremum(c); });
      report(c, "mcws_measure default (delaunayMeasure), area only", [&] { return delaunay(c); });
    } else {
      report(c, "pcl::ConcaveHull 3-D (alpha = 3h)", [&] { return concaveHull(c, 3 * h); });
      report(c, "CGAL Fixed_alpha_shape_3 (alpha = (3h)^2)",
             [&] { return cgalFixedAlphaShape3(c, 3 * h); });
      report(c, "KdTreeFLANN octant test (axis frame, r = 4h)",
             [&] { return axisOrthants(c, 4 * h); });
      report(c, "mcws OrthantBoundary (mcws_boundary defaults)", [&] { return orthant(c, 0.0); });
      report(c, "mcws GridBoundary 3-D (automatic cell)", [&] { return grid(c); });
      report(c, "mcws_measure default (delaunayMeasure), volume only", [&] { return delaunay(c); });
    }
  }
  return 0;
}
