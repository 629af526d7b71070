// scripts/plot_cloud.sh through its command line (issue 16, section 3): colouring by a field
// (a colour bar for z and float fields, one named colour per value of a label field), the key
// naming the clouds, and bad options (exit 2, one line naming the value, no picture left).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "png_image.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

const std::string kPlot = std::string(MCWS_SCRIPTS_DIR) + "/plot_cloud.sh";

// viridis' ends and tab10's colours, as the script writes them.
constexpr test::Rgb kViridisLow = 0x440154, kViridisHigh = 0xfde725;
constexpr test::Rgb kBlue = 0x1f77b4, kGreen = 0x2ca02c;
// Points are anti-aliased discs: their centres have the exact colour, their rims blend with the
// background; a colour is "seen" within this tolerance per channel.
constexpr int kColourTolerance = 12;

/// An ASCII PCD file with the given FIELDS/TYPE lines (SIZE 4, COUNT 1) and rows.
void writePcd(const std::string& path, const std::vector<std::string>& fields,
              const std::vector<char>& types, const std::vector<std::vector<double>>& rows) {
  std::ostringstream pcd;
  pcd << "# .PCD v0.7\nVERSION 0.7\nFIELDS";
  for (const auto& f : fields) pcd << ' ' << f;
  pcd << "\nSIZE";
  for (std::size_t i = 0; i < fields.size(); ++i) pcd << " 4";
  pcd << "\nTYPE";
  for (char t : types) pcd << ' ' << t;
  pcd << "\nCOUNT";
  for (std::size_t i = 0; i < fields.size(); ++i) pcd << " 1";
  pcd << "\nWIDTH " << rows.size() << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << rows.size()
      << "\nDATA ascii\n";
  for (const auto& row : rows) {
    for (std::size_t i = 0; i < row.size(); ++i) pcd << (i ? " " : "") << row[i];
    pcd << '\n';
  }
  test::writeFile(path, pcd.str());
}

/// 20 x 20 points on the cylinder x^2 + y^2 = 1, z in [0, 1], with a label (0 for x < 0, 2 for
/// x >= 0) and a float field m = 10 z + 5.
std::vector<std::vector<double>> cylinderRows() {
  std::vector<std::vector<double>> rows;
  for (int i = 0; i < 20; ++i) {
    for (int k = 0; k < 20; ++k) {
      const double a = 2 * M_PI * i / 20, z = k / 19.0;
      rows.push_back({std::cos(a), std::sin(a), z, std::cos(a) < 0 ? 0.0 : 2.0, 10 * z + 5});
    }
  }
  return rows;
}

/// The mean row (y, down) of the pixels of one colour; NaN when there is none.
double meanRow(const test::PngImage& image, test::Rgb colour) {
  double sum = 0, n = 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      if (image.is(x, y, colour, kColourTolerance)) sum += y, n += 1;
    }
  }
  return n > 0 ? sum / n : NAN;
}

/// The mean column (x) of the pixels of one colour; NaN when there is none.
double meanColumn(const test::PngImage& image, test::Rgb colour) {
  double sum = 0, n = 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      if (image.is(x, y, colour, kColourTolerance)) sum += x, n += 1;
    }
  }
  return n > 0 ? sum / n : NAN;
}

class PlotCloud : public ::testing::Test {
 protected:
  void SetUp() override {
    cloud_ = inputs_.file("cylinder.pcd");
    writePcd(cloud_, {"x", "y", "z", "label", "manipulability"}, {'F', 'F', 'F', 'U', 'F'},
             cylinderRows());
  }
  /// Runs the script with `args` after --input (the cylinder) and --output (out.png).
  test::RunResult plot(const std::string& args) const {
    return test::run(kPlot + " --input " + cloud_ + " --output " + png() + " " + args);
  }
  std::string png() const { return outputs_.file("out.png"); }
  std::string script() const { return outputs_.file("plot.gp"); }
  /// Checks a failed run: its exit code, one line "plot_cloud: ..." with `message`, and nothing
  /// (no picture, no temporary file) left in the output directory.
  void expectFailure(const std::string& args, int exit_code, const std::string& message) const {
    SCOPED_TRACE(args);
    const test::RunResult r = plot(args);
    EXPECT_EQ(r.exit_code, exit_code) << r.err;
    EXPECT_EQ(r.err.rfind("plot_cloud: ", 0), 0u) << r.err;
    EXPECT_THAT(r.err, HasSubstr(message));
    EXPECT_EQ(test::lineCount(r.err), 1) << r.err;
    EXPECT_EQ(outputs_.fileCount(), 0u);
  }

