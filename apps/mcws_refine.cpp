// mcws_refine: boundary refinement (Liu et al. 2013): new samples in
// small joint-space neighbourhoods of the configurations that produced boundary points.
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <numeric>
#include <optional>

#include "common/app.h"
#include "common/flags.h"
#include "mcws/collision/collision_checker.h"
#include "mcws/collision/collision_model.h"
#include "mcws/collision/collision_sampler.h"
#include "mcws/distributed/sample_writer.h"
#include "mcws/io/cloud_io.h"
#include "mcws/io/provenance.h"
#include "mcws/workspace/refine.h"
#include "mcws/workspace/refine_inputs.h"
#include "mcws/workspace/refine_report.h"

namespace {

constexpr char kUsage[] =
    "mcws_refine --robot FILE --input boundary.pcd --samples K --output FILE [options]";

constexpr char kSummary[] =
    R"(Draws K new samples near the boundary points' joint values (fields q1..qn, as mcws_sample
writes them and mcws_boundary keeps them): sample i moves each joint of boundary point i mod P by
up to --spread times the joint's range, clamped to its limits. The new samples are drawn as the
cloud's were, as its header records it (mcws_sample writes point=, collision=, fix=; mcws_boundary
keeps them): at the same point (tool or flange; a different --point is refused), with the same
joints pinned at the same values, and with --collision labels from the robot file's collision
model. A cloud that does not record this (other tools, mcws before the record) or has no joint
fields (a mcws_reach map) is refused. With --cloud, the output is that cloud
followed by the new samples: the refined cloud to pass to mcws_boundary and mcws_measure. Same
--seed, same output, for any --threads. A cloud whose header records the robot it was made from
(name and SHA-256 of the robot file, as mcws_sample writes it) must come from the --robot file;
the output records that robot.
With --collision (a cloud of mcws_sample --collision), only the --input points labelled free
are parents (--label: those of another label), so that the edge of the collision-free region,
where free samples meet colliding ones, fills in: pass the boundary of the free points
(mcws_select --label 0, then mcws_boundary), and repeat on the refined cloud's. The new samples
are labelled as the cloud's were, whatever their parents'. A cloud with no label field, or
sampled without --collision, is refused.

Under mpirun (-np K, MPI builds) each process computes a contiguous block of the new samples and
writes it at its place in one PCD file (MPI-IO; rank 0 alone reads --cloud and writes it), which
appears, byte for byte the file of one process, when every process has finished; a failed or
killed process leaves no output. --threads is then per process (0: the cores shared among the
processes on a machine).)";

void declareFlags(mcws::app::CommandLine& cli) {
  mcws::app::declareRobotFlags(cli,
                               "robot description the cloud was sampled from (.yaml or .urdf)");
  cli.addValue("input", "boundary points (PCD with q1..qn)");
  cli.addValue("samples", "number of new samples K");
  cli.addValue("output", "output PCD file");
  cli.addValue("cloud", "cloud to copy into the output before the new samples");
  cli.addValue(
      "spread",
      "neighbourhood half-width, a fraction of each joint's range in (0, 1] (default 0.1)");
  cli.addValue("point", "tool | flange: must be the point the cloud records (default: that one)");
  cli.addValue("seed", "random seed, a whole number >= 0 (default 1)");
  cli.addValue("threads", "worker threads, 0 = all cores (default 0)");
  cli.addSwitch("collision",
                "refine only the boundary of the collision-free region: the --input points "
                "labelled free (a cloud of mcws_sample --collision)");
  cli.addValue("label",
               "with --collision, the region refined instead: link-link, tool-link or "
               "environment (or the label's code; default free)");
  cli.addSwitch("json", "print a JSON summary on stdout");
}

/// --label (with --collision): a collision label by its name (labelName()) or its code.
std::uint32_t readLabel(const mcws::app::CommandLine& cli) {
  if (cli.has("label") && !cli.has("collision"))
    throw mcws::app::UsageError("--label needs --collision");
  const std::string text = cli.text("label", "free");
  for (std::uint32_t code = mcws::kLabelFree; code <= mcws::kLabelEnvironment; ++code) {
    if (text == mcws::labelName(code) || text == std::to_string(code)) return code;
  }
  throw mcws::app::UsageError("--label: '" + text +
                              "' is not free, link-link, tool-link or environment (or 0 to 3)");
}

mcws::RefineOptions readOptions(const mcws::app::CommandLine& cli) {
  mcws::RefineOptions options;
  options.seed = mcws::app::readSeed(cli);
  options.spread = mcws::app::parseNumber(cli.text("spread", "0.1"), "spread");
  if (!(options.spread > 0.0 && options.spread <= 1.0))
    throw mcws::app::UsageError("--spread: " + cli.text("spread", "") + " is not in (0, 1]");
  return options;
}

