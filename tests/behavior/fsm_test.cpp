// The generic state-machine engine (mcws::StateMachine) on the CB1 of Wang et al. 2018 and on small
// machines built by hand: firing, wrong events, entry counts, determinism, DOT text, nesting.
#include "mcws/behavior/fsm.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "mcws/behavior/behavior_model.h"
#include "mcws/core/error.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

using test::errorOf;

StateMachine cb1Machine() {
  const BehaviorModel model =
      loadBehaviorModel(std::string(MCWS_ROBOTS_DIR) + "/insulator_cleaner_behaviors.yaml");
  return stateMachineOf(*model.combinedBehavior("CB1"));
}

TEST(StateMachine, Cb1GoesRoundQ1ToQ6AndBackOnItsSixEndingEvents) {
  StateMachine m = cb1Machine();
  EXPECT_EQ(m.name(), "CB1");
  EXPECT_THAT(m.states(), ElementsAre("q1", "q2", "q3", "q4", "q5", "q6"));
  EXPECT_THAT(m.events(),
              ElementsAre("zero_switch", "encoder_reached", "current_held", "encoder_zero"));
  EXPECT_EQ(m.initial(), "q1");
  EXPECT_THAT(m.finals(), ElementsAre("q1"));
  EXPECT_EQ(m.current(), "q1");
  EXPECT_TRUE(m.inFinal());
  const std::vector<std::string> events = {"zero_switch", "encoder_reached", "current_held",
                                           "zero_switch", "encoder_zero",    "current_held"};
  const std::vector<std::string> visited = {"q2", "q3", "q4", "q5", "q6", "q1"};
  for (std::size_t i = 0; i < events.size(); ++i) {
    const StateMachine::Firing f = m.fire(events[i]);
    ASSERT_TRUE(f.fired) << events[i];
    EXPECT_EQ(f.transition, i);  // CB1's transitions fire in file order
    EXPECT_EQ(m.current(), visited[i]);
    EXPECT_EQ(m.inFinal(), i + 1 == events.size()) << i;
  }
  EXPECT_EQ(m.steps(), 6u);
  EXPECT_EQ(m.entries("q1"), 2);  // at reset and on return
  for (const char* s : {"q2", "q3", "q4", "q5", "q6"}) EXPECT_EQ(m.entries(s), 1) << s;
  m.reset();
  EXPECT_EQ(m.current(), "q1");
  EXPECT_EQ(m.entries("q1"), 1);
  EXPECT_EQ(m.entries("q2"), 0);
  EXPECT_EQ(m.steps(), 0u);
}

TEST(StateMachine, AWrongEventDoesNothing) {
  StateMachine m = cb1Machine();
  for (const char* event : {"encoder_reached", "current_held", "speed_reached", "no_such", ""}) {
    const StateMachine::Firing f = m.fire(event);
    EXPECT_FALSE(f.fired) << event;
    EXPECT_FALSE(static_cast<bool>(f));
    EXPECT_EQ(m.current(), "q1");
  }
  EXPECT_EQ(m.steps(), 0u);
  EXPECT_THAT(m.enabledEvents(), ElementsAre("zero_switch"));
  ASSERT_TRUE(m.fire("zero_switch"));
  EXPECT_FALSE(m.fire("zero_switch"));  // q2 waits for the encoder, not the switch
  EXPECT_EQ(m.current(), "q2");
  EXPECT_EQ(m.next("q2", "encoder_reached"), "q3");
  EXPECT_EQ(m.next("q2", "zero_switch"), std::nullopt);
}

TEST(StateMachine, DotHasEveryTransitionOfCb1) {
  const StateMachine m = cb1Machine();
  const std::string dot = m.toDot();
  EXPECT_EQ(dot.rfind("digraph \"CB1\" {\n  rankdir=LR;\n  node [shape=circle];\n", 0), 0u) << dot;
  for (const char* edge :
       {"\"q1\" -> \"q2\" [label=\"BB_UG_Release\\nzero_switch\"];",
        "\"q2\" -> \"q3\" [label=\"BB_MP_Extend\\nencoder_reached\"];",
        "\"q3\" -> \"q4\" [label=\"BB_UG_Clamp\\ncurrent_held\"];",
        "\"q4\" -> \"q5\" [label=\"BB_LG_Release\\nzero_switch\"];",
        "\"q5\" -> \"q6\" [label=\"BB_MP_Home\\nencoder_zero\"];",
        "\"q6\" -> \"q1\" [label=\"BB_LG_Clamp\\ncurrent_held\"];", "\"__start\" -> \"q1\";",
        "\"q1\" [label=\"q1\", shape=doublecircle];", "\"q2\" [label=\"q2\"];"}) {
    EXPECT_THAT(dot, HasSubstr(edge));
  }
  std::size_t arrows = 0;
  for (std::size_t at = dot.find("->"); at != std::string::npos; at = dot.find("->", at + 1)) {
    ++arrows;
  }
  EXPECT_EQ(arrows, 7u);  // six transitions and the start arrow
  EXPECT_EQ(dot.substr(dot.size() - 2), "}\n");
}

