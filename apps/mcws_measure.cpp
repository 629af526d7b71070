// mcws_measure: area (2-D, --plane) or volume (3-D) of the region a workspace cloud samples.
#include <pcl/io/pcd_io.h>

#include <cstdint>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <vector>

#include "common/app.h"
#include "common/flags.h"
#include "common/units.h"
#include "mcws/filters/boundary_geometry.h"
#include "mcws/io/boundary_record.h"
#include "mcws/io/cloud_io.h"
#include "mcws/sampling/sample_report.h"
#include "mcws/workspace/measure.h"
#include "mcws/workspace/measure_report.h"

namespace {

using namespace mcws;

constexpr std::size_t kProgressPoints = 200000;  ///< larger inputs report their phases on stderr

constexpr char kUsage[] =
    "mcws_measure --input CLOUD.pcd [--plane xy|xz|yz] [--boundary B.pcd] [options]";

constexpr char kSummary[] =
    R"(Area (with --plane) or volume of the sampled region. Default method 'delaunay': the cloud's
Delaunay triangulation (CGAL) restricted to simplices no wider than --alpha local spacings,
corrected for the band the samples miss along the edge by leave-one-out (Efron's identity; it
assumes the density near the edge is about that inside, as for uniform samples). A cloud from
mcws_refine has samples on the edge itself (joint limits): measure it with --correction none
(--alpha 5). Only the points that an empty ball of --alpha radius may touch are triangulated
(a shell a few spacings deep along every edge; the others are proven inside on a grid), which
gives the same measure as triangulating every point (--triangulate all) in a fraction of the time
and memory. Method 'column': the rectangles of Yin, Wang & Yu 2010, eqs. (2)-(4), over --boundary
points grouped into crossings per column. Every boundary point must be a point of --input (exit 1
naming the first that is not), and the whole boundary of --input itself: mcws_boundary records
the point count and SHA-256 of the cloud it read and the number of boundary points it wrote, which
must be --input's and the boundary's (exit 1 for the boundary of a subset or of an older cloud, a
part of a boundary, or a boundary without the record of a cloud that records its robot; clouds
that record no robot, such as --shape samples, are checked point by point only).
Which number to trust: the default measures the region the samples cover, to 0.02 % (1e5 points,
2-D) and 0.003 % (1e6) on uniform clouds, 0.04 % / 0.008 % for a ball's volume (mean absolute
error over 10 seeds, BENCHMARKS.md). An arm's joint-sampled cloud is not uniform: where the joints
sample the edge sparsely the cloud itself stops short of the true edge (de-icing arm, 1e5 samples:
-3.3 % area), which no estimator recovers; refine the edge (mcws_boundary, mcws_refine) and
measure with --correction none (-0.04 % at 1e5). With --boundary the output also gives the
paper's column method as "cross_check": it reads crossings a little outside the edge and is
biased high (+0.2 to +0.3 % on a uniform disk, more on sparse or concave edges); it is there to
compare with the paper, not the result.
Output: the area [length unit^2] or volume [length unit^3] (lengths in the cloud's recorded
unit, or --unit); with --json also "uncorrected" (the kept simplices' total before the edge
correction), "points" (distinct points), "triangulated" (of those, the points triangulated: the
shell of points an empty ball of alpha radius may touch, or all with --triangulate all; the
triangulation of the shell gives the same measure, in a fraction of the time and memory),
"boundary_vertices" (vertices between kept
and dropped simplices: the region's edge), "outside" (of those, the ones outside the region of
all other points: Efron's count V; the correction divides by 1 - V / points), "length_unit" and
"units" (the unit of each dimensioned number).
With --label L, the region of the points labelled L (0: collision-free, mcws_sample
--collision) within the triangulation of every point, with the whole cloud's local spacing and
alpha limit: a kept simplex counts whole when its points are all labelled L or its centre lies in
the labelled points' own region, else the share of its points labelled L; the edge correction
counts the whole cloud's outside points labelled L. So the label's measure never exceeds the
whole cloud's, which is given too ("all"). Measured on its own (mcws_select, then mcws_measure)
a sparser subset can come out larger than the whole: its wider local spacing widens the alpha
limit and its edge correction. Every point is triangulated (no --triangulate, --leave-one-out).
The cloud must have at least 3 distinct finite points in the plane (4 in 3-D), or it has no
area or volume (exit 1, for 2-D and 3-D alike; so must the boundary); with --plane it must extend
along both of the plane's axes (a cloud flat in one of them is a --plane error, exit 2, naming
the plane it lies in; a 3-D cloud is projected). --alpha lies in [1, 1000] local spacings,
--column-width between a tenth of the cloud's mean spacing and its extent in the plane (or 0), in
the cloud's unit.)";

