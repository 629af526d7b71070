#include "mcws/workspace/drawing.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <utility>

#include "mcws/core/error.h"
#include "mcws/core/file_name.h"
#include "mcws/io/gnuplot.h"

namespace mcws {
namespace {

constexpr double kPi = M_PI;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

using Edge = std::pair<std::uint32_t, std::uint32_t>;  // smaller vertex index first

Edge undirected(std::uint32_t a, std::uint32_t b) { return a < b ? Edge{a, b} : Edge{b, a}; }

/// An angle in (-pi, pi].
double wrapAngle(double a) {
  a = std::remainder(a, 2.0 * kPi);
  return a <= -kPi ? a + 2.0 * kPi : a;
}

double degrees(double radians) { return radians * 180.0 / kPi; }

/// The section's cut of one edge crossing the plane, the same from both of its triangles.
Eigen::Vector2d cutPoint(const TriangleSurface& surface, const std::vector<double>& height, Edge e,
                         const Eigen::Vector3d& along) {
  const double t = height[e.first] / (height[e.first] - height[e.second]);
  const Eigen::Vector3d p =
      surface.vertices[e.first] + t * (surface.vertices[e.second] - surface.vertices[e.first]);
  return {p.dot(along), p.z()};
}

/// The longest run of full-reach bins around the circle: first bin and length.
std::pair<int, int> longestRun(const std::vector<bool>& full) {
  const int n = static_cast<int>(full.size());
  if (std::all_of(full.begin(), full.end(), [](bool f) { return f; })) return {0, n};
  int start = 0;
  while (full[start]) ++start;  // a bin that is not full: no run wraps past it
  std::pair<int, int> best{0, 0};
  for (int m = 1, run = 0; m <= n; ++m) {
    const int k = (start + m) % n;
    if (full[k]) {
      ++run;
      if (run > best.second) best = {(k - run + 1 + n) % n, run};
    } else {
      run = 0;
    }
  }
  return best;
}

std::string number(double value) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(std::abs(value) >= 100.0 ? 1 : 2);
  out << value;
  return out.str();
}

/// The files of a drawing: the data gnuplot plots and the picture it writes.
struct DrawingFiles {
  std::string section_data, top_data, outline_data, picture;
};

/// Writes the section's loops and the top view's bins (each a quadrilateral from inner to outer
/// distance, and its outer point for the outline) to the data files.
void writeDrawingData(const EnvelopeDrawing& drawing, const DrawingFiles& files) {
  const EnvelopeSection& side = drawing.side;
  const EnvelopeTopView& top = drawing.top;
  std::ofstream out(files.section_data);
  out.precision(8);
  for (const auto& loop : side.loops) {
    for (const auto& p : loop) out << p.x() << ' ' << p.y() << '\n';
    out << loop.front().x() << ' ' << loop.front().y() << "\n\n";
  }
  std::ofstream fill(files.top_data), outline(files.outline_data);
  fill.precision(8);
  outline.precision(8);
  const int bins = static_cast<int>(top.outer.size());
  for (int k = 0; k < bins; ++k) {  // each bin a quadrilateral from inner to outer distance
    if (std::isnan(top.outer[k])) {
      outline << '\n';
      continue;
    }
    const double ac = -kPi + k * top.bin, a0 = ac - 0.5 * top.bin, a1 = ac + 0.5 * top.bin;
    for (const auto& [r, a] : {std::pair{top.inner[k], a0}, std::pair{top.outer[k], a0},
                               std::pair{top.outer[k], a1}, std::pair{top.inner[k], a1}})
      fill << r * std::cos(a) << ' ' << r * std::sin(a) << '\n';
    fill << "\n";
    outline << top.outer[k] * std::cos(ac) << ' ' << top.outer[k] * std::sin(ac) << '\n';
  }
  if (!out || !fill || !outline) throw Error("drawing: writing the data files failed");
}

/// A length as the drawing labels it: number() and the unit.
std::string length(double value, const std::string& unit) { return number(value) + " " + unit; }

/// The gnuplot commands of the side view: the section, the axis, reach in front and behind,
/// highest and lowest point.
void writeSideView(std::ostream& gp, const EnvelopeSection& side, const std::string& unit,
                   const DrawingFiles& files) {
  const double width = side.front_reach + side.back_reach;
  const double tall = side.highest - side.lowest, gap = 0.08 * std::max(width, tall);
  const double level = side.lowest - gap, right = side.front_reach + gap;
  gp << "set title "
     << io::gnuplotQuoted("side view: section through the first joint's axis at " +
                          number(degrees(side.azimuth)) + " deg")
     << "\nset xlabel " << io::gnuplotQuoted("horizontal distance from the axis [" + unit + "]")
     << "\nset ylabel " << io::gnuplotQuoted("z [" + unit + "]") << "\n"
     << "set xrange [" << -side.back_reach - 2 * gap << ":" << right + 2.5 * gap << "]\n"
     << "set yrange [" << level - gap << ":" << side.highest + gap << "]\n"
     << "set arrow 1 from 0," << level - gap << " to 0," << side.highest + gap
     << " nohead dt '-.' lc rgb '#555555'\n"
     << "set arrow 2 from 0," << level << " to " << side.front_reach << "," << level
     << " heads size screen 0.008,20 lw 1.5\n"
     << "set label 1 " << io::gnuplotQuoted(length(side.front_reach, unit)) << " at "
     << 0.5 * side.front_reach << "," << level + 0.25 * gap << " center\n"
     << "set arrow 3 from " << right << ",0 to " << right << "," << side.highest
     << " heads size screen 0.008,20 lw 1.5\n"
     << "set label 2 " << io::gnuplotQuoted(length(side.highest, unit)) << " at "
     << right + 0.15 * gap << "," << 0.5 * side.highest << " left\n"
     << "set arrow 4 from " << right << ",0 to " << right << "," << side.lowest
     << " heads size screen 0.008,20 lw 1.5\n"
     << "set label 3 " << io::gnuplotQuoted(length(side.lowest, unit)) << " at "
     << right + 0.15 * gap << "," << 0.5 * side.lowest << " left\n"
     << "set arrow 5 from 0,0 to " << right + 0.5 * gap << ",0 nohead dt 3 lc rgb '#555555'\n"
     << "set arrow 6 from " << side.front_reach << "," << side.lowest << " to " << right + 0.5 * gap
     << "," << side.lowest << " nohead dt 3 lc rgb '#555555'\n"
     << "set arrow 7 from " << side.front_reach << "," << side.highest << " to "
     << right + 0.5 * gap << "," << side.highest << " nohead dt 3 lc rgb '#555555'\n";
  if (side.back_reach > 0.0) {
    gp << "set arrow 8 from " << -side.back_reach << "," << level << " to 0," << level
       << " heads size screen 0.008,20 lw 1.5\n"
       << "set label 4 " << io::gnuplotQuoted(length(side.back_reach, unit)) << " at "
       << -0.5 * side.back_reach << "," << level - 0.45 * gap << " center\n";
  }
  gp << "set label 5 " << io::gnuplotQuoted("section area " + number(side.area) + " " + unit + "^2")
     << " at graph 0.02, graph 0.97 left\n"
     << "plot " << io::gnuplotQuoted(files.section_data)
     << " with filledcurves closed lc rgb '#5b8fc9', '' with lines lw 1.5 lc rgb '#1f4e8c'\n"
     << "unset arrow\nunset label\n";
}

/// The gnuplot commands of the top view: the projection, the swept arc at full reach, maximum
/// and minimum reach, and the highest and lowest point of the surface.
void writeTopView(std::ostream& gp, const EnvelopeDrawing& drawing, const std::string& unit,
                  const DrawingFiles& files) {
  const EnvelopeTopView& top = drawing.top;
  const double reach = top.max_reach, middle = top.sweep_from + 0.5 * top.sweep;
  const double margin = 0.12 * reach;
  gp << "set title 'top view: projection on the horizontal plane'\n"
     << "set xlabel " << io::gnuplotQuoted("x [" + unit + "]") << "\nset ylabel "
     << io::gnuplotQuoted("y [" + unit + "]") << "\n"
     << "set xrange [" << -reach - margin << ":" << reach + margin << "]\n"
     << "set yrange [" << -reach - margin << ":" << reach + margin << "]\n"
     << "set arrow 1 from 0,0 to " << reach * std::cos(middle) << "," << reach * std::sin(middle)
     << " head size screen 0.01,20 lw 1.5\n"
     << "set label 1 " << io::gnuplotQuoted("R " + length(reach, unit)) << " at "
     << 0.6 * reach * std::cos(middle) << "," << 0.6 * reach * std::sin(middle)
     << " center offset 0,1\n"
     << "set label 2 "
     << io::gnuplotQuoted("max reach " + length(reach, unit) + ", min reach " +
                          length(top.min_reach, unit))
     << " at graph 0.02, graph 0.97 left\n"
     << "set label 3 "
     << io::gnuplotQuoted("swept at full reach " + number(degrees(top.sweep)) + " deg")
     << " at graph 0.02, graph 0.93 left\n"
     << "set label 4 "
     << io::gnuplotQuoted("highest " + length(drawing.highest, unit) + ", lowest " +
                          length(drawing.lowest, unit))
     << " at graph 0.02, graph 0.89 left\n";
  if (top.sweep < 2.0 * kPi) {
    for (const double a : {top.sweep_from, top.sweep_to}) {
      gp << "set arrow from 0,0 to " << 1.08 * reach * std::cos(a) << ","
         << 1.08 * reach * std::sin(a) << " nohead dt '-.' lc rgb '#555555'\n";
    }
  }
  gp << "set object 1 circle at 0,0 size " << reach << " arc [" << degrees(top.sweep_from) << ":"
     << degrees(top.sweep_from + top.sweep) << "] fs empty border lc rgb '#555555' dt 2\n"
     << "plot " << io::gnuplotQuoted(files.top_data)
     << " with filledcurves closed lc rgb '#5b8fc9', " << io::gnuplotQuoted(files.outline_data)
     << " with lines lw 1.5 lc rgb '#1f4e8c'\n";
}

}  // namespace

