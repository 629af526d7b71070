#include "mcws/behavior/task_plan.h"

#include "mcws/core/error.h"

namespace mcws {

std::vector<Subtask> planCleaningTask(int discs) {
  constexpr int kMostDiscs = 200;  // a 1000 kV string has about 60; more is a typing mistake
  if (discs < 1 || discs > kMostDiscs) {
    throw Error("insulators: " + std::to_string(discs) + " discs; a string has 1 to " +
                std::to_string(kMostDiscs));
  }
  std::vector<Subtask> plan;
  for (int disc = 1; disc <= discs; ++disc) {
    plan.push_back({"CB1", "move down one disc", disc});
    plan.push_back({"CB2", "clean disc", disc});
  }
  for (int disc = discs - 1; disc >= 0; --disc) plan.push_back({"CB3", "move up one disc", disc});
  return plan;
}

std::string describePlan(const std::vector<Subtask>& plan) {
  std::string out;
  for (std::size_t k = 0; k < plan.size(); ++k) {
    out += std::to_string(k + 1) + " " + plan[k].behavior + " " + plan[k].action + " -> disc " +
           std::to_string(plan[k].disc) + "\n";
  }
  return out;
}

}  // namespace mcws
