// The de-icing arm (Yin, Wang & Yu 2010): exact X-Z area and 3-D volume (closed-form membership
// integrated on grids of decreasing step), then the pipeline's measures from joint-space samples
// and their errors. Usage: deicing_exact [N ...]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "deicing_region.h"
#include "mcws/filters/orthant_boundary.h"
#include "mcws/kinematics/robot_yaml.h"
#include "mcws/sampling/sampler.h"
#include "mcws/workspace/measure.h"
#include "mcws/workspace/refine.h"

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
  // Plain: n joint samples, Efron-corrected measure. Refined: n/2 samples, their boundary
  // (mcws_boundary's defaults), n/2 refined samples (mcws_refine's default spread), measured
  // as mcws_measure --correction none does: without correction (the refined samples lie on the
  // edge itself) and with alpha 5.
  auto project = [](const pcl::PointCloud<mcws::WorkspacePoint>& cloud, bool xz) {
    pcl::PointCloud<pcl::PointXYZ> points;
    for (const auto& p : cloud) {
      points.push_back(xz ? pcl::PointXYZ(p.x, p.z, 0.0f) : pcl::PointXYZ(p.x, p.y, p.z));
    }
    return points;
  };
  auto refined = [&](std::size_t n, const mcws::RobotSamplerOptions& options, bool xz) {
    auto cloud = std::make_shared<pcl::PointCloud<mcws::WorkspacePoint>>(
        mcws::sampleCloud(mcws::RobotSampler(robot, options), n / 2, 0));
    mcws::OrthantBoundary<mcws::WorkspacePoint> boundary;
    boundary.setInputCloud(cloud);
    boundary.setPlane(xz ? mcws::BoundaryPlane::kXZ : mcws::BoundaryPlane::k3D);  // recommended
    pcl::PointCloud<mcws::WorkspacePoint> rim;
    boundary.filter(rim);
    mcws::RefineOptions refine;
    refine.seed = options.seed + 1000;
    *cloud += mcws::sampleCloud(mcws::RefineSampler(robot, rim, refine), n - n / 2, 0);
    mcws::MeasureOptions measure;
    measure.edge_correction = false;
    measure.alpha_factor = 5.0;
    return mcws::delaunayMeasure(project(*cloud, xz), xz ? 2 : 3, measure).uncorrected;
  };
  std::printf("| joint samples | X-Z area, plain | refined | 3-D volume, plain | refined |\n");
  std::printf("|---|---|---|---|---|\n");
  for (const std::size_t n : sizes) {
    mcws::RobotSamplerOptions plane, space;
    plane.fixed = {{"theta3", 0.0}};
    const auto area = mcws::delaunayMeasure(
        project(mcws::sampleCloud(mcws::RobotSampler(robot, plane), n, 0), true), 2);
    const auto volume = mcws::delaunayMeasure(
        project(mcws::sampleCloud(mcws::RobotSampler(robot, space), n, 0), false), 3);
    const double area_refined = refined(n, plane, true), volume_refined = refined(n, space, false);
    std::printf(
        "| %zu | %.1f (%+.3f %%) | %.1f (**%+.3f %%**) | %.0f (%+.3f %%) | %.0f (**%+.3f %%**) |\n",
        n, area.measure, 100 * (area.measure / exact.area - 1), area_refined,
        100 * (area_refined / exact.area - 1), volume.measure,
        100 * (volume.measure / exact.volume - 1), volume_refined,
        100 * (volume_refined / exact.volume - 1));
    std::fflush(stdout);
  }
}
