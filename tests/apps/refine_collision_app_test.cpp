// mcws_refine --collision (issue 33 item 6): only the points of the collision-free region (or of
// --label's) are refined, and the new samples are labelled as a direct collision check labels
// them. The robot is robots/planar2.yaml, a planar 2R arm (40 cm and 30 cm capsules of radius
// 2.5 cm) among three tall posts, whose labels the test computes in closed form.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "apps/tool_paths.h"
#include "mcws/points/point_types.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;

// ---- the oracle: planar2's collision label in closed form ----

/// An axis-aligned square post seen from above [cm]: the posts are 40 cm tall around z = 0, where
/// the arm moves, so the 3-D distance is the distance in the x-y plane.
struct PlanarPost {
  Eigen::Vector2d centre;
  double half;
};
const PlanarPost kPosts[] = {{{30, 38}, 5}, {{-32, 36}, 5}, {{0, -52}, 4}};
constexpr double kArmRadius = 2.5;  ///< both capsules [cm]
/// Samples whose closed-form clearance is this close to zero may fall either way in the checker's
/// arithmetic (GJK on float joint values) [cm].
constexpr double kClearanceTie = 1e-5;

double pointSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

double pointSquare(const Eigen::Vector2d& p, const PlanarPost& post) {
  const Eigen::Vector2d d = ((p - post.centre).cwiseAbs().array() - post.half).max(0.0);
  return d.norm();
}

bool segmentCrossesSquare(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                          const PlanarPost& post) {
  // Liang-Barsky clipping of the segment to the square.
  double t0 = 0.0, t1 = 1.0;
  const Eigen::Vector2d d = b - a;
  for (int axis = 0; axis < 2; ++axis) {
    const double lo = post.centre[axis] - post.half - a[axis];
    const double hi = post.centre[axis] + post.half - a[axis];
    if (d[axis] == 0.0) {
      if (lo > 0.0 || hi < 0.0) return false;
      continue;
    }
    double enter = lo / d[axis], leave = hi / d[axis];
    if (enter > leave) std::swap(enter, leave);
    t0 = std::max(t0, enter);
    t1 = std::min(t1, leave);
  }
  return t0 <= t1;
}

/// Distance between a segment and a square (0 when they meet).
double segmentSquare(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const PlanarPost& post) {
  if (segmentCrossesSquare(a, b, post)) return 0.0;
  double d = std::min(pointSquare(a, post), pointSquare(b, post));
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) {
      d = std::min(d, pointSegment(post.centre + post.half * Eigen::Vector2d(sx, sy), a, b));
    }
  }
  return d;
}

/// The least clearance between planar2's two capsules and the posts at (q1, q2) [rad] [cm]
/// (negative: they overlap). The base sphere (radius 5 at the origin) reaches no post, and the
/// forearm never comes within 15 cm of the base (q2 is within 160 deg), so the label is
/// environment (3) exactly when this is negative, else free (0).
double planar2Clearance(double q1, double q2) {
  const Eigen::Vector2d elbow = 40.0 * Eigen::Vector2d(std::cos(q1), std::sin(q1));
  const Eigen::Vector2d tip = elbow + 30.0 * Eigen::Vector2d(std::cos(q1 + q2), std::sin(q1 + q2));
  double least = 1e30;
  for (const PlanarPost& post : kPosts) {
    least = std::min({least, segmentSquare(Eigen::Vector2d::Zero(), elbow, post),
                      segmentSquare(elbow, tip, post)});
  }
  return least - kArmRadius;
}

// ---- the tool ----

pcl::PointCloud<WorkspacePoint> loadPlanar2Cloud(const std::string& path) {
  pcl::PointCloud<WorkspacePoint> cloud;
  EXPECT_EQ(pcl::io::loadPCDFile(path, cloud), 0) << path;
  return cloud;
}

/// The joint ranges of planar2 [rad]: q1 in [-180, 180] deg, q2 in [-160, 160] deg.
const double kRange[2] = {2.0 * M_PI, 320.0 * M_PI / 180.0};
/// Joint values are stored as float (6e-8 rad near pi) [rad].
constexpr double kJointTol = 1e-6;