EnvelopeSection envelopeSection(const TriangleSurface& surface, double azimuth) {
  EnvelopeSection section;
  section.azimuth = azimuth;
  const Eigen::Vector3d along(std::cos(azimuth), std::sin(azimuth), 0.0);
  const Eigen::Vector3d normal(-std::sin(azimuth), std::cos(azimuth), 0.0);
  std::vector<double> height(surface.vertices.size());
  for (std::size_t i = 0; i < height.size(); ++i) height[i] = surface.vertices[i].dot(normal);
  const auto ahead = [&](std::uint32_t v) { return height[v] >= 0.0; };  // on the plane: ahead

  // Each crossing triangle gives one segment, from the cut of its edge that leaves the part
  // behind the plane to the cut of the edge that enters it: the boundary of the surface behind
  // the plane, counter-clockwise in (s, z) for an outward-oriented surface.
  std::map<Edge, Edge> next;  // a segment's first cut edge -> its second
  for (const auto& t : surface.triangles) {
    Edge leaving{0, 0}, entering{0, 0};
    int cuts = 0;
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t u = t[i], v = t[(i + 1) % 3];
      if (ahead(u) == ahead(v)) continue;
      (ahead(v) ? leaving : entering) = undirected(u, v);
      ++cuts;
    }
    if (cuts == 2 && !next.emplace(leaving, entering).second)
      throw Error("section: the surface is not closed and oriented where the plane cuts it");
  }
  if (next.empty()) {
    throw Error("section: the vertical plane at azimuth " + number(degrees(azimuth)) +
                " deg misses the envelope");
  }
  while (!next.empty()) {
    std::vector<Eigen::Vector2d> loop;
    const Edge first = next.begin()->first;
    Edge edge = first;
    for (auto at = next.find(edge); at != next.end(); at = next.find(edge)) {
      loop.push_back(cutPoint(surface, height, at->first, along));
      edge = at->second;
      next.erase(at);
    }
    if (edge != first) {
      throw Error(
          "section: the cut does not close (the surface is not closed where the plane "
          "cuts it)");
    }
    double twice = 0.0;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Eigen::Vector2d &a = loop[i], &b = loop[(i + 1) % loop.size()];
      twice += a.x() * b.y() - a.y() * b.x();
    }
    section.area += 0.5 * twice;
    section.loops.push_back(std::move(loop));
  }
  section.front_reach = -std::numeric_limits<double>::infinity();
  section.highest = -std::numeric_limits<double>::infinity();
  section.lowest = std::numeric_limits<double>::infinity();
  for (const auto& loop : section.loops) {
    for (const auto& p : loop) {
      section.front_reach = std::max(section.front_reach, p.x());
      section.back_reach = std::max(section.back_reach, -p.x());
      section.highest = std::max(section.highest, p.y());
      section.lowest = std::min(section.lowest, p.y());
    }
  }
  return section;
}

