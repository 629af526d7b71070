// Example 01: Monte Carlo workspace of a robot, written as a PCD file.
//
// The de-icing arm of Yin, Wang & Yu 2010 (robots/deicing.yaml, lengths in cm) in the X-Z plane:
// joint values uniform within their limits, the shoulder yaw pinned at 0, mapped to the tool
// point. Usage: example_01_sample_workspace [OUTPUT.pcd]  (default deicing_xz.pcd)
#include <cmath>
#include <iostream>
#include <string>

#include "mcws/io/cloud_io.h"
#include "mcws/kinematics/robot_yaml.h"
#include "mcws/sampling/sampler.h"

int main(int argc, char** argv) {
  const mcws::Robot robot = mcws::loadRobot(MCWS_ROBOTS_DIR "/deicing.yaml");

  mcws::RobotSamplerOptions options;
  options.seed = 1;                   // same seed, same cloud, for any thread count
  options.fixed = {{"theta3", 0.0}};  // shoulder yaw [rad]: the X-Z plane
  const mcws::RobotSampler sampler(robot, options);

  // Streamed to a binary PCD file (fields x y z q1..q8 label) on all cores (threads = 0).
  const std::string path = argc > 1 ? argv[1] : "deicing_xz.pcd";
  const std::size_t samples = 6000;
  const mcws::SampleSummary summary =
      mcws::writeSamples(sampler, samples, path, mcws::io::PcdFormat::kBinary, 0);

  const char* unit = mcws::unitName(robot.length_unit);
  std::cout << summary.points << " samples of '" << robot.name << "' -> " << path << "\n"
            << "x in [" << summary.min.x() << ", " << summary.max.x() << "] " << unit << ", z in ["
            << summary.min.z() << ", " << summary.max.z() << "] " << unit << "\n";

  // Check, through the library's checked reader (io::readCloud: header, data size, field types and
  // coordinates checked before PCL reads the file): the file holds every sample, each in the X-Z
  // plane and within the reach a1 + a2,max = 50 + 70 cm of the shoulder.
  const mcws::io::WorkspaceCloud::Ptr cloud = mcws::io::readCloud(path);
  if (cloud->size() != samples) return 1;
  for (const mcws::WorkspacePoint& p : *cloud) {
    if (std::abs(p.y) > 1e-3f || p.getVector3fMap().norm() > 120.0f + 1e-3f) return 1;
  }
  return 0;
}
