// The one message app::run() prints for what a tool's body throws (issue 17 section 4): running
// out of memory names what was being read and the flags given, instead of a bare std::bad_alloc;
// control bytes from a file or flag are escaped, so a message stays one line.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <new>

#include "common/app.h"
#include "common/pose_args.h"
#include "mcws/core/control_bytes.h"
#include "mcws/core/decimal.h"
#include "test_support.h"

namespace mcws {
namespace {

TEST(AppRun, OutOfMemoryNamesTheActivityAndTheFlags) {
  app::CommandLine cli("t --input FILE", "test");
  cli.addValue("input", "a cloud");
  const char* argv[] = {"t", "--input", "big.pcd"};
  ASSERT_TRUE(cli.parse(3, const_cast<char**>(argv)));
  ::testing::internal::CaptureStderr();
  const int code = app::run("mcws_test", [] {
    const app::Activity reading("reading 'big.pcd'");
    throw std::bad_alloc();
    return 0;
  });
  EXPECT_EQ(code, app::kExitFailure);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(),
            "mcws_test: out of memory while reading 'big.pcd' (given: --input big.pcd): a file or "
            "flag asks for more than this machine has\n");
  EXPECT_EQ(app::Activity::takeFailed(), "");  // unwound, and forgotten once reported
}

TEST(AppRun, ControlBytesInAMessageAreEscaped) {
  ::testing::internal::CaptureStderr();
  const int code = app::run("mcws_test", []() -> int {
    throw Error(
        "a\nb\x1b[31m\x7f"
        "z");
  });
  EXPECT_EQ(code, app::kExitFailure);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "mcws_test: a\\x0ab\\x1b[31m\\x7fz\n");
  EXPECT_EQ(escapedControlBytes("caf\xc3\xa9\t"), "caf\xc3\xa9\\x09");  // UTF-8 kept
}

TEST(AppFlags, RealNumbersAreDecimalOnlyAndListsHaveNoEmptyItems) {
  EXPECT_EQ(app::parseNumber("-1.5e3", "x"), -1500.0);
  EXPECT_EQ(app::parseNumber("+.5", "x"), 0.5);
  for (const char* bad : {"0x10", "inf", "-infinity", "nan", " 5", "5 ", "1e400", "", "1,5"}) {
    EXPECT_EQ(test::errorOf([&] { app::parseNumber(bad, "x"); }),
              "--x: '" + std::string(bad) + "' is not a finite number");
  }
  EXPECT_EQ(app::parseNumberList("0, 1 2,3", "q"), Eigen::Vector4d(0, 1, 2, 3));
  EXPECT_EQ(test::errorOf([] { app::parseNumberList("0,,0,0,30", "q"); }),
            "--q: no number between commas in '0,,0,0,30'");
  EXPECT_EQ(test::errorOf([] { app::parseNumberList(",1", "q"); }),
            "--q: no number between commas in ',1'");
  EXPECT_EQ(test::errorOf([] { app::parseNumberList("1,2,", "q"); }),
            "--q: no number after the last comma in '1,2,'");
}

TEST(AppFlags, AnEmptyValueIsAUsageErrorNamingTheFlag) {
  // `--output ""` (an unset shell variable) was taken for "no output" and failed later with exit
  // 1 and a message naming no flag. Switches take no value and are not affected.
  app::CommandLine cli("t --output FILE", "test");
  cli.addValue("output", "a cloud");
  cli.addValues("via", "via points");
  cli.addSwitch("json", "JSON");
  const char* empty[] = {"t", "--output", "", "--json"};
  EXPECT_EQ(test::errorOf([&] { cli.parse(4, const_cast<char**>(empty)); }),
            "--output: the value is empty");
  app::CommandLine cli2("t --output FILE", "test");
  cli2.addValue("output", "a cloud");
  cli2.addValues("via", "via points");
  cli2.addSwitch("json", "JSON");
  const char* empty_via[] = {"t", "--output", "a.pcd", "--via", "1 2", "--via", ""};
  EXPECT_EQ(test::errorOf([&] { cli2.parse(7, const_cast<char**>(empty_via)); }),
            "--via: a value is empty");
  app::CommandLine cli3("t --output FILE", "test");
  cli3.addValue("output", "a cloud");
  cli3.addSwitch("json", "JSON");
  const char* fine[] = {"t", "--output", "a.pcd", "--json"};
  EXPECT_TRUE(cli3.parse(4, const_cast<char**>(fine)));
  ::testing::internal::CaptureStderr();
  const int code = app::run("mcws_test", [&] { return cli.parse(4, const_cast<char**>(empty)); });
  ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(code, app::kExitUsage);
}

TEST(AppFlags, AWholeNumberOutOfRangeIsSaidToBeOutOfRange) {
  // 18446744073709551615 is a whole number, beyond what --seed takes: not "not a whole number".
  const std::int64_t max = std::numeric_limits<std::int64_t>::max();
  EXPECT_EQ(test::errorOf([&] { app::parseInteger("18446744073709551615", "seed", 0, max); }),
            "--seed: 18446744073709551615 is more than 9223372036854775807");
  EXPECT_EQ(test::errorOf([&] { app::parseInteger("-99999999999999999999", "seed", 0, max); }),
            "--seed: -99999999999999999999 is less than 0");
  EXPECT_EQ(test::errorOf([&] { app::parseInteger("12", "threads", 1, 8); }),
            "--threads: 12 is more than 8");
  EXPECT_EQ(app::parseInteger("+7", "threads", 1, 8), 7);
  for (const char* bad : {"1e3", " 5", "5x", "", "-", "0x10", "1.0"}) {
    EXPECT_EQ(test::errorOf([&] { app::parseInteger(bad, "seed", 0, max); }),
              "--seed: '" + std::string(bad) + "' is not a whole number");
  }
}

TEST(AppFlags, SmallNumbersInMessagesKeepTheirDigits) {
  // std::to_string printed 1e-9 as "0.000000" ("--resolution 1e-9 prints resolution 0.000000").
  EXPECT_EQ(formatNumber(1e-9), "1e-09");
  EXPECT_EQ(formatNumber(0.102375), "0.102375");
  EXPECT_EQ(formatNumber(39.0), "39");
  EXPECT_EQ(app::shortNumber(2e6), "2e+06");
}

TEST(AppFlags, PoseValuesBeyondWhatRobotFilesHoldAreRefused) {
  EXPECT_EQ(test::errorOf([] { app::parsePose("1e300 0 0 0 0 0", "pose"); }),
            "--pose: value 1 (1e+300) is out of range (at most 1e9 in size, as in robot files)");
  EXPECT_NO_THROW(app::parsePose("1e9 0 0 0 0 0", "pose"));
}

}  // namespace
}  // namespace mcws
