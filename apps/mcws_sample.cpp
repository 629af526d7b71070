// mcws_sample: Monte Carlo workspace sampling of a robot (Yin, Wang & Yu 2010, section 3; Fu, Hu,
// Chen & Pan 2016, eq. (5)), or of a validation shape with known area or volume. Writes a PCD cloud
// of mcws::WorkspacePoint.
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "common/app.h"
#include "common/flags.h"
#include "common/units.h"
#include "mcws/collision/collision_report.h"
#include "mcws/collision/collision_sampler.h"
#include "mcws/distributed/sample_writer.h"
#include "mcws/io/cloud_io.h"
#include "mcws/reach/quality_sampler.h"
#include "mcws/reach/reach_report.h"
#include "mcws/sampling/sample_report.h"
#include "mcws/sampling/sampler.h"

namespace {

using namespace mcws;

constexpr char kUsage[] = "mcws_sample (--robot FILE | --shape NAME) --output FILE [options]";

constexpr char kSummary[] =
    R"(Draws joint values uniformly within their limits (sample i's random numbers depend only on
--seed and i, so the file is the same for any --threads) and writes the tool or flange positions
with the joint values that produced them (fields x y z q1..q8 label) to a PCD file. Joint values
on the command line are in rad (revolute) and in the robot file's length unit (prismatic). With
--shape, samples a region of known size instead: disk (unit disk, z = 0), annulus
(0.5 <= r <= 1, z = 0), ball (unit ball), box (unit cube [-0.5, 0.5]^3), uniform in area or
volume. With --collision, each sample's label is its collision status under the robot file's
collision: model: 0 free, 1 link-link, 2 tool-link (the tool against a link it is not mounted
on), 3 environment; where several hold, the lowest non-zero code (see mcws_collide,
mcws_select). With --quality, each sample also carries the arm's quality there (fields
manipulability, inverse_condition; pcl_viewer colours by them): Yoshikawa's manipulability, the
product of the singular values of the Jacobian at the recorded point, and sigma_min / sigma_max.
--quality-task position measures the point's velocity only (manipulability in length unit^n; a
planar 2R arm's is l1 l2 |sin q2|); full measures the whole twist with the velocity rows divided
by --length L (dimensionless). The default is full with L = the chain's length (the sum of its
offsets) for arms with six or more joints, position for fewer.

Under mpirun (-np K, MPI builds) each process computes a contiguous block of the sample indices
and writes it at its place in one binary PCD file (MPI-IO), which appears, byte for byte the
file of one process, when every process has finished; a failed or killed process leaves no
output. --threads is then per process (0: the cores shared among the processes on a machine).)";

void declareFlags(app::CommandLine& cli) {
  app::declareRobotFlags(cli, "robot description (.yaml or .urdf)");
  cli.addValue("shape", "disk | annulus | ball | box, instead of --robot");
  cli.addValue("samples", "number of samples (default 6000)");
  cli.addValue("seed", "random seed, a whole number >= 0 (default 1)");
  cli.addValue("output", "output PCD file");
  cli.addValues("fix", "pin joints instead of sampling them: name=value[,name=value] (repeatable)");
  cli.addValue("point", "tool | flange: which point to record (default tool)");
  cli.addValue("threads", "worker threads, 0 = all cores (default 0)");
  cli.addSwitch("collision",
                "label each sample by collision (needs a robot YAML with collision: or a URDF with "
                "<collision> elements)");
  cli.addSwitch("quality", "add fields manipulability and inverse_condition (needs --robot)");
  app::declareQualityFlags(cli);
  cli.addSwitch("ascii", "write ASCII PCD instead of binary");
  cli.addSwitch("json", "print a JSON summary on stdout");
}

/// What draws the samples; `checker` (for --collision) outlives `generator`, which refers to it.
struct Source {
  std::unique_ptr<CollisionChecker> checker;
  std::unique_ptr<PointGenerator> generator;
  std::unique_ptr<QualitySampler> quality;  ///< --quality: generator's points with the quality
  nlohmann::json summary;                   ///< what the source adds to --json
  std::optional<io::CloudProvenance> provenance;  ///< the robot, recorded in the cloud's header
};