  test::TempDir inputs_, outputs_;
  std::string cloud_;
};

TEST_F(PlotCloud, ThreeDViewIsColouredByZUnderANamedColourBar) {
  const test::RunResult r = plot("--unit cm --keep-script " + script());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string gp = test::readFile(script());
  EXPECT_THAT(gp, HasSubstr("set cblabel 'z [cm]'"));
  EXPECT_THAT(gp, HasSubstr("set cbrange [0:1]"));
  EXPECT_THAT(gp, HasSubstr("using 1:2:3:4"));
  EXPECT_THAT(gp, HasSubstr("lc palette"));
  // Both ends of the palette are drawn, the high one (z = 1) above the low one (z = 0).
  const test::PngImage image(png());
  EXPECT_GT(image.count(kViridisLow, kColourTolerance), 20u);
  EXPECT_GT(image.count(kViridisHigh, kColourTolerance), 20u);
  EXPECT_LT(meanRow(image, kViridisHigh), meanRow(image, kViridisLow));
}

TEST_F(PlotCloud, ColorNoneAndPlaneViewsDrawOneColour) {
  for (const std::string view : {"3d --color none", "xz"}) {
    SCOPED_TRACE(view);
    const test::RunResult r = plot("--view " + view + " --keep-script " + script());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_THAT(test::readFile(script()), Not(HasSubstr("palette")));
    const test::PngImage image(png());
    EXPECT_GT(image.count(kBlue, kColourTolerance), 100u);
    EXPECT_EQ(image.count(kViridisLow, kColourTolerance), 0u);
    EXPECT_EQ(image.count(kViridisHigh, kColourTolerance), 0u);
  }
}

TEST_F(PlotCloud, FloatFieldGetsAColourBarWithItsRangeAndName) {
  const test::RunResult r = plot("--view xz --color manipulability --keep-script " + script());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string gp = test::readFile(script());
  EXPECT_THAT(gp, HasSubstr("set cblabel 'manipulability'"));
  EXPECT_THAT(gp, HasSubstr("set cbrange [5:15]"));
  EXPECT_THAT(gp, HasSubstr("using 1:3:4"));
  // In the X-Z view m = 10 z + 5 grows upwards like z.
  const test::PngImage image(png());
  EXPECT_LT(meanRow(image, kViridisHigh), meanRow(image, kViridisLow));

  ASSERT_EQ(
      plot("--color manipulability --color-label 'manipulability [cm^3]' --keep-script " + script())
          .exit_code,
      0);
  EXPECT_THAT(test::readFile(script()), HasSubstr("set cblabel 'manipulability [cm^3]'"));
}

TEST_F(PlotCloud, LabelFieldGetsOneColourPerValueNamedInTheKey) {
  const test::RunResult r =
      plot("--view xy --color label --color-names 0=free,2=tool-link --keep-script " + script());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string gp = test::readFile(script());
  EXPECT_THAT(gp, HasSubstr("title 'free (label 0)'"));
  EXPECT_THAT(gp, HasSubstr("title 'tool-link (label 2)'"));
  EXPECT_THAT(gp, Not(HasSubstr("palette")));
  // Value 0 is tab10's first colour (blue), value 2 its third (green), whatever else the cloud
  // holds; label 0 lies at x < 0, on the left of the X-Y view.
  const test::PngImage image(png());
  EXPECT_GT(image.count(kBlue, kColourTolerance), 50u);
  EXPECT_GT(image.count(kGreen, kColourTolerance), 50u);
  EXPECT_LT(meanColumn(image, kBlue), meanColumn(image, kGreen));
}

