#pragma once
/// \file
/// \brief Monte Carlo workspace sampling (Yin, Wang & Yu 2010, section 3; Fu, Hu, Chen & Pan 2016,
/// eq. (5)) and validation shapes of known area or volume.

#include <pcl/point_cloud.h>

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "mcws/core/counter_rng.h"
#include "mcws/io/pcd_stream_writer.h"
#include "mcws/io/provenance.h"
#include "mcws/kinematics/point_kinematics.h"
#include "mcws/kinematics/robot.h"
#include "mcws/points/point_types.h"

namespace mcws {

/// \brief Anything that turns sample indices into points of type PointT, deterministically.
template <typename PointT>
class BasicPointGenerator {
 public:
  using Point = PointT;
  virtual ~BasicPointGenerator() = default;
  /// \brief Writes samples first .. first+count-1 to out[0 .. count).
  virtual void generate(std::uint64_t first, std::size_t count, PointT* out) const = 0;
};

/// \brief Anything that turns sample indices into workspace points, deterministically.
using PointGenerator = BasicPointGenerator<WorkspacePoint>;

/// \brief Which point of the robot a sample records (the P and T clouds of Fu, Hu, Chen & Pan
/// 2016).
enum class SamplePoint { kTool, kFlange };

/// \brief The kinematics that map a sample's joint values to its recorded point: the tool point
/// (the tool frame's origin) or the flange origin.
/// \throws mcws::Error for a robot with more than kMaxJoints joints (a WorkspacePoint cannot
///   record their values).
PointKinematics samplePointKinematics(const Robot& robot, SamplePoint point);

/// \brief The provenance of clouds made from `robot`: its name, the base name and SHA-256 of the
/// file it was read from (Robot::source), its length unit and, for a URDF robot, its chain
/// (Robot::base_link, Robot::tip_link).
/// \throws mcws::Error naming the file when it cannot be read any more.
io::CloudProvenance robotProvenance(const Robot& robot);

/// \brief The batch loop of the joint-space samplers: samples first .. first+count-1 mapped
/// through the vectorised kernel PointKinematics::kLanes at a time and written to
/// out[0 .. count) as x y z [length unit], q1..qn and label 0. A last, partial batch is padded
/// with copies of its last sample, so every sample takes the same code path whatever the batch
/// boundaries (and the output does not depend on how the samples were split).
/// \param draw `draw(index, q)` writes sample `index`'s joint values to q[0 .. dof)
///   [rad | length unit]; it must depend on the index only.
template <typename Draw>
void generateFromJointValues(const PointKinematics& kinematics, std::uint64_t first,
                             std::size_t count, WorkspacePoint* out, const Draw& draw) {
  constexpr int kLanes = PointKinematics::kLanes;
  const int n = kinematics.dof();
  double sample_q[kMaxJoints], q[kMaxJoints * kLanes], x[kLanes], y[kLanes], z[kLanes];
  for (std::size_t begin = 0; begin < count; begin += kLanes) {
    const int lanes = static_cast<int>(std::min<std::size_t>(kLanes, count - begin));
    for (int k = 0; k < kLanes; ++k) {
      draw(first + begin + static_cast<std::uint64_t>(std::min(k, lanes - 1)), sample_q);
      for (int j = 0; j < n; ++j) q[j * kLanes + k] = sample_q[j];
    }
    kinematics.positions(q, x, y, z);
    for (int k = 0; k < lanes; ++k) {
      WorkspacePoint& point = out[begin + k];
      point = WorkspacePoint();
      point.x = static_cast<float>(x[k]);
      point.y = static_cast<float>(y[k]);
      point.z = static_cast<float>(z[k]);
      for (int j = 0; j < n; ++j) point.q[j] = static_cast<float>(q[j * kLanes + k]);
    }
  }
}

/// \brief Options of RobotSampler.
struct RobotSamplerOptions {
  std::uint64_t seed{1};
  SamplePoint point{SamplePoint::kTool};
  /// Joints pinned to a value [rad | length unit] instead of sampled, by name.
  std::vector<std::pair<std::string, double>> fixed;
};

/// \brief Joint values uniform within their limits (Fu, Hu, Chen & Pan 2016, eq. (5):
/// q_i = q_i,min + (q_i,max - q_i,min) t_i, t_i uniform in [0, 1)), mapped through forward
/// kinematics. The point carries x y z [length unit], q1..qn and label 0.
class RobotSampler : public PointGenerator {
 public:
  /// \throws mcws::Error for a robot with more than kMaxJoints joints, an unknown joint in
  ///   `fixed`, or a fixed value outside its joint's limits.
  RobotSampler(const Robot& robot, const RobotSamplerOptions& options);
  void generate(std::uint64_t first, std::size_t count, WorkspacePoint* out) const override;
  /// \brief The joint values of sample `index`, exactly as generate() draws them, into
  /// q[0 .. dof) [rad | length unit].
  void jointValues(std::uint64_t index, double* q) const;

