#include "mcws/distributed/sample_writer.h"

#include <limits>
#include <mutex>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/io/pcd_stream_writer.h"

namespace mcws::distributed {

template <typename PointT>
SampleSummary writeSamplesTogether(const Processes& processes,
                                   const BasicPointGenerator<PointT>& generator, std::size_t n,
                                   const std::string& path, int threads,
                                   const std::function<void(std::size_t, std::size_t)>& progress,
                                   const std::optional<io::CloudProvenance>& provenance,
                                   const PointT* prefix, std::uint64_t prefix_size) {
  const std::uint64_t total = prefix_size + n;
  if (total > static_cast<std::uint64_t>(std::numeric_limits<int>::max())) {
    throw Error("cannot write '" + path + "': a PCD file holds at most 2^31-1 points");
  }
  const io::PcdRecordLayout<PointT> layout;
  const std::string header = layout.header(total, io::PcdFormat::kBinary, provenance);
  const std::uint64_t record = layout.recordSize();
  SharedFile file(processes, path);
  std::vector<char> bytes;
  auto writePoints = [&](std::uint64_t first_record, const PointT* points, std::size_t count) {
    bytes.resize(count * record);
    layout.pack(points, count, bytes.data());
    file.writeAt(header.size() + first_record * record, bytes.data(), bytes.size());
  };
  if (processes.rank() == 0) {
    file.writeAt(0, header.data(), header.size());
    for (std::uint64_t k = 0; k < prefix_size; k += 1u << 16) {
      writePoints(k, prefix + k,
                  static_cast<std::size_t>(std::min<std::uint64_t>(1u << 16, prefix_size - k)));
    }
  }
  const Block block = blockOf(n, processes.rank(), processes.size());
  std::mutex writing;  // SharedFile::writeAt() one thread at a time (MPI_THREAD_SERIALIZED)
  const SampleSummary own = streamSamples<PointT>(
      generator, block.begin, block.end, threads,
      [&layout](const PointT* points, std::size_t count, std::vector<char>& out) {
        out.resize(count * layout.recordSize());
        layout.pack(points, count, out.data());
      },
      [&](std::uint64_t first, const char* data, std::size_t size, std::size_t) {
        const std::lock_guard<std::mutex> lock(writing);
        file.writeAt(header.size() + (prefix_size + first) * record, data, size);
      },
      SinkOrder::kAnyOrder,
      processes.rank() == 0 ? progress : std::function<void(std::size_t, std::size_t)>());
  file.commit();
  return combineSummaries(processes, own);
}

SampleSummary combineSummaries(const Processes& processes, const SampleSummary& own) {
  SampleSummary all;
  std::vector<std::uint64_t> points{own.points};
  processes.sum(points);
  all.points = static_cast<std::size_t>(points[0]);
  std::vector<double> lo(own.min.data(), own.min.data() + 3),
      hi(own.max.data(), own.max.data() + 3);
  processes.min(lo);
  processes.max(hi);
  all.min = Eigen::Vector3d(lo[0], lo[1], lo[2]);
  all.max = Eigen::Vector3d(hi[0], hi[1], hi[2]);
  if (all.points == 0) all.min = all.max = Eigen::Vector3d::Zero();
  std::vector<std::uint64_t> labels;  // (label, count) pairs
  for (const auto& [label, count] : own.label_counts) {
    labels.push_back(label);
    labels.push_back(count);
  }
  const std::vector<std::uint64_t> gathered = processes.gather(labels);
  for (std::size_t k = 0; k + 1 < gathered.size(); k += 2) {
    all.label_counts[static_cast<std::uint32_t>(gathered[k])] +=
        static_cast<std::size_t>(gathered[k + 1]);
  }
  return all;
}

template SampleSummary writeSamplesTogether(const Processes&,
                                            const BasicPointGenerator<WorkspacePoint>&, std::size_t,
                                            const std::string&, int,
                                            const std::function<void(std::size_t, std::size_t)>&,
                                            const std::optional<io::CloudProvenance>&,
                                            const WorkspacePoint*, std::uint64_t);
template SampleSummary writeSamplesTogether(const Processes&,
                                            const BasicPointGenerator<QualityPoint>&, std::size_t,
                                            const std::string&, int,
                                            const std::function<void(std::size_t, std::size_t)>&,
                                            const std::optional<io::CloudProvenance>&,
                                            const QualityPoint*, std::uint64_t);

}  // namespace mcws::distributed