TEST_F(PlotCloud, KeyNamesTheCloudsByLabelNotByFileName) {
  const std::string rim = inputs_.file("rim_points.pcd");
  writePcd(rim, {"x", "y", "z"}, {'F', 'F', 'F'}, {{1, 0, 0}, {-1, 0, 1}});
  ASSERT_EQ(plot("--view xz --overlay " + rim + " --keep-script " + script()).exit_code, 0);
  std::string gp = test::readFile(script());
  EXPECT_THAT(gp, HasSubstr("title 'samples'"));
  EXPECT_THAT(gp, HasSubstr("title 'boundary'"));
  EXPECT_THAT(gp, Not(HasSubstr("title 'cylinder.pcd'")));
  EXPECT_THAT(gp, Not(HasSubstr("title 'rim_points.pcd'")));
  EXPECT_THAT(gp, Not(HasSubstr("unset key")));

  ASSERT_EQ(plot("--overlay " + rim + " --label 'joint samples' --overlay-label 'their rim'" +
                 " --keep-script " + script())
                .exit_code,
            0);
  gp = test::readFile(script());
  EXPECT_THAT(gp, HasSubstr("title 'joint samples'"));
  EXPECT_THAT(gp, HasSubstr("title 'their rim'"));
  // One cloud and no --label: no key.
  ASSERT_EQ(plot("--keep-script " + script()).exit_code, 0);
  EXPECT_THAT(test::readFile(script()), HasSubstr("unset key"));
}

TEST_F(PlotCloud, NonFiniteFieldValuesAreLeftOutWithANote) {
  writePcd(cloud_, {"x", "y", "z", "m"}, {'F', 'F', 'F', 'F'},
           {{0, 0, 0, 1}, {1, 0, 1, NAN}, {0, 1, 1, 3}});
  const test::RunResult r = plot("--color m");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("1 points with a non-finite m left out"));
}

TEST_F(PlotCloud, UnknownFieldIsAUsageErrorNamingItAndTheFieldsThereAre) {
  expectFailure("--color reachability", 2,
                "--color reachability: " + cloud_ +
                    " has no such field (its fields: x y z label manipulability)");
}

TEST_F(PlotCloud, BadFlagValuesAreUsageErrors) {
  expectFailure("--view side", 2, "--view must be xz, xy, yz or 3d, not 'side'");
  expectFailure("--color 'a b'", 2, "--color must be a field name or none, not 'a b'");
  expectFailure("--angles 200,10", 2, "--angles must be ROT_X,ROT_Z in degrees");
  expectFailure("--angles 60", 2, "not '60'");
  expectFailure("--view xz --color-names 0=free", 2, "--color-names needs --color FIELD");
  expectFailure("--color label --color-names 0=free,x=y", 2, "not 'x=y'");
  expectFailure("--label", 2, "--label needs a value");
  expectFailure("--colour z", 2, "unknown argument: --colour");
}

TEST_F(PlotCloud, MissingOrBadInputFailsWithNothingWritten) {
  const std::string missing = inputs_.file("missing.pcd");
  const test::RunResult r =
      test::run(kPlot + " --input " + missing + " --output " + png() + " --color z");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err, "plot_cloud: cannot read input file: " + missing + "\n");
  EXPECT_EQ(outputs_.fileCount(), 0u);

  const std::string text = inputs_.file("text.pcd");
  test::writeFile(text, "not a cloud\n");
  const test::RunResult t = test::run(kPlot + " --input " + text + " --output " + png());
  EXPECT_EQ(t.exit_code, 1) << t.err;
  EXPECT_THAT(t.err, HasSubstr("not a PCD file"));
  EXPECT_EQ(outputs_.fileCount(), 0u);
}

TEST_F(PlotCloud, HelpListsTheColouringOptions) {
  const test::RunResult r = test::run(kPlot + " --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* flag : {"--color ", "--color-label", "--color-names", "--label",
                           "--overlay-label", "--angles", "--keep-script"}) {
    EXPECT_THAT(r.out, HasSubstr(flag));
  }
}

}  // namespace
}  // namespace mcws
