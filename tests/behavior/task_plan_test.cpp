// Wang et al. 2018, section 2.3: the cleaning job as a sequence of sub-tasks.
#include "mcws/behavior/task_plan.h"

#include <gtest/gtest.h>

#include "mcws/core/error.h"

namespace mcws {
namespace {

TEST(TaskPlan, ThreeDiscsDownCleaningEachThenBackUp) {
  // Figure 8 for three discs, written out by hand: (CB1, CB2) per disc from the tower end down,
  // then one CB3 per disc back to the mounting position (disc 0).
  const std::vector<Subtask> plan = planCleaningTask(3);
  const std::vector<std::pair<std::string, int>> expected = {{"CB1", 1}, {"CB2", 1}, {"CB1", 2},
                                                             {"CB2", 2}, {"CB1", 3}, {"CB2", 3},
                                                             {"CB3", 2}, {"CB3", 1}, {"CB3", 0}};
  ASSERT_EQ(plan.size(), expected.size());
  for (std::size_t k = 0; k < plan.size(); ++k) {
    EXPECT_EQ(plan[k].behavior, expected[k].first) << k;
    EXPECT_EQ(plan[k].disc, expected[k].second) << k;
  }
  // Every disc cleaned once; the robot ends where it was mounted.
  int cleaned = 0, position = 0;
  for (const Subtask& s : plan) {
    if (s.behavior == "CB1") ++position;
    if (s.behavior == "CB3") --position;
    if (s.behavior == "CB2") {
      ++cleaned;
      EXPECT_EQ(s.disc, position);
    }
  }
  EXPECT_EQ(cleaned, 3);
  EXPECT_EQ(position, 0);
}

TEST(TaskPlan, DescribesEachSubtaskOnALine) {
  EXPECT_EQ(describePlan(planCleaningTask(1)),
            "1 CB1 move down one disc -> disc 1\n"
            "2 CB2 clean disc -> disc 1\n"
            "3 CB3 move up one disc -> disc 0\n");
}

TEST(TaskPlan, TwentyEightDiscsOfA500kVString) {
  const std::vector<Subtask> plan = planCleaningTask(28);
  EXPECT_EQ(plan.size(), 3u * 28u);
  EXPECT_EQ(plan.back().disc, 0);
}

TEST(TaskPlan, RejectsImpossibleDiscCounts) {
  for (int discs : {0, -3, 201}) {
    try {
      planCleaningTask(discs);
      ADD_FAILURE() << discs;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("insulators: " + std::to_string(discs) + " discs"),
                std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace mcws
