// mcws_envelope: the workspace envelope of a 3-D cloud as a closed, outward-oriented triangle mesh
// (PLY, STL or VTK) enclosing the volume mcws_measure gives.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "common/app.h"
#include "common/flags.h"
#include "common/units.h"
#include "mcws/filters/boundary_geometry.h"
#include "mcws/io/atomic_file.h"
#include "mcws/io/cloud_io.h"
#include "mcws/sampling/sample_report.h"
#include "mcws/workspace/drawing.h"
#include "mcws/workspace/envelope.h"
#include "mcws/workspace/envelope_report.h"

namespace {

using namespace mcws;

constexpr double kDegree = M_PI / 180.0;
constexpr std::size_t kProgressPoints = 200000;  ///< larger inputs report their phases on stderr
/// A repair volume above this share of the kept tetrahedra's gets a warning (Envelope::filled).
constexpr double kFilledWarning = 0.01;

constexpr char kUsage[] =
    "mcws_envelope --input CLOUD.pcd [--output ENVELOPE.ply|.stl|.vtk] [--plot VIEWS.png]\n"
    "              [--drawing RANGE.png|.svg] [options]";

constexpr char kSummary[] =
    R"(The envelope of the region a 3-D workspace cloud samples, as a closed triangle mesh, every
triangle counter-clockwise seen from outside: the surface of the tetrahedra mcws_measure keeps
(the alpha shape of the Delaunay triangulation at the same --alpha, in local spacings), moved
outward along the vertex normals by the band the samples miss along the edge (the Efron
correction of mcws_measure; the offset is fitted so that the mesh encloses mcws_measure's
volume). With --correction none (refined clouds) the alpha surface as it is.
To make it a closed 2-manifold, interior cavities are filled and where the region pinches
itself along an edge or at a vertex the smaller side is filled (or, where parts of it touch at
one vertex only, the smaller parts dropped): "filled_volume", the net change, is well under a
per mille (a warning above 1 %).
Binary PLY, binary STL or ASCII VTK by the --output extension; pcl_viewer shows .ply and .vtk,
MeshLab all three; --plot a shaded PNG from two views (gnuplot). Lengths in the cloud's unit or
--unit (the files' too).
--drawing: the working range as a datasheet draws it, PNG or SVG (gnuplot): the side view is the
section of the envelope by the vertical plane through the first joint's axis (the base z axis)
at --azimuth, with the reach in front of and behind the axis and the highest and lowest point;
the top view is the projection of the samples on the horizontal plane (the mesh would bridge
narrow joint-limit gaps) with the maximum and minimum reach and the angle swept at full reach
(where the outline is within 10 % of the maximum reach). The drawing's title (and --plot's) names
the robot and the frame whose origin the samples are (a URDF's tip link, or a D-H robot's tool or
flange) as the cloud records them, else the cloud's file name; so does the mesh's comment. The
numbers go into the JSON under "drawing", the robot and the frame under "robot" and "tip" (null
when the cloud does not record them). --json: "volume"
(enclosed by the mesh), "measure_volume" (mcws_measure's), "uncorrected" (the kept tetrahedra's),
"filled_volume", "area", "offset", the counts, "euler_characteristic" (V - E + F: 2 for a surface
like a sphere's, 0 for a torus's) and "closed_and_oriented" (every edge in two triangles, once
each way).)";

void declareFlags(app::CommandLine& cli) {
  cli.addValue("input", "workspace cloud (PCD), 3-D");
  cli.addValue("output", "mesh file: .ply, .stl or .vtk");
  cli.addValue("drawing", "datasheet drawing (side and top view with dimensions): .png or .svg");
  cli.addValue("azimuth", "drawing: direction of the side view's plane from +x [deg] (default 0)");
  app::declareRegionFlags(cli);
  cli.addValue("plot", "PNG: the mesh shaded, from two views (gnuplot)");
  app::declareUnitFlag(cli);
  cli.addSwitch("json", "print a JSON summary on stdout");
}

/// The files of a run and how to write them.
struct Files {
  std::string input, output, plot, drawing;
  DrawingFormat drawing_format{};
  std::optional<io::CloudProvenance> recorded;  ///< the input's robot, for titles and comments
};

Files readFiles(const app::CommandLine& cli) {
  Files files{cli.required("input"),
              cli.text("output", ""),
              cli.text("plot", ""),
              cli.text("drawing", ""),
              {},
              {}};
  if (files.output.empty() && files.drawing.empty() && files.plot.empty())
    throw app::UsageError("give at least one of --output, --plot and --drawing");
  if (!files.output.empty())
    app::asUsageError("output", [&] { surfaceFormatOf(files.output); });  // refused before the work
  if (!files.drawing.empty()) {
    files.drawing_format =
        app::asUsageError("drawing", [&] { return drawingFormatOf(files.drawing); });
  }
  return files;
}

/// The cloud's points, checked to span a volume.
pcl::PointCloud<pcl::PointXYZ> loadPoints(const std::string& input) {
  const io::WorkspaceCloud::Ptr cloud = io::readCloud(input);
  requireRegionPoints(summarizeCloud(*cloud, BoundaryPlane::k3D), input);
  io::requireVolume(*cloud, input);
  return projectedToPlane(*cloud, BoundaryPlane::k3D);
}

