#include "mcws/trajectory/trajectory_io.h"

#include <algorithm>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

#include "mcws/core/decimal.h"
#include "mcws/core/error.h"
#include "mcws/io/gnuplot.h"
#include "mcws/kinematics/forward_kinematics.h"

namespace mcws {
namespace {

using io::gnuplotQuoted;
using io::ScratchDir;

void checkFits(const Robot& robot, const SampledTrajectory& tr) {
  const auto n = static_cast<Eigen::Index>(tr.t.size());
  if (tr.q.rows() != n || tr.qd.rows() != n || tr.qdd.rows() != n || tr.q.cols() != robot.dof() ||
      tr.qd.cols() != robot.dof() || tr.qdd.cols() != robot.dof()) {
    throw Error("trajectory of " + std::to_string(tr.q.cols()) + " joints and " +
                std::to_string(n) + " samples does not fit robot '" + robot.name + "' with " +
                std::to_string(robot.dof()) + " joints");
  }
}

}  // namespace

Eigen::MatrixXd toolPositions(const Robot& robot, const SampledTrajectory& tr) {
  checkFits(robot, tr);
  Eigen::MatrixXd xyz(tr.q.rows(), 3);
  for (Eigen::Index i = 0; i < tr.q.rows(); ++i) {
    xyz.row(i) = toolPose(robot, tr.q.row(i).transpose()).translation().transpose();
  }
  return xyz;
}

void writeTrajectoryCsv(const Robot& robot, const SampledTrajectory& tr,
                        const std::function<void(const std::string&, std::size_t)>& sink,
                        std::size_t rows) {
  const Eigen::MatrixXd xyz = toolPositions(robot, tr);
  // Every column named with its unit, as the behaviour timeline's: t_s, j1_rad, j1_rad_per_s,
  // j1_rad_per_s2 (a prismatic joint's in the length unit), x_mm.
  const std::string length = unitName(robot.length_unit);
  std::string out = "t_s";
  for (const char* per : {"", "_per_s", "_per_s2"}) {
    for (const Joint& joint : robot.joints) {
      out += "," + joint.name + "_" + (joint.type == JointType::kRevolute ? "rad" : length) + per;
    }
  }
  for (const char* axis : {"x", "y", "z"}) out += "," + std::string(axis) + "_" + length;
  out += "\n";
  auto put = [&](double value) { out += "," + formatNumber(value, 12); };
  const auto n = static_cast<std::size_t>(tr.size());
  rows = std::max<std::size_t>(rows, 1);
  std::size_t begin = 0;
  do {  // once with the header alone for no samples
    const std::size_t end = begin + std::min(rows, n - begin);
    for (auto i = static_cast<Eigen::Index>(begin); i < static_cast<Eigen::Index>(end); ++i) {
      out += formatNumber(tr.t[i], 12);
      for (const Eigen::MatrixXd* m : {&tr.q, &tr.qd, &tr.qdd}) {
        for (Eigen::Index j = 0; j < m->cols(); ++j) put((*m)(i, j));
      }
      for (int k = 0; k < 3; ++k) put(xyz(i, k));
      out += '\n';
    }
    sink(out, end);
    out.clear();
    begin = end;
  } while (begin < n);
}

std::string trajectoryCsv(const Robot& robot, const SampledTrajectory& tr) {
  std::string csv;
  writeTrajectoryCsv(
      robot, tr, [&](const std::string& piece, std::size_t) { csv += piece; },
      std::numeric_limits<std::size_t>::max());
  return csv;
}

std::string renderTrajectoryPng(const Robot& robot, const SampledTrajectory& tr,
                                const std::string& title) {
  const std::string csv = trajectoryCsv(robot, tr);
  ScratchDir dir;
  const std::string data = dir.file("trajectory.csv"), png = dir.file("trajectory.png");
  std::ofstream(data, std::ios::binary) << csv;

  const int n = robot.dof();
  const std::string unit = unitName(robot.length_unit);
  bool any_prismatic = false, any_revolute = false;
  for (const Joint& joint : robot.joints) {
    (joint.type == JointType::kPrismatic ? any_prismatic : any_revolute) = true;
  }
  // Axis unit of the joint panels: "rad", "cm" or "rad | cm", per s and s^2 for the others.
  auto jointUnit = [&](const std::string& per) {
    const std::string rad = "rad" + per, length = unit + per;
    return any_prismatic && any_revolute ? rad + " | " + length : any_prismatic ? length : rad;
  };
  std::ostringstream gp;
  gp << "set terminal pngcairo noenhanced size 1400,1000 font 'Sans,11'\n"
     << "set output " << gnuplotQuoted(png) << "\n"
     << "set datafile separator ','\n"
     << "set grid\nset key outside right top\n"
     << "set multiplot layout 2,2 title " << gnuplotQuoted(title) << "\n";
  const char* panels[3][2] = {
      {"joint positions", ""}, {"joint velocities", "/s"}, {"joint accelerations", "/s^2"}};
  for (int p = 0; p < 3; ++p) {
    gp << "set title " << gnuplotQuoted(panels[p][0]) << "\n"
       << "set xlabel 't [s]'\nset ylabel " << gnuplotQuoted("[" + jointUnit(panels[p][1]) + "]")
       << "\nplot ";
    for (int j = 0; j < n; ++j) {
      gp << (j ? ", " : "") << gnuplotQuoted(data) << " every ::1 using 1:" << 2 + p * n + j
         << " with lines lw 2 title " << gnuplotQuoted(robot.joints[j].name);
    }
    gp << "\n";
  }
  // Tool path in a cube around it (equal scales; a flat or straight path stays visible).
  const Eigen::MatrixXd xyz = toolPositions(robot, tr);
  const Eigen::Vector3d low = xyz.colwise().minCoeff(), high = xyz.colwise().maxCoeff();
  const Eigen::Vector3d middle = (low + high) / 2;
  double half = 0.55 * (high - low).maxCoeff();
  if (!(half > 0.0)) half = std::max(1.0, 0.1 * middle.norm());
  const int x = 2 + 3 * n;
  gp << "set title 'tool path'\nset key inside top right\n";
  const char* axes[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    gp << "set " << axes[k] << "range [" << middle[k] - half << ":" << middle[k] + half << "]\n"
       << "set " << axes[k] << "label " << gnuplotQuoted(std::string(axes[k]) + " [" + unit + "]")
       << "\n";
  }
  gp << "set zlabel rotate parallel\nset view 60,30,1.1\nset xyplane relative 0\n"
     << "set xtics offset -0.5,-0.3\nset ytics offset 0.5,-0.3\n"
     << "splot " << gnuplotQuoted(data) << " every ::1 using " << x << ":" << x + 1 << ":" << x + 2
     << " with lines lw 2 lc rgb '#1f77b4' title 'tool', " << gnuplotQuoted(data)
     << " every ::1::1 using " << x << ":" << x + 1 << ":" << x + 2
     << " with points pt 7 ps 1.5 lc rgb '#2ca02c' title 'start', " << gnuplotQuoted(data)
     << " every ::" << tr.size() << "::" << tr.size() << " using " << x << ":" << x + 1 << ":"
     << x + 2 << " with points pt 7 ps 1.5 lc rgb '#d62728' title 'end'\n"
     << "unset multiplot\n";
  return io::runGnuplot(dir, gp.str(), png);
}

}  // namespace mcws
