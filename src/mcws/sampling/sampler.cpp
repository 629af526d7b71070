#include "mcws/sampling/sampler.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <future>
#include <limits>
#include <sstream>

#include "mcws/core/error.h"

namespace mcws {

io::CloudProvenance robotProvenance(const Robot& robot) {
  io::CloudProvenance provenance(robot.name,
                                 std::filesystem::path(robot.source).filename().string(),
                                 io::sha256OfFile(robot.source), unitName(robot.length_unit));
  provenance.base_link = robot.base_link;
  provenance.tip_link = robot.tip_link;
  return provenance;
}

namespace {

constexpr std::size_t kBlock = 4096;      ///< samples per parallel work item
constexpr std::size_t kChunk = 1u << 18;  ///< samples per chunk (one write in writeSamples())

}  // namespace

PointKinematics samplePointKinematics(const Robot& robot, SamplePoint point) {
  if (robot.dof() > kMaxJoints) {
    throw Error("robot '" + robot.name + "' has " + std::to_string(robot.dof()) +
                " joints; a workspace point records at most " + std::to_string(kMaxJoints));
  }
  return PointKinematics(robot, point == SamplePoint::kTool
                                    ? Eigen::Vector3d(robot.T_flange_tool.translation())
                                    : Eigen::Vector3d::Zero());
}

RobotSampler::RobotSampler(const Robot& robot, const RobotSamplerOptions& options)
    : rng_(options.seed),
      kinematics_(samplePointKinematics(robot, options.point)),
      lower_(robot.lowerLimits()),
      range_(robot.upperLimits() - robot.lowerLimits()) {
  std::vector<bool> pinned(robot.dof(), false);
  for (const auto& [name, value] : options.fixed) {
    const int i = robot.jointIndex(name);
    const Joint& joint = robot.joints[i];
    if (pinned[i]) throw Error("joint '" + name + "' is fixed twice");
    pinned[i] = true;
    if (!std::isfinite(value) || value < joint.lower || value > joint.upper) {
      std::ostringstream msg;
      msg.precision(10);
      msg << "fixed value " << value << " of joint '" << name << "' is outside its limits "
          << describeLimits(joint, robot.length_unit);
      throw Error(msg.str());
    }
    lower_[i] = value;
    range_[i] = 0.0;
  }
}

void RobotSampler::generate(std::uint64_t first, std::size_t count, WorkspacePoint* out) const {
  generateFromJointValues(kinematics_, first, count, out,
                          [this](std::uint64_t index, double* q) { jointValues(index, q); });
}

void RobotSampler::jointValues(std::uint64_t index, double* q) const {
  for (int j = 0; j < kinematics_.dof(); ++j) q[j] = lower_[j] + range_[j] * rng_.uniform(index, j);
}

Shape parseShape(const std::string& name) {
  if (name == "disk") return Shape::kDisk;
  if (name == "annulus") return Shape::kAnnulus;
  if (name == "ball") return Shape::kBall;
  if (name == "box") return Shape::kBox;
  throw Error("unknown shape '" + name + "' (known: disk, annulus, ball, box)");
}

double shapeMeasure(Shape shape) {
  switch (shape) {
    case Shape::kDisk:
      return M_PI;
    case Shape::kAnnulus:
      return 0.75 * M_PI;
    case Shape::kBall:
      return 4.0 * M_PI / 3.0;
    case Shape::kBox:
      return 1.0;
  }
  return 0.0;
}

bool shapeIsPlanar(Shape shape) { return shape == Shape::kDisk || shape == Shape::kAnnulus; }

double shapeBoundaryDistance(Shape shape, const Eigen::Vector3d& p) {
  const double r2d = p.head<2>().norm();
  switch (shape) {
    case Shape::kDisk:
      return std::abs(1.0 - r2d);
    case Shape::kAnnulus:
      return std::min(std::abs(1.0 - r2d), std::abs(r2d - 0.5));
    case Shape::kBall:
      return std::abs(1.0 - p.norm());
    case Shape::kBox: {
      const Eigen::Vector3d outside = (p.cwiseAbs().array() - 0.5).matrix();
      if (outside.maxCoeff() <= 0.0) return -outside.maxCoeff();  // inside: nearest face
      return outside.cwiseMax(0.0).norm();
    }
  }
  return 0.0;
}

void ShapeSampler::generate(std::uint64_t first, std::size_t count, WorkspacePoint* out) const {
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint64_t i = first + k;
    const double u0 = rng_.uniform(i, 0), u1 = rng_.uniform(i, 1), u2 = rng_.uniform(i, 2);
    double x = 0.0, y = 0.0, z = 0.0;
    switch (shape_) {
      case Shape::kDisk:
      case Shape::kAnnulus: {
        // Uniform in area: P(r < s) is proportional to s^2 - r_inner^2.
        const double r_inner2 = shape_ == Shape::kDisk ? 0.0 : 0.25;
        const double r = std::sqrt(r_inner2 + (1.0 - r_inner2) * u0);
        x = r * std::cos(2.0 * M_PI * u1);
        y = r * std::sin(2.0 * M_PI * u1);
        break;
      }
      case Shape::kBall: {
        // Uniform in volume: r = cbrt(u), direction uniform on the sphere (Archimedes).
        const double r = std::cbrt(u0);
        const double cos_polar = 1.0 - 2.0 * u1;
        const double sin_polar = std::sqrt(std::max(0.0, 1.0 - cos_polar * cos_polar));
        x = r * sin_polar * std::cos(2.0 * M_PI * u2);
        y = r * sin_polar * std::sin(2.0 * M_PI * u2);
        z = r * cos_polar;
        break;
      }
      case Shape::kBox:
        x = u0 - 0.5;
        y = u1 - 0.5;
        z = u2 - 0.5;
        break;
    }
    out[k] = WorkspacePoint();
    out[k].x = static_cast<float>(x);
    out[k].y = static_cast<float>(y);
    out[k].z = static_cast<float>(z);
  }
}