EnvelopeTopView sampleTopView(const pcl::PointCloud<pcl::PointXYZ>& points, int bins) {
  if (bins < 8) throw Error("top view: at least 8 azimuth bins, not " + std::to_string(bins));
  EnvelopeTopView view;
  view.bin = 2.0 * kPi / bins;
  view.inner.assign(bins, kNaN);
  view.outer.assign(bins, kNaN);
  bool any = false;
  for (const auto& p : points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
    const double x = p.x, y = p.y, r = std::hypot(x, y);
    const int k = static_cast<int>(std::lround((std::atan2(y, x) + kPi) / view.bin)) % bins;
    view.inner[k] = std::isnan(view.inner[k]) ? r : std::min(view.inner[k], r);
    view.outer[k] = std::isnan(view.outer[k]) ? r : std::max(view.outer[k], r);
    any = true;
  }
  if (!any) throw Error("top view: no finite points");
  view.max_reach = 0.0;
  view.min_reach = std::numeric_limits<double>::infinity();
  for (int k = 0; k < bins; ++k) {
    if (std::isnan(view.outer[k])) continue;
    view.max_reach = std::max(view.max_reach, view.outer[k]);
    view.min_reach = std::min(view.min_reach, view.inner[k]);
  }
  std::vector<bool> full(bins);
  for (int k = 0; k < bins; ++k)
    full[k] = !std::isnan(view.outer[k]) && view.outer[k] >= kFullReachShare * view.max_reach;
  const auto [first, length] = longestRun(full);
  // From the first bin's centre to the last's: samples at a joint limit lie on a centre, not
  // on either side of a bin edge by rounding.
  view.sweep = length == bins ? 2.0 * kPi : (length - 1) * view.bin;
  view.sweep_from = length == bins ? -kPi : wrapAngle(-kPi + first * view.bin);
  view.sweep_to = length == bins ? kPi : wrapAngle(view.sweep_from + view.sweep);
  return view;
}

