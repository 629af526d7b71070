// The robot a cloud comes from: its header line, the SHA-256 of the robot file, the writer.
#include "mcws/io/provenance.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>

#include "mcws/io/pcd_stream_writer.h"
#include "mcws/points/point_types.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

// SHA-256 test vectors of FIPS 180-2 (appendix B.1) and of the empty message.
constexpr char kSha256Abc[] = "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad";
constexpr char kSha256Empty[] = "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855";

io::CloudProvenance example() { return {"deicing", "deicing.yaml", kSha256Abc, "cm"}; }

/// What `sha256sum` says of a file: an oracle independent of OpenSSL.
std::string sha256sum(const std::string& path) {
  const test::RunResult r = test::run("sha256sum " + path);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.out.substr(0, r.out.find(' '));
}

TEST(Sha256OfFile, GivesTheDigestsOfTheStandardAndOfSha256sum) {
  test::TempDir dir;
  test::writeFile(dir.file("abc"), "abc");
  test::writeFile(dir.file("empty"), "");
  EXPECT_EQ(io::sha256OfFile(dir.file("abc")), kSha256Abc);
  EXPECT_EQ(io::sha256OfFile(dir.file("empty")), kSha256Empty);
  // More than one 64 KiB read, ending inside the second.
  std::string big(100000, '\0');
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<char>(i * 7 % 251);
  test::writeFile(dir.file("big"), big);
  EXPECT_EQ(io::sha256OfFile(dir.file("big")), sha256sum(dir.file("big")));
  EXPECT_THAT(test::errorOf([&] { io::sha256OfFile(dir.file("none.yaml")); }),
              HasSubstr(dir.file("none.yaml") + ": cannot read the file to hash it"));
}

TEST(ProvenanceComment, PercentEncodesNamesAndReadsBack) {
  io::CloudProvenance p = example();
  EXPECT_EQ(io::provenanceComment(p),
            std::string("# mcws robot=deicing file=deicing.yaml sha256=") + kSha256Abc +
                " length_unit=cm");
  p.robot = "arm 100%=Ä";
  p.file = "my robot.yaml";
  const std::string line = io::provenanceComment(p);
  EXPECT_THAT(line, HasSubstr("robot=arm%20100%25%3D%C3%84 file=my%20robot.yaml "));
  EXPECT_TRUE(io::isProvenanceComment(line));
  EXPECT_EQ(io::parseProvenanceComment(line), p);
  // Keys in another order, blanks and tabs, unknown keys (of later versions) ignored.
  EXPECT_EQ(io::parseProvenanceComment(std::string("  #\tmcws  length_unit=cm future=1 sha256=") +
                                       kSha256Abc + " file=deicing.yaml robot=deicing\t"),
            example());
}

TEST(ProvenanceComment, TellsItsLineFromOtherComments) {
  EXPECT_TRUE(io::isProvenanceComment("# mcws robot=x"));
  EXPECT_TRUE(io::isProvenanceComment("#mcws"));
  EXPECT_TRUE(io::isProvenanceComment(" \t# mcws a"));
  EXPECT_FALSE(io::isProvenanceComment("# .PCD v0.7 - Point Cloud Data file format"));
  EXPECT_FALSE(io::isProvenanceComment("# mcwsx robot=x"));
  EXPECT_FALSE(io::isProvenanceComment("# made by mcws"));
  EXPECT_FALSE(io::isProvenanceComment("# MCWS robot=x"));
  EXPECT_FALSE(io::isProvenanceComment("mcws robot=x"));
}

