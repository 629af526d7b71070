#include "mcws/sampling/sampler.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <filesystem>
#include <limits>
#include <mutex>
#include <sstream>

#include "mcws/core/error.h"
#include "mcws/core/first_error.h"

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
constexpr std::size_t kChunk = 1u << 18;  ///< samples per chunk of generateInChunks()

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

namespace {

/// The bounding box and label counts of a thread's blocks. A bound that several samples share
/// exactly (+0 and -0 compare equal) keeps the value of the sample of lowest index, as a scan of
/// the samples in order would: the result does not depend on which thread drew which block.
struct PartialSummary {
  double min[3], max[3];
  std::uint64_t min_block[3], max_block[3];     ///< the block each bound comes from
  std::size_t small_labels[4] = {0, 0, 0, 0};   ///< the collision codes, counted without the map
  std::map<std::uint32_t, std::size_t> labels;  ///< the other labels

  PartialSummary() {
    for (int a = 0; a < 3; ++a) {
      min[a] = std::numeric_limits<double>::infinity();
      max[a] = -std::numeric_limits<double>::infinity();
      min_block[a] = max_block[a] = std::numeric_limits<std::uint64_t>::max();
    }
  }

  /// Takes `value` of block `block` as the lower bound on axis `a` where it is lower, or equal
  /// and from an earlier block.
  void lower(int a, double value, std::uint64_t block) {
    if (value < min[a] || (value == min[a] && block < min_block[a])) {
      min[a] = value;
      min_block[a] = block;
    }
  }
  /// The same for the upper bound.
  void upper(int a, double value, std::uint64_t block) {
    if (value > max[a] || (value == max[a] && block < max_block[a])) {
      max[a] = value;
      max_block[a] = block;
    }
  }

  template <typename PointT>
  void add(const PointT* points, std::size_t count, std::uint64_t block) {
    double low[3], high[3];
    for (int a = 0; a < 3; ++a) {
      low[a] = std::numeric_limits<double>::infinity();
      high[a] = -std::numeric_limits<double>::infinity();
    }
    std::size_t codes[4] = {0, 0, 0, 0};
    for (std::size_t i = 0; i < count; ++i) {
      const PointT& p = points[i];
      const double v[3] = {p.x, p.y, p.z};
      for (int a = 0; a < 3; ++a) {
        if (v[a] < low[a]) low[a] = v[a];  // the first of equal values stays, as in a scan
        if (v[a] > high[a]) high[a] = v[a];
      }
      if (p.label < 4) {
        ++codes[p.label];
      } else {
        ++labels[p.label];
      }
    }
    for (int a = 0; a < 3; ++a) {
      lower(a, low[a], block);
      upper(a, high[a], block);
    }
    for (int k = 0; k < 4; ++k) small_labels[k] += codes[k];
  }

  void merge(const PartialSummary& other) {
    for (int a = 0; a < 3; ++a) {
      lower(a, other.min[a], other.min_block[a]);
      upper(a, other.max[a], other.max_block[a]);
    }
    for (int k = 0; k < 4; ++k) small_labels[k] += other.small_labels[k];
    for (const auto& [label, count] : other.labels) labels[label] += count;
  }
};

/// Hands the blocks of streamSamples() over in order: a thread waits for its block's turn.
class Turns {
 public:
  /// Waits until block `block` is next; false when a lower block failed meanwhile. A failure
  /// of a higher block does not stop it: the lowest failing block, whose error is reported, is
  /// then the same whatever the threads (a generator's failure above a block the sink refuses).
  bool wait(std::uint64_t block, const FirstError& error) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return next_ == block || error.failedBefore(block); });
    return next_ == block && !error.failedBefore(block);
  }
  /// The next block's turn.
  void pass() {
    const std::lock_guard<std::mutex> lock(mutex_);
    ++next_;
    changed_.notify_all();
  }
  /// Wakes the waiting threads after a failure (recorded before: they see it under the lock).
  void wake() {
    const std::lock_guard<std::mutex> lock(mutex_);
    changed_.notify_all();
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::uint64_t next_{0};
};

}  // namespace

