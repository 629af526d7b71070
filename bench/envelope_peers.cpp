// The workspace envelope (mcws::workspaceEnvelope, as mcws_envelope makes it) beside CGAL's
// alpha wrapping (CGAL::alpha_wrap_3, Portaneri et al. 2022, "Alpha wrapping with an offset") on
// the same points (issue 35): each one's time, the process's peak memory after it, its mesh's
// volume, and the relative volume difference of the two meshes.
// Usage: envelope_peers CLOUD.pcd [none|efron] [ALPHA_SPACINGS] [OFFSET_SPACINGS]
//   none|efron: mcws's edge correction (default none, for refined clouds, at alpha 5; efron at 3).
//   The wrap's alpha and offset are in mean spacings h = cbrt(V / N) of mcws's volume V and the
//   N points (defaults 5 and 0.1). mcws runs first (its volume gives h); the peak memory printed
//   after each is the process's so far (the wrap's own only where it exceeds mcws's): for
//   mcws's alone, /usr/bin/time -v mcws_envelope on the same cloud.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/alpha_wrap_3.h>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "mcws/io/cloud_io.h"
#include "mcws/workspace/envelope.h"

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The process's peak resident memory so far [MiB].
double peakMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // ru_maxrss in KiB on Linux
}

double parseArgument(char** argv, int argc, int index, double fallback) {
  if (argc <= index) return fallback;
  char* end = nullptr;
  const double value = std::strtod(argv[index], &end);
  if (end == argv[index] || *end != '\0' || !(value > 0.0)) {
    throw std::runtime_error(std::string("argument ") + std::to_string(index) + ": '" +
                             argv[index] + "' is not a positive number");
  }
  return value;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 5) {
    std::fprintf(stderr,
                 "usage: envelope_peers CLOUD.pcd [none|efron] [ALPHA_SPACINGS] "
                 "[OFFSET_SPACINGS]\n");
    return 2;
  }
  try {
    const std::string correction = argc > 2 ? argv[2] : "none";
    if (correction != "none" && correction != "efron") {
      std::fprintf(stderr, "envelope_peers: correction '%s' is not none or efron\n",
                   correction.c_str());
      return 2;
    }
    const double alpha_spacings = parseArgument(argv, argc, 3, 5.0);
    const double offset_spacings = parseArgument(argv, argc, 4, 0.1);
    const mcws::io::WorkspaceCloud::Ptr cloud = mcws::io::readCloud(argv[1]);
    pcl::PointCloud<pcl::PointXYZ> points;
    std::vector<Kernel::Point_3> wrap_points;
    for (const auto& p : *cloud) {
      points.push_back(pcl::PointXYZ(p.x, p.y, p.z));
      wrap_points.emplace_back(p.x, p.y, p.z);
    }
    std::printf("cloud %s: %zu points, peak %.0f MiB after loading\n", argv[1], points.size(),
                peakMiB());

    mcws::MeasureOptions options;
    options.edge_correction = correction == "efron";
    options.alpha_factor = options.edge_correction ? 3.0 : 5.0;
    auto start = std::chrono::steady_clock::now();
    const mcws::Envelope envelope = mcws::workspaceEnvelope(points, options);
    const double mcws_seconds = secondsSince(start);
    const double mcws_peak = peakMiB();
    std::printf("mcws envelope: %.3f s, peak %.0f MiB, %zu triangles, volume %.9g\n", mcws_seconds,
                mcws_peak, envelope.mesh.triangles.size(), envelope.volume);

    const double h = std::cbrt(envelope.volume / static_cast<double>(points.size()));
    const double alpha = alpha_spacings * h, offset = offset_spacings * h;
    CGAL::Surface_mesh<Kernel::Point_3> wrap;
    start = std::chrono::steady_clock::now();
    CGAL::alpha_wrap_3(wrap_points, alpha, offset, wrap);
    const double wrap_seconds = secondsSince(start);
    const double wrap_volume = CGAL::Polygon_mesh_processing::volume(wrap);
    std::printf(
        "CGAL alpha_wrap_3 (alpha %.4g = %g h, offset %.4g = %g h): %.3f s, peak %.0f MiB, "
        "%zu triangles, volume %.9g\n",
        alpha, alpha_spacings, offset, offset_spacings, wrap_seconds, peakMiB(),
        static_cast<std::size_t>(wrap.number_of_faces()), wrap_volume);
    std::printf("volume difference (wrap - mcws) / mcws: %+.4f %%; time ratio wrap / mcws: %.2f\n",
                100.0 * (wrap_volume - envelope.volume) / envelope.volume,
                wrap_seconds / mcws_seconds);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "envelope_peers: %s\n", e.what());
    return 1;
  }
}
