#pragma once
/// \file
/// \brief Writes a PCD file chunk by chunk, so a cloud never has to be held in memory whole.

#include <pcl/io/pcd_io.h>
#include <pcl/point_cloud.h>

#include <atomic>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/io/atomic_file.h"
#include "mcws/io/provenance.h"

namespace mcws::io {

/// \brief PCD encoding.
enum class PcdFormat { kBinary, kAscii };

/// \brief How pcl::PCDWriter lays out points of type PointT: the header it generates and the
/// binary records it packs (the fields in order, padding left out), shared by the writers of
/// this file and of mcws/distributed.
template <typename PointT>
class PcdRecordLayout {
 public:
  PcdRecordLayout() {
    for (const pcl::PCLPointField& field : pcl::getFields<PointT>()) {
      if (field.name != "_") fields_.push_back(field);
    }
    // Fields that follow each other in memory are copied as one run.
    for (const pcl::PCLPointField& field : fields_) {
      const std::size_t size =
          pcl::getFieldSize(field.datatype) * std::max<std::uint32_t>(field.count, 1);
      if (!runs_.empty() && runs_.back().offset + runs_.back().size == field.offset) {
        runs_.back().size += size;
      } else {
        runs_.push_back({field.offset, size});
      }
      record_size_ += size;
    }
  }

  /// \brief The fields written, in order.
  const std::vector<pcl::PCLPointField>& fields() const { return fields_; }
  /// \brief Bytes of one binary record.
  std::size_t recordSize() const { return record_size_; }

  /// \brief PCL's header for `points` points (at most INT_MAX), with the provenance comment
  /// after its first line: `provenance`, else that of the ScopedProvenance alive on this thread.
  std::string header(std::size_t points, PcdFormat format,
                     const std::optional<CloudProvenance>& provenance) const {
    const pcl::PointCloud<PointT> shape;  // the header reads only its viewpoint
    std::string text = pcl::PCDWriter::generateHeader<PointT>(shape, static_cast<int>(points)) +
                       (format == PcdFormat::kBinary ? "DATA binary\n" : "DATA ascii\n");
    const std::optional<CloudProvenance> robot = provenance ? provenance : scopedProvenance();
    if (robot) text.insert(text.find('\n') + 1, provenanceComment(*robot) + "\n");
    return text;
  }

  /// \brief Packs `count` points as binary records into `out` (count * recordSize() bytes).
  void pack(const PointT* points, std::size_t count, char* out) const {
    for (std::size_t i = 0; i < count; ++i) {
      const char* point = reinterpret_cast<const char*>(&points[i]);
      for (const Run& run : runs_) {
        std::memcpy(out, point + run.offset, run.size);
        out += run.size;
      }
    }
  }

 private:
  struct Run {
    std::size_t offset, size;  ///< bytes in the point struct
  };
  std::vector<pcl::PCLPointField> fields_;
  std::vector<Run> runs_;
  std::size_t record_size_{0};
};

/// \brief Streams points of type PointT into a PCD file whose point count is known up front.
///
/// The header is PCL's own (pcl::PCDWriter::generateHeader), and binary data is packed exactly as
/// pcl::PCDWriter::writeBinary packs it, so the file is byte for byte what
/// pcl::io::savePCDFileBinary would write for the same cloud, but for the one header comment line
/// that records the robot the cloud comes from (CloudProvenance) when there is one. The file is
/// written under a temporary name and appears only on commit() (see AtomicFile).
template <typename PointT>
class PcdStreamWriter {
 public:
  /// \param path target file.
  /// \param points number of points that will be written (at most INT_MAX, as in PCL).
  /// \param format binary (default) or ASCII.
  /// \param provenance the robot the points come from, recorded as a header comment after PCL's
  ///   first line; without it, that of the ScopedProvenance alive on this thread, if any.
  /// \throws mcws::Error when the path cannot be written or `points` is too large.
  PcdStreamWriter(const std::string& path, std::size_t points,
                  PcdFormat format = PcdFormat::kBinary,
                  const std::optional<CloudProvenance>& provenance = std::nullopt)
      : file_(path), declared_(points), format_(format) {
    if (points > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
      throw Error("cannot write '" + path + "': a PCD file holds at most 2^31-1 points");
    }
    const std::string header = layout_.header(points, format, provenance);
    file_.write(header.data(), header.size());
    header_size_ = header.size();
    if (format == PcdFormat::kBinary) file_.reserve(header_size_ + points * layout_.recordSize());
  }

