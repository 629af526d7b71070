// mcws_boundary: boundary points of a workspace cloud by the local quadrant/octant test of
// seed 000 (section 4.3), on a plane (--plane) or in 3-D.
#include <pcl/common/common.h>

#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "common/app.h"
#include "common/cloud_io.h"
#include "mcws/filters/orthant_boundary.h"
#include "mcws/io/atomic_file.h"

namespace {
// 90 degrees is seed 000's quadrant. 92 trades a little recall for precision: on uniform disks
// of 1e5 and 1e6 points, precision 0.991 and recall 0.982-0.984 (BENCHMARKS.md).
constexpr int kDefaultGapDegrees = 92;
}  // namespace

int main(int argc, char** argv) {
  using namespace mcws;
  return app::run("mcws_boundary", [&] {
    app::CommandLine cli(
        "mcws_boundary --input CLOUD.pcd --output BOUNDARY.pcd [options]",
        "Keeps the points on the boundary of the sampled region: a point is a boundary point when\n"
        "some quadrant (--plane) or octant (3-D) around it holds no neighbour within the radius.\n"
        "2-D: in every rotation of the local frame (a 90-degree gap between neighbours); 3-D: in\n"
        "the axis frame or in a frame centred on the outward direction. By default each point's "
        "radius\n"
        "is twice the distance to its k-th neighbour (k = 24 in 2-D, 16 in 3-D: about 5.5 and 3\n"
        "mean spacings), which follows the density of joint-space samples; --radius fixes it,\n"
        "--auto-radius takes c x the cloud's mean spacing.\n"
        "NaN points are dropped from both outputs; a point without neighbours is a boundary "
        "point.");
    cli.add()("input", app::po::value<std::string>(), "workspace cloud (PCD)")(
        "output", app::po::value<std::string>(), "boundary points (PCD)")(
        "interior", app::po::value<std::string>(), "also write the interior points here")(
        "plane", app::po::value<std::string>(), "xy | xz | yz: work in that plane (default 3-D)")(
        "radius", app::po::value<std::string>(), "fixed search radius r [length unit]")(
        "auto-radius", app::po::value<std::string>(),
        "r = c x mean spacing (default: c automatic)")(
        "adaptive", app::po::value<std::string>(),
        "k: per-point r = 2 x distance to k-th neighbour (default)")(
        "outer-radius", app::po::value<std::string>(),
        "seed 000's second stage at R: a length > r with --radius/--auto-radius, else a factor > 1 "
        "of each point's radius")(
        "min-gap", app::po::value<std::string>(),
        "2-D: empty sector that makes a boundary point, 90..179 deg (default 92)")(
        "threads", app::po::value<std::string>(), "worker threads, 0 = all cores (default 0)")(
        "json", "print a JSON summary on stdout");
    if (!cli.parse(argc, argv)) return app::kExitOk;

    const std::string input = cli.required("input"), output = cli.required("output");
    OrthantBoundary<WorkspacePoint> boundary(true);
    try {
      boundary.setPlane(cli.has("plane") ? parseBoundaryPlane(cli.required("plane"))
                                         : BoundaryPlane::k3D);
    } catch (const Error& e) {
      throw app::UsageError(std::string("--plane: ") + e.what());
    }
    if (cli.has("radius") + cli.has("auto-radius") + cli.has("adaptive") > 1) {
      throw app::UsageError("give at most one of --radius, --auto-radius, --adaptive");
    }
    auto positive = [&](const std::string& flag) {
      const double value = app::parseNumber(cli.required(flag), flag);
      if (!(value > 0.0))
        throw app::UsageError("--" + flag + ": must be positive, not " + cli.required(flag));
      return value;
    };
    const int default_k = boundary.getPlane() == BoundaryPlane::k3D ? 16 : 24;
    boundary.setAdaptiveRadius(
        static_cast<int>(app::parseInteger(cli.text("adaptive", std::to_string(default_k)),
                                           "adaptive", 1, 1000)),
        2.0);
    if (cli.has("auto-radius")) boundary.setAutoRadius(positive("auto-radius"));
    if (cli.has("radius")) boundary.setRadiusSearch(positive("radius"));
    if (cli.has("outer-radius")) boundary.setOuterRadius(positive("outer-radius"));
    const double gap =
        app::parseNumber(cli.text("min-gap", std::to_string(kDefaultGapDegrees)), "min-gap");
    if (!(gap >= 90.0 && gap < 180.0))
      throw app::UsageError("--min-gap: must be in [90, 180), not " + cli.text("min-gap", ""));
    boundary.setMinimumGap(gap * M_PI / 180.0);
    boundary.setNumberOfThreads(app::parseInteger(cli.text("threads", "0"), "threads", 0, 256));

    // Both destinations are checked before any work, so neither is written when the other cannot
    // be.
    io::checkOutputPath(output);
    if (cli.has("interior")) {
      if (cli.required("interior") == output) {
        throw app::UsageError("--interior and --output name the same file");
      }
      io::checkOutputPath(cli.required("interior"));
    }
    app::Progress clock("mcws_boundary", "points");
    const app::WorkspaceCloud::Ptr cloud = app::loadCloud(input);
    if (boundary.getPlane() == BoundaryPlane::k3D) app::requireVolume(*cloud, input);
    boundary.setInputCloud(cloud);
    pcl::Indices kept;
    boundary.filter(kept);
    app::saveCloud(*cloud, kept, output);
    pcl::Indices interior;
    if (cli.has("interior")) {
      for (const auto i : *boundary.getRemovedIndices()) {
        if (pcl::isFinite((*cloud)[i])) interior.push_back(i);
      }
      try {
        app::saveCloud(*cloud, interior, cli.required("interior"));
      } catch (...) {
        std::remove(output.c_str());  // all or nothing
        throw;
      }
    }

    nlohmann::json summary = {{"input", input},
                              {"output", output},
                              {"method", "orthant"},
                              {"plane", boundaryPlaneName(boundary.getPlane())},
                              {"points", cloud->size()},
                              {"boundary", kept.size()},
                              {"radius", boundary.usedRadius()},
                              {"spacing", boundary.usedSpacing()},
                              {"seconds", clock.seconds()}};
    if (cli.has("interior")) summary["interior"] = interior.size();
    if (cli.has("json")) {
      std::cout << summary.dump() << "\n";
    } else {
      std::cerr << "[done, " << static_cast<int>(clock.seconds() * 1000) << " ms : " << kept.size()
                << " of " << cloud->size() << " points on the boundary] -> " << output << "\n";
    }
    return app::kExitOk;
  });
}
