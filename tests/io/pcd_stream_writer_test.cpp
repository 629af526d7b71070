#include "mcws/io/pcd_stream_writer.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include "mcws/points/point_types.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;
using Cloud = pcl::PointCloud<WorkspacePoint>;

Cloud smallCloud() {
  Cloud cloud;
  for (int i = 0; i < 1000; ++i) {
    WorkspacePoint p;
    p.x = 0.1f * i;
    p.y = -1.5f * i;
    p.z = 1e-3f * i * i;
    for (int j = 0; j < kMaxJoints; ++j) p.q[j] = 0.01f * (i + j);
    p.label = static_cast<std::uint32_t>(i % 4);
    cloud.push_back(p);
  }
  return cloud;
}

void writeAll(const Cloud& cloud, const std::string& path, io::PcdFormat format) {
  io::PcdStreamWriter<WorkspacePoint> writer(path, cloud.size(), format);
  writer.write(cloud.data(), 300);  // in uneven pieces
  writer.write(cloud.data() + 300, cloud.size() - 300);
  writer.commit();
}

TEST(PcdStreamWriter, BinaryFileIsByteForBytePclsOwn) {
  test::TempDir dir;
  const Cloud cloud = smallCloud();
  writeAll(cloud, dir.file("mine.pcd"), io::PcdFormat::kBinary);
  ASSERT_EQ(pcl::io::savePCDFileBinary(dir.file("pcl.pcd"), cloud), 0);
  EXPECT_EQ(test::readFile(dir.file("mine.pcd")), test::readFile(dir.file("pcl.pcd")));
}

TEST(PcdStreamWriter, AsciiFileReadsBackExactly) {
  test::TempDir dir;
  const Cloud cloud = smallCloud();
  writeAll(cloud, dir.file("a.pcd"), io::PcdFormat::kAscii);
  EXPECT_THAT(test::readFile(dir.file("a.pcd")), HasSubstr("DATA ascii\n"));
  Cloud back;
  ASSERT_EQ(pcl::io::loadPCDFile(dir.file("a.pcd"), back), 0);
  ASSERT_EQ(back.size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    ASSERT_EQ(back[i].x, cloud[i].x);  // %.9g round-trips a float exactly
    ASSERT_EQ(back[i].z, cloud[i].z);
    ASSERT_EQ(back[i].q8, cloud[i].q8);
    ASSERT_EQ(back[i].label, cloud[i].label);
  }
}

TEST(PcdStreamWriter, ToolsThatKnowOnlyXyzOrXyzlReadTheFile) {
  test::TempDir dir;
  const Cloud cloud = smallCloud();
  writeAll(cloud, dir.file("ws.pcd"), io::PcdFormat::kBinary);
  pcl::PointCloud<pcl::PointXYZ> xyz;
  ASSERT_EQ(pcl::io::loadPCDFile(dir.file("ws.pcd"), xyz), 0);
  pcl::PointCloud<pcl::PointXYZL> xyzl;
  ASSERT_EQ(pcl::io::loadPCDFile(dir.file("ws.pcd"), xyzl), 0);
  ASSERT_EQ(xyz.size(), cloud.size());
  EXPECT_EQ(xyz[999].y, cloud[999].y);
  EXPECT_EQ(xyzl[7].label, 3u);
}

TEST(PcdStreamWriter, IncompleteFileIsNeverCreated) {
  test::TempDir dir;
  const Cloud cloud = smallCloud();
  {
    io::PcdStreamWriter<WorkspacePoint> writer(dir.file("short.pcd"), cloud.size());
    writer.write(cloud.data(), 10);
    try {
      writer.commit();
      FAIL();
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("10 of 1000 points written"));
    }
  }
  {
    io::PcdStreamWriter<WorkspacePoint> writer(dir.file("abandoned.pcd"), cloud.size());
    writer.write(cloud.data(), 10);
  }  // destroyed without commit, as when an exception unwinds
  EXPECT_EQ(dir.fileCount(), 0u);
}

TEST(PcdStreamWriter, RejectsMorePointsThanDeclared) {
  test::TempDir dir;
  const Cloud cloud = smallCloud();
  io::PcdStreamWriter<WorkspacePoint> writer(dir.file("x.pcd"), 5);
  EXPECT_THROW(writer.write(cloud.data(), 6), Error);
}

TEST(AtomicFile, ReportsMissingDirectoryAndFileAsDirectory) {
  test::TempDir dir;
  try {
    io::AtomicFile file(dir.file("missing/x.pcd"));
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("/missing' does not exist"));
  }
  test::writeFile(dir.file("plain"), "x");
  try {
    io::AtomicFile file(dir.file("plain/x.pcd"));
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("/plain' is not a directory"));
  }
  try {
    io::AtomicFile file(dir.file(""));
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("it is a directory"));
  }
}

}  // namespace
}  // namespace mcws
