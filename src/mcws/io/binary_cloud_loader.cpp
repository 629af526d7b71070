#include "mcws/io/binary_cloud_loader.h"

#include <fcntl.h>
#include <omp.h>
#include <pcl/console/print.h>
#include <pcl/conversions.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/core/first_error.h"

namespace mcws::io {

namespace {

/// Bytes of the file one thread reads and converts at a time: the piece stays in the core's
/// cache while it is converted.
constexpr std::size_t kPieceBytes = std::size_t{256} << 10;

/// A file descriptor closed when it leaves scope.
class DataFile {
 public:
  explicit DataFile(const std::string& path) : fd_(::open(path.c_str(), O_RDONLY | O_CLOEXEC)) {
    if (fd_ < 0) throw Error(path + ": cannot read the file");
  }
  ~DataFile() { ::close(fd_); }
  DataFile(const DataFile&) = delete;
  DataFile& operator=(const DataFile&) = delete;

  /// Whether all `size` bytes at `offset` were read into `out`.
  bool readAt(std::uint64_t offset, std::size_t size, std::uint8_t* out) const {
    while (size > 0) {
      const ssize_t got = ::pread(fd_, out, size, static_cast<off_t>(offset));
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) return false;
      out += got;
      offset += static_cast<std::uint64_t>(got);
      size -= static_cast<std::size_t>(got);
    }
    return true;
  }

 private:
  int fd_;
};

/// What becomes of one record: the byte ranges PCL's field mapping copies into the point, and
/// the float values whose finiteness decides is_dense (pcl::PCDReader checks every field's).
struct RecordLayout {
  pcl::MsgFieldMap copies;
  std::vector<std::uint32_t> floats, doubles;  ///< byte offsets in the record
  std::size_t bytes{0};                        ///< bytes per record

  RecordLayout(const std::vector<pcl::PCLPointField>& fields, std::size_t record_bytes)
      : bytes(record_bytes) {
    const pcl::console::VERBOSITY_LEVEL level = pcl::console::getVerbosityLevel();
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);  // missing q/label fields are fine
    pcl::createMapping<WorkspacePoint>(fields, copies);
    pcl::console::setVerbosityLevel(level);
    for (const pcl::PCLPointField& f : fields) {
      for (std::uint32_t c = 0; c < f.count; ++c) {
        if (f.datatype == pcl::PCLPointField::FLOAT32) floats.push_back(f.offset + 4 * c);
        if (f.datatype == pcl::PCLPointField::FLOAT64) doubles.push_back(f.offset + 8 * c);
      }
    }
  }

  /// Whether every float value of the record is finite.
  bool finite(const std::uint8_t* record) const {
    for (const std::uint32_t offset : floats) {
      float v;
      std::memcpy(&v, record + offset, sizeof v);
      if (!std::isfinite(v)) return false;
    }
    for (const std::uint32_t offset : doubles) {
      double v;
      std::memcpy(&v, record + offset, sizeof v);
      if (!std::isfinite(v)) return false;
    }
    return true;
  }

  /// Converts `count` records to the points `out` (constructed), as fromPCLPointCloud2() does;
  /// returns false when a float value is not finite (only looked for while `dense`).
  bool convert(const std::uint8_t* records, std::size_t count, WorkspacePoint* out, bool dense,
               CoordinateRange& range) const {
    for (std::size_t k = 0; k < count; ++k) {
      const std::uint8_t* record = records + k * bytes;
      auto* point = reinterpret_cast<std::uint8_t*>(out + k);
      for (const pcl::detail::FieldMapping& m : copies) {
        std::memcpy(point + m.struct_offset, record + m.serialized_offset, m.size);
      }
      if (dense) dense = finite(record);
      range.add(out[k]);
    }
    return dense;
  }
};

}  // namespace

std::vector<pcl::PCLPointField> pcdFields(const pcd::PcdHeader& header) {
  std::vector<pcl::PCLPointField> fields;
  std::uint32_t offset = 0;
  for (const pcd::PcdField& f : header.fields) {
    fields.push_back(pcd::pclField(f, offset));
    offset += static_cast<std::uint32_t>(f.size * f.count);
  }
  return fields;
}

void loadBinaryCloud(const std::string& path, const pcd::PcdHeader& header,
                     const std::vector<pcl::PCLPointField>& fields, WorkspaceCloud& cloud,
                     CoordinateRange& range) {
  const RecordLayout layout(fields, header.pointSize());
  const std::uint64_t n = header.points;
  cloud.width = static_cast<std::uint32_t>(header.width);
  cloud.height = static_cast<std::uint32_t>(header.height);
  cloud.resize(n);  // default points: the bytes no field of the file fills
  const DataFile file(path);
  const std::size_t piece = std::max<std::size_t>(1, kPieceBytes / layout.bytes);
  const auto pieces = static_cast<std::int64_t>((n + piece - 1) / piece);
  FirstError error;
  bool dense = true;
  std::vector<CoordinateRange> ranges(static_cast<std::size_t>(omp_get_max_threads()));
#pragma omp parallel reduction(&& : dense)
  {
    std::vector<std::uint8_t> bytes(piece * layout.bytes);
    CoordinateRange& own = ranges[static_cast<std::size_t>(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 4)
    for (std::int64_t p = 0; p < pieces; ++p) {
      error.run(static_cast<std::size_t>(p), [&] {
        const std::uint64_t first = static_cast<std::uint64_t>(p) * piece;
        const std::size_t count =
            static_cast<std::size_t>(std::min<std::uint64_t>(piece, n - first));
        if (!file.readAt(header.data_offset + first * layout.bytes, count * layout.bytes,
                         bytes.data())) {
          throw Error(path + ": cannot read points " + std::to_string(first) + " to " +
                      std::to_string(first + count) + " (the file changed while it was read?)");
        }
        dense = layout.convert(bytes.data(), count, &cloud[first], dense, own);
      });
    }
  }
  error.rethrow();
  cloud.is_dense = dense;
  for (const CoordinateRange& r : ranges) range.merge(r);
}

}  // namespace mcws::io
