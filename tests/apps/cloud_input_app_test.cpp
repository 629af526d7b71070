// Broken and hostile PCD input through the real tools (mcws issue 17): every file PCL's reader
// would crash on, allocate gigabytes for, or read as something else, gives one line naming the
// file and the problem, exit code 1 and no output, at once; valid files of PCL's three encodings
// load as the same cloud.
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "apps/tool_paths.h"
#include "mcws/points/point_types.h"
#include "test_support.h"

namespace mcws {
namespace {

/// A rejected file is rejected before any reading of its data: far below this even under
/// AddressSanitizer (the 4 GB claim took 34 s before the checks).
constexpr double kFastSeconds = 5.0;

/// The header PCL writes for fields x y z (4-byte floats) and `points` points, lines 1 to 11.
std::string pcdHeader(int points, const std::string& data = "ascii") {
  const std::string n = std::to_string(points);
  return "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\n"
         "TYPE F F F\nCOUNT 1 1 1\nWIDTH " +
         n + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + n + "\nDATA " + data + "\n";
}

/// Four points spanning a volume, as ASCII rows (lines 12 to 15 after pcdHeader).
const std::string kRows = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";

/// A 6 x 6 grid of spacing 1 in the xy plane, label k % 3 for the k-th point.
pcl::PointCloud<WorkspacePoint> grid() {
  pcl::PointCloud<WorkspacePoint> cloud;
  for (int k = 0; k < 36; ++k) {
    WorkspacePoint p;
    p.x = static_cast<float>(k % 6);
    p.y = static_cast<float>(k / 6);
    p.z = 0.0f;
    p.q1 = 0.25f * static_cast<float>(k);
    p.label = static_cast<std::uint32_t>(k % 3);
    cloud.push_back(p);
  }
  return cloud;
}

class CloudInputApp : public ::testing::Test {
 protected:
  /// Writes `text` as the input file `name` and returns its path.
  std::string input(const std::string& name, const std::string& text) {
    const std::string path = inputs_.file(name);
    test::writeFile(path, text);
    return path;
  }

  /// Writes `points` at `points` (x, y, z) with PCL's binary writer and returns the path.
  std::string binaryCloud(const std::string& name, const std::vector<Eigen::Vector3f>& points) {
    pcl::PointCloud<pcl::PointXYZ> cloud;
    for (const Eigen::Vector3f& p : points) cloud.push_back({p.x(), p.y(), p.z()});
    const std::string path = inputs_.file(name);
    EXPECT_EQ(pcl::io::savePCDFileBinary(path, cloud), 0);
    return path;
  }

  /// `tool` on `path` (with `args`, and --output but for mcws_measure, which writes none) fails
  /// with exit code 1, one line "tool: path: message", nothing written, and fast.
  void expectRejected(const std::string& tool, const std::string& path, const std::string& message,
                      const std::string& args = "") {
    const std::string output = tool == kMeasure ? "" : " --output " + outputs_.file("out.pcd");
    const auto start = std::chrono::steady_clock::now();
    test::expectToolFailure(tool, "--input " + path + output + " " + args, 1, path + ": " + message,
                            outputs_);
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    EXPECT_LT(elapsed.count(), kFastSeconds) << path;
  }

