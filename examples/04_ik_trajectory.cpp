// Example 04: inverse kinematics, then a joint-space move to the solution.
//
// The six-axis inspection arm of Liu, Han, Xu & Li 2021 (robots/inspection6.yaml, lengths in mm):
// the tool pose at the paper's joint vector [pi/3, pi/6, pi/2, pi/4, pi/3, pi/6] is solved for
// from the paper's start vector, then reached from the zero vector by the paper's quintic blend
// (its eq. (10)) in 4 s.
#include <cmath>
#include <iostream>

#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/inverse_kinematics.h"
#include "mcws/kinematics/robot_yaml.h"
#include "mcws/trajectory/joint_trajectory.h"

int main() {
  const mcws::Robot robot = mcws::loadRobot(MCWS_ROBOTS_DIR "/inspection6.yaml");
  Eigen::VectorXd q_paper(6);
  q_paper << M_PI / 3, M_PI / 6, M_PI / 2, M_PI / 4, M_PI / 3, M_PI / 6;  // [rad]
  const Eigen::Isometry3d T_world_tool_goal = mcws::toolPose(robot, q_paper);

  Eigen::VectorXd q_seed(6);
  q_seed << 1.0, 0.5, 1.5, 0.8, 1.0, 0.5;  // [rad]
  const mcws::IkResult ik = mcws::solveIk(robot, T_world_tool_goal, q_seed);
  const Eigen::IOFormat row(6, Eigen::DontAlignCols, " ", " ");
  std::cout << "IK " << mcws::ikStatusName(ik.status) << " after " << ik.iterations
            << " iterations: q = [" << ik.q.transpose().format(row) << "] rad, position error "
            << ik.position_error << " mm\n";
  if (!ik.converged() || (ik.q - q_paper).norm() > 1e-6) return 1;

  // Whole trajectory checked against the joint limits, then sampled at 100 Hz.
  const double duration = 4.0;  // [s]
  const Eigen::VectorXd q_start = Eigen::VectorXd::Zero(robot.dof());
  const mcws::JointTrajectory move =
      mcws::pointToPoint(q_start, ik.q, duration, mcws::TimeProfile::kQuintic);
  mcws::checkTrajectoryLimits(robot, move);
  const mcws::SampledTrajectory samples = mcws::sampleTrajectory(move, 100.0);
  double path = 0.0;  // tool path length [mm]
  Eigen::Vector3d p_world_tool = mcws::toolPose(robot, q_start).translation();
  for (int i = 1; i < samples.size(); ++i) {
    const Eigen::Vector3d p_next =
        mcws::toolPose(robot, samples.q.row(i).transpose()).translation();
    path += (p_next - p_world_tool).norm();
    p_world_tool = p_next;
  }
  const double peak = samples.qd.cwiseAbs().maxCoeff();                   // [rad/s]
  const double expected = 1.875 * ik.q.cwiseAbs().maxCoeff() / duration;  // at t = T/2
  std::cout << samples.size() << " samples over " << duration << " s, tool path " << path
            << " mm, peak joint speed " << peak << " rad/s (1.875 D/T = " << expected << ")\n";

  // Check: IK found the paper's joint vector (above); the last sample is on the goal pose and the
  // peak speed is the quintic's 1.875 D/T.
  const bool reached = (p_world_tool - T_world_tool_goal.translation()).norm() < 1e-3;  // [mm]
  return reached && std::abs(peak - expected) < 1e-9 * expected ? 0 : 1;
}
