// The reading step the file readers share (mcws::readRest): every byte of what is left, with
// no translation, and an empty rest that is not a failed read.

#include "mcws/core/text_file.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

namespace mcws {
namespace {

TEST(ReadRest, KeepsEveryByteIncludingNulAndCarriageReturns) {
  const std::string bytes("solid a\r\n\0\x01\xff end", 16);
  std::istringstream in(bytes);
  EXPECT_EQ(readRest(in), bytes);
  EXPECT_FALSE(in.bad());
}

TEST(ReadRest, StartsWhereTheStreamStands) {
  std::istringstream in("header\nbody 1\nbody 2\n");
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(readRest(in), "body 1\nbody 2\n");
}

TEST(ReadRest, AnEmptyRestIsEmptyAndNotAFailedRead) {
  std::istringstream in("");
  EXPECT_EQ(readRest(in), "");
  EXPECT_FALSE(in.bad());
}

}  // namespace
}  // namespace mcws
