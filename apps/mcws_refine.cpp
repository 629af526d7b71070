// mcws_refine: boundary refinement (Liu et al. 2013, seed 002's reference [8]): new samples in
// small joint-space neighbourhoods of the configurations that produced boundary points.
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <numeric>

#include "common/app.h"
#include "common/cloud_io.h"
#include "mcws/kinematics/robot_yaml.h"
#include "mcws/workspace/refine.h"

int main(int argc, char** argv) {
  using namespace mcws;
  return app::run("mcws_refine", [&] {
    app::CommandLine cli(
        "mcws_refine --robot FILE --input boundary.pcd --samples K --output FILE [options]",
        "Draws K new samples near the boundary points' joint values (fields q1..qn, as\n"
        "mcws_sample writes them and mcws_boundary keeps them): sample i moves each joint of\n"
        "boundary point i mod P by up to --spread times the joint's range, clamped to its limits.\n"
        "Joints with one value in every boundary point (pinned by mcws_sample --fix) keep it.\n"
        "With --cloud, the output is that cloud followed by the new samples: the refined cloud\n"
        "to pass to mcws_boundary and mcws_measure. Same --seed, same output, for any --threads.");
    cli.add()("robot", app::po::value<std::string>(),
              "robot description the cloud was sampled from")(
        "input", app::po::value<std::string>(), "boundary points (PCD with q1..qn)")(
        "samples", app::po::value<std::string>(), "number of new samples K")(
        "output", app::po::value<std::string>(), "output PCD file")(
        "cloud", app::po::value<std::string>(),
        "cloud to copy into the output before the new samples")(
        "spread", app::po::value<std::string>(),
        "neighbourhood half-width, a fraction of each joint's range in (0, 1] (default 0.1)")(
        "point", app::po::value<std::string>(), "tool | flange, as sampled (default tool)")(
        "seed", app::po::value<std::string>(), "random seed, a whole number >= 0 (default 1)")(
        "threads", app::po::value<std::string>(), "worker threads, 0 = all cores (default 0)")(
        "json", "print a JSON summary on stdout");
    if (!cli.parse(argc, argv)) return app::kExitOk;

    const auto samples =
        app::parseInteger(cli.required("samples"), "samples", 1, std::numeric_limits<int>::max());
    RefineOptions options;
    options.seed = static_cast<std::uint64_t>(app::parseInteger(
        cli.text("seed", "1"), "seed", 0, std::numeric_limits<std::int64_t>::max()));
    options.spread = app::parseNumber(cli.text("spread", "0.1"), "spread");
    if (!(options.spread > 0.0 && options.spread <= 1.0))
      throw app::UsageError("--spread: " + cli.text("spread", "") + " is not in (0, 1]");
    const std::string point = cli.text("point", "tool");
    if (point != "tool" && point != "flange")
      throw app::UsageError("--point: '" + point + "' is not tool or flange");
    options.point = point == "tool" ? SamplePoint::kTool : SamplePoint::kFlange;
    const auto threads = app::parseInteger(cli.text("threads", "0"), "threads", 0, 256);
    const std::string output = cli.required("output");

    const Robot robot = loadRobot(cli.required("robot"));
    const auto boundary = app::loadCloud(cli.required("input"));
    const RefineSampler sampler(robot, *boundary, options);
    const auto refined = cli.has("cloud") ? app::loadCloud(cli.required("cloud"))
                                          : std::make_shared<app::WorkspaceCloud>();
    const std::size_t kept = refined->size();
    refined->resize(kept + static_cast<std::size_t>(samples));
    app::Progress progress("mcws_refine", "samples");
    constexpr std::size_t kChunk = 1u << 18;
    for (std::size_t done = 0; done < static_cast<std::size_t>(samples); done += kChunk) {
      const std::size_t count = std::min<std::size_t>(kChunk, samples - done);
      generateParallel(sampler, done, count, refined->data() + kept + done,
                       static_cast<int>(threads));
      progress.update(done + count, static_cast<std::size_t>(samples));
    }
    pcl::Indices all(refined->size());
    std::iota(all.begin(), all.end(), 0);
    app::saveCloud(*refined, all, output);

    if (cli.has("json")) {
      nlohmann::json summary{{"robot", robot.name},
                             {"boundary_points", boundary->size()},
                             {"samples", samples},
                             {"copied", kept},
                             {"points", refined->size()},
                             {"spread", options.spread},
                             {"pinned", sampler.pinnedJoints()},
                             {"seed", options.seed},
                             {"output", output},
                             {"seconds", progress.seconds()}};
      std::cout << summary.dump() << "\n";
    } else {
      std::cerr << "[done, " << static_cast<int>(progress.seconds() * 1000) << " ms : " << samples
                << " new samples near " << boundary->size() << " boundary points, "
                << refined->size() << " points] -> " << output << "\n";
    }
    return app::kExitOk;
  });
}