  test::TempDir inputs_, outputs_;
};

TEST_F(CloudInputApp, HeaderWithAnUnknownKeyword) {
  std::string text = pcdHeader(4) + kRows;
  text.replace(text.find("VERSION"), 7, "FOO");
  expectRejected(kBoundary, input("foo.pcd", text),
                 "not a readable PCD file: line 2: unknown header keyword 'FOO' (a PCD header has "
                 "VERSION FIELDS SIZE "
                 "TYPE COUNT WIDTH HEIGHT VIEWPOINT POINTS DATA, in this order)");
}

TEST_F(CloudInputApp, HeaderWithANulByteIsReportedEscaped) {
  std::string text = pcdHeader(4) + kRows;
  text[text.find("FIELDS x y") + 8] = '\0';  // FIELDS x\0y z
  const std::string path = input("nul.pcd", text);
  expectRejected(kBoundary, path,
                 "not a readable PCD file: line 3: control byte \\x00 in the header");
  EXPECT_EQ(test::run(kBoundary + " --input " + path + " --output " + outputs_.file("o.pcd"))
                .err.find('\0'),
            std::string::npos);
}

TEST_F(CloudInputApp, HeaderLinesOutOfOrderOrMissing) {
  std::string swapped = pcdHeader(4) + kRows;
  swapped.replace(swapped.find("SIZE 4 4 4\nTYPE F F F"), 21, "TYPE F F F\nSIZE 4 4 4");
  expectRejected(kBoundary, input("swapped.pcd", swapped),
                 "not a readable PCD file: line 4: TYPE where SIZE belongs (VERSION FIELDS");
  std::string no_height = pcdHeader(4) + kRows;
  no_height.erase(no_height.find("HEIGHT 1\n"), 9);
  expectRejected(kBoundary, input("noheight.pcd", no_height),
                 "not a readable PCD file: line 8: VIEWPOINT where HEIGHT belongs");
}

TEST_F(CloudInputApp, SizeThatDoesNotMatchTheType) {
  std::string half = pcdHeader(4) + kRows;
  half.replace(half.find("SIZE 4 4 4"), 10, "SIZE 4 4 2");
  expectRejected(
      kBoundary, input("half.pcd", half),
      "not a readable PCD file: line 5: field 'z' is TYPE F SIZE 2: a float has SIZE 4 or 8");
  std::string three = pcdHeader(4) + kRows;
  three.replace(three.find("SIZE 4 4 4"), 10, "SIZE 4 4 3");
  expectRejected(kBoundary, input("three.pcd", three),
                 "not a readable PCD file: line 4: SIZE '3' of field 'z' is not 1, 2, 4 or 8");
  std::string fewer = pcdHeader(4) + kRows;
  fewer.replace(fewer.find("COUNT 1 1 1"), 11, "COUNT 1 1");
  expectRejected(kBoundary, input("fewer.pcd", fewer),
                 "not a readable PCD file: line 6: COUNT has 2 values for 3 FIELDS");
}

TEST_F(CloudInputApp, UnknownType) {
  std::string text = pcdHeader(4) + kRows;
  text.replace(text.find("TYPE F F F"), 10, "TYPE F F X");
  expectRejected(kBoundary, input("type.pcd", text),
                 "not a readable PCD file: line 5: TYPE 'X' of field 'z' is not I, U or F");
}

TEST_F(CloudInputApp, PointsThatAreNotWidthTimesHeight) {
  std::string text = pcdHeader(4) + kRows;
  text.replace(text.find("POINTS 4"), 8, "POINTS 5");
  expectRejected(kBoundary, input("points.pcd", text),
                 "not a readable PCD file: line 10: POINTS 5 is not WIDTH x HEIGHT = 4 x 1");
}

TEST_F(CloudInputApp, BinaryFileShorterThanItsHeaderSays) {
  const std::string path =
      binaryCloud("short.pcd", std::vector<Eigen::Vector3f>(8, Eigen::Vector3f(1.0f, 2.0f, 3.0f)));
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 5);
  // 8 points of x y z floats: 96 bytes, 5 of them cut.
  expectRejected(kBoundary, path,
                 "the binary data is 91 bytes, POINTS 8 x 12 bytes need 96 (the file is cut "
                 "short)");
}

TEST_F(CloudInputApp, CompressedDataWithSizesItCannotHave) {
  pcl::PointCloud<pcl::PointXYZ> cloud;
  for (int k = 0; k < 8; ++k) cloud.push_back({float(k), float(k % 2), float(k % 3)});
  const std::string valid = inputs_.file("valid.pcd");
  ASSERT_EQ(pcl::io::savePCDFileBinaryCompressed(valid, cloud), 0);
  const std::string text = test::readFile(valid);
  const std::size_t sizes = text.find("DATA binary_compressed\n") + 23;
  std::uint32_t compressed = 0;
  std::memcpy(&compressed, text.data() + sizes, 4);
  ASSERT_EQ(sizes + 8 + compressed, text.size());  // PCL's layout: two sizes, then the data

  std::string huge = text;  // 4 GB uncompressed, as in the review
  const std::uint32_t four_gb = 0xffffffffu;
  std::memcpy(huge.data() + sizes + 4, &four_gb, 4);
  expectRejected(kBoundary, input("huge.pcd", huge),
                 "the compressed data claims 4294967295 bytes uncompressed, POINTS 8 x 12 bytes "
                 "are 96");

  std::string beyond = text;  // more compressed bytes than the file holds
  const std::uint32_t claimed = compressed + 1;
  std::memcpy(beyond.data() + sizes, &claimed, 4);
  expectRejected(kBoundary, input("beyond.pcd", beyond),
                 "the compressed data claims " + std::to_string(claimed) +
                     " bytes, the file holds " + std::to_string(compressed));

  // 200 million points of 12 bytes (2.4 GB) in a file of a few hundred bytes: the sizes agree
  // with the header, but LZF expands n bytes to at most 88 n.
  std::string many = text;
  many.replace(many.find("WIDTH 8"), 7, "WIDTH 200000000");
  many.replace(many.find("POINTS 8"), 8, "POINTS 200000000");
  const std::size_t many_sizes = many.find("DATA binary_compressed\n") + 23;
  const std::uint32_t bytes = 2400000000u;
  std::memcpy(many.data() + many_sizes + 4, &bytes, 4);
  expectRejected(kBoundary, input("many.pcd", many),
                 std::to_string(compressed) +
                     " compressed bytes cannot hold POINTS 200000000 x 12 bytes (LZF expands at "
                     "most 88 times)");
}

TEST_F(CloudInputApp, AsciiValuesThatAreNotNumbers) {
  expectRejected(kBoundary, input("abc.pcd", pcdHeader(4) + "0 0 0\n1 abc 0\n0 1 0\n0 0 1\n"),
                 "line 13: value 2 'abc' of field 'y' (TYPE F SIZE 4) is not a number");
  expectRejected(kBoundary, input("big.pcd", pcdHeader(4) + "0 0 0\n1 0 0\n0 1 1e39\n0 0 1\n"),
                 "line 14: value 3 '1e39' of field 'z' (TYPE F SIZE 4) is beyond the range of a "
                 "4-byte float");
}

TEST_F(CloudInputApp, AsciiRowsThatDoNotMatchTheHeader) {
  expectRejected(kBoundary, input("short.pcd", pcdHeader(4) + "0 0 0\n1 0\n0 1 0\n0 0 1\n"),
                 "line 13: 2 values, the fields need 3");
  expectRejected(kBoundary, input("extra.pcd", pcdHeader(4) + kRows + "1 1 1\n"),
                 "line 16: a row beyond the 4 POINTS the header declares");
  expectRejected(kBoundary, input("missing.pcd", pcdHeader(5) + kRows),
                 "the ascii data has 4 rows, POINTS says 5");
}

TEST_F(CloudInputApp, CoordinatesBeyondWhatTheGeometryCanRepresent) {
  for (const float far : {1e38f, 1e20f}) {
    // A corner tetrahedron of edge `far` and a point inside: a region in 3-D and in the plane,
    // but one whose squared distances overflow a float.
    const std::string path = binaryCloud(
        "far.pcd", {{0, 0, 0}, {far, 0, 0}, {0, far, 0}, {0, 0, far}, {far / 4, far / 4, far / 4}});
    const std::string message = "coordinates up to " +
                                std::string(far > 1e30f ? "1e+38" : "1e+20") +
                                " are beyond what the geometry can represent (|x| <= 1e+18)";
    for (const std::string& tool : {kBoundary, kMeasure}) {
      expectRejected(tool, path, message);
      expectRejected(tool, path, message, "--plane xy");
    }
  }
}

TEST_F(CloudInputApp, ExtentTooSmallForTheGeometry) {
  const float tiny = 1e-25f;
  const std::string path =
      binaryCloud("tiny.pcd", {{0, 0, 0}, {tiny, 0, 0}, {0, tiny, 0}, {0, 0, tiny}});
  const std::string message =
      "the points span only 1e-25, too little for the geometry to resolve (an extent >= 1e-19, "
      "or all points at one place)";
  expectRejected(kBoundary, path, message);
  expectRejected(kMeasure, path, message, "--plane xy");
}

TEST_F(CloudInputApp, LabelThatIsNotAnUnsignedInteger) {
  for (const std::string type : {"F", "I"}) {
    const std::string text =
        "VERSION 0.7\nFIELDS x y z label\nSIZE 4 4 4 4\nTYPE F F F " + type +
        "\nCOUNT 1 1 1 1\nWIDTH 2\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA ascii\n"
        "0 0 0 1\n1 0 0 0\n";
    expectRejected(kSelect, input("label.pcd", text),
                   "field 'label' is TYPE " + type +
                       " SIZE 4 COUNT 1, not the TYPE U SIZE 4 COUNT 1 it is read as",
                   "--label 0");
  }
}

TEST_F(CloudInputApp, EveryPclEncodingLoadsAsTheSameCloud) {
  const pcl::PointCloud<WorkspacePoint> cloud = grid();
  const std::string ascii = inputs_.file("ascii.pcd"), binary = inputs_.file("binary.pcd"),
                    compressed = inputs_.file("compressed.pcd");
  ASSERT_EQ(pcl::io::savePCDFileASCII(ascii, cloud), 0);
  ASSERT_EQ(pcl::io::savePCDFileBinary(binary, cloud), 0);
  ASSERT_EQ(pcl::io::savePCDFileBinaryCompressed(compressed, cloud), 0);
  std::string first_boundary;
  for (const std::string& path : {ascii, binary, compressed}) {
    // On a grid of spacing 1 within radius 1.5, the 20 points of the rim have an empty
    // quadrant and the 16 inside none.
    const std::string boundary = outputs_.file("boundary.pcd");
    const test::RunResult r = test::run(kBoundary + " --input " + path + " --output " + boundary +
                                        " --plane xy --radius 1.5 --json");
    ASSERT_EQ(r.exit_code, 0) << path << "\n" << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["boundary"].get<int>(), 20) << path;
    if (first_boundary.empty()) first_boundary = test::readFile(boundary);
    EXPECT_EQ(test::readFile(boundary), first_boundary) << path;  // labels and joints too

    // Labels 0, 1, 2 in turn: a third of the 36 points each.
    const test::RunResult select = test::run(kSelect + " --input " + path + " --label 1 --output " +
                                             outputs_.file("selected.pcd") + " --json");
    ASSERT_EQ(select.exit_code, 0) << path << "\n" << select.err;
    EXPECT_EQ(nlohmann::json::parse(select.out)["points_out"].get<int>(), 12) << path;
  }
}

}  // namespace
}  // namespace mcws