/// Every file complete under a temporary name before any gets its own. The pictures' titles
/// name the robot and the frame measured as the cloud records them, else the cloud's file name.
void saveOutputs(const Files& files, const TriangleSurface& shown,
                 const std::optional<EnvelopeDrawing>& drawing, const ResultUnits& units) {
  const std::string name = files.recorded ? files.recorded->robot
                                          : std::filesystem::path(files.input).filename().string();
  const std::string tip = files.recorded ? io::recordedTip(*files.recorded).value_or("") : "";
  const std::string unit = units.lengthName();
  io::OutputSet outputs;
  if (!files.output.empty())
    saveSurface(shown, files.output, io::describeCloud(files.input, files.recorded), unit);
  if (!files.plot.empty())
    io::writeWholeFile(files.plot, renderEnvelopePng(shown, name, unit, tip));
  if (drawing) {
    io::writeWholeFile(files.drawing,
                       renderEnvelopeDrawing(*drawing, files.drawing_format, name, unit, tip));
  }
  outputs.commit();
}

/// The --json summary: the files and envelopeSummary().
nlohmann::json summary(const Files& files, const Envelope& envelope, const MeasureOptions& options,
                       const std::optional<EnvelopeDrawing>& drawing, const ResultUnits& units,
                       double seconds) {
  nlohmann::json out = envelopeSummary(envelope, options, drawing, units);
  out["input"] = files.input;
  addRecordedRobotNames(out, files.recorded);
  out["output"] = files.output.empty() ? nlohmann::json() : nlohmann::json(files.output);
  out["seconds"] = seconds;
  out["units"]["seconds"] = "s";
  if (drawing) out["drawing"]["file"] = files.drawing;
  return out;
}

void printText(const Files& files, const nlohmann::json& out, const SurfaceTopology& topology,
               const ResultUnits& units, double seconds) {
  std::cout.precision(10);
  std::cout << "volume " << out["volume"].get<double>() << " " << units.volumeName() << "\n";
  if (out.contains("drawing")) {
    const std::string unit = " " + units.lengthName();
    const auto& d = out["drawing"];
    std::cout << "max reach " << d["max_reach"].get<double>() << unit << ", min reach "
              << d["min_reach"].get<double>() << unit << ", highest " << d["highest"].get<double>()
              << unit << ", lowest " << d["lowest"].get<double>() << unit << ", swept "
              << d["swept_angle"].get<double>() << " deg\n";
  }
  std::cerr << "[done, " << static_cast<int>(seconds * 1000) << " ms : " << topology.triangles
            << " triangles, " << topology.vertices << " vertices"
            << (topology.closedAndOriented() ? "" : ", surface touches itself") << "] ->";
  for (const std::string& file : {files.output, files.plot, files.drawing}) {
    if (!file.empty()) std::cerr << " " << file;
  }
  std::cerr << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  return app::run("mcws_envelope", [&] {
    app::CommandLine cli(kUsage, kSummary);
    declareFlags(cli);
    if (!cli.parse(argc, argv)) return app::kExitOk;
    Files files = readFiles(cli);
    const double azimuth = app::parseNumber(cli.text("azimuth", "0"), "azimuth") * kDegree;
    MeasureOptions options = app::readRegionOptions(cli);
    app::checkOutputs({{"output", files.output}, {"plot", files.plot}, {"drawing", files.drawing}},
                      {{"input", files.input}});
    const ResultUnits units = app::readResultUnits(cli, io::recordedUnit(files.input), files.input);
    files.recorded = io::readProvenance(files.input);

    app::Progress clock("mcws_envelope", "points");
    const pcl::PointCloud<pcl::PointXYZ> points = loadPoints(files.input);
    if (points.size() >= kProgressPoints) {
      options.phase = [&](const std::string& phase) {
        std::cerr << "mcws_envelope: " << phase << " (" << points.size() << " points, "
                  << static_cast<int>(clock.seconds()) << " s)\n";
      };
    }
    const Envelope envelope = workspaceEnvelope(points, options);
    TriangleSurface shown = envelope.mesh;
    for (auto& v : shown.vertices) v *= units.length(1.0);
    std::optional<EnvelopeDrawing> drawing;
    if (!files.drawing.empty()) {
      pcl::PointCloud<pcl::PointXYZ> samples = points;
      for (auto& p : samples) p.getVector3fMap() *= static_cast<float>(units.length(1.0));
      drawing =
          app::asUsageError("azimuth", [&] { return envelopeDrawing(shown, samples, azimuth); });
    }
    saveOutputs(files, shown, drawing, units);

    const nlohmann::json out = summary(files, envelope, options, drawing, units, clock.seconds());
    if (std::abs(envelope.filled) > kFilledWarning * envelope.measure.uncorrected) {
      std::cerr << "mcws_envelope: warning: making the surface a closed 2-manifold changed "
                << app::shortNumber(100.0 * envelope.filled / envelope.measure.uncorrected)
                << " % of the volume; a sparse edge pinches the region often: refine the cloud "
                   "(mcws_boundary, mcws_refine) and use --correction none\n";
    }
    if (cli.has("json")) {
      std::cout << out.dump() << "\n";
    } else {
      printText(files, out, surfaceTopology(envelope.mesh), units, clock.seconds());
    }
    return app::kExitOk;
  });
}
