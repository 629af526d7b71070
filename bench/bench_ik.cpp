// IK benchmark (issue 4): mcws::IkSolver / solveIk against orocos-kdl's ChainIkSolverPos_NR_JL and
// ChainIkSolverPos_LMA on the same random reachable poses, the same first guesses and the same
// tolerances. Prints one table row per robot and solver: success rate, mean and 99th-percentile
// time per solve, mean iterations where the solver reports them.
//
// Usage: bench_ik [--kdl-restarts] [POSES [REPEATS [ROBOT ...]]]
//        (defaults: 10000, 5, inspection6 ta1400)
// Times are per solve (including the success check), in CPU time of the benchmark's thread
// (CLOCK_THREAD_CPUTIME_ID, the clock's own cost subtracted), so that time the thread spends
// descheduled on a shared machine does not count. mcws rows: the median over REPEATS runs of the
// same poses; KDL's rows, 50 to 1000 times slower, run once. --kdl-restarts adds KDL wrapped in
// restarts (slow: minutes per robot).
//
// Pose k: a target joint vector drawn uniformly within the limits, its tool pose as the target,
// and an independent joint vector within the limits as every solver's first guess. A solve
// succeeds when the returned joint vector is within the joint limits (revolute joints spanning a
// full turn are wrapped first, as angles) and its tool pose (mcws FK, the same check for all) is
// within 1e-6 [length unit] and 1e-6 rad of the target.
//
// Equal tolerance: mcws stops when |dp| <= 1e-6 and the rotation angle <= 1e-6. KDL NR_JL stops
// when every twist component is below eps, given eps = 1e-6 / sqrt(3) so that its test implies
// ours; KDL LMA stops when |(dp, dw)| < eps (weights L = 1), given eps = 1e-6. KDL's solvers
// make one attempt from the first guess; the "+ restarts" rows wrap them in the restart loop
// mcws uses (up to 20 more attempts from the same seeded random joint vectors), as TRAC-IK does.
#include <time.h>
#include <algorithm>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainiksolverpos_lma.hpp>
#include <kdl/chainiksolverpos_nr_jl.hpp>
#include <kdl/chainiksolvervel_pinv.hpp>
#include <string>
#include <vector>

#include "kinematics/kdl_chain.h"
#include "mcws/core/counter_rng.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/inverse_kinematics.h"
#include "mcws/kinematics/robot_yaml.h"

namespace {

using mcws::Robot;

constexpr double kTolerance = 1e-6;  // [length unit] and [rad]
constexpr int kRestarts = 20;        // mcws's default
constexpr std::uint64_t kSeed = 1;   // mcws's default

struct Case {
  Eigen::VectorXd q_target, q_seed;
  Eigen::Isometry3d T_target;
};

Eigen::VectorXd randomJoints(const Robot& robot, const mcws::CounterRng& rng, std::uint64_t index) {
  Eigen::VectorXd q(robot.dof());
  for (int j = 0; j < robot.dof(); ++j) {
    const mcws::Joint& joint = robot.joints[j];
    q[j] = joint.lower + (joint.upper - joint.lower) * rng.uniform(index, j);
  }
  return q;
}

/// Wraps full-turn revolute joints into their limits, then checks limits and pose error.
bool succeeded(const Robot& robot, Eigen::VectorXd q, const Eigen::Isometry3d& T_target) {
  if (q.size() != robot.dof() || !q.allFinite()) return false;
  for (int j = 0; j < robot.dof(); ++j) {
    const mcws::Joint& joint = robot.joints[j];
    if (joint.type == mcws::JointType::kRevolute && joint.upper - joint.lower >= 2 * M_PI - 1e-9) {
      while (q[j] > joint.upper) q[j] -= 2 * M_PI;
      while (q[j] < joint.lower) q[j] += 2 * M_PI;
    }
    if (q[j] < joint.lower || q[j] > joint.upper) return false;
  }
  const Eigen::Isometry3d T = mcws::toolPose(robot, q);
  const double dp = (T.translation() - T_target.translation()).norm();
  const double dw = Eigen::AngleAxisd(T_target.linear() * T.linear().transpose()).angle();
  return dp <= kTolerance && dw <= kTolerance;
}

KDL::Frame toKdl(const Eigen::Isometry3d& T) {
  KDL::Frame F;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) F.M(r, c) = T(r, c);
    F.p[r] = T(r, 3);
  }
  return F;
}

