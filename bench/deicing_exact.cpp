// The de-icing arm (seed 000): exact X-Z area and 3-D volume (closed-form membership integrated
// on grids of decreasing step), then the pipeline's measures from joint-space samples and their
// errors. Usage: deicing_exact [N ...]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "deicing_region.h"
#include "mcws/kinematics/robot_yaml.h"
#include "mcws/workspace/measure.h"
#include "mcws/workspace/sampler.h"

int main(int argc, char** argv) {
  std::printf("exact (grid integration of the closed-form region):\n");
  mcws::test::DeicingMeasures exact{};
  for (double step : {0.2, 0.1, 0.05, 0.025}) {
    exact = mcws::test::integrateDeicing(step);
    std::printf("  step %.3f cm: area %.3f cm^2, volume %.1f cm^3\n", step, exact.area,
                exact.volume);
  }
  const mcws::Robot robot = mcws::loadRobot(std::string(MCWS_ROBOTS_DIR) + "/deicing.yaml");
  std::vector<std::size_t> sizes;
  for (int k = 1; k < argc; ++k) sizes.push_back(std::strtoull(argv[k], nullptr, 10));
  if (sizes.empty()) sizes = {100000, 1000000};
  for (const std::size_t n : sizes) {
    mcws::RobotSamplerOptions plane;
    plane.fixed = {{"theta3", 0.0}};
    const auto xz = mcws::sampleCloud(mcws::RobotSampler(robot, plane), n, 0);
    pcl::PointCloud<pcl::PointXYZ> projected;
    for (const auto& p : xz) projected.push_back(pcl::PointXYZ(p.x, p.z, 0.0f));
    const auto area = mcws::delaunayMeasure(projected, 2);
    const auto full = mcws::sampleCloud(mcws::RobotSampler(robot, {}), n, 0);
    pcl::PointCloud<pcl::PointXYZ> points;
    pcl::copyPointCloud(full, points);
    const auto volume = mcws::delaunayMeasure(points, 3);
    std::printf("| %zu | %.1f | %+.3f %% | %+.3f %% | %.0f | %+.3f %% | %+.3f %% |\n", n,
                area.measure, 100 * (area.measure / exact.area - 1),
                100 * (area.uncorrected / exact.area - 1), volume.measure,
                100 * (volume.measure / exact.volume - 1),
                100 * (volume.uncorrected / exact.volume - 1));
  }
}
