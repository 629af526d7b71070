// mcws_refine: boundary refinement (Liu et al. 2013): new samples in
// small joint-space neighbourhoods of the configurations that produced boundary points.
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <numeric>

#include "common/app.h"
#include "common/cloud_io.h"
#include "common/flags.h"
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
the output records that robot.)";

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
  return app::run("mcws_refine", [&] {
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
    const int threads = app::readThreads(cli);
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
    const auto refined = cli.has("cloud") ? app::loadCloud(cli.required("cloud"))
                                          : std::make_shared<app::WorkspaceCloud>();
    const std::size_t kept = refined->size();
    refined->resize(kept + samples);
    app::Progress progress("mcws_refine", "samples");
    generateInChunks(sampler, samples, refined->data() + kept, threads,
                     [&](std::size_t done, std::size_t total) { progress.update(done, total); });
    pcl::Indices all(refined->size());
    std::iota(all.begin(), all.end(), 0);
    app::saveCloud(*refined, all, output, provenance);

    if (cli.has("json")) {
      nlohmann::json summary{{"robot", robot.name},
                             {"boundary_points", boundary->size()},
                             {"samples", samples},
                             {"copied", kept},
                             {"points", refined->size()},
                             {"spread", options.spread},
                             {"length_unit", unitName(robot.length_unit)},
                             {"pinned", sampler.pinnedJoints()},
                             {"seed", options.seed},
                             {"output", output},
                             {"seconds", progress.seconds()},
                             {"units", {{"spread", "joint ranges"}, {"seconds", "s"}}}};
      std::cout << summary.dump() << "\n";
    } else {
      std::cerr << "[done, " << static_cast<int>(progress.seconds() * 1000) << " ms : " << samples
                << " new samples near " << boundary->size() << " boundary points, "
                << refined->size() << " points] -> " << output << "\n";
    }
    return app::kExitOk;
  });
}