TEST(StateMachine, Cb2LabelsCarryTheTarget) {
  const BehaviorModel model =
      loadBehaviorModel(std::string(MCWS_ROBOTS_DIR) + "/insulator_cleaner_behaviors.yaml");
  StateMachine m = stateMachineOf(*model.combinedBehavior("CB2"));
  EXPECT_THAT(m.toDot(),
              HasSubstr("\"q7\" -> \"q8\" [label=\"BB_CP_Move upper_shed\\nencoder_reached\"];"));
  for (const char* event : {"speed_reached", "encoder_reached", "encoder_reached", "encoder_zero",
                            "encoder_reached", "encoder_zero", "speed_zero", "encoder_zero"}) {
    ASSERT_TRUE(m.fire(event)) << event << " in " << m.current();
  }
  EXPECT_EQ(m.current(), "q1");
  EXPECT_EQ(m.steps(), 8u);
}

TEST(StateMachine, BuildingMistakesThrowNamingTheItem) {
  StateMachine m("door");
  m.addState("closed");
  m.addState("open");
  EXPECT_EQ(errorOf([&] { m.addState("open"); }), "state machine 'door': state 'open' added twice");
  EXPECT_EQ(errorOf([&] { m.addState(""); }), "state machine 'door': a state needs a name");
  EXPECT_EQ(errorOf([&] { m.fire("push"); }), "state machine 'door': no initial state");
  EXPECT_EQ(errorOf([&] { m.current(); }), "state machine 'door': no initial state");
  EXPECT_EQ(errorOf([&] { m.addTransition("ajar", "push", "open"); }),
            "state machine 'door': 'ajar' is not a state");
  EXPECT_EQ(errorOf([&] { m.setInitial("ajar"); }), "state machine 'door': 'ajar' is not a state");
  m.addTransition("closed", "push", "open");
  EXPECT_EQ(errorOf([&] { m.addTransition("closed", "push", "closed"); }),
            "state machine 'door': state 'closed' already has a transition on 'push' (to 'open')");
  EXPECT_EQ(m.addEvent("push"), 0u);  // already in Sigma
  EXPECT_EQ(m.addEvent("pull"), 1u);
}

TEST(StateMachine, SelfLoopsCountEntriesAndLabelsAreEscaped) {
  StateMachine m("say \"hi\"");
  m.addState("a");
  m.addState("b");
  m.addTransition("a", "tick", "a");
  m.addTransition("a", "go", "b", "run \\ go");
  m.setInitial("a");
  m.setStateLabel("b", "b\nbrush=on");
  EXPECT_FALSE(m.inFinal());  // F is empty
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(m.fire("tick"));
  EXPECT_EQ(m.entries("a"), 4);
  EXPECT_EQ(m.steps(), 3u);
  ASSERT_TRUE(m.fire("go"));
  const std::string dot = m.toDot({/*mark_current=*/true, "TB", false});
  EXPECT_THAT(dot, HasSubstr("digraph \"say \\\"hi\\\"\" {\n  rankdir=TB;"));
  EXPECT_THAT(dot, HasSubstr("\"a\" -> \"a\" [label=\"tick\"];"));
  EXPECT_THAT(dot, HasSubstr("\"a\" -> \"b\" [label=\"run \\\\ go\"];"));
  EXPECT_THAT(dot, HasSubstr("\"b\" [label=\"b\\nbrush=on\", style=filled];"));
}

TEST(StateMachine, NestsAsATaskMachineOfSubMachines) {
  // A task machine whose superstates run sub-machines: the caller runs CB1 while the task machine
  // is in "CB1" and fires "done" when CB1 is back in its final state.
  StateMachine task("task");
  for (const char* s : {"start", "CB1", "end"}) task.addState(s);
  task.addTransition("start", "go", "CB1");
  task.addTransition("CB1", "done", "end");
  task.setInitial("start");
  task.addFinal("end");
  StateMachine cb1 = cb1Machine();
  ASSERT_TRUE(task.fire("go"));
  int runs = 0;
  for (const char* event : {"zero_switch", "encoder_reached", "current_held", "zero_switch",
                            "encoder_zero", "current_held"}) {
    ASSERT_EQ(task.current(), "CB1");
    ASSERT_TRUE(cb1.fire(event));
    ++runs;
    if (cb1.inFinal() && cb1.steps() > 0) task.fire("done");
  }
  EXPECT_EQ(runs, 6);
  EXPECT_EQ(task.current(), "end");
  EXPECT_TRUE(task.inFinal());
  DotOptions cluster;
  cluster.as_cluster = true;
  const std::string dot = cb1.toDot(cluster);
  EXPECT_EQ(dot.rfind("subgraph \"cluster_CB1\" {\n  label=\"CB1\";\n", 0), 0u) << dot;
  EXPECT_THAT(dot, HasSubstr("\"CB1/q6\" -> \"CB1/q1\""));
}

TEST(StateMachine, JumpToResumesPartWayAsAnEntry) {
  // CB3 resumed at q4 on the way back: CB1's machine from q4 runs q4 -> q5 -> q6 -> q1 on its
  // last three events; the jump is an entry, not a step.
  StateMachine cb1 = cb1Machine();
  cb1.jumpTo("q4");
  EXPECT_EQ(cb1.current(), "q4");
  EXPECT_EQ(cb1.entries("q4"), 1);
  EXPECT_EQ(cb1.steps(), 0u);
  for (const char* event : {"zero_switch", "encoder_zero", "current_held"}) {
    ASSERT_TRUE(cb1.fire(event)) << event;
  }
  EXPECT_EQ(cb1.current(), "q1");
  EXPECT_EQ(cb1.entries("q1"), 2);  // q0 at reset, then the return
  EXPECT_EQ(cb1.steps(), 3u);
  EXPECT_THROW(cb1.jumpTo("q99"), Error);
}

}  // namespace
}  // namespace mcws