void declareFlags(app::CommandLine& cli) {
  cli.addValue("input", "workspace cloud (PCD)");
  cli.addValue("boundary", "its boundary points (from mcws_boundary)");
  cli.addValue("plane", "xy | xz | yz: an area in that plane (default: volume)");
  cli.addValue("method", "delaunay | column (default delaunay)");
  app::declareRegionFlags(cli, "delaunay: ");
  cli.addValue(
      "leave-one-out",
      R"(efron: star (each vertex's star, all threads; default) | reinsert (remove, locate, reinsert each vertex: the same count, one thread, slower))");
  cli.addValue(
      "triangulate",
      R"(delaunay: shell (only the points an empty ball of --alpha radius may touch; default) | all (every point: the same measure, slower; always with --leave-one-out reinsert))");
  cli.addValue("column-width", "column: L [length unit] (default automatic)");
  cli.addValue("label",
               "delaunay: measure only the points with this label (0: collision-free, from "
               "mcws_sample --collision) within the triangulation of every point, which is "
               "measured too (\"all\"): the label's measure never exceeds it");
  app::declareUnitFlag(cli);
  cli.addSwitch("json", "print a JSON summary on stdout");
}

/// The command line, checked.
struct Settings {
  std::string input, method;
  BoundaryPlane plane{BoundaryPlane::k3D};
  MeasureOptions delaunay;
  double column_width{0.0};            ///< 0: automatic
  std::optional<std::uint32_t> label;  ///< --label: measure the points with it
};

Settings readSettings(const app::CommandLine& cli) {
  Settings s;
  s.input = cli.required("input");
  s.method = app::parseChoice(cli.text("method", "delaunay"), "method", {"delaunay", "column"});
  s.plane = app::readPlane(cli);
  if (s.method == "column" && (s.plane == BoundaryPlane::k3D || !cli.has("boundary")))
    throw app::UsageError("--method column measures an area: give --plane and --boundary");
  if (cli.has("boundary") && s.plane == BoundaryPlane::k3D)
    throw app::UsageError("--boundary: the column cross-check measures an area: give --plane");
  if (cli.has("column-width") && !cli.has("boundary"))
    throw app::UsageError("--column-width applies to the column method: give --boundary");
  if (s.method == "column") {
    for (const char* flag : {"alpha", "correction", "leave-one-out", "threads", "triangulate"}) {
      if (cli.has(flag))
        throw app::UsageError("--" + std::string(flag) + " does not apply to --method column");
    }
  }
  s.delaunay = app::readRegionOptions(cli);
  s.delaunay.leave_one_out = app::parseChoice(cli.text("leave-one-out", "star"), "leave-one-out",
                                              {"star", "reinsert"}) == "star"
                                 ? LeaveOneOut::kStar
                                 : LeaveOneOut::kRemoveAndReinsert;
  s.delaunay.shell = app::parseChoice(cli.text("triangulate", "shell"), "triangulate",
                                      {"shell", "all"}) == "shell";
  s.column_width = app::parseNonNegative(cli.text("column-width", "0"), "column-width");
  if (cli.has("label")) {
    for (const char* flag : {"boundary", "triangulate", "leave-one-out"}) {
      if (cli.has(flag))
        throw app::UsageError("--" + std::string(flag) +
                              " does not apply to --label (every point is triangulated)");
    }
    if (s.method != "delaunay") throw app::UsageError("--label measures by --method delaunay");
    s.label = static_cast<std::uint32_t>(
        app::parseInteger(cli.required("label"), "label", 0, 4294967295LL));
  }
  return s;
}

/// The cloud at `path`, checked to be a region in the plane (or 3-D): requireRegionPoints(), and
/// a --plane that fits it (a usage error).
io::WorkspaceCloud::Ptr loadRegion(const std::string& path, BoundaryPlane plane,
                                   SummaryDetail detail, CloudSummary& summary) {
  io::WorkspaceCloud::Ptr cloud = io::readCloud(path);
  summary = summarizeCloud(*cloud, plane, detail);
  requireRegionPoints(summary, path);
  if (plane == BoundaryPlane::k3D) io::requireVolume(*cloud, path);
  app::asUsageError("plane", [&] { requirePlaneFits(summary, path); });
  return cloud;
}

/// The --boundary points, checked to be points of the --input cloud and to be a region.
io::WorkspaceCloud::Ptr loadBoundary(const std::string& path, const std::string& input,
                                     const io::WorkspaceCloud& cloud, BoundaryPlane plane) {
  io::WorkspaceCloud::Ptr boundary = io::readCloud(path);
  io::requireBoundaryOf(path, input, cloud.size(), boundary->size());
  if (const std::optional<std::size_t> i = firstPointNotIn(*boundary, cloud)) {
    const auto& p = (*boundary)[*i];
    throw Error("--boundary " + path + ": point " + std::to_string(*i) + " (" +
                app::shortNumber(p.x) + ", " + app::shortNumber(p.y) + ", " +
                app::shortNumber(p.z) + ") is not a point of --input " + input +
                ": a boundary of another cloud?");
  }
  requireRegionPoints(summarizeCloud(*boundary, plane), path);
  return boundary;
}