  /// \brief Appends `count` points. \throws mcws::Error on a write error or too many points.
  void write(const PointT* points, std::size_t count) {
    encode(points, count, buffer_);
    writeEncoded(buffer_.data(), buffer_.size(), count);
  }

  /// \brief The bytes `count` points take in this file (binary records or ASCII lines), into
  /// `out` (replacing what it held). Reads only the layout: safe on several threads at once.
  /// \throws mcws::Error for a field type the ASCII writer does not handle.
  void encode(const PointT* points, std::size_t count, std::vector<char>& out) const {
    if (format_ == PcdFormat::kBinary) {
      out.resize(count * layout_.recordSize());  // no clear(): pack() writes every byte
      layout_.pack(points, count, out.data());
    } else {
      out.clear();
      for (std::size_t i = 0; i < count; ++i)
        appendAscii(reinterpret_cast<const char*>(&points[i]), out);
    }
  }

  /// \brief Appends what encode() made of the next `count` points (`size` bytes).
  /// \throws mcws::Error on a write error or too many points.
  void writeEncoded(const char* bytes, std::size_t size, std::size_t count) {
    claim(written_, count);
    file_.write(bytes, size);
    written_ += count;
  }

  /// \brief Whether writeEncodedAt() may be used: binary records into a file that can be written
  /// at offsets (AtomicFile::positional()).
  bool positional() const { return format_ == PcdFormat::kBinary && file_.positional(); }

  /// \brief Writes what encode() made of points first .. first+count-1 at their place in the
  /// file. Safe on several threads at once and in any order, each point written once; not to be
  /// mixed with write() or writeEncoded(). \pre positional().
  /// \throws mcws::Error on a write error or a point beyond the declared number.
  void writeEncodedAt(std::size_t first, const char* bytes, std::size_t count) {
    claim(first, count);
    file_.writeAt(header_size_ + first * layout_.recordSize(), bytes, count * layout_.recordSize());
    written_ += count;
  }

  /// \brief Closes the file and gives it its name.
  /// \throws mcws::Error when fewer points were written than declared, or on a write error.
  void commit() {
    if (written_ != declared_) {
      throw Error("cannot write '" + file_.path() + "': " + std::to_string(written_) + " of " +
                  std::to_string(declared_) + " points written");
    }
    file_.commit();
  }

 private:
  /// Refuses points first .. first+count-1 beyond the declared number.
  void claim(std::size_t first, std::size_t count) const {
    if (first + count > declared_) {
      throw Error("cannot write '" + file_.path() + "': more points than the header declares");
    }
  }

  void appendAscii(const char* point, std::vector<char>& out) const {
    char text[64];
    bool first = true;
    for (const pcl::PCLPointField& field : layout_.fields()) {
      const std::size_t size = pcl::getFieldSize(field.datatype);
      for (std::uint32_t k = 0; k < std::max<std::uint32_t>(field.count, 1); ++k) {
        const char* value = point + field.offset + k * size;
        int length = 0;
        switch (field.datatype) {
          case pcl::PCLPointField::FLOAT32: {
            float v;
            std::memcpy(&v, value, sizeof v);
            length = std::snprintf(text, sizeof text, "%.9g", static_cast<double>(v));
            break;
          }
          case pcl::PCLPointField::FLOAT64: {
            double v;
            std::memcpy(&v, value, sizeof v);
            length = std::snprintf(text, sizeof text, "%.17g", v);
            break;
          }
          case pcl::PCLPointField::UINT32: {
            std::uint32_t v;
            std::memcpy(&v, value, sizeof v);
            length = std::snprintf(text, sizeof text, "%" PRIu32, v);
            break;
          }
          case pcl::PCLPointField::INT32: {
            std::int32_t v;
            std::memcpy(&v, value, sizeof v);
            length = std::snprintf(text, sizeof text, "%" PRId32, v);
            break;
          }
          default:
            throw Error("cannot write '" + file_.path() + "': field '" + field.name +
                        "' has a type the ASCII writer does not handle");
        }
        if (!first) out.push_back(' ');
        out.insert(out.end(), text, text + length);
        first = false;
      }
    }
    out.push_back('\n');
  }

  AtomicFile file_;
  PcdRecordLayout<PointT> layout_;
  std::size_t declared_{0};
  std::atomic<std::size_t> written_{0};
  std::size_t header_size_{0};
  PcdFormat format_;
  std::vector<char> buffer_;
};

}  // namespace mcws::io
