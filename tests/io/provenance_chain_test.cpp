// A URDF robot's chain in a cloud's header line (issue 33 item 6): base_link= and tip_link=, read
// back, required together, and the frame the points are of (io::recordedTip()).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mcws/io/provenance.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

constexpr char kChainSha[] = "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad";

io::CloudProvenance ur5AtEeLink() {
  io::CloudProvenance p("ur5_shaped", "ur5.urdf", kChainSha, "m");
  p.base_link = "world";
  p.tip_link = "ee_link";
  p.sampling = io::SamplingRecord{"tool", true, {}};
  return p;
}

TEST(ProvenanceChain, RecordsTheChainBeforeTheSamplingAndReadsItBack) {
  const io::CloudProvenance p = ur5AtEeLink();
  const std::string line = io::provenanceComment(p);
  EXPECT_EQ(line, std::string("# mcws robot=ur5_shaped file=ur5.urdf sha256=") + kChainSha +
                      " length_unit=m base_link=world tip_link=ee_link point=tool collision=1 "
                      "fix=none");
  EXPECT_EQ(io::parseProvenanceComment(line), p);
  // A link name with a blank stays one word.
  io::CloudProvenance spaced = p;
  spaced.tip_link = "tool 0";
  EXPECT_THAT(io::provenanceComment(spaced), HasSubstr(" tip_link=tool%200 "));
  EXPECT_EQ(io::parseProvenanceComment(io::provenanceComment(spaced)), spaced);
  // Another chain of the same file is another record.
  spaced.tip_link = "tool0";
  EXPECT_NE(spaced, p);
}

TEST(ProvenanceChain, ADhRobotRecordsNoChain) {
  io::CloudProvenance p = ur5AtEeLink();
  p.base_link.clear();
  p.tip_link.clear();
  EXPECT_THAT(io::provenanceComment(p), Not(HasSubstr("_link=")));
}

TEST(ProvenanceChain, TheBaseAndTheTipComeTogether) {
  io::CloudProvenance p = ur5AtEeLink();
  p.base_link.clear();
  EXPECT_THAT(test::errorOf([&] { io::provenanceComment(p); }),
              HasSubstr("base link '' and tip link 'ee_link' come both or neither"));
  const std::string head =
      std::string("# mcws robot=r file=r.urdf sha256=") + kChainSha + " length_unit=m ";
  EXPECT_THAT(test::errorOf([&] { io::parseProvenanceComment(head + "tip_link=ee_link"); }),
              HasSubstr("base_link= and tip_link= come together: the line has one of them"));
  EXPECT_THAT(
      test::errorOf([&] { io::parseProvenanceComment(head + "base_link=world tip_link="); }),
      HasSubstr("base_link= and tip_link= name a link each: one is empty"));
}

TEST(ProvenanceChain, TheTipIsTheChainsElseTheSampledPoint) {
  io::CloudProvenance p = ur5AtEeLink();
  EXPECT_EQ(io::recordedTip(p), "ee_link");
  EXPECT_EQ(io::describeCloud("a.pcd", p), "robot 'ur5_shaped', tip ee_link, from a.pcd");
  p.base_link.clear();
  p.tip_link.clear();
  p.sampling->point = "flange";
  EXPECT_EQ(io::recordedTip(p), "flange");
  p.sampling.reset();  // a cloud of an mcws before the sampling record
  EXPECT_EQ(io::recordedTip(p), std::nullopt);
  EXPECT_EQ(io::describeCloud("a.pcd", p), "robot 'ur5_shaped', from a.pcd");
  EXPECT_EQ(io::describeCloud("a.pcd", std::nullopt), "a.pcd");
}

}  // namespace
}  // namespace mcws