/// --column-width, 0 or between a tenth of the cloud's mean spacing and its extent.
void checkColumnWidth(const app::CommandLine& cli, double width, const CloudSummary& cloud) {
  if (width == 0.0) return;
  const LengthRange length = parameterLengths(cloud);
  if (width >= length.min && width <= length.max) return;
  throw app::UsageError("--column-width: " + cli.required("column-width") + " is not 0 or in [" +
                        app::shortNumber(length.min) + ", " + app::shortNumber(length.max) +
                        "] [length unit] (a tenth of the cloud's mean spacing " +
                        app::shortNumber(*cloud.spacing) + " to its extent)");
}

/// Which points of `cloud` (read from `path`) have `label`.
/// \throws mcws::Error when the file has no label field or no point has it.
std::vector<char> labelled(const io::WorkspaceCloud& cloud, const std::string& path,
                           std::uint32_t label) {
  pcl::PCLPointCloud2 header;
  pcl::PCDReader().readHeader(path, header);
  if (pcl::getFieldIndex(header, "label") < 0) {
    throw Error(path + ": has no field 'label' for --label");
  }
  std::vector<char> flags(cloud.size(), 0);
  for (std::size_t i = 0; i < cloud.size(); ++i) flags[i] = cloud[i].label == label;
  return flags;
}

/// The plain output: the measure with its unit; with --label the whole cloud's after it; with
/// --boundary (delaunay) the column method's cross-check.
void printMeasure(const nlohmann::json& out, const std::string& key, const Settings& settings) {
  std::cout.precision(10);
  const std::string unit = out["units"][key];
  std::cout << key << " " << out[key].get<double>() << " " << unit << "\n";
  if (settings.label) {
    std::cout << "all_" << key << " " << out["all"][key].get<double>() << " " << unit
              << " (every point, measured the same way; the above is label " << *settings.label
              << "'s)\n";
  }
  if (out.contains("cross_check")) {
    std::cout << "cross_check " << out["cross_check"][key].get<double>() << " " << unit << " ("
              << kColumnCrossCheckNote << ")\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  return app::run("mcws_measure", [&] {
    app::CommandLine cli(kUsage, kSummary);
    declareFlags(cli);
    if (!cli.parse(argc, argv)) return app::kExitOk;
    Settings settings = readSettings(cli);

    app::Progress clock("mcws_measure", "points");
    const char* key = boundaryDimensions(settings.plane) == 2 ? "area" : "volume";
    CloudSummary summary;
    // The spacing only for a --column-width to check (a pass over every point).
    io::WorkspaceCloud::Ptr cloud = loadRegion(
        settings.input, settings.plane,
        settings.column_width > 0.0 ? SummaryDetail::kSpacing : SummaryDetail::kCounts, summary);
    checkColumnWidth(cli, settings.column_width, summary);
    std::optional<ColumnArea> column;
    if (cli.has("boundary")) {
      const io::WorkspaceCloud::Ptr boundary =
          loadBoundary(cli.required("boundary"), settings.input, *cloud, settings.plane);
      column = columnArea(projectedToPlane(*boundary, settings.plane), settings.column_width);
    }
    const ResultUnits units =
        app::readResultUnits(cli, io::recordedUnit(settings.input), settings.input);
    const pcl::PointCloud<pcl::PointXYZ> region = projectedToPlane(*cloud, settings.plane);
    const std::vector<char> subset =
        settings.label ? labelled(*cloud, settings.input, *settings.label) : std::vector<char>();
    cloud.reset();  // the triangulation's memory is the peak
    const int dimensions = boundaryDimensions(settings.plane);
    nlohmann::json out;
    if (settings.method == "delaunay") {
      if (region.size() >= kProgressPoints) {  // minutes for a million points in 3-D
        settings.delaunay.phase = [&](const std::string& phase) {
          std::cerr << "mcws_measure: " << phase << " (" << region.size() << " points, "
                    << static_cast<int>(clock.seconds()) << " s)\n";
        };
      }
      // The measure's own failures (the points lie in a plane, too few for the edge correction)
      // name the cloud they are about.
      try {
        out = settings.label
                  ? subsetMeasureJson(
                        delaunayMeasureSubset(region, subset, dimensions, settings.delaunay),
                        *settings.label, settings.delaunay, dimensions, units)
                  : regionMeasureJson(delaunayMeasure(region, dimensions, settings.delaunay),
                                      settings.delaunay, dimensions, units);
      } catch (const UsageError&) {
        throw;
      } catch (const Error& e) {
        throw Error(settings.input + ": " + e.what());
      }
      if (column) addColumnCrossCheck(out, *column, units);
    } else {
      out = columnAreaJson(*column, units);
    }
    out["input"] = settings.input;
    out["plane"] = boundaryPlaneName(settings.plane);
    out["method"] = settings.method;
    out["seconds"] = clock.seconds();
    out["length_unit"] = units.lengthName();
    addRecordedRobotNames(out, io::readProvenance(settings.input));
    out["units"]["seconds"] = "s";
    if (cli.has("json")) {
      std::cout << out.dump() << "\n";
    } else {
      printMeasure(out, key, settings);
    }
    return app::kExitOk;
  });
}