 private:
  CounterRng rng_;
  PointKinematics kinematics_;
  Eigen::VectorXd lower_, range_;  ///< range 0 for a fixed joint
};

/// \brief Regions with a known area or volume, sampled uniformly in area or volume.
enum class Shape {
  kDisk,     ///< unit disk in the x-y plane (z = 0), area pi
  kAnnulus,  ///< annulus 0.5 <= r <= 1 in the x-y plane, area 0.75 pi
  kBall,     ///< unit ball, volume 4 pi / 3
  kBox,      ///< unit cube [-0.5, 0.5]^3, volume 1
};

/// \brief Shape from its name (disk, annulus, ball, box).
/// \throws mcws::Error naming the unknown shape and the known ones.
Shape parseShape(const std::string& name);
/// \brief Exact area (2-D shapes) or volume (3-D shapes).
double shapeMeasure(Shape shape);
/// \brief True for the planar shapes (disk, annulus).
bool shapeIsPlanar(Shape shape);
/// \brief Distance from p to the shape's boundary (for a planar shape, within its plane z = 0):
/// the rim of the disk, both circles of the annulus, the sphere, the cube's faces.
double shapeBoundaryDistance(Shape shape, const Eigen::Vector3d& p);

/// \brief Uniform samples of a validation shape (q fields zero, label 0).
class ShapeSampler : public PointGenerator {
 public:
  ShapeSampler(Shape shape, std::uint64_t seed) : shape_(shape), rng_(seed) {}
  void generate(std::uint64_t first, std::size_t count, WorkspacePoint* out) const override;

 private:
  Shape shape_;
  CounterRng rng_;
};

/// \brief generator.generate() over [first, first+count) split across `threads` threads
/// (0: all cores). The result does not depend on `threads`. PointT: WorkspacePoint or
/// QualityPoint.
template <typename PointT>
void generateParallel(const BasicPointGenerator<PointT>& generator, std::uint64_t first,
                      std::size_t count, PointT* out, int threads);

/// \brief Samples 0 .. n-1 into out[0 .. n), chunk by chunk, each chunk split across `threads`
/// threads (0: all cores). The result does not depend on `threads`. \param progress called after
/// each chunk with (points done, n); may be empty.
void generateInChunks(const PointGenerator& generator, std::size_t n, WorkspacePoint* out,
                      int threads,
                      const std::function<void(std::size_t, std::size_t)>& progress = {});

/// \brief Samples 0 .. n-1 as a cloud in memory.
pcl::PointCloud<WorkspacePoint> sampleCloud(const PointGenerator& generator, std::size_t n,
                                            int threads);

/// \brief What writeSamples() wrote.
struct SampleSummary {
  std::size_t points{0};
  Eigen::Vector3d min{Eigen::Vector3d::Zero()};  ///< bounding box [length unit]
  Eigen::Vector3d max{Eigen::Vector3d::Zero()};
  std::map<std::uint32_t, std::size_t> label_counts;  ///< points per label value
};

/// \brief Turns a block of points into the bytes they take in an output: (points, their number,
/// the bytes, replaced). Called on several threads at once.
template <typename PointT>
using BlockEncoder = std::function<void(const PointT*, std::size_t, std::vector<char>&)>;

/// \brief Receives the blocks of streamSamples(): (index of the block's first sample, its bytes,
/// their number, the block's number of samples).
using EncodedSink = std::function<void(std::uint64_t, const char*, std::size_t, std::size_t)>;

/// \brief How streamSamples() hands its blocks to the sink.
enum class SinkOrder {
  kInOrder,   ///< one at a time, in the order of their samples (a stream, an ASCII file)
  kAnyOrder,  ///< as they are ready, on several threads at once (writes at offsets)
};

/// \brief Samples first .. last-1 in blocks of a few thousand, on `threads` threads (0: all
/// cores), each thread drawing a block, encoding it with `encode` and handing the bytes to `sink`
/// itself, so that writing one block overlaps computing the others without a writing thread or a
/// second copy of the points; returns their summary (with no points, a bounding box of +inf ..
/// -inf). Memory: a block of points and its bytes per thread. The blocks and their bytes do not
/// depend on `threads`, nor does the summary.
/// \param order kAnyOrder: `sink` must be safe on several threads at once.
/// \param progress called on the calling thread now and then, and at the end, with (samples
///   done, last - first); may be empty. What it throws (a cancellation) ends the loop and is
///   rethrown.
/// PointT: WorkspacePoint or QualityPoint. Rethrows what `generator`, `encode` or `sink` throws
/// (that of the lowest block) once every thread has stopped.
template <typename PointT>
SampleSummary streamSamples(const BasicPointGenerator<PointT>& generator, std::uint64_t first,
                            std::uint64_t last, int threads, const BlockEncoder<PointT>& encode,
                            const EncodedSink& sink, SinkOrder order,
                            const std::function<void(std::size_t, std::size_t)>& progress = {});

/// \brief Streams samples 0 .. n-1 into a PCD file block by block (streamSamples(); binary records
/// into a regular file are written at their offsets by the threads that compute them), so clouds
/// larger than memory can be written; the file appears only when complete.
/// \param progress called now and then, and at the end, with (points done, n); may be empty.
/// PointT: WorkspacePoint or QualityPoint.
/// \throws mcws::Error when the file cannot be written.
template <typename PointT>
SampleSummary writeSamples(const BasicPointGenerator<PointT>& generator, std::size_t n,
                           const std::string& path, io::PcdFormat format, int threads,
                           const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace mcws
