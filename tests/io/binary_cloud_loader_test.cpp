// io::readCloud()'s binary loader against the reader it replaces (PCL's reader and
// pcl::fromPCLPointCloud2(), io::readCloudWithPcl()): the same points byte for byte, width,
// height, is_dense and header, on many field layouts, and the same errors.
#include "mcws/io/binary_cloud_loader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "mcws/io/cloud_io.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

/// A field of a hand-made PCD file.
struct Field {
  std::string name;
  char type;
  int size;
  int count;
};

/// Random record bytes: floats mostly ordinary numbers, now and then NaN or infinity when
/// `specials`; other types random bytes.
void appendValue(std::string& data, const Field& f, std::mt19937& rng, bool specials) {
  std::uniform_real_distribution<double> number(-10.0, 10.0);
  if (f.type == 'F') {
    double v = number(rng);
    if (specials && rng() % 50 == 0) {
      v = rng() % 2 ? std::numeric_limits<double>::quiet_NaN()
                    : -std::numeric_limits<double>::infinity();
    }
    if (f.size == 4) {
      const auto s = static_cast<float>(v);
      data.append(reinterpret_cast<const char*>(&s), 4);
    } else {
      data.append(reinterpret_cast<const char*>(&v), 8);
    }
    return;
  }
  for (int b = 0; b < f.size; ++b) data.push_back(static_cast<char>(rng() & 0xff));
}

/// Writes a DATA binary PCD file of `width` x `height` random points with these fields; x, y, z
/// are NaN now and then when `specials`.
void writePcd(const std::string& path, const std::vector<Field>& fields, std::size_t width,
              std::size_t height, unsigned seed, bool specials, const std::string& comment = "") {
  std::string names, sizes, types, counts;
  for (const Field& f : fields) {
    names += " " + f.name;
    sizes += " " + std::to_string(f.size);
    types += std::string(" ") + f.type;
    counts += " " + std::to_string(f.count);
  }
  std::string text = "# .PCD v0.7 - Point Cloud Data file format\n" + comment +
                     "VERSION 0.7\nFIELDS" + names + "\nSIZE" + sizes + "\nTYPE" + types +
                     "\nCOUNT" + counts + "\nWIDTH " + std::to_string(width) + "\nHEIGHT " +
                     std::to_string(height) + "\nVIEWPOINT 1 2 3 1 0 0 0\nPOINTS " +
                     std::to_string(width * height) + "\nDATA binary\n";
  std::mt19937 rng(seed);
  for (std::size_t i = 0; i < width * height; ++i) {
    for (const Field& f : fields) {
      for (int c = 0; c < f.count; ++c) appendValue(text, f, rng, specials);
    }
  }
  test::writeFile(path, text);
}

/// The bytes of a point that the conversion defines: every member, not the padding after label.
constexpr std::size_t kDefinedBytes = offsetof(WorkspacePoint, label) + sizeof(std::uint32_t);

/// Expects readCloud() and the PCL path to give the same cloud for `path`.
void expectSameCloud(const std::string& path) {
  SCOPED_TRACE(path);
  const io::WorkspaceCloud::Ptr fast = io::readCloud(path);
  const io::WorkspaceCloud::Ptr pcl = io::readCloudWithPcl(path);
  ASSERT_EQ(fast->size(), pcl->size());
  EXPECT_EQ(fast->width, pcl->width);
  EXPECT_EQ(fast->height, pcl->height);
  EXPECT_EQ(fast->is_dense, pcl->is_dense);
  EXPECT_EQ(fast->header.seq, pcl->header.seq);
  EXPECT_EQ(fast->header.stamp, pcl->header.stamp);
  EXPECT_EQ(fast->header.frame_id, pcl->header.frame_id);
  EXPECT_EQ(fast->sensor_origin_, pcl->sensor_origin_);
  EXPECT_EQ(fast->sensor_orientation_.coeffs(), pcl->sensor_orientation_.coeffs());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < fast->size(); ++i) {
    differing += std::memcmp(&(*fast)[i], &(*pcl)[i], kDefinedBytes) != 0;
  }
  EXPECT_EQ(differing, 0u);
}

