// mcws_envelope: the workspace envelope of a 3-D cloud as a closed, outward-oriented triangle mesh
// (PLY, STL or VTK) enclosing the volume mcws_measure gives.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "common/app.h"
#include "common/cloud_io.h"
#include "common/flags.h"
#include "common/units.h"
#include "mcws/filters/boundary_geometry.h"
#include "mcws/io/atomic_file.h"
#include "mcws/workspace/envelope.h"

namespace {

using namespace mcws;

constexpr std::size_t kProgressPoints = 200000;  ///< larger inputs report their phases on stderr
/// A filled volume above this share of the kept tetrahedra's gets a warning (Envelope::filled).
constexpr double kFilledWarning = 0.01;

constexpr char kUsage[] =
    "mcws_envelope --input CLOUD.pcd --output ENVELOPE.ply|.stl|.vtk [options]";

constexpr char kSummary[] =
    R"(The envelope of the region a 3-D workspace cloud samples, as a closed triangle mesh, every
triangle counter-clockwise seen from outside: the surface of the tetrahedra mcws_measure keeps
(the alpha shape of the Delaunay triangulation at the same --alpha, in local spacings), moved
outward along the vertex normals by the band the samples miss along the edge (the Efron
correction of mcws_measure; the offset is fitted so that the mesh encloses mcws_measure's
volume). With --correction none (refined clouds) the alpha surface as it is.
To make it a closed 2-manifold, interior cavities and the dropped tetrahedra where the region
pinches itself are filled ("filled_volume"): a few per mille on uniform and refined clouds. On
plain joint-space samples, whose edge is sparse, filling also closes concave parts (a warning
above 1 %): refine such clouds first (mcws_boundary, mcws_refine).
Binary PLY, binary STL or ASCII VTK by the --output extension; pcl_viewer shows .ply and .vtk,
MeshLab all three; --plot a shaded PNG from two views (gnuplot). Lengths in the cloud's unit or --unit (the file's too). --json: "volume"
(enclosed by the mesh), "measure_volume" (mcws_measure's), "uncorrected" (the kept tetrahedra's),
"filled_volume", "area", "offset", the counts, "euler_characteristic" (V - E + F: 2 for a surface
like a sphere's, 0 for a torus's) and "closed_and_oriented" (every edge in two triangles, once
each way).)";

void declareFlags(app::CommandLine& cli) {
  cli.addValue("input", "workspace cloud (PCD), 3-D");
  cli.addValue("output", "mesh file: .ply, .stl or .vtk");
  app::declareRegionFlags(cli);
  cli.addValue("plot", "PNG: the mesh shaded, from two views (gnuplot)");
  app::declareUnitFlag(cli);
  cli.addSwitch("json", "print a JSON summary on stdout");
}

}  // namespace

int main(int argc, char** argv) {
  return app::run("mcws_envelope", [&] {
    app::CommandLine cli(kUsage, kSummary);
    declareFlags(cli);
    if (!cli.parse(argc, argv)) return app::kExitOk;
    const std::string input = cli.required("input"), output = cli.required("output");
    const MeshFormat format = app::asUsageError("output", [&] { return meshFormatOf(output); });
    MeasureOptions options = app::readRegionOptions(cli);
    app::checkOutputs({{"output", output}, {"plot", cli.text("plot", "")}}, {{"input", input}});
    const app::ResultUnits units = app::readResultUnits(cli, app::recordedUnit(input), input);

    app::Progress clock("mcws_envelope", "points");
    pcl::PointCloud<pcl::PointXYZ> points;
    {
      const app::WorkspaceCloud::Ptr cloud = app::loadCloud(input);
      requireRegionPoints(summarizeCloud(*cloud, BoundaryPlane::k3D), input);
      app::requireVolume(*cloud, input);
      pcl::Indices all(cloud->size()), source;
      for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<pcl::index_t>(i);
      projectToPlane(*cloud, all, BoundaryPlane::k3D, points, source);
    }
    if (points.size() >= kProgressPoints) {
      options.phase = [&](const std::string& phase) {
        std::cerr << "mcws_envelope: " << phase << " (" << points.size() << " points, "
                  << static_cast<int>(clock.seconds()) << " s)\n";
      };
    }
    const Envelope envelope = workspaceEnvelope(points, options);
    TriangleSurface shown = envelope.mesh;
    for (auto& v : shown.vertices) v *= units.length(1.0);
    // Both files complete under temporary names before either gets its own.
    io::AtomicFile file(output);
    writeSurface(shown, format, "mcws_envelope of " + input + ", lengths in " + units.lengthName(),
                 file.stream());
    std::optional<io::AtomicFile> picture;
    if (cli.has("plot")) {
      const std::string png = renderEnvelopePng(
          shown, std::filesystem::path(input).filename().string(), units.lengthName());
      picture.emplace(cli.required("plot"));
      picture->write(png.data(), png.size());
    }
    file.commit();
    if (picture) picture->commit();

    const SurfaceTopology topology = surfaceTopology(envelope.mesh);
    const std::string volume = units.volumeName();
    const nlohmann::json out{{"input", input},
                             {"output", output},
                             {"volume", units.volume(envelope.volume)},
                             {"measure_volume", units.volume(envelope.measure.measure)},
                             {"uncorrected", units.volume(envelope.measure.uncorrected)},
                             {"area", units.area(envelope.area)},
                             {"offset", units.length(envelope.offset)},
                             {"alpha", options.alpha_factor},
                             {"correction", options.edge_correction ? "efron" : "none"},
                             {"points", envelope.measure.points},
                             {"vertices", topology.vertices},
                             {"triangles", topology.triangles},
                             {"edges", topology.edges},
                             {"euler_characteristic", topology.euler_characteristic},
                             {"closed_and_oriented", topology.closedAndOriented()},
                             {"non_manifold_edges", topology.non_manifold_edges},
                             {"filled_volume", units.volume(envelope.filled)},
                             {"seconds", clock.seconds()},
                             {"length_unit", units.lengthName()},
                             {"units",
                              {{"volume", volume},
                               {"measure_volume", volume},
                               {"uncorrected", volume},
                               {"area", units.areaName()},
                               {"offset", units.lengthName()},
                               {"filled_volume", volume},
                               {"alpha", "local spacings"},
                               {"seconds", "s"}}}};
    if (envelope.filled > kFilledWarning * envelope.measure.uncorrected) {
      std::cerr << "mcws_envelope: warning: making the surface a closed 2-manifold filled "
                << app::shortNumber(100.0 * envelope.filled / envelope.measure.uncorrected)
                << " % of the volume (concave parts the sparse edge pinches off); refine the cloud "
                   "(mcws_boundary, mcws_refine) and use --correction none\n";
    }
    if (cli.has("json")) {
      std::cout << out.dump() << "\n";
    } else {
      std::cout.precision(10);
      std::cout << "volume " << out["volume"].get<double>() << " " << volume << "\n";
      std::cerr << "[done, " << static_cast<int>(clock.seconds() * 1000)
                << " ms : " << topology.triangles << " triangles, " << topology.vertices
                << " vertices" << (topology.closedAndOriented() ? "" : ", surface touches itself")
                << "] -> " << output << "\n";
    }
    return app::kExitOk;
  });
}