template <typename PointT>
SampleSummary streamSamples(const BasicPointGenerator<PointT>& generator, std::uint64_t first,
                            std::uint64_t last, int threads, const BlockEncoder<PointT>& encode,
                            const EncodedSink& sink, SinkOrder order,
                            const std::function<void(std::size_t, std::size_t)>& progress) {
  const std::uint64_t n = last > first ? last - first : 0;
  const std::uint64_t blocks = (n + kBlock - 1) / kBlock;
  const int n_threads = threads > 0 ? threads : omp_get_num_procs();
  std::vector<PartialSummary> partial(static_cast<std::size_t>(n_threads));
  std::atomic<std::uint64_t> next_block{0}, done{0};
  FirstError error;
  Turns turns;
#pragma omp parallel num_threads(n_threads)
  {
    PartialSummary& own = partial[static_cast<std::size_t>(omp_get_thread_num())];
    std::vector<PointT, Eigen::aligned_allocator<PointT>> points;
    std::vector<char> bytes;
    std::uint64_t next_report = kChunk;  // the calling thread reports every kChunk samples
    // Blocks are taken in increasing order, so the lowest block not yet written is always being
    // worked on: in order, a thread waits only for blocks under way.
    for (std::uint64_t block; (block = next_block++) < blocks && !error.failed();) {
      const std::uint64_t begin = first + block * kBlock;
      const auto count = static_cast<std::size_t>(std::min<std::uint64_t>(kBlock, last - begin));
      // Every block taken is drawn, also after another failed: the lowest failing block always
      // runs, and its error is the one reported, whatever the threads.
      try {
        points.resize(count);
        generator.generate(begin, count, points.data());
        own.add(points.data(), count, block);
        encode(points.data(), count, bytes);
        if (order == SinkOrder::kAnyOrder || turns.wait(block, error)) {
          sink(begin, bytes.data(), bytes.size(), count);
          if (order == SinkOrder::kInOrder) turns.pass();
        }
      } catch (...) {
        error.record(static_cast<std::size_t>(block), std::current_exception());
        turns.wake();
      }
      const std::uint64_t now = done += count;
      if (progress && omp_get_thread_num() == 0 && now >= next_report && now < n) {
        next_report = (now / kChunk + 1) * kChunk;
        try {  // what it throws (a cancellation) ends the loop too
          progress(static_cast<std::size_t>(now), static_cast<std::size_t>(n));
        } catch (...) {
          error.record(static_cast<std::size_t>(block), std::current_exception());
          turns.wake();
        }
      }
    }
  }
  error.rethrow();
  PartialSummary all;
  for (const PartialSummary& part : partial) all.merge(part);
  SampleSummary summary;
  summary.min = Eigen::Vector3d(all.min[0], all.min[1], all.min[2]);
  summary.max = Eigen::Vector3d(all.max[0], all.max[1], all.max[2]);
  for (std::uint32_t label = 0; label < 4; ++label) {
    if (all.small_labels[label] > 0) summary.label_counts[label] = all.small_labels[label];
  }
  for (const auto& [label, count] : all.labels) summary.label_counts[label] += count;
  summary.points = static_cast<std::size_t>(n);
  if (progress && n > 0) progress(static_cast<std::size_t>(n), static_cast<std::size_t>(n));
  return summary;
}

template <typename PointT>
SampleSummary writeSamples(const BasicPointGenerator<PointT>& generator, std::size_t n,
                           const std::string& path, io::PcdFormat format, int threads,
                           const std::function<void(std::size_t, std::size_t)>& progress) {
  io::PcdStreamWriter<PointT> writer(path, n, format);
  const BlockEncoder<PointT> encode = [&writer](const PointT* points, std::size_t count,
                                                std::vector<char>& bytes) {
    writer.encode(points, count, bytes);
  };
  SampleSummary summary;
  if (writer.positional()) {  // binary records into a regular file: at their offsets
    summary = streamSamples<PointT>(
        generator, 0, n, threads, encode,
        [&writer](std::uint64_t first, const char* bytes, std::size_t, std::size_t count) {
          writer.writeEncodedAt(static_cast<std::size_t>(first), bytes, count);
        },
        SinkOrder::kAnyOrder, progress);
  } else {  // ASCII, a FIFO, a device: one block after the other
    summary = streamSamples<PointT>(
        generator, 0, n, threads, encode,
        [&writer](std::uint64_t, const char* bytes, std::size_t size, std::size_t count) {
          writer.writeEncoded(bytes, size, count);
        },
        SinkOrder::kInOrder, progress);
  }
  writer.commit();
  if (n == 0) summary.min = summary.max = Eigen::Vector3d::Zero();
  return summary;
}

template void generateParallel(const BasicPointGenerator<WorkspacePoint>&, std::uint64_t,
                               std::size_t, WorkspacePoint*, int);
template void generateParallel(const BasicPointGenerator<QualityPoint>&, std::uint64_t, std::size_t,
                               QualityPoint*, int);
template SampleSummary streamSamples(const BasicPointGenerator<WorkspacePoint>&, std::uint64_t,
                                     std::uint64_t, int, const BlockEncoder<WorkspacePoint>&,
                                     const EncodedSink&, SinkOrder,
                                     const std::function<void(std::size_t, std::size_t)>&);
template SampleSummary streamSamples(const BasicPointGenerator<QualityPoint>&, std::uint64_t,
                                     std::uint64_t, int, const BlockEncoder<QualityPoint>&,
                                     const EncodedSink&, SinkOrder,
                                     const std::function<void(std::size_t, std::size_t)>&);
template SampleSummary writeSamples(const BasicPointGenerator<WorkspacePoint>&, std::size_t,
                                    const std::string&, io::PcdFormat, int,
                                    const std::function<void(std::size_t, std::size_t)>&);
template SampleSummary writeSamples(const BasicPointGenerator<QualityPoint>&, std::size_t,
                                    const std::string&, io::PcdFormat, int,
                                    const std::function<void(std::size_t, std::size_t)>&);

}  // namespace mcws
