// Area / volume accuracy of delaunayMeasure on the validation shapes: mean absolute error over
// seeds 1..S. Usage: area_accuracy SHAPE N SEEDS [alpha-factor]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "mcws/workspace/measure.h"
#include "mcws/workspace/sampler.h"

int main(int argc, char** argv) {
  if (argc < 4) return 2;
  const mcws::Shape shape = mcws::parseShape(argv[1]);
  const std::size_t n = std::strtoull(argv[2], nullptr, 10);
  const int seeds = std::atoi(argv[3]);
  const double alpha = argc > 4 ? std::atof(argv[4]) : 3.0;
  const double truth = mcws::shapeMeasure(shape);
  double error = 0, raw_error = 0, seconds = 0, bias = 0;
  for (int seed = 1; seed <= seeds; ++seed) {
    pcl::PointCloud<pcl::PointXYZ> cloud;
    pcl::copyPointCloud(mcws::sampleCloud(mcws::ShapeSampler(shape, seed), n, 0), cloud);
    const auto start = std::chrono::steady_clock::now();
    const auto m = mcws::delaunayMeasure(cloud, mcws::shapeIsPlanar(shape) ? 2 : 3, alpha);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    error += std::abs(m.measure / truth - 1);
    bias += m.measure / truth - 1;
    raw_error += std::abs(m.uncorrected / truth - 1);
  }
  std::printf("%-8s N=%-8zu alpha=%.1f  MAE=%.4f%%  bias=%+.4f%%  uncorrected MAE=%.3f%%  %.2fs\n",
              argv[1], n, alpha, 100 * error / seeds, 100 * bias / seeds, 100 * raw_error / seeds,
              seconds / seeds);
}