class RefineCollisionApp : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_EQ(
        test::run(kSample + robot_ + " --collision --samples 3000 --seed 5 --output " + cloud_)
            .exit_code,
        0);
  }
  test::RunResult refine(const std::string& input, const std::string& extra) {
    return test::run(kRefine + robot_ + " --input " + input + " --samples 400 --output " + out_ +
                     " --json " + extra);
  }
  /// Checks that new sample i moved from parents[i mod P] by at most --spread (0.1) of each
  /// joint's range, and that its label is the closed form's. \return the labels' counts.
  static std::vector<int> checkNewSamples(const pcl::PointCloud<WorkspacePoint>& refined,
                                          const pcl::PointCloud<WorkspacePoint>& parents) {
    EXPECT_EQ(refined.size(), 400u);
    std::vector<int> counts(4, 0);
    for (std::size_t i = 0; i < refined.size(); ++i) {
      const WorkspacePoint& parent = parents[i % parents.size()];
      for (int j = 0; j < 2; ++j) {
        EXPECT_LE(std::abs(refined[i].q[j] - parent.q[j]), 0.1 * kRange[j] + kJointTol)
            << "sample " << i << ", q" << j + 1;
      }
      const double gap = planar2Clearance(refined[i].q[0], refined[i].q[1]);
      if (std::abs(gap) > kClearanceTie) {
        EXPECT_EQ(refined[i].label, gap < 0.0 ? kLabelEnvironment : kLabelFree)
            << "sample " << i << ", clearance " << gap << " cm";
      }
      ++counts[std::min<std::uint32_t>(refined[i].label, 3)];
    }
    return counts;
  }
  test::TempDir dir_, nothing_written_;
  const std::string robot_ = " --robot " + test::robotPath("planar2");
  const std::string cloud_ = dir_.file("all.pcd"), out_ = dir_.file("refined.pcd");
};

/// The points of `cloud` labelled `label`, in order.
pcl::PointCloud<WorkspacePoint> pointsLabelled(const pcl::PointCloud<WorkspacePoint>& cloud,
                                               std::uint32_t label) {
  pcl::PointCloud<WorkspacePoint> out;
  for (const auto& p : cloud) {
    if (p.label == label) out.push_back(p);
  }
  return out;
}

TEST_F(RefineCollisionApp, TheSamplerLabelsAsTheClosedFormDoes) {
  // The oracle itself, on the cloud mcws_sample labelled: both labels occur and agree.
  const auto cloud = loadPlanar2Cloud(cloud_);
  int environment = 0;
  for (const auto& p : cloud) {
    const double gap = planar2Clearance(p.q[0], p.q[1]);
    if (std::abs(gap) > kClearanceTie) {
      ASSERT_EQ(p.label, gap < 0.0 ? kLabelEnvironment : kLabelFree) << gap;
    }
    environment += p.label == kLabelEnvironment;
  }
  EXPECT_GT(environment, 100);
  EXPECT_LT(environment, 2900);
}

TEST_F(RefineCollisionApp, RefinesOnlyTheFreePointsAndLabelsTheNewSamples) {
  // The whole labelled cloud as --input: without --collision every point would be a parent.
  const test::RunResult r = refine(cloud_, "--collision");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto free = pointsLabelled(loadPlanar2Cloud(cloud_), kLabelFree);
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["boundary_points"], free.size());
  EXPECT_EQ(json["label"], "free");
  EXPECT_EQ(json["collision"], true);
  const std::vector<int> counts = checkNewSamples(loadPlanar2Cloud(out_), free);
  // Free parents next to the posts give colliding children too: the edge is refined both ways.
  EXPECT_GT(counts[kLabelFree], 0);
  EXPECT_GT(counts[kLabelEnvironment], 0);
  EXPECT_EQ(counts[kLabelFree] + counts[kLabelEnvironment], 400);
}

