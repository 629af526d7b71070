// ReachMap.query: points and tool orientations looked up in a reachability map (the library's
// ReachMap::find and ReachMap::reached).
#include "reach_query.h"

#include <cmath>
#include <string>

namespace mcws::python {

namespace {

/// Whether row i of `directions` (N, 3) or (N, 3, 3) was reached in voxel v.
bool orientationReached(const ReachMap& map, std::size_t v, const DoubleArray& directions,
                        py::ssize_t i) {
  const double* d = directions.data() + i * (directions.ndim() == 2 ? 3 : 9);
  if (directions.ndim() == 2) {
    return map.approachReached(v, map.bins().sphere().region(Eigen::Vector3d(d[0], d[1], d[2])));
  }
  const Eigen::Matrix3d R = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d);
  return map.reached(v, map.bins().bin(R.col(2), R.col(0)));
}

void checkDirections(const DoubleArray& directions, py::ssize_t n) {
  const bool approaches = directions.ndim() == 2 && directions.shape(1) == 3;
  const bool rotations =
      directions.ndim() == 3 && directions.shape(1) == 3 && directions.shape(2) == 3;
  if (!(approaches || rotations) || directions.shape(0) != n) {
    throw UsageError("directions: shape " + shapeText(directions) + " is neither (" +
                     std::to_string(n) + ", 3) nor (" + std::to_string(n) + ", 3, 3)");
  }
  const py::ssize_t row = approaches ? 3 : 9;
  for (py::ssize_t i = 0; i < n; ++i) {
    const double* d = directions.data() + i * row;
    bool finite = true;
    for (py::ssize_t k = 0; k < row; ++k) finite = finite && std::isfinite(d[k]);
    // The approach: the row itself, or the rotation's third column.
    const Eigen::Vector3d z =
        approaches ? Eigen::Vector3d(d[0], d[1], d[2]) : Eigen::Vector3d(d[2], d[5], d[8]);
    if (!finite || z.norm() == 0.0) {
      throw UsageError("directions: row " + std::to_string(i) +
                       " is not finite or has a zero approach");
    }
  }
}

}  // namespace

py::dict queryMap(const ReachMap& map, const py::handle& points_value,
                  const py::handle& directions_value) {
  const DoubleArray points = doubleArray(points_value, "points");
  if (points.ndim() != 2 || points.shape(1) != 3) {
    throw UsageError("points: shape " + shapeText(points) + " is not (N, 3)");
  }
  const py::ssize_t n = points.shape(0);
  std::optional<DoubleArray> directions;
  if (!directions_value.is_none()) {
    directions = doubleArray(directions_value, "directions");
    checkDirections(*directions, n);
  }
  py::array_t<std::int64_t> voxel(n);
  py::array_t<double> reachability(n);
  py::array_t<float> manipulability(n);
  py::array_t<std::uint64_t> count(n);
  py::array_t<bool> reached(directions ? n : 0);
  {
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < n; ++i) {
      const double* p = points.data() + 3 * i;
      const long v = map.find(Eigen::Vector3d(p[0], p[1], p[2]));
      const auto u = static_cast<std::size_t>(v);
      voxel.mutable_data()[i] = v;
      reachability.mutable_data()[i] = v < 0 ? 0.0 : map.reachability(u);
      manipulability.mutable_data()[i] = v < 0 ? 0.0f : map.bestManipulability(u);
      count.mutable_data()[i] = v < 0 ? 0 : map.count(u);
      if (directions) {
        reached.mutable_data()[i] = v >= 0 && orientationReached(map, u, *directions, i);
      }
    }
  }
  py::dict out;
  out["voxel"] = voxel;
  out["reachability"] = reachability;
  out["manipulability"] = manipulability;
  out["count"] = count;
  if (directions) out["reached"] = reached;
  return out;
}

}  // namespace mcws::python
