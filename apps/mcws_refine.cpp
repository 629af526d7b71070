// mcws_refine: boundary refinement (Liu et al. 2013): new samples in
// small joint-space neighbourhoods of the configurations that produced boundary points.
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <numeric>

#include "common/app.h"
#include "common/cloud_io.h"
#include "common/flags.h"
#include "mcws/distributed/sample_writer.h"
#include "mcws/io/provenance.h"
#include "mcws/workspace/refine.h"

namespace {

constexpr char kUsage[] =
    "mcws_refine --robot FILE --input boundary.pcd --samples K --output FILE [options]";

constexpr char kSummary[] =
    R"(Draws K new samples near the boundary points' joint values (fields q1..qn, as mcws_sample
writes them and mcws_boundary keeps them): sample i moves each joint of boundary point i mod P by
up to --spread times the joint's range, clamped to its limits. Joints with one value in every
boundary point (pinned by mcws_sample --fix) keep it. With --cloud, the output is that cloud
followed by the new samples: the refined cloud to pass to mcws_boundary and mcws_measure. Same
--seed, same output, for any --threads. A cloud whose header records the robot it was made from
(name and SHA-256 of the robot file, as mcws_sample writes it) must come from the --robot file;
the output records that robot.

Under mpirun (-np K, MPI builds) each process computes a contiguous block of the new samples and
writes it at its place in one PCD file (MPI-IO; rank 0 alone reads --cloud and writes it), which
appears, byte for byte the file of one process, when every process has finished; a failed or
killed process leaves no output. --threads is then per process (0: the cores shared among the
processes on a machine).)";

void declareFlags(mcws::app::CommandLine& cli) {
  cli.addValue("robot", "robot description the cloud was sampled from (.yaml or .urdf)");
  cli.addValue("input", "boundary points (PCD with q1..qn)");
  cli.addValue("samples", "number of new samples K");
  cli.addValue("output", "output PCD file");
  cli.addValue("cloud", "cloud to copy into the output before the new samples");
  cli.addValue(
      "spread",
      "neighbourhood half-width, a fraction of each joint's range in (0, 1] (default 0.1)");
  cli.addValue("point", "tool | flange, as sampled (default tool)");
  cli.addValue("seed", "random seed, a whole number >= 0 (default 1)");
  cli.addValue("threads", "worker threads, 0 = all cores (default 0)");
  cli.addSwitch("json", "print a JSON summary on stdout");
}

}  // namespace

int main(int argc, char** argv) {
  using namespace mcws;
  distributed::Processes processes(argc, argv);
  return app::run("mcws_refine", processes, [&] {
    app::CommandLine cli(kUsage, kSummary);
    declareFlags(cli);
    if (!cli.parse(argc, argv)) return app::kExitOk;

    const auto samples = static_cast<std::size_t>(
        app::parseInteger(cli.required("samples"), "samples", 1, std::numeric_limits<int>::max()));
    RefineOptions options;
    options.seed = app::readSeed(cli);
    options.spread = app::parseNumber(cli.text("spread", "0.1"), "spread");
    if (!(options.spread > 0.0 && options.spread <= 1.0))
      throw app::UsageError("--spread: " + cli.text("spread", "") + " is not in (0, 1]");
    options.point = app::readPoint(cli);
    const int threads = app::threadsPerProcess(app::readThreads(cli), processes);
    const std::string output = cli.required("output");
    app::checkOutputs({{"output", output}}, {{"robot", cli.required("robot")},
                                             {"input", cli.required("input")},
                                             {"cloud", cli.text("cloud", "")}});

    const Robot robot = app::readRobot(cli);
    const io::CloudProvenance provenance = app::robotProvenance(robot);
    for (const char* flag : {"input", "cloud"}) {
      if (cli.has(flag)) {
        const std::string path = cli.required(flag);
        app::requireSameRobot(flag, path, app::readProvenance(path), provenance);
      }
    }
    const auto boundary = app::loadCloud(cli.required("input"));
    const RefineSampler sampler(robot, *boundary, options);
    // Several processes: rank 0 alone holds the copied cloud and writes it.
    const bool holds_cloud = cli.has("cloud") && processes.rank() == 0;
    const auto refined = holds_cloud ? app::loadCloud(cli.required("cloud"))
                                     : std::make_shared<app::WorkspaceCloud>();
    // A bad flag or file on any process ends them all here; so do other robot or input files.
    processes.setUpDone(
        {{"robot", provenance.sha256}, {"input", io::sha256OfFile(cli.required("input"))}});
    const std::size_t kept = processes.broadcast(static_cast<std::uint64_t>(refined->size()));
    app::Progress progress("mcws_refine", "samples");  // rank 0 reports its block
    const auto report = [&](std::size_t done, std::size_t total) { progress.update(done, total); };
    if (processes.distributed()) {
      distributed::writeSamplesTogether(processes, sampler, samples, output, threads, report,
                                        provenance, refined->data(), kept);
    } else {
      refined->resize(kept + samples);
      generateInChunks(sampler, samples, refined->data() + kept, threads, report);
      pcl::Indices all(refined->size());
      std::iota(all.begin(), all.end(), 0);
      app::saveCloud(*refined, all, output, provenance);
    }
    if (processes.rank() != 0) return app::kExitOk;  // rank 0 reports for all

    if (cli.has("json")) {
      nlohmann::json summary{{"robot", robot.name},
                             {"boundary_points", boundary->size()},
                             {"samples", samples},
                             {"copied", kept},
                             {"points", kept + samples},
                             {"spread", options.spread},
                             {"length_unit", unitName(robot.length_unit)},
                             {"pinned", sampler.pinnedJoints()},
                             {"seed", options.seed},
                             {"output", output},
                             {"processes", processes.size()},
                             {"seconds", progress.seconds()},
                             {"units", {{"spread", "joint ranges"}, {"seconds", "s"}}}};
      std::cout << summary.dump() << "\n";
    } else {
      std::cerr << "[done, " << static_cast<int>(progress.seconds() * 1000) << " ms : " << samples
                << " new samples near " << boundary->size() << " boundary points, "
                << kept + samples << " points] -> " << output << "\n";
    }
    return app::kExitOk;
  });
}
