#include "mcws/trajectory/trajectory_io.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/kinematics/forward_kinematics.h"

extern char** environ;

namespace mcws {
namespace {

namespace fs = std::filesystem;

void checkFits(const Robot& robot, const SampledTrajectory& tr) {
  const auto n = static_cast<Eigen::Index>(tr.t.size());
  if (tr.q.rows() != n || tr.qd.rows() != n || tr.qdd.rows() != n || tr.q.cols() != robot.dof() ||
      tr.qd.cols() != robot.dof() || tr.qdd.cols() != robot.dof()) {
    throw Error("trajectory of " + std::to_string(tr.q.cols()) + " joints and " +
                std::to_string(n) + " samples does not fit robot '" + robot.name + "' with " +
                std::to_string(robot.dof()) + " joints");
  }
}

/// A directory under the system's temporary directory, removed with its contents at scope exit.
class ScratchDir {
 public:
  ScratchDir() {
    std::string pattern = (fs::temp_directory_path() / "mcws_plot_XXXXXX").string();
    if (!::mkdtemp(pattern.data())) {
      throw Error(std::string("cannot create a temporary directory: ") + std::strerror(errno));
    }
    path_ = pattern;
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// A string as a gnuplot single-quoted literal.
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') out += '\'';
    if (c != '\n') out += c;
  }
  return out + "'";
}

/// Runs `gnuplot script`, stdout and stderr into `log`. \return exit status, or -1 on spawn error.
int runGnuplot(const std::string& script, const std::string& log, int& spawn_errno) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  std::string program = "gnuplot", argument = script;
  char* argv[] = {program.data(), argument.data(), nullptr};
  pid_t pid = 0;
  spawn_errno = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawn_errno != 0) return -1;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
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

std::string trajectoryCsv(const Robot& robot, const SampledTrajectory& tr) {
  const Eigen::MatrixXd xyz = toolPositions(robot, tr);
  std::string out = "t";
  for (const char* suffix : {"", "_vel", "_acc"}) {
    for (const Joint& joint : robot.joints) out += "," + joint.name + suffix;
  }
  out += ",x,y,z\n";
  char number[32];
  auto put = [&](double value) {
    std::snprintf(number, sizeof number, ",%.12g", value);
    out += number;
  };
  for (int i = 0; i < tr.size(); ++i) {
    std::snprintf(number, sizeof number, "%.12g", tr.t[i]);
    out += number;
    for (const Eigen::MatrixXd* m : {&tr.q, &tr.qd, &tr.qdd}) {
      for (Eigen::Index j = 0; j < m->cols(); ++j) put((*m)(i, j));
    }
    for (int k = 0; k < 3; ++k) put(xyz(i, k));
    out += '\n';
  }
  return out;
}

std::string renderTrajectoryPng(const Robot& robot, const SampledTrajectory& tr,
                                const std::string& title) {
  const std::string csv = trajectoryCsv(robot, tr);
  ScratchDir dir;
  const std::string data = dir.file("trajectory.csv"), png = dir.file("trajectory.png");
  const std::string script_path = dir.file("plot.gp"), log = dir.file("gnuplot.log");
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
     << "set output " << quoted(png) << "\n"
     << "set datafile separator ','\n"
     << "set grid\nset key outside right top\n"
     << "set multiplot layout 2,2 title " << quoted(title) << "\n";
  const char* panels[3][2] = {
      {"joint positions", ""}, {"joint velocities", "/s"}, {"joint accelerations", "/s^2"}};
  for (int p = 0; p < 3; ++p) {
    gp << "set title " << quoted(panels[p][0]) << "\n"
       << "set xlabel 't [s]'\nset ylabel " << quoted("[" + jointUnit(panels[p][1]) + "]")
       << "\nplot ";
    for (int j = 0; j < n; ++j) {
      gp << (j ? ", " : "") << quoted(data) << " every ::1 using 1:" << 2 + p * n + j
         << " with lines lw 2 title " << quoted(robot.joints[j].name);
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
       << "set " << axes[k] << "label " << quoted(std::string(axes[k]) + " [" + unit + "]") << "\n";
  }
  gp << "set zlabel rotate parallel\nset view 60,30,1.1\nset xyplane relative 0\n"
     << "set xtics offset -0.5,-0.3\nset ytics offset 0.5,-0.3\n"
     << "splot " << quoted(data) << " every ::1 using " << x << ":" << x + 1 << ":" << x + 2
     << " with lines lw 2 lc rgb '#1f77b4' title 'tool', " << quoted(data) << " every ::1::1 using "
     << x << ":" << x + 1 << ":" << x + 2
     << " with points pt 7 ps 1.5 lc rgb '#2ca02c' title 'start', " << quoted(data)
     << " every ::" << tr.size() << "::" << tr.size() << " using " << x << ":" << x + 1 << ":"
     << x + 2 << " with points pt 7 ps 1.5 lc rgb '#d62728' title 'end'\n"
     << "unset multiplot\n";
  std::ofstream(script_path, std::ios::binary) << gp.str();

  int spawn_errno = 0;
  const int status = runGnuplot(script_path, log, spawn_errno);
  if (status < 0) {
    throw Error(std::string("cannot run gnuplot (package gnuplot-nox): ") +
                std::strerror(spawn_errno ? spawn_errno : errno));
  }
  const std::string bytes = readAll(png);
  if (status != 0 || bytes.rfind("\x89PNG", 0) != 0) {
    const std::string text = readAll(log);
    std::istringstream lines(text);
    std::string line, message;
    while (std::getline(lines, line)) {
      if (!line.empty() && line.find_first_not_of(" \t^") != std::string::npos) message = line;
    }
    throw Error("gnuplot failed (exit " + std::to_string(status) + ")" +
                (message.empty() ? "" : ": " + message));
  }
  return bytes;
}

}  // namespace mcws
