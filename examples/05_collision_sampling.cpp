// Example 05: workspace samples labelled by collision.
//
// The TA1400 welding arm of Fu, Hu, Chen & Pan 2016 with its torch (robots/ta1400.yaml, lengths
// in mm, links as capsules): one joint vector checked, then 10000 samples, each labelled free,
// link-link, tool-link or environment by mcws::CollisionChecker (FCL underneath).
#include <iostream>
#include <string>

#include "mcws/collision/collision_sampler.h"
#include "mcws/kinematics/robot_yaml.h"

int main() {
  const std::string file = MCWS_ROBOTS_DIR "/ta1400.yaml";
  const mcws::Robot robot = mcws::loadRobot(file);
  const mcws::CollisionChecker checker(robot, mcws::loadCollisionModel(robot, file));

  Eigen::VectorXd q_folded(6);  // the elbow folded into the base [rad]
  q_folded << 0.0, 0.8726646, 1.0471976, 0.0, 0.0, 0.0;
  const std::uint32_t folded = checker.label(q_folded);
  std::cout << "q = [" << q_folded.transpose().format(Eigen::IOFormat(7, Eigen::DontAlignCols))
            << "] rad: " << mcws::labelName(folded) << "\n";

  constexpr std::size_t kSamples = 10000;
  const mcws::LabelledRobotSampler sampler(robot, mcws::RobotSamplerOptions{}, checker);
  const pcl::PointCloud<mcws::WorkspacePoint> cloud = mcws::sampleCloud(sampler, kSamples, 0);
  std::size_t counts[4] = {0, 0, 0, 0};
  for (const mcws::WorkspacePoint& p : cloud) ++counts[p.label];
  for (std::uint32_t label = 0; label < 4; ++label) {
    std::cout << "  " << label << " " << mcws::labelName(label) << ": " << counts[label] << " ("
              << 100.0 * double(counts[label]) / double(kSamples) << " %)\n";
  }

  // Check: the folded arm hits itself, and the samples are neither all free nor all colliding.
  const bool mixed = counts[mcws::kLabelFree] > 0 && counts[mcws::kLabelFree] < kSamples;
  return folded == mcws::kLabelLinkLink && mixed ? 0 : 1;
}