/// The message of what `read` throws ("" when nothing).
template <typename Read>
std::string errorOf(Read read) {
  try {
    read();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

const Field kX{"x", 'F', 4, 1}, kY{"y", 'F', 4, 1}, kZ{"z", 'F', 4, 1};
const Field kLabel{"label", 'U', 4, 1};

std::vector<Field> workspaceFields() {
  std::vector<Field> fields{kX, kY, kZ};
  for (int j = 1; j <= kMaxJoints; ++j) fields.push_back({"q" + std::to_string(j), 'F', 4, 1});
  fields.push_back(kLabel);
  return fields;
}

TEST(BinaryCloudLoader, WorkspaceFilesAsTheSamplerWritesThem) {
  test::TempDir dir;
  // Pieces of 256 KiB hold 5461 records of 48 bytes: one point, fewer than a piece, several
  // pieces and a partial last one.
  for (const std::size_t n : {1u, 100u, 5461u, 5462u, 30001u}) {
    const std::string path = dir.file("w" + std::to_string(n) + ".pcd");
    writePcd(path, workspaceFields(), n, 1, static_cast<unsigned>(n), true);
    expectSameCloud(path);
  }
  // As the tools write it, with the provenance line.
  io::WorkspaceCloud cloud;
  for (int i = 0; i < 2000; ++i) {
    WorkspacePoint p;
    p.x = 0.5f * static_cast<float>(i);
    p.y = std::sin(static_cast<float>(i));
    p.z = i % 7 == 0 ? std::numeric_limits<float>::quiet_NaN() : 1.0f;
    p.q[i % kMaxJoints] = 0.25f;
    p.label = static_cast<std::uint32_t>(i % 4);
    cloud.push_back(p);
  }
  pcl::Indices all(cloud.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<pcl::index_t>(i);
  io::writeCloud(cloud, all, dir.file("tool.pcd"));
  expectSameCloud(dir.file("tool.pcd"));
}

TEST(BinaryCloudLoader, PclPointTypes) {
  test::TempDir dir;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  pcl::PointCloud<pcl::PointXYZ> xyz;
  pcl::PointCloud<pcl::PointXYZL> xyzl;
  pcl::PointCloud<pcl::PointXYZI> xyzi;
  pcl::PointCloud<pcl::PointNormal> normal;  // PCL writes its padding as "_" fields
  pcl::PointCloud<pcl::PointXYZRGBNormal> rgb;
  for (int i = 0; i < 7000; ++i) {
    xyz.emplace_back(u(rng), u(rng), u(rng));
    pcl::PointXYZL l;
    l.getVector3fMap() = xyz.back().getVector3fMap();
    l.label = static_cast<std::uint32_t>(i);
    xyzl.push_back(l);
    pcl::PointXYZI intensity(u(rng));
    intensity.getVector3fMap() = xyz.back().getVector3fMap();
    xyzi.push_back(intensity);
    pcl::PointNormal n;
    n.getVector3fMap() = xyz.back().getVector3fMap();
    n.normal_x = u(rng);
    n.curvature = u(rng);
    normal.push_back(n);
    pcl::PointXYZRGBNormal c;
    c.getVector3fMap() = xyz.back().getVector3fMap();
    c.rgba = rng();
    c.normal_z = u(rng);
    rgb.push_back(c);
  }
  xyz[5].x = std::numeric_limits<float>::quiet_NaN();
  ASSERT_EQ(pcl::io::savePCDFileBinary(dir.file("xyz.pcd"), xyz), 0);
  ASSERT_EQ(pcl::io::savePCDFileBinary(dir.file("xyzl.pcd"), xyzl), 0);
  ASSERT_EQ(pcl::io::savePCDFileBinary(dir.file("xyzi.pcd"), xyzi), 0);
  ASSERT_EQ(pcl::io::savePCDFileBinary(dir.file("normal.pcd"), normal), 0);
  ASSERT_EQ(pcl::io::savePCDFileBinary(dir.file("rgb.pcd"), rgb), 0);
  for (const char* name : {"xyz.pcd", "xyzl.pcd", "xyzi.pcd", "normal.pcd", "rgb.pcd"}) {
    expectSameCloud(dir.file(name));
  }
}

TEST(BinaryCloudLoader, FieldLayouts) {
  test::TempDir dir;
  const Field pad{"_", 'F', 4, 1}, bytes{"_", 'U', 1, 3};
  const Field q1{"q1", 'F', 4, 1}, q2{"q2", 'F', 4, 1}, q8{"q8", 'F', 4, 1};
  const Field wide{"normal", 'F', 8, 3}, small{"ring", 'U', 2, 1}, sign{"t", 'I', 8, 1};
  const std::vector<std::vector<Field>> layouts = {
      {kX, kY, kZ},                                  // pcl::PointXYZ
      {kX, kY, kZ, kLabel},                          // pcl::PointXYZL
      {kX, kY, kZ, pad, q1, q2},                     // padding copied into the 4th coordinate
      {kX, kY, kZ, pad, q1, q2, q8, kLabel},         // q3..q7 missing
      {kZ, kY, kX},                                  // reordered
      {kLabel, q8, kX, wide, kY, small, kZ, q1},     // scattered, with foreign fields
      {bytes, kX, kY, kZ, sign, kLabel, bytes, q2},  // odd record size
      {q1, q2, kX, kY, kZ},                          // x y z after q
  };
  for (std::size_t k = 0; k < layouts.size(); ++k) {
    const std::string path = dir.file("layout" + std::to_string(k) + ".pcd");
    writePcd(path, layouts[k], 9000, 1, static_cast<unsigned>(k), k % 2 == 1);
    expectSameCloud(path);
  }
  // PCL's field mapping copies x to q2 as one range of bytes across the padding field: the
  // file's "_" lands in the point's 4th coordinate (1 by default), and the loader does the same.
  const io::WorkspaceCloud::Ptr padded = io::readCloud(dir.file("layout2.pcd"));
  EXPECT_NE((*padded)[0].data[3], 1.0f);
}

TEST(BinaryCloudLoader, OrganisedCloudsAndDensity) {
  test::TempDir dir;
  writePcd(dir.file("organised.pcd"), workspaceFields(), 70, 30, 11, false);
  expectSameCloud(dir.file("organised.pcd"));
  EXPECT_TRUE(io::readCloud(dir.file("organised.pcd"))->is_dense);
  EXPECT_EQ(io::readCloud(dir.file("organised.pcd"))->height, 30u);
  // A NaN in a field that is not read still makes the cloud not dense, as in PCL's reader.
  const Field extra{"w", 'F', 8, 2};
  writePcd(dir.file("extra.pcd"), {kX, kY, kZ, extra}, 50000, 1, 12, true);
  expectSameCloud(dir.file("extra.pcd"));
  EXPECT_FALSE(io::readCloud(dir.file("extra.pcd"))->is_dense);
  // A record longer than a piece.
  writePcd(dir.file("long.pcd"), {kX, {"blob", 'U', 1, 300000}, kY, kZ}, 3, 2, 13, false);
  expectSameCloud(dir.file("long.pcd"));
}

TEST(BinaryCloudLoader, SameErrors) {
  test::TempDir dir;
  const std::string wrong = dir.file("wrong.pcd");
  writePcd(wrong, {kX, kY, kZ, {"label", 'F', 4, 1}}, 10, 1, 1, false);
  const std::string far = dir.file("far.pcd");
  {
    io::WorkspaceCloud cloud;
    cloud.resize(3);
    cloud[1].y = -3e18f;
    io::writeCloud(cloud, {0, 1, 2}, far);
  }
  const std::string tiny = dir.file("tiny.pcd");
  {
    io::WorkspaceCloud cloud;
    cloud.resize(2);
    cloud[1].z = 1e-21f;
    io::writeCloud(cloud, {0, 1}, tiny);
  }
  const std::string cut = dir.file("cut.pcd");
  writePcd(cut, workspaceFields(), 100, 1, 2, false);
  const std::string text = test::readFile(cut);
  test::writeFile(cut, text.substr(0, text.size() - 10));
  for (const std::string& path : {wrong, far, tiny, cut}) {
    const std::string message = errorOf([&] { io::readCloud(path); });
    EXPECT_THAT(message, HasSubstr(path));
    EXPECT_EQ(message, errorOf([&] { io::readCloudWithPcl(path); }));
  }
}

}  // namespace
}  // namespace mcws
