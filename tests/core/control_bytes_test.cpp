// Control bytes in names and messages (core/control_bytes.h): the byte classes and the \xNN
// text worked out from the ASCII table.

#include "mcws/core/control_bytes.h"

#include <gtest/gtest.h>

#include <string>

namespace mcws {
namespace {

TEST(ControlBytes, BelowSpaceAndDeleteAreControlBytesUtf8IsNot) {
  EXPECT_TRUE(isControlByte(0x00));
  EXPECT_TRUE(isControlByte('\t'));
  EXPECT_TRUE(isControlByte('\n'));
  EXPECT_TRUE(isControlByte(0x1f));
  EXPECT_TRUE(isControlByte(0x7f));
  EXPECT_FALSE(isControlByte(' '));
  EXPECT_FALSE(isControlByte('~'));
  EXPECT_FALSE(isControlByte(0x80));
  EXPECT_FALSE(isControlByte(0xff));
}

TEST(ControlBytes, EscapedByteIsBackslashXAndTwoLowercaseHexDigits) {
  EXPECT_EQ(escapedByte(0x00), "\\x00");
  EXPECT_EQ(escapedByte('\n'), "\\x0a");
  EXPECT_EQ(escapedByte(0x7f), "\\x7f");
  EXPECT_EQ(escapedByte(0xff), "\\xff");
}

TEST(ControlBytes, NamesWithAndWithoutControlBytes) {
  EXPECT_FALSE(hasControlByte("arm 2"));
  EXPECT_FALSE(hasControlByte("Gelenk\xc3\xa4"));  // "Gelenkä" in UTF-8
  EXPECT_FALSE(hasControlByte(""));
  EXPECT_TRUE(hasControlByte("arm\n2"));
  EXPECT_TRUE(hasControlByte(std::string("a\0b", 3)));
}

TEST(ControlBytes, EscapedControlBytesKeepsEveryOtherByte) {
  EXPECT_EQ(escapedControlBytes("arm\n2"), "arm\\x0a2");
  EXPECT_EQ(escapedControlBytes(std::string("\0\t\x7f", 3)), "\\x00\\x09\\x7f");
  EXPECT_EQ(escapedControlBytes("Gelenk\xc3\xa4 1"), "Gelenk\xc3\xa4 1");
  EXPECT_EQ(escapedControlBytes(""), "");
}

}  // namespace
}  // namespace mcws