TEST_F(RefineCollisionApp, RefinesTheFreeRegionsBoundaryThroughThePipeline) {
  // mcws_select the free points, mcws_boundary their edge, refine it with --collision.
  const std::string free = dir_.file("free.pcd"), edge = dir_.file("edge.pcd");
  ASSERT_EQ(test::run(kSelect + " --input " + cloud_ + " --label 0 --output " + free).exit_code, 0);
  ASSERT_EQ(test::run(kBoundary + " --input " + free + " --plane xy --output " + edge).exit_code,
            0);
  const test::RunResult r = refine(edge, "--collision --cloud " + cloud_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["points"], 3400);
  // The copied cloud first, then the new samples.
  auto refined = loadPlanar2Cloud(out_);
  ASSERT_EQ(refined.size(), 3400u);
  refined.erase(refined.begin(), refined.begin() + 3000);
  const std::vector<int> counts = checkNewSamples(refined, loadPlanar2Cloud(edge));
  // The free region's edge runs along the posts: some children cross it.
  EXPECT_GT(counts[kLabelEnvironment], 0);
  EXPECT_GT(counts[kLabelFree], counts[kLabelEnvironment]);
}

TEST_F(RefineCollisionApp, RefinesTheRegionOfTheLabelNamed) {
  for (const std::string label : {"environment", "3"}) {
    const test::RunResult r = refine(cloud_, "--collision --label " + label);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto parents = pointsLabelled(loadPlanar2Cloud(cloud_), kLabelEnvironment);
    EXPECT_EQ(nlohmann::json::parse(r.out)["boundary_points"], parents.size());
    EXPECT_EQ(nlohmann::json::parse(r.out)["label"], "environment");
    checkNewSamples(loadPlanar2Cloud(out_), parents);
  }
}

TEST_F(RefineCollisionApp, RefusesCloudsWithoutCollisionLabelsAndBadLabels) {
  const std::string out = nothing_written_.file("o.pcd");
  const auto expectRefused = [&](const std::string& input, const std::string& extra, int code,
                                 const std::string& message) {
    test::expectToolFailure(
        kRefine, robot_ + " --input " + input + " --samples 10 --output " + out + " " + extra, code,
        message, nothing_written_);
  };
  // Sampled without --collision: every label reads 0.
  const std::string plain = dir_.file("plain.pcd");
  ASSERT_EQ(test::run(kSample + robot_ + " --samples 200 --output " + plain).exit_code, 0);
  expectRefused(plain, "--collision", 1,
                "--collision: --input '" + plain + "' was sampled without collision labels");
  // A labelled cloud whose label field was dropped (PCL would read every label as 0).
  const std::string ascii = dir_.file("ascii.pcd"), unlabelled = dir_.file("unlabelled.pcd");
  ASSERT_EQ(
      test::run(kSample + robot_ + " --collision --samples 50 --ascii --output " + ascii).exit_code,
      0);
  std::istringstream lines(test::readFile(ascii));
  std::string text;
  for (std::string line; std::getline(lines, line);) {
    const bool header = line.rfind("FIELDS", 0) == 0 || line.rfind("SIZE", 0) == 0 ||
                        line.rfind("TYPE", 0) == 0 || line.rfind("COUNT", 0) == 0;
    const bool data = !line.empty() && (std::isdigit(line[0]) || line[0] == '-');
    if (header || data) line.erase(line.rfind(' '));  // the last column: label
    text += line + "\n";
  }
  ASSERT_THAT(text, HasSubstr("FIELDS x y z q1 q2 q3 q4 q5 q6 q7 q8\n"));
  test::writeFile(unlabelled, text);
  expectRefused(unlabelled, "--collision", 1,
                "--collision: --input '" + unlabelled + "' has no field 'label'");
  // No point of the label: planar2's links never touch one another.
  expectRefused(cloud_, "--collision --label link-link", 1,
                "--collision: none of the 3000 points of --input '" + cloud_ +
                    "' is labelled link-link (label 1): nothing to refine");
  expectRefused(cloud_, "--label free", 2, "--label needs --collision");
  expectRefused(cloud_, "--collision --label walls", 2,
                "--label: 'walls' is not free, link-link, tool-link or environment (or 0 to 3)");
  expectRefused(cloud_, "--collision --label 4", 2, "--label: '4' is not free");
}

}  // namespace
}  // namespace mcws
