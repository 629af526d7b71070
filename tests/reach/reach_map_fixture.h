#pragma once
// The reach map tests' grids and samplings, and the byte images of a map and its contents voxel
// by voxel (reach_map_test.cpp, reach_map_build_test.cpp and voxel_box_test.cpp).

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "mcws/kinematics/robot.h"
#include "mcws/reach/quality.h"
#include "mcws/reach/reach_map.h"

namespace mcws::test {

/// A map grid of `resolution` voxels [robot length unit] and `directions` x `rolls` orientation
/// bins.
inline ReachGrid reachGrid(double resolution, int directions, int rolls) {
  ReachGrid grid;
  grid.resolution = resolution;
  grid.directions = directions;
  grid.rolls = rolls;
  return grid;
}

/// `samples` samples of `robot` from `seed` on `threads` threads, its default manipulability.
inline ReachSampling reachSampling(const Robot& robot, std::uint64_t samples, std::uint64_t seed,
                                   int threads) {
  ReachSampling sampling;
  sampling.samples = samples;
  sampling.seed = seed;
  sampling.threads = threads;
  sampling.quality = defaultQualityOptions(robot);
  return sampling;
}

inline std::string bytesOf(const ReachMap& map, const std::string& header = "{}") {
  std::ostringstream out(std::ios::binary);
  map.write(out, header);
  return out.str();
}

inline ReachMap readBytes(const std::string& bytes, const std::string& source,
                          std::string* header = nullptr) {
  std::istringstream in(bytes, std::ios::binary);
  return ReachMap::read(in, source, header);
}

using VoxelIndex = std::array<int, 3>;
inline VoxelIndex key(const Eigen::Vector3i& i) { return {i.x(), i.y(), i.z()}; }

/// What one voxel of a map holds.
struct Voxel {
  std::uint64_t count{0};
  float best{0.f};
  std::set<int> bins;
  bool operator==(const Voxel& o) const {
    return count == o.count && best == o.best && bins == o.bins;
  }
};

inline std::map<VoxelIndex, Voxel> contents(const ReachMap& map) {
  std::map<VoxelIndex, Voxel> out;
  for (std::size_t v = 0; v < map.size(); ++v) {
    Voxel& voxel = out[key(map.voxel(v))];
    voxel.count = map.count(v);
    voxel.best = map.bestManipulability(v);
    for (int b = 0; b < map.bins().size(); ++b) {
      if (map.reached(v, b)) voxel.bins.insert(b);
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Hand-made maps.

}  // namespace mcws::test