EnvelopeDrawing envelopeDrawing(const TriangleSurface& surface,
                                const pcl::PointCloud<pcl::PointXYZ>& points, double azimuth,
                                int bins) {
  EnvelopeDrawing drawing;
  drawing.top = sampleTopView(points, bins);
  drawing.side = envelopeSection(surface, azimuth);
  drawing.highest = -std::numeric_limits<double>::infinity();
  drawing.lowest = std::numeric_limits<double>::infinity();
  for (const auto& v : surface.vertices) {
    drawing.highest = std::max(drawing.highest, v.z());
    drawing.lowest = std::min(drawing.lowest, v.z());
  }
  return drawing;
}

DrawingFormat drawingFormatOf(const std::string& path) {
  const std::string extension = lowercaseExtension(path);
  if (extension == ".png") return DrawingFormat::kPng;
  if (extension == ".svg") return DrawingFormat::kSvg;
  throw Error(path + ": not a drawing file name this tool writes (.png or .svg)");
}

std::string renderEnvelopeDrawing(const EnvelopeDrawing& drawing, DrawingFormat format,
                                  const std::string& title, const std::string& unit,
                                  const std::string& tip) {
  io::ScratchDir dir;
  const DrawingFiles files{dir.file("section.dat"), dir.file("top.dat"), dir.file("outline.dat"),
                           dir.file(format == DrawingFormat::kPng ? "d.png" : "d.svg")};
  writeDrawingData(drawing, files);
  std::ostringstream gp;
  gp << (format == DrawingFormat::kPng
             ? "set terminal pngcairo noenhanced size 1600,800 font 'Sans,11'\n"
             : "set terminal svg noenhanced size 1600,800 font 'Sans,11'\n")
     << "set output " << io::gnuplotQuoted(files.picture) << "\n"
     << "set multiplot layout 1,2 title "
     << io::gnuplotQuoted(title + ": working range" + (tip.empty() ? "" : " of " + tip) +
                          " (lengths in " + unit + ")")
     << "\n"
     << "set size ratio -1\nset grid lc rgb '#dddddd'\nunset key\n"
     << "set style fill transparent solid 0.35 noborder\n";
  writeSideView(gp, drawing.side, unit, files);
  writeTopView(gp, drawing, unit, files);
  gp << "unset multiplot\n";
  return io::runGnuplot(dir, gp.str(), files.picture);
}

}  // namespace mcws
