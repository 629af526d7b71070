#pragma once
/// \file
/// \brief Samples of a point generator (the library's sampling module) computed with the GIL
/// released and handed to NumPy without a copy: what mcws.sample, mcws.sample_shape and
/// mcws.refine return.

#include <Eigen/Core>
#include <algorithm>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bindings.h"
#include "mcws/reach/quality.h"
#include "mcws/sampling/sampler.h"
#include "point_layout.h"

namespace mcws::python {

/// \brief Samples computed between two looks for Ctrl-C (a fraction of a second of work).
constexpr std::size_t kSamplePiece = std::size_t{1} << 16;

/// \brief Samples 0 .. n-1 of `generator` on `threads` threads (0: all cores) with the GIL
/// released, into an array of pointDtype(joints, PointT) that owns them. The points do not depend
/// on `threads` (a sample's random numbers depend on its index only). `checkpoint` after each
/// piece: Ctrl-C stops the loop and raises KeyboardInterrupt.
template <typename PointT>
py::array samplePoints(const BasicPointGenerator<PointT>& generator, std::size_t n, int threads,
                       int joints, Checkpoint& checkpoint) {
  auto points = std::make_unique<std::vector<PointT, Eigen::aligned_allocator<PointT>>>(n);
  PointT* out = points->data();
  // The records' padding too is defined (zero), so that equal points are equal bytes.
  if (n > 0) std::memset(static_cast<void*>(out), 0, n * sizeof(PointT));
  {
    py::gil_scoped_release release;
    for (std::size_t begin = 0; begin < n; begin += kSamplePiece) {
      generateParallel(generator, begin, std::min(kSamplePiece, n - begin), out + begin, threads);
      checkpoint(begin + std::min(kSamplePiece, n - begin), n);
    }
  }
  const py::dtype dtype = pointDtype<PointT>(joints);
  return ownedArray(std::move(points), dtype, {static_cast<py::ssize_t>(n)},
                    {static_cast<py::ssize_t>(sizeof(PointT))}, out);
}

/// \brief A sample count n >= 0. \throws UsageError "n: ... is negative".
std::size_t sampleCount(std::int64_t n);

/// \brief mcws.sample's `fix`: a dict joint name -> value [rad | length unit], or None (empty).
/// \throws UsageError naming `fix` and the bad entry.
std::vector<std::pair<std::string, double>> fixedJoints(const py::handle& fix);

/// \brief The sample point "tool" or "flange". \throws UsageError naming `point` and the value.
SamplePoint samplePoint(const std::string& point);

/// \brief How manipulability is measured: the robot's default (defaultQualityOptions()), with the
/// task "position" or "full" and the characteristic length L [length unit] of "full" if given.
/// \throws UsageError naming quality_task or length and the bad value.
QualityOptions qualityOptions(const Robot& robot, const std::optional<std::string>& task,
                              const std::optional<double>& length);

}  // namespace mcws::python