Source robotSource(const app::CommandLine& cli, std::uint64_t seed, SamplePoint point) {
  Source source;
  const Robot robot = app::readRobot(cli);
  source.provenance = robotProvenance(robot);
  if (robot.dof() > kMaxJoints) {  // the robot file's fault, not --fix's (exit 1)
    throw Error(cli.required("robot") + ": robot '" + robot.name + "' has " +
                std::to_string(robot.dof()) + " joints; a workspace point records at most " +
                std::to_string(kMaxJoints));
  }
  RobotSamplerOptions options;
  options.seed = seed;
  options.point = point;
  for (const std::string& fix : cli.all("fix")) {
    for (const auto& pinned : app::parseAssignments(fix, "fix")) options.fixed.push_back(pinned);
  }
  // How the samples are drawn, so that mcws_refine draws more the same way.
  source.provenance->sampling = io::SamplingRecord{point == SamplePoint::kTool ? "tool" : "flange",
                                                   cli.has("collision"), options.fixed};
  if (cli.has("collision")) {
    source.checker = std::make_unique<CollisionChecker>(
        robot, loadRequiredCollisionModel(robot, cli.required("robot")));
  }
  source.generator = app::asUsageError("fix", [&]() -> std::unique_ptr<PointGenerator> {
    if (source.checker)
      return std::make_unique<LabelledRobotSampler>(robot, options, *source.checker);
    return std::make_unique<RobotSampler>(robot, options);
  });
  source.summary = {{"length_unit", unitName(robot.length_unit)},
                    {"point", point == SamplePoint::kTool ? "tool" : "flange"}};
  addRobotNames(source.summary, robot, point);
  if (cli.has("quality")) {
    const QualityOptions quality = app::readQualityOptions(cli, robot);
    source.quality = std::make_unique<QualitySampler>(robot, options, *source.generator, quality);
    source.summary["quality"] = qualitySummary(quality, robot);
  }
  return source;
}

Source shapeSource(const app::CommandLine& cli, std::uint64_t seed) {
  const std::string name = cli.required("shape");
  const Shape shape = app::asUsageError("shape", [&] { return parseShape(name); });
  Source source;
  source.generator = std::make_unique<ShapeSampler>(shape, seed);
  source.summary = shapeSummary(name, shape);
  addRecordedRobotNames(source.summary, std::nullopt);  // no robot: null
  return source;
}

}  // namespace

int main(int argc, char** argv) {
  distributed::Processes processes(argc, argv);
  return app::run("mcws_sample", processes, [&] {
    app::CommandLine cli(kUsage, kSummary);
    declareFlags(cli);
    if (!cli.parse(argc, argv)) return app::kExitOk;

    const auto samples = static_cast<std::size_t>(app::parseInteger(
        cli.text("samples", "6000"), "samples", 1, std::numeric_limits<int>::max()));
    const std::uint64_t seed = app::readSeed(cli);
    const int threads = distributed::threadsPerProcess(app::readThreads(cli), processes);
    const std::string output = cli.required("output");
    const SamplePoint point = app::readPoint(cli);
    if (cli.has("robot") == cli.has("shape"))
      throw app::UsageError("give one of --robot and --shape");
    if (cli.has("shape") &&
        (cli.has("fix") || cli.has("point") || cli.has("collision") || cli.has("quality")))
      throw app::UsageError("--fix, --point, --collision and --quality need --robot");
    if (cli.has("shape") && (cli.has("base") || cli.has("tip")))
      throw app::UsageError("--base and --tip need --robot");
    if (cli.has("shape") && cli.has("package-path"))
      throw app::UsageError("--package-path needs --robot");
    if (!cli.has("quality") && (cli.has("quality-task") || cli.has("length")))
      throw app::UsageError("--quality-task and --length need --quality");
    if (processes.distributed() && cli.has("ascii"))
      throw app::UsageError("--ascii: several processes write binary PCD only");
    app::checkOutputs({{"output", output}}, {{"robot", cli.text("robot", "")}});

    const Source source = cli.has("robot") ? robotSource(cli, seed, point) : shapeSource(cli, seed);
    // A bad flag or file on any process ends them all here; so does another robot file.
    if (source.provenance) {
      processes.setUpDone({{"robot", source.provenance->sha256}});
    } else {
      processes.setUpDone();
    }
    app::Progress progress("mcws_sample", "samples");  // rank 0 reports its block
    const auto format = cli.has("ascii") ? io::PcdFormat::kAscii : io::PcdFormat::kBinary;
    const auto report = [&](std::size_t done, std::size_t total) { progress.update(done, total); };
    std::optional<io::ScopedProvenance> provenance;  // for the writer inside writeSamples()
    if (source.provenance) provenance.emplace(*source.provenance);
    SampleSummary result;
    if (processes.distributed()) {
      result = source.quality ? distributed::writeSamplesTogether(processes, *source.quality,
                                                                  samples, output, threads, report)
                              : distributed::writeSamplesTogether(processes, *source.generator,
                                                                  samples, output, threads, report);
    } else {
      result = source.quality
                   ? writeSamples(*source.quality, samples, output, format, threads, report)
                   : writeSamples(*source.generator, samples, output, format, threads, report);
    }
    if (processes.rank() != 0) return app::kExitOk;  // rank 0 reports for all

    nlohmann::json summary = source.summary;
    summary["output"] = output;
    summary["points"] = result.points;
    summary["seed"] = seed;
    summary["processes"] = processes.size();
    summary["seconds"] = progress.seconds();
    if (source.checker) summary["labels"] = labelCountsJson(result, samples);
    addBoundingBox(summary, result, summary["length_unit"].get<std::string>());
    summary["units"]["seconds"] = "s";
    if (cli.has("json")) {
      std::cout << summary.dump() << "\n";
    } else {
      std::cerr << "[done, " << static_cast<int>(progress.seconds() * 1000)
                << " ms : " << result.points << " points] -> " << output << "\n";
    }
    return app::kExitOk;
  });
}