TEST(ProvenanceComment, RefusesMalformedLinesSayingWhy) {
  const std::string hash = kSha256Abc;
  const auto error = [](const std::string& line) {
    return test::errorOf([&] { io::parseProvenanceComment(line); });
  };
  const std::string rest = " file=d.yaml sha256=" + hash + " length_unit=cm";
  EXPECT_THAT(error("# mcws" + rest), HasSubstr("no robot= value"));
  EXPECT_THAT(error("# mcws robot=" + rest), HasSubstr("no robot= value"));
  EXPECT_THAT(error("# mcws robot=a robot=b" + rest), HasSubstr("robot= given twice"));
  EXPECT_THAT(error("# mcws robot=a deicing" + rest), HasSubstr("'deicing' is not key=value"));
  EXPECT_THAT(error("# mcws robot=a%2" + rest), HasSubstr("robot=a%2: '%' not followed by two"));
  EXPECT_THAT(error("# mcws robot=a%0A" + rest), HasSubstr("encodes a control byte"));
  EXPECT_THAT(error("# mcws robot=a file=d.yaml sha256=" + hash + " length_unit=ft"),
              HasSubstr("length_unit=ft is not m, cm or mm"));
  EXPECT_THAT(error("# mcws robot=a file=d.yaml length_unit=cm"), HasSubstr("no sha256= value"));
  EXPECT_THAT(error("# mcws robot=a file=d.yaml sha256=AB" + hash.substr(2) + " length_unit=cm"),
              HasSubstr(" is not 64 lowercase hex digits"));
  EXPECT_THAT(error("# mcws robot=a file=d.yaml sha256=" + hash + "0 length_unit=cm"),
              HasSubstr(" is not 64 lowercase hex digits"));
  io::CloudProvenance bad = example();
  bad.sha256 = "abc";
  EXPECT_THAT(test::errorOf([&] { io::provenanceComment(bad); }), HasSubstr("sha256 'abc'"));
}

TEST(ProvenanceComment, RecordsHowTheCloudWasSampledAndReadsItBackExactly) {
  io::CloudProvenance p = example();
  // 0.1 and 1/3 need all 17 digits to read back as the same double.
  p.sampling = io::SamplingRecord{"flange", true, {{"theta 3", 0.1}, {"d:1,x", -1.0 / 3.0}}};
  const std::string line = io::provenanceComment(p);
  EXPECT_THAT(line, HasSubstr(" length_unit=cm point=flange collision=1 "
                              "fix=theta%203:0.10000000000000001,d%3A1%2Cx:-0.33333333333333331"));
  const io::CloudProvenance back = io::parseProvenanceComment(line);
  ASSERT_TRUE(back.sampling);
  EXPECT_EQ(back.sampling->fixed[0].second, 0.1);
  EXPECT_EQ(back.sampling->fixed[1].second, -1.0 / 3.0);
  EXPECT_EQ(back, p);
  p.sampling = io::SamplingRecord{};
  EXPECT_THAT(io::provenanceComment(p), HasSubstr(" point=tool collision=0 fix=none"));
  EXPECT_EQ(io::parseProvenanceComment(io::provenanceComment(p)), p);
  // A boundary's input cloud.
  p.input = io::InputCloud{20000, kSha256Empty, 700};
  EXPECT_THAT(io::provenanceComment(p), HasSubstr(std::string(" input_points=20000 input_sha256=") +
                                                  kSha256Empty + " boundary_points=700"));
  EXPECT_EQ(io::parseProvenanceComment(io::provenanceComment(p)), p);
  // A line of mcws before the record: read, with no sampling and no input.
  const io::CloudProvenance old = io::parseProvenanceComment(io::provenanceComment(example()));
  EXPECT_FALSE(old.sampling);
  EXPECT_FALSE(old.input);
}

