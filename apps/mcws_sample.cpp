// mcws_sample: Monte Carlo workspace sampling of a robot (seed 000 section 3, seed 002 eq. (5)),
// or of a validation shape with known area or volume. Writes a PCD cloud of mcws::WorkspacePoint.
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>

#include "common/app.h"
#include "mcws/collision/collision_sampler.h"
#include "mcws/kinematics/robot_yaml.h"
#include "mcws/workspace/sampler.h"

namespace {
constexpr std::int64_t kMaxThreads = 256;  ///< more is a typing mistake, not a machine
}

int main(int argc, char** argv) {
  using namespace mcws;
  return app::run("mcws_sample", [&] {
    app::CommandLine cli(
        "mcws_sample (--robot FILE | --shape NAME) --output FILE [options]",
        "Draws joint values uniformly within their limits (sample i's random numbers depend only "
        "on\n"
        "--seed and i, so the file is the same for any --threads) and writes the tool or flange\n"
        "positions with the joint values that produced them (fields x y z q1..q8 label) to a PCD\n"
        "file. Joint values on the command line are in rad (revolute) and in the robot file's\n"
        "length unit (prismatic). With --shape, samples a region of known size instead: disk\n"
        "(unit disk, z = 0), annulus (0.5 <= r <= 1, z = 0), ball (unit ball), box (unit cube\n"
        "[-0.5, 0.5]^3), uniform in area or volume. With --collision, each sample's label is\n"
        "its collision status under the robot file's collision: model: 0 free, 1 link-link,\n"
        "2 tool-link (the tool against a link it is not mounted on), 3 environment; where\n"
        "several hold, the lowest non-zero code (see mcws_collide, mcws_select).");
    cli.add()("robot", app::po::value<std::string>(), "robot description (.yaml)")(
        "shape", app::po::value<std::string>(), "disk | annulus | ball | box, instead of --robot")(
        "samples", app::po::value<std::string>(), "number of samples (default 6000)")(
        "seed", app::po::value<std::string>(), "random seed, a whole number >= 0 (default 1)")(
        "output", app::po::value<std::string>(), "output PCD file")(
        "fix", app::po::value<std::vector<std::string>>(),
        "pin joints instead of sampling them: name=value[,name=value] (repeatable)")(
        "point", app::po::value<std::string>(),
        "tool | flange: which point to record (default tool)")(
        "threads", app::po::value<std::string>(), "worker threads, 0 = all cores (default 0)")(
        "collision", "label each sample by collision (needs --robot with collision:)")(
        "ascii", "write ASCII PCD instead of binary")("json", "print a JSON summary on stdout");
    if (!cli.parse(argc, argv)) return app::kExitOk;

    const auto samples = app::parseInteger(cli.text("samples", "6000"), "samples", 1,
                                           std::numeric_limits<int>::max());
    const auto seed = app::parseInteger(cli.text("seed", "1"), "seed", 0,
                                        std::numeric_limits<std::int64_t>::max());
    const auto threads = app::parseInteger(cli.text("threads", "0"), "threads", 0, kMaxThreads);
    const std::string output = cli.required("output");
    const std::string point = cli.text("point", "tool");
    if (point != "tool" && point != "flange") {
      throw app::UsageError("--point: '" + point + "' is not tool or flange");
    }
    if (cli.has("robot") == cli.has("shape"))
      throw app::UsageError("give one of --robot and --shape");
    if (cli.has("shape") && (cli.has("fix") || cli.has("point") || cli.has("collision"))) {
      throw app::UsageError("--fix, --point and --collision need --robot");
    }

    std::unique_ptr<PointGenerator> generator;
    std::unique_ptr<CollisionChecker> checker;
    nlohmann::json summary;
    if (cli.has("robot")) {
      const Robot robot = loadRobot(cli.required("robot"));
      RobotSamplerOptions options;
      options.seed = static_cast<std::uint64_t>(seed);
      options.point = point == "tool" ? SamplePoint::kTool : SamplePoint::kFlange;
      for (const std::string& fix : cli.all("fix")) {
        for (const auto& pinned : app::parseAssignments(fix, "fix"))
          options.fixed.push_back(pinned);
      }
      if (cli.has("collision")) {
        const CollisionModel model = loadCollisionModel(robot, cli.required("robot"));
        if (!hasGeometry(model))
          throw Error(cli.required("robot") + ": has no collision geometry (collision: key)");
        checker = std::make_unique<CollisionChecker>(robot, model);
      }
      try {
        if (checker) {
          generator = std::make_unique<LabelledRobotSampler>(robot, options, *checker);
        } else {
          generator = std::make_unique<RobotSampler>(robot, options);
        }
      } catch (const Error& e) {
        throw app::UsageError(std::string("--fix: ") + e.what());
      }
      summary["robot"] = robot.name;
      summary["unit"] = unitName(robot.length_unit);
      summary["point"] = point;
    } else {
      const std::string name = cli.required("shape");
      Shape shape;
      try {
        shape = parseShape(name);
      } catch (const Error& e) {
        throw app::UsageError(std::string("--shape: ") + e.what());
      }
      generator = std::make_unique<ShapeSampler>(shape, static_cast<std::uint64_t>(seed));
      summary["shape"] = name;
      summary[shapeIsPlanar(shape) ? "area" : "volume"] = shapeMeasure(shape);
    }

    app::Progress progress("mcws_sample", "samples");
    const SampleSummary result =
        writeSamples(*generator, static_cast<std::size_t>(samples), output,
                     cli.has("ascii") ? io::PcdFormat::kAscii : io::PcdFormat::kBinary,
                     static_cast<int>(threads),
                     [&](std::size_t done, std::size_t total) { progress.update(done, total); });

    summary["output"] = output;
    summary["points"] = result.points;
    summary["seed"] = seed;
    summary["seconds"] = progress.seconds();
    if (checker) {
      for (std::uint32_t label : {kLabelFree, kLabelLinkLink, kLabelToolLink, kLabelEnvironment}) {
        const auto found = result.label_counts.find(label);
        const std::size_t count = found == result.label_counts.end() ? 0 : found->second;
        summary["labels"][labelName(label)] = {
            {"label", label}, {"count", count}, {"fraction", double(count) / double(samples)}};
      }
    }
    summary["bbox"] = {{"min", {result.min.x(), result.min.y(), result.min.z()}},
                       {"max", {result.max.x(), result.max.y(), result.max.z()}}};
    if (cli.has("json")) {
      std::cout << summary.dump() << "\n";
    } else {
      std::cerr << "[done, " << static_cast<int>(progress.seconds() * 1000)
                << " ms : " << result.points << " points] -> " << output << "\n";
    }
    return app::kExitOk;
  });
}