/// One solver: (case, first guess) -> joint vector (empty when the solver reported failure).
using Solve = std::function<Eigen::VectorXd(const Case&, const Eigen::VectorXd&)>;

struct Row {
  std::string name;
  double success{0}, mean_us{0}, p99_us{0};
};

/// CPU time of this thread [us].
double threadMicros() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e6 * static_cast<double>(t.tv_sec) + 1e-3 * static_cast<double>(t.tv_nsec);
}

/// Cost of reading the clock twice [us], subtracted from every timing.
double clockCost() {
  std::vector<double> costs;
  for (int i = 0; i < 1000; ++i) {
    const double start = threadMicros();
    costs.push_back(threadMicros() - start);
  }
  std::sort(costs.begin(), costs.end());
  return costs[costs.size() / 2];
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

/// Runs `solve` on every case, `repeats` times; restarts > 0 wraps it in the restart loop.
Row measure(const std::string& name, const Robot& robot, const std::vector<Case>& cases,
            int repeats, int restarts, const Solve& solve) {
  const mcws::CounterRng rng(kSeed);
  static const double clock_cost = clockCost();
  std::vector<double> means, p99s;
  Row row;
  row.name = name;
  for (int rep = 0; rep < repeats; ++rep) {
    std::vector<double> times;
    times.reserve(cases.size());
    int successes = 0;
    for (const Case& c : cases) {
      const double start = threadMicros();
      bool ok = false;
      for (int attempt = 0; attempt <= restarts && !ok; ++attempt) {
        const Eigen::VectorXd q_first =
            attempt == 0 ? c.q_seed : randomJoints(robot, rng, static_cast<std::uint64_t>(attempt));
        const Eigen::VectorXd q = solve(c, q_first);
        ok = q.size() > 0 && succeeded(robot, q, c.T_target);
      }
      times.push_back(threadMicros() - start - clock_cost);
      successes += ok;
    }
    double sum = 0;
    for (double t : times) sum += t;
    means.push_back(sum / times.size());
    std::sort(times.begin(), times.end());
    p99s.push_back(times[static_cast<std::size_t>(0.99 * (times.size() - 1))]);
    row.success = 100.0 * successes / cases.size();
  }
  row.mean_us = median(means);
  row.p99_us = median(p99s);
  return row;
}

void benchRobot(const std::string& robot_name, int poses, int repeats, bool kdl_restarts) {
  const std::string path = std::string(MCWS_ROBOTS_DIR) + "/" + robot_name + ".yaml";
  const Robot robot = mcws::loadRobot(path);
  const KDL::Chain chain = mcws::test::kdlChainFromFile(path);
  const int n = robot.dof();

  // The same cases for every solver; target and first guess from separate counter streams.
  const mcws::CounterRng targets(2024), guesses(4048);
  std::vector<Case> cases;
  for (int k = 0; k < poses; ++k) {
    Case c;
    c.q_target = randomJoints(robot, targets, k);
    c.q_seed = randomJoints(robot, guesses, k);
    c.T_target = mcws::toolPose(robot, c.q_target);
    cases.push_back(c);
  }

  mcws::IkOptions options;
  options.position_tolerance = kTolerance;
  options.orientation_tolerance = kTolerance;
  options.seed = kSeed;
  // Prepared once, as KDL's solvers below.
  const mcws::IkSolver solver(robot);
  std::vector<Row> rows;
  rows.push_back(measure("mcws IkSolver (20 restarts)", robot, cases, repeats, 0,
                         [&](const Case& c, const Eigen::VectorXd& q0) {
                           const mcws::IkResult r = solver.solve(c.T_target, q0, options);
                           return r.converged() ? r.q : Eigen::VectorXd();
                         }));
  mcws::IkOptions single = options;
  single.restarts = 0;
  rows.push_back(measure("mcws IkSolver, no restarts", robot, cases, repeats, 0,
                         [&](const Case& c, const Eigen::VectorXd& q0) {
                           const mcws::IkResult r = solver.solve(c.T_target, q0, single);
                           return r.converged() ? r.q : Eigen::VectorXd();
                         }));

  KDL::JntArray q_min(n), q_max(n);
  q_min.data = robot.lowerLimits();
  q_max.data = robot.upperLimits();
  KDL::ChainFkSolverPos_recursive fk(chain);
  KDL::ChainIkSolverVel_pinv vel(chain);
  KDL::ChainIkSolverPos_NR_JL nr_jl(chain, q_min, q_max, fk, vel, 100, kTolerance / std::sqrt(3.0));
  Eigen::Matrix<double, 6, 1> L = Eigen::Matrix<double, 6, 1>::Ones();
  KDL::ChainIkSolverPos_LMA lma(chain, L, kTolerance, 500);
  auto kdl = [&](KDL::ChainIkSolverPos& solver) {
    return [&solver, n](const Case& c, const Eigen::VectorXd& q0) {
      KDL::JntArray q_init(n), q_out(n);
      q_init.data = q0;
      return solver.CartToJnt(q_init, toKdl(c.T_target), q_out) >= 0 ? Eigen::VectorXd(q_out.data)
                                                                     : Eigen::VectorXd();
    };
  };
  rows.push_back(measure("mcws solveIk (20 restarts, prepares per call)", robot, cases, repeats, 0,
                         [&](const Case& c, const Eigen::VectorXd& q0) {
                           const mcws::IkResult r = mcws::solveIk(robot, c.T_target, q0, options);
                           return r.converged() ? r.q : Eigen::VectorXd();
                         }));
  rows.push_back(measure("KDL NR_JL", robot, cases, 1, 0, kdl(nr_jl)));
  rows.push_back(measure("KDL LMA", robot, cases, 1, 0, kdl(lma)));
  if (kdl_restarts) {
    rows.push_back(measure("KDL NR_JL + 20 restarts", robot, cases, 1, kRestarts, kdl(nr_jl)));
    rows.push_back(measure("KDL LMA + 20 restarts", robot, cases, 1, kRestarts, kdl(lma)));
  }

  for (const Row& row : rows) {
    std::printf("| %s | %s | %.2f %% | %.1f | %.1f |\n", robot_name.c_str(), row.name.c_str(),
                row.success, row.mean_us, row.p99_us);
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  const bool kdl_restarts = !args.empty() && args[0] == "--kdl-restarts";
  if (kdl_restarts) args.erase(args.begin());
  const int poses = args.size() > 0 ? std::atoi(args[0].c_str()) : 10000;
  const int repeats = args.size() > 1 ? std::atoi(args[1].c_str()) : 5;
  std::vector<std::string> robots(args.begin() + std::min<std::size_t>(2, args.size()), args.end());
  if (robots.empty()) robots = {"inspection6", "ta1400"};
  if (poses < 1 || repeats < 1) {
    std::fprintf(stderr, "usage: bench_ik [--kdl-restarts] [POSES [REPEATS [ROBOT ...]]]\n");
    return 2;
  }
  std::printf(
      "%d poses per robot, tolerance %g [length unit] and %g rad; mcws: median of %d runs\n\n",
      poses, kTolerance, kTolerance, repeats);
  std::printf("| robot | solver | success | mean us | p99 us |\n|---|---|---|---|---|\n");
  std::fflush(stdout);
  for (const std::string& robot : robots) benchRobot(robot, poses, repeats, kdl_restarts);
  return 0;
}
