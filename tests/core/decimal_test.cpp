// The text of a number (mcws::formatNumber, mcws::formatFixed): every expected string worked out
// by hand from the value's digits, and the claims of sameness checked against std::ostream.

#include "mcws/core/decimal.h"

#include <gtest/gtest.h>

#include <ios>
#include <limits>
#include <sstream>
#include <string>

namespace mcws {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(FormatNumber, SixSignificantDigitsWithoutTrailingZeros) {
  EXPECT_EQ(formatNumber(0.102375), "0.102375");
  EXPECT_EQ(formatNumber(39.0), "39");
  EXPECT_EQ(formatNumber(0.5), "0.5");
  EXPECT_EQ(formatNumber(-1.0), "-1");
  EXPECT_EQ(formatNumber(1234567.0), "1.23457e+06");  // 7 digits: exponent form, last rounded up
  EXPECT_EQ(formatNumber(0.0001), "0.0001");          // exponent -4: still fixed form
  EXPECT_EQ(formatNumber(0.00001), "1e-05");          // exponent -5: exponent form
  EXPECT_EQ(formatNumber(1e30), "1e+30");
  EXPECT_EQ(formatNumber(0.0), "0");
  EXPECT_EQ(formatNumber(-0.0), "-0");
}

TEST(FormatNumber, NonFiniteValuesReadAsPrintfWritesThem) {
  EXPECT_EQ(formatNumber(kNaN), "nan");
  EXPECT_EQ(formatNumber(kInf), "inf");
  EXPECT_EQ(formatNumber(-kInf), "-inf");
  EXPECT_EQ(formatNumber(kInf, 17), "inf");
}

TEST(FormatNumber, GivenSignificantDigits) {
  // 0.1 is 0.1000000000000000055511151231257827... as a double: 17 digits show the 1 at the end.
  EXPECT_EQ(formatNumber(0.1, 17), "0.10000000000000001");
  EXPECT_EQ(formatNumber(0.1, 15), "0.1");
  EXPECT_EQ(formatNumber(-0.1, 15), "-0.1");
  // 0.1f is 0.100000001490116...: 9 digits tell the float from 0.1.
  EXPECT_EQ(formatNumber(0.1f, 9), "0.100000001");
  // The largest float, 3.40282346638528859811704e+38, to 3 digits.
  EXPECT_EQ(formatNumber(std::numeric_limits<float>::max(), 3), "3.4e+38");
  EXPECT_EQ(formatNumber(1e-19f, 3), "1e-19");
  EXPECT_EQ(formatNumber(2.5, 12), "2.5");
  EXPECT_EQ(formatNumber(123456789012.7, 12), "123456789013");
  EXPECT_EQ(formatNumber(1234567890123.0, 12), "1.23456789012e+12");
  EXPECT_EQ(formatNumber(0.125, 1), "0.1");
}

TEST(FormatNumber, SeventeenDigitsReadBackAsTheSameDouble) {
  for (double value : {0.1, 1.0 / 3.0, 2.0 / 3.0, 1e-300, 123456.789, -9.87654321e100}) {
    EXPECT_EQ(std::stod(formatNumber(value, 17)), value) << formatNumber(value, 17);
  }
}

TEST(FormatNumber, SameTextAsAStreamWithItsPrecision) {
  for (double value :
       {0.102375, 1e-9, 1e30, -2.5, 1234567.0, 0.30000000000000004, 7.0, kNaN, kInf, -kInf, -0.0}) {
    for (int digits : {1, 3, 6, 9, 12, 15, 17}) {
      std::ostringstream stream;
      stream.precision(digits);
      stream << value;
      EXPECT_EQ(formatNumber(value, digits), stream.str()) << value << " to " << digits;
    }
    std::ostringstream stream;
    stream << value;
    EXPECT_EQ(formatNumber(value), stream.str());
  }
}

TEST(FormatFixed, ExactlyTheGivenDecimals) {
  EXPECT_EQ(formatFixed(2.5, 2), "2.50");
  EXPECT_EQ(formatFixed(0.0004, 3), "0.000");
  EXPECT_EQ(formatFixed(1234.5678, 1), "1234.6");
  EXPECT_EQ(formatFixed(0.12345, 4), "0.1235");  // 0.12345 is 0.123450000000000004...: rounds up
  EXPECT_EQ(formatFixed(-0.004, 2), "-0.00");
  EXPECT_EQ(formatFixed(7.0, 0), "7");
  EXPECT_EQ(formatFixed(kNaN, 2), "nan");
  EXPECT_EQ(formatFixed(-kInf, 2), "-inf");
}

TEST(FormatFixed, TheLargestDoubleIsNotCutShort) {
  // DBL_MAX is about 1.8e308: 309 digits before the point, then "." and two decimals.
  const std::string text = formatFixed(std::numeric_limits<double>::max(), 2);
  EXPECT_EQ(text.size(), 309u + 3u);
  EXPECT_EQ(text.substr(0, 6), "179769");
  EXPECT_EQ(text.substr(text.size() - 3), ".00");
}

TEST(FormatFixed, SameTextAsAFixedStream) {
  for (double value : {0.0004, 2.5, -3.14159, 1e10, 0.995, kNaN, -0.0}) {
    for (int decimals : {0, 1, 2, 3, 4}) {
      std::ostringstream stream;
      stream.setf(std::ios::fixed);
      stream.precision(decimals);
      stream << value;
      EXPECT_EQ(formatFixed(value, decimals), stream.str()) << value << " to " << decimals;
    }
  }
}

}  // namespace
}  // namespace mcws