/// Sets the point and the pinned joints of `options` to the cloud's; a --point other than the
/// recorded one is refused.
void drawAsRecorded(const mcws::app::CommandLine& cli, const mcws::io::SamplingRecord& sampling,
                    mcws::SamplePoint asked_point, mcws::RefineOptions& options) {
  using mcws::SamplePoint;
  const SamplePoint recorded_point =
      sampling.point == "flange" ? SamplePoint::kFlange : SamplePoint::kTool;
  if (cli.has("point") && asked_point != recorded_point) {
    throw mcws::app::UsageError("--point " + cli.required("point") + ": --input '" +
                                cli.required("input") + "' was sampled at the " + sampling.point +
                                " (point=" + sampling.point +
                                "); leave out --point to refine it there");
  }
  options.point = recorded_point;
  options.fixed = sampling.fixed;
}

/// The parents: the --input points, with --collision only those of the label refined.
mcws::io::WorkspaceCloud::Ptr parentsOf(const mcws::app::CommandLine& cli,
                                        mcws::io::WorkspaceCloud::Ptr input,
                                        const mcws::io::SamplingRecord& sampling,
                                        std::uint32_t label) {
  if (!cli.has("collision")) return input;
  return mcws::labelledParents({"input", cli.required("input")}, *input, sampling, label,
                               mcws::labelName(label))
      .makeShared();
}

void printSummary(const mcws::app::CommandLine& cli, const mcws::Robot& robot,
                  std::size_t boundary_points, std::size_t samples, std::size_t kept,
                  const mcws::RefineOptions& options, const std::vector<std::string>& pinned,
                  const mcws::io::SamplingRecord& sampling, int processes, double seconds) {
  const std::string output = cli.required("output");
  if (cli.has("json")) {
    nlohmann::json summary =
        mcws::refineSummary(robot, boundary_points, samples, kept, options, pinned, sampling);
    if (cli.has("collision")) summary["label"] = mcws::labelName(readLabel(cli));
    summary["output"] = output;
    summary["processes"] = processes;
    summary["seconds"] = seconds;
    summary["units"]["seconds"] = "s";
    std::cout << summary.dump() << "\n";
  } else {
    std::cerr << "[done, " << static_cast<int>(seconds * 1000) << " ms : " << samples
              << " new samples near " << boundary_points << " boundary points"
              << (cli.has("collision") ? std::string(" labelled ") + mcws::labelName(readLabel(cli))
                                       : "")
              << ", " << kept + samples << " points] -> " << output << "\n";
  }
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
    RefineOptions options = readOptions(cli);
    const SamplePoint asked_point = app::readPoint(cli);  // checked now; compared below
    const std::uint32_t label = readLabel(cli);
    const int threads = distributed::threadsPerProcess(app::readThreads(cli), processes);
    const std::string output = cli.required("output");
    app::checkOutputs({{"output", output}}, {{"robot", cli.required("robot")},
                                             {"input", cli.required("input")},
                                             {"cloud", cli.text("cloud", "")}});

    const Robot robot = app::readRobot(cli);
    io::CloudProvenance provenance = robotProvenance(robot);
    const auto input = io::readCloud(cli.required("input"));
    std::vector<RefineCloud> clouds{{"input", cli.required("input")}};
    if (cli.has("cloud")) clouds.emplace_back("cloud", cli.required("cloud"));
    recordRefineSampling(clouds, robot.dof(), provenance);
    // New samples are drawn as the cloud's were: the same point, pinned joints and labels.
    const io::SamplingRecord& sampling = *provenance.sampling;
    drawAsRecorded(cli, sampling, asked_point, options);
    const io::WorkspaceCloud::Ptr boundary = parentsOf(cli, input, sampling, label);
    const RefineSampler refine(robot, *boundary, options);
    std::unique_ptr<CollisionChecker> checker;
    std::unique_ptr<LabelledSampler<RefineSampler>> labelled;
    if (sampling.collision) {
      checker = std::make_unique<CollisionChecker>(
          robot, loadRequiredCollisionModel(robot, cli.required("robot")));
      labelled = std::make_unique<LabelledSampler<RefineSampler>>(refine, *checker);
    }
    const PointGenerator& sampler = labelled ? static_cast<const PointGenerator&>(*labelled)
                                             : static_cast<const PointGenerator&>(refine);
    // Several processes: rank 0 alone holds the copied cloud and writes it.
    const bool holds_cloud = cli.has("cloud") && processes.rank() == 0;
    const auto refined =
        holds_cloud ? io::readCloud(cli.required("cloud")) : std::make_shared<io::WorkspaceCloud>();
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
      io::writeCloud(*refined, all, output, provenance);
    }
    if (processes.rank() != 0) return app::kExitOk;  // rank 0 reports for all

    printSummary(cli, robot, boundary->size(), samples, kept, options, refine.pinnedJoints(),
                 sampling, processes.size(), progress.seconds());
    return app::kExitOk;
  });
}
