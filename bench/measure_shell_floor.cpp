// How far mcws_measure's shell (MeasureOptions::shell) is from the least triangulation its volume
// and edge correction need, and what that least one costs with CGAL on this machine.
// The volume needs the vertices of the dropped simplices; the edge correction needs every
// boundary vertex's whole star, so the least shell is the boundary vertices and their neighbours
// in the triangulation of every point (found here by triangulating every point once). The
// program times CGAL's Delaunay triangulation (the measure's own settings: parallel on the
// OpenMP thread count, or sequential) of the measure's shell (the exposed points) and of that
// least shell, alternating, and of as many uniform random points in a cube (CGAL's rate on
// points without structure). Prints a markdown table of the medians.
// Usage: measure_shell_floor CLOUD.pcd [ALPHA_SPACINGS (default 3)] [RUNS (default 7)]
#include <omp.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <random>
#include <string>
#include <vector>

#include "mcws/io/cloud_io.h"
#include "mcws/workspace/detail/alpha_triangulation.h"
#include "mcws/workspace/detail/measure_steps.h"
#include "mcws/workspace/exposed_points.h"

namespace {

using Points = pcl::PointCloud<pcl::PointXYZ>;

/// The points an empty ball of alpha radius may touch: the measure's shell.
std::vector<char> measureShell(const Points& points, const std::vector<double>& spacing,
                               double alpha, int threads) {
  std::vector<double> radius(spacing.size());
  for (std::size_t i = 0; i < spacing.size(); ++i) radius[i] = alpha * spacing[i];
  return mcws::exposedPoints(points, 3, radius, threads).exposed;
}

/// The least shell: the boundary vertices of the triangulation of every point (between kept and
/// dropped tetrahedra) and their neighbours there; the vertices of the dropped tetrahedra are
/// boundary vertices too (checked).
std::vector<char> leastShell(const Points& points, const std::vector<double>& spacing,
                             double alpha) {
  using Delaunay = mcws::detail::Simplices<3, CGAL::Parallel_tag>::Delaunay;
  Delaunay dt;
  mcws::detail::triangulate<3, CGAL::Parallel_tag>(dt, points, std::vector<char>(points.size(), 1),
                                                   {});
  for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c) {
    c->info() = !dt.is_infinite(c) && mcws::detail::withinAlpha<3>(c, spacing, alpha);
  }
  std::vector<char> boundary(points.size(), 0), dropped(points.size(), 0);
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
    for (int i = 0; i < 4; ++i) {
      if (!c->info()) dropped[c->vertex(i)->info()] = 1;
      if (!c->info() || c->neighbor(i)->info()) continue;
      for (int j = 0; j < 4; ++j) {
        if (j != i) boundary[c->vertex(j)->info()] = 1;
      }
    }
  }
  std::vector<char> least = boundary;
  std::vector<Delaunay::Vertex_handle> around;
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
    if (dropped[v->info()] && !boundary[v->info()]) {
      throw std::runtime_error("a dropped tetrahedron's vertex is not a boundary vertex");
    }
    if (!boundary[v->info()]) continue;
    around.clear();
    dt.finite_adjacent_vertices(v, std::back_inserter(around));
    for (const auto a : around) least[a->info()] = 1;
  }
  return least;
}

/// Seconds CGAL takes to triangulate the points flagged in `in` as the measure does.
double triangulationSeconds(const Points& points, const std::vector<char>& in, bool parallel) {
  const auto start = std::chrono::steady_clock::now();
  if (parallel) {
    mcws::detail::Simplices<3, CGAL::Parallel_tag>::Delaunay dt;
    mcws::detail::triangulate<3, CGAL::Parallel_tag>(dt, points, in, {});
  } else {
    mcws::detail::Simplices<3, CGAL::Sequential_tag>::Delaunay dt;
    mcws::detail::triangulate<3, CGAL::Sequential_tag>(dt, points, in, {});
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

std::size_t count(const std::vector<char>& flags) {
  return static_cast<std::size_t>(std::count(flags.begin(), flags.end(), 1));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 4) {
    std::fprintf(stderr, "usage: measure_shell_floor CLOUD.pcd [ALPHA_SPACINGS] [RUNS]\n");
    return 2;
  }
  try {
    const double alpha = argc > 2 ? std::stod(argv[2]) : 3.0;
    const int runs = argc > 3 ? std::stoi(argv[3]) : 7;
    const int threads = omp_get_max_threads();
    const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism,
                                          static_cast<std::size_t>(threads));
    const mcws::io::WorkspaceCloud::Ptr cloud = mcws::io::readCloud(argv[1]);
    Points points;
    for (const auto& p : *cloud) points.push_back(pcl::PointXYZ(p.x, p.y, p.z));
    const std::vector<double> spacing = mcws::detail::localSpacing(points, 3, threads);
    const std::vector<char> shell = measureShell(points, spacing, alpha, threads);
    const std::vector<char> least = leastShell(points, spacing, alpha);
    std::size_t outside = 0;  // least-shell points the measure's shell leaves out (joined later)
    for (std::size_t i = 0; i < points.size(); ++i) outside += least[i] && !shell[i];
    Points cube;
    std::mt19937 random(1);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (std::size_t i = 0; i < count(shell); ++i) {
      cube.push_back(pcl::PointXYZ(unit(random), unit(random), unit(random)));
    }
    const std::vector<char> every(cube.size(), 1);
    std::vector<double> t_shell, t_least, t_cube;
    for (int run = 0; run < runs; ++run) {
      t_shell.push_back(triangulationSeconds(points, shell, threads > 1));
      t_least.push_back(triangulationSeconds(points, least, threads > 1));
      t_cube.push_back(triangulationSeconds(cube, every, threads > 1));
    }
    std::printf("%zu points, alpha %g spacings, %d threads, median of %d runs\n\n", points.size(),
                alpha, threads, runs);
    std::printf(
        "| triangulated | points | CGAL Delaunay [s] | us per point |\n|---|---|---|---|\n");
    const auto row = [](const char* what, std::size_t n, double seconds) {
      std::printf("| %s | %zu | %.3f | %.2f |\n", what, n, seconds, 1e6 * seconds / n);
    };
    row("the measure's shell (exposed points)", count(shell), median(t_shell));
    row("the least shell (boundary vertices and their neighbours)", count(least), median(t_least));
    row("uniform random points in a cube, as many as the shell", cube.size(), median(t_cube));
    std::printf("\nleast-shell points outside the measure's shell (joined by it later): %zu\n",
                outside);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "measure_shell_floor: %s\n", e.what());
    return 1;
  }
}
