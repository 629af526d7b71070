#include "mcws/search/grid_then_tree_search.h"

#include <gtest/gtest.h>

#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace mcws {
namespace {

/// A 40 x 40 lattice of unit spacing in the x-y plane, and the identity numbering.
GridThenTreeSearch lattice(std::vector<pcl::index_t>& position_of, bool use_grid) {
  pcl::PointCloud<pcl::PointXYZ> cloud;
  for (int x = 0; x < 40; ++x) {
    for (int y = 0; y < 40; ++y) cloud.push_back(pcl::PointXYZ(x, y, 0.0f));
  }
  position_of.resize(cloud.size());
  std::iota(position_of.begin(), position_of.end(), 0);
  return GridThenTreeSearch(std::move(cloud), position_of, 2, 2.0, 1.0, use_grid);
}

// A task that throws on one point on two threads: the exception leaves forEachPoint() as it was
// thrown, where without the guard it would leave the OpenMP region and end the process
// (std::terminate), with the grid and with the tree alike.
TEST(GridThenTreeSearch, ATaskThatThrowsLeavesForEachPointAsItsException) {
  for (const bool use_grid : {true, false}) {
    std::vector<pcl::index_t> position_of;
    GridThenTreeSearch search = lattice(position_of, use_grid);
    std::vector<pcl::index_t> points(search.size());
    std::iota(points.begin(), points.end(), 0);
    const pcl::index_t failing = position_of[777];
    int served = 0;
    try {
      search.forEachPoint<int>(points, 2, [&](auto&, pcl::index_t i, int&) {
        if (i == failing) throw std::runtime_error("point " + std::to_string(i));
#pragma omp atomic
        ++served;
        return true;
      });
      ADD_FAILURE() << "no exception (grid " << use_grid << ")";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), "point " + std::to_string(failing));
    }
    EXPECT_LT(served, 1600);
  }
}

}  // namespace
}  // namespace mcws