template <typename PointT>
void generateParallel(const BasicPointGenerator<PointT>& generator, std::uint64_t first,
                      std::size_t count, PointT* out, int threads) {
  const int n_threads = threads > 0 ? threads : omp_get_num_procs();
  const std::int64_t blocks = static_cast<std::int64_t>((count + kBlock - 1) / kBlock);
#pragma omp parallel for schedule(static) num_threads(n_threads)
  for (std::int64_t b = 0; b < blocks; ++b) {
    const std::size_t begin = static_cast<std::size_t>(b) * kBlock;
    generator.generate(first + begin, std::min(kBlock, count - begin), out + begin);
  }
}

void generateInChunks(const PointGenerator& generator, std::size_t n, WorkspacePoint* out,
                      int threads, const std::function<void(std::size_t, std::size_t)>& progress) {
  for (std::size_t begin = 0; begin < n; begin += kChunk) {
    const std::size_t count = std::min(kChunk, n - begin);
    generateParallel(generator, begin, count, out + begin, threads);
    if (progress) progress(begin + count, n);
  }
}

pcl::PointCloud<WorkspacePoint> sampleCloud(const PointGenerator& generator, std::size_t n,
                                            int threads) {
  pcl::PointCloud<WorkspacePoint> cloud;
  cloud.resize(n);
  generateParallel(generator, 0, n, cloud.data(), threads);
  cloud.width = static_cast<std::uint32_t>(n);
  cloud.height = 1;
  cloud.is_dense = true;
  return cloud;
}

template <typename PointT>
SampleSummary streamSamples(const BasicPointGenerator<PointT>& generator, std::uint64_t first,
                            std::uint64_t last, int threads, const ChunkSink<PointT>& sink,
                            const std::function<void(std::size_t, std::size_t)>& progress) {
  SampleSummary summary;
  summary.min.setConstant(std::numeric_limits<double>::infinity());
  summary.max.setConstant(-std::numeric_limits<double>::infinity());
  const std::uint64_t n = last > first ? last - first : 0;

  // Two buffers: the next chunk is computed while the previous one is being written.
  std::vector<PointT, Eigen::aligned_allocator<PointT>> buffers[2];
  std::future<void> pending;
  for (std::uint64_t begin = first, chunk = 0; begin < last; begin += kChunk, ++chunk) {
    const std::size_t count =
        static_cast<std::size_t>(std::min<std::uint64_t>(kChunk, last - begin));
    auto& buffer = buffers[chunk % 2];
    buffer.resize(count);
    generateParallel(generator, begin, count, buffer.data(), threads);
    std::size_t small_labels[4] = {0, 0, 0, 0};  // the collision codes, counted without the map
    for (const PointT& p : buffer) {
      const Eigen::Vector3d v(p.x, p.y, p.z);
      summary.min = summary.min.cwiseMin(v);
      summary.max = summary.max.cwiseMax(v);
      if (p.label < 4) {
        ++small_labels[p.label];
      } else {
        ++summary.label_counts[p.label];
      }
    }
    for (std::uint32_t label = 0; label < 4; ++label) {
      if (small_labels[label] > 0) summary.label_counts[label] += small_labels[label];
    }
    if (pending.valid()) pending.get();  // rethrows a write error
    pending = std::async(std::launch::async,
                         [&sink, &buffer, begin, count] { sink(begin, buffer.data(), count); });
    if (progress)
      progress(static_cast<std::size_t>(begin - first + count), static_cast<std::size_t>(n));
  }
  if (pending.valid()) pending.get();
  summary.points = static_cast<std::size_t>(n);
  return summary;
}

template <typename PointT>
SampleSummary writeSamples(const BasicPointGenerator<PointT>& generator, std::size_t n,
                           const std::string& path, io::PcdFormat format, int threads,
                           const std::function<void(std::size_t, std::size_t)>& progress) {
  io::PcdStreamWriter<PointT> writer(path, n, format);
  SampleSummary summary = streamSamples<PointT>(
      generator, 0, n, threads,
      [&writer](std::uint64_t, const PointT* points, std::size_t count) {
        writer.write(points, count);
      },
      progress);
  writer.commit();
  if (n == 0) summary.min = summary.max = Eigen::Vector3d::Zero();
  return summary;
}

template void generateParallel(const BasicPointGenerator<WorkspacePoint>&, std::uint64_t,
                               std::size_t, WorkspacePoint*, int);
template void generateParallel(const BasicPointGenerator<QualityPoint>&, std::uint64_t, std::size_t,
                               QualityPoint*, int);
template SampleSummary streamSamples(const BasicPointGenerator<WorkspacePoint>&, std::uint64_t,
                                     std::uint64_t, int, const ChunkSink<WorkspacePoint>&,
                                     const std::function<void(std::size_t, std::size_t)>&);
template SampleSummary streamSamples(const BasicPointGenerator<QualityPoint>&, std::uint64_t,
                                     std::uint64_t, int, const ChunkSink<QualityPoint>&,
                                     const std::function<void(std::size_t, std::size_t)>&);
template SampleSummary writeSamples(const BasicPointGenerator<WorkspacePoint>&, std::size_t,
                                    const std::string&, io::PcdFormat, int,
                                    const std::function<void(std::size_t, std::size_t)>&);
template SampleSummary writeSamples(const BasicPointGenerator<QualityPoint>&, std::size_t,
                                    const std::string&, io::PcdFormat, int,
                                    const std::function<void(std::size_t, std::size_t)>&);

}  // namespace mcws