TEST(ProvenanceComment, RefusesMalformedSamplingAndInputKeysSayingWhy) {
  const auto error = [](const std::string& keys) {
    return test::errorOf(
        [&] { io::parseProvenanceComment(io::provenanceComment(example()) + " " + keys); });
  };
  EXPECT_THAT(error("point=tool collision=0"),
              HasSubstr("point=, collision= and fix= come together: the line has 2 of them"));
  EXPECT_THAT(error("point=elbow collision=0 fix=none"), HasSubstr("point=elbow is not tool"));
  EXPECT_THAT(error("point=tool collision=yes fix=none"), HasSubstr("collision=yes is not 0 or 1"));
  EXPECT_THAT(error("point=tool collision=0 fix="), HasSubstr("fix=: '' is not NAME:VALUE"));
  EXPECT_THAT(error("point=tool collision=0 fix=a:1,"), HasSubstr("'' is not NAME:VALUE"));
  EXPECT_THAT(error("point=tool collision=0 fix=a:1x"), HasSubstr("'1x' is not a finite number"));
  EXPECT_THAT(error("point=tool collision=0 fix=a:inf"), HasSubstr("'inf' is not a finite"));
  EXPECT_THAT(error("point=tool collision=0 fix=a:1,a:2"), HasSubstr("joint 'a' given twice"));
  EXPECT_THAT(error("point=tool point=tool collision=0 fix=none"), HasSubstr("point= given twice"));
  EXPECT_THAT(error("input_points=5"),
              HasSubstr("input_points=, input_sha256= and boundary_points= come together: the "
                        "line has 1 of them"));
  EXPECT_THAT(
      error(std::string("input_points=-5 input_sha256=") + kSha256Abc + " boundary_points=1"),
      HasSubstr("input_points=-5 is not a whole number"));
  EXPECT_THAT(
      error(std::string("input_points=5 input_sha256=") + kSha256Abc + " boundary_points=1e3"),
      HasSubstr("boundary_points=1e3 is not a whole number"));
  EXPECT_THAT(error("input_points=5 input_sha256=abc boundary_points=1"),
              HasSubstr("input_sha256=abc is not 64 lowercase hex digits"));
  io::CloudProvenance bad = example();
  bad.sampling = io::SamplingRecord{"elbow", false, {}};
  EXPECT_THAT(test::errorOf([&] { io::provenanceComment(bad); }),
              HasSubstr("point 'elbow' is not tool or flange"));
}

TEST(PcdStreamWriter, RecordsTheProvenanceAfterPclsFirstLineAndPclStillReadsTheFile) {
  test::TempDir dir;
  pcl::PointCloud<WorkspacePoint> cloud;
  for (int i = 0; i < 50; ++i) {
    WorkspacePoint p;
    p.x = 0.5f * i;
    p.y = 1.0f;
    p.z = -0.25f * i;
    p.q[0] = 0.01f * i;
    cloud.push_back(p);
  }
  {
    io::PcdStreamWriter<WorkspacePoint> writer(dir.file("mine.pcd"), cloud.size(),
                                               io::PcdFormat::kBinary, example());
    writer.write(cloud.data(), cloud.size());
    writer.commit();
  }
  ASSERT_EQ(pcl::io::savePCDFileBinary(dir.file("pcl.pcd"), cloud), 0);
  // PCL's own file with the line inserted after its first line.
  std::string expected = test::readFile(dir.file("pcl.pcd"));
  expected.insert(expected.find('\n') + 1, io::provenanceComment(example()) + "\n");
  EXPECT_EQ(test::readFile(dir.file("mine.pcd")), expected);
  pcl::PointCloud<pcl::PointXYZ> back;
  ASSERT_EQ(pcl::io::loadPCDFile(dir.file("mine.pcd"), back), 0);
  ASSERT_EQ(back.size(), cloud.size());
  EXPECT_EQ(back[49].z, cloud[49].z);
}

TEST(ScopedProvenance, ReachesWritersMadeInsideACallAndEndsWithItsScope) {
  test::TempDir dir;
  const WorkspacePoint point;
  const auto write = [&](const std::string& name) {
    io::PcdStreamWriter<WorkspacePoint> writer(dir.file(name), 1, io::PcdFormat::kAscii);
    writer.write(&point, 1);
    writer.commit();
    return test::readFile(dir.file(name));
  };
  const std::string line = io::provenanceComment(example()) + "\n";
  EXPECT_THAT(write("before.pcd"), ::testing::Not(HasSubstr("# mcws")));
  {
    const io::ScopedProvenance outer(example());
    EXPECT_THAT(write("outer.pcd"), HasSubstr("format\n" + line + "VERSION"));
    io::CloudProvenance other = example();
    other.robot = "other";
    {
      const io::ScopedProvenance inner(other);
      EXPECT_THAT(write("inner.pcd"), HasSubstr("robot=other "));
    }
    EXPECT_THAT(write("outer_again.pcd"), HasSubstr(line));
  }
  EXPECT_THAT(write("after.pcd"), ::testing::Not(HasSubstr("# mcws")));
}

}  // namespace
}  // namespace mcws
