#include "mcws/reach/reach_plot.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "mcws/core/error.h"
#include "mcws/io/gnuplot.h"

namespace mcws {

using io::gnuplotQuoted;

std::string renderHalfCutPng(const ReachMap& map, double y_cut, const std::string& title,
                             const std::string& unit) {
  io::ScratchDir dir;
  const std::string data = dir.file("slab.dat"), png = dir.file("halfcut.png");
  std::ostringstream cut;
  cut << y_cut;  // "0", "12.5": no trailing zeros
  const int slab = map.voxelOf({0.0, y_cut, 0.0}).y();
  std::size_t voxels = 0;
  {
    std::ofstream out(data);
    out.precision(9);
    for (std::size_t v = 0; v < map.size(); ++v) {
      const Eigen::Vector3i index = map.voxel(v);
      if (index.y() != slab) continue;
      const Eigen::Vector3d c = map.voxelCentre(index);
      out << c.x() << ' ' << c.z() << ' ' << map.reachability(v) << '\n';
      ++voxels;
    }
  }
  if (voxels == 0) throw Error("half-cut view: no voxel of the map at y = " + cut.str());
  const double half = 0.5 * map.grid().resolution;
  std::ostringstream gp;
  gp << "set terminal pngcairo noenhanced size 1100,900 font 'Sans,11'\n"
     << "set output " << gnuplotQuoted(png) << "\n"
     << "set title "
     << gnuplotQuoted(title + ": reachability index D, the slab through y = " + cut.str() + " " +
                      unit + " seen along y")
     << "\nset xlabel " << gnuplotQuoted("x [" + unit + "]") << "\nset ylabel "
     << gnuplotQuoted("z [" + unit + "]") << "\nset size ratio -1\nset grid\n"
     << "set cbrange [0:1]\nset cblabel 'D: share of orientation bins reached [1]'\n"
     << "set palette defined (0 '#30123b', 0.25 '#4686fb', 0.5 '#1ae4b6', 0.75 '#faba39', "
        "1 '#7a0403')\n"
     << "plot " << gnuplotQuoted(data) << " using 1:2:(" << half << "):(" << half
     << "):3 with boxxyerror fs solid 1.0 noborder fc palette notitle\n";
  return io::runGnuplot(dir, gp.str(), png);
}

std::string renderReachabilityHistogramPng(const ReachMap& map, const std::string& title) {
  if (map.size() == 0) throw Error("histogram of D: the map is empty");
  constexpr int kBins = 20;
  std::size_t counts[kBins] = {};
  for (std::size_t v = 0; v < map.size(); ++v) {
    ++counts[std::min(kBins - 1, static_cast<int>(map.reachability(v) * kBins))];
  }
  io::ScratchDir dir;
  const std::string data = dir.file("histogram.dat"), png = dir.file("histogram.png");
  {
    std::ofstream out(data);
    for (int b = 0; b < kBins; ++b) out << (b + 0.5) / kBins << ' ' << counts[b] << '\n';
  }
  std::ostringstream gp;
  gp << "set terminal pngcairo noenhanced size 1000,650 font 'Sans,11'\n"
     << "set output " << gnuplotQuoted(png) << "\n"
     << "set title "
     << gnuplotQuoted(title + ": reachability index over " + std::to_string(map.size()) +
                      " occupied voxels")
     << "\nset xlabel 'D: share of orientation bins reached [1]'\nset ylabel 'voxels'\n"
     << "set xrange [0:1]\nset yrange [0:*]\nset grid ytics\nset boxwidth " << 1.0 / kBins
     << "\nset style fill solid 0.8 border rgb '#1f3b73'\n"
     << "plot " << gnuplotQuoted(data)
     << " using 1:2 with boxes lc rgb '#4686fb' title 'voxels per 0.05 of D'\n";
  return io::runGnuplot(dir, gp.str(), png);
}

}  // namespace mcws
