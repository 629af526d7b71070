// Boundary quality on the validation shapes: precision (share of reported points within two mean
// spacings of the true boundary) and recall (share of the points within half a spacing of the
// true boundary that are reported), mean over seeds, with the filter's time.
// Usage: boundary_quality SHAPE N SEEDS [axis|outward|both|any] [auto-factor, or -k: adaptive]
// Environment: GAP (degrees, the any-rotation test's sector), HULL (the hull depth t, 2-D).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "boundary_metrics.h"
#include "mcws/filters/orthant_boundary.h"
#include "mcws/sampling/sampler.h"

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: boundary_quality SHAPE N SEEDS [axis|outward|both] [factor]\n");
    return 2;
  }
  const mcws::Shape shape = mcws::parseShape(argv[1]);
  const std::size_t n = std::strtoull(argv[2], nullptr, 10);
  const int seeds = std::atoi(argv[3]);
  const std::string frames = argc > 4 ? argv[4] : "both";
  const double factor = argc > 5 ? std::atof(argv[5]) : 0.0;
  const bool planar = mcws::shapeIsPlanar(shape);
  const double h = std::pow(mcws::shapeMeasure(shape) / n, planar ? 0.5 : 1.0 / 3.0);

  double precision = 0, recall = 0, seconds = 0, radius = 0, reported = 0;
  for (int seed = 1; seed <= seeds; ++seed) {
    const auto cloud = std::make_shared<pcl::PointCloud<mcws::WorkspacePoint>>(
        mcws::sampleCloud(mcws::ShapeSampler(shape, seed), n, 0));
    mcws::OrthantBoundary<mcws::WorkspacePoint> filter;
    filter.setInputCloud(cloud);
    filter.setPlane(planar ? mcws::BoundaryPlane::kXY : mcws::BoundaryPlane::k3D);
    if (factor < 0) {
      filter.setAdaptiveRadius(static_cast<int>(-factor), 2.0);  // negative factor: adaptive k
    } else {
      filter.setAutoRadius(factor);
    }
    using mcws::OrthantFrame;
    filter.setFrames(frames == "axis"      ? OrthantFrame::kAxis
                     : frames == "outward" ? OrthantFrame::kOutward
                     : frames == "both"    ? OrthantFrame::kAxis | OrthantFrame::kOutward
                     : frames == "any"     ? OrthantFrame::kAnyRotation
                                           : mcws::OrthantFrames());
    // The paper's test alone unless GAP [degrees] or HULL [spacings] say otherwise.
    filter.setMinimumGap((std::getenv("GAP") ? std::atof(std::getenv("GAP")) : 90.0) * M_PI /
                         180.0);
    filter.setHullDepth(std::getenv("HULL") ? std::atof(std::getenv("HULL")) : 0.0);
    pcl::Indices kept;
    const auto start = std::chrono::steady_clock::now();
    filter.filter(kept);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    radius += filter.usedRadius() / h;
    const mcws::bench::BoundaryQuality quality =
        mcws::bench::boundaryQuality(shape, *cloud, kept, h);
    precision += quality.precision;
    recall += quality.recall;
    reported += kept.size();
  }
  std::printf(
      "%-8s N=%-8zu frames=%-7s r=%.2fh  reported=%.0f  precision=%.4f  recall=%.4f  "
      "filter=%.3fs\n",
      argv[1], n, frames.c_str(), radius / seeds, reported / seeds, precision / seeds,
      recall / seeds, seconds / seeds);
  return 0;
}
