// What a check of one joint vector reports (reportedLabel, pairsToShow): the lowest label of a
// colliding pair, and the pairs worth showing, nearest first, on hand-made pair lists.
#include <gtest/gtest.h>

#include <vector>

#include "mcws/collision/collision_checker.h"

namespace mcws {
namespace {

PairReport pair(const char* a, std::uint32_t label, double distance) {
  PairReport p;
  p.body_a = a;
  p.body_b = "b";
  p.label = label;
  p.colliding = distance <= 0.0;
  p.distance = distance;
  return p;
}

TEST(PairReports, TheLabelIsTheLowestOfTheCollidingPairsAndOnlyThoseAreShown) {
  const std::vector<PairReport> pairs{
      pair("free1", kLabelLinkLink, 0.5), pair("tool", kLabelToolLink, -0.1),
      pair("free2", kLabelEnvironment, 0.2), pair("link", kLabelLinkLink, -0.3)};
  EXPECT_EQ(reportedLabel(pairs), kLabelLinkLink);
  const std::vector<PairReport> shown = pairsToShow(pairs, false);
  ASSERT_EQ(shown.size(), 2u);
  EXPECT_EQ(shown[0].body_a, "link");  // -0.3 first
  EXPECT_EQ(shown[1].body_a, "tool");
  const std::vector<PairReport> all = pairsToShow(pairs, true);
  ASSERT_EQ(all.size(), 4u);
  EXPECT_EQ(all[3].body_a, "free1");
}

TEST(PairReports, WhenNothingCollidesThePairOfLeastClearanceIsShown) {
  const std::vector<PairReport> pairs{pair("far", kLabelLinkLink, 0.5),
                                      pair("near", kLabelEnvironment, 0.2)};
  EXPECT_EQ(reportedLabel(pairs), kLabelFree);
  const std::vector<PairReport> shown = pairsToShow(pairs, false);
  ASSERT_EQ(shown.size(), 1u);
  EXPECT_EQ(shown[0].body_a, "near");
}

}  // namespace
}  // namespace mcws
