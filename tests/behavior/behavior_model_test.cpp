// The behaviour model of Wang et al. 2018 (mcws::loadBehaviorModel, validateBehaviorModel,
// checkPoseConsistency): the shipped model's tables and counts worked out by hand, the corrected
// robot file, and every malformed model rejected with one line naming the file line and item.
#include "mcws/behavior/behavior_model.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "kinematics/ur5_shaped_urdf.h"
#include "mcws/core/error.h"
#include "mcws/kinematics/forward_kinematics.h"
#include "mcws/kinematics/robot_yaml.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::ElementsAre;
using ::testing::ElementsAreArray;
using ::testing::HasSubstr;

const std::string kModelPath = std::string(MCWS_ROBOTS_DIR) + "/insulator_cleaner_behaviors.yaml";
const std::string kLiteralPath = std::string(MCWS_ROBOTS_DIR) +
                                 "/../tests/behavior/data/insulator_cleaner_behaviors_literal.yaml";
const std::string kRobotLine = "robot: insulator_cleaner.yaml";

using test::errorOf;

/// The shipped model's text with the robot file named by its absolute path, so that the text
/// parses under any source name. Same lines as the file.
std::string shippedText() {
  std::string text = test::readFile(kModelPath);
  const std::size_t at = text.find(kRobotLine);
  EXPECT_NE(at, std::string::npos);
  if (at != std::string::npos) {
    text.replace(at, kRobotLine.size(),
                 "robot: " + std::string(MCWS_ROBOTS_DIR) + "/insulator_cleaner.yaml");
  }
  return text;
}

/// `text` with its only `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "no '" << from << "' in the model";
  if (at == std::string::npos) return text;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << "'" << from << "' is not unique";
  return text.replace(at, from.size(), to);
}

/// 1-based line of the only line of `text` containing `marker`.
int lineOf(const std::string& text, const std::string& marker) {
  const std::size_t at = text.find(marker);
  EXPECT_NE(at, std::string::npos) << "no '" << marker << "'";
  EXPECT_EQ(text.find(marker, at + 1), std::string::npos) << "'" << marker << "' is not unique";
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
}

/// "model.yaml:<line>: <message>", and the message is one line.
void expectError(const std::string& error, const std::string& text, const std::string& marker,
                 const std::string& message) {
  EXPECT_EQ(error, "model.yaml:" + std::to_string(lineOf(text, marker)) + ": " + message);
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

std::string validationError(const std::string& text) {
  return errorOf([&] { validateBehaviorModel(parseBehaviorModel(text, "model.yaml")); });
}

std::string parseError(const std::string& text) {
  return errorOf([&] { parseBehaviorModel(text, "model.yaml"); });
}

using Row = std::tuple<std::string, std::string, std::string, std::string, std::string>;

/// (from, to, behaviour, target, event) of each transition, in file order.
std::vector<Row> rows(const CombinedBehavior& cb) {
  std::vector<Row> out;
  for (const Transition& t : cb.transitions) {
    out.emplace_back(t.from, t.to, t.behavior, t.target, t.event);
  }
  return out;
}

class ShippedModel : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { model_ = new BehaviorModel(loadBehaviorModel(kModelPath)); }
  static void TearDownTestSuite() {
    delete model_;
    model_ = nullptr;
  }
  const BehaviorModel& model() const { return *model_; }
  const CombinedBehavior& cb(const std::string& name) const {
    const CombinedBehavior* found = model_->combinedBehavior(name);
    EXPECT_NE(found, nullptr) << name;
    return *found;
  }
  /// The pose of `state` described as "fixed_clamp=... brush=...".
  std::string pose(const std::string& state) const {
    const StatePose* p = model_->poseOf(state);
    EXPECT_NE(p, nullptr) << state;
    return p ? model_->state_vector.describe(p->pose) : "";
  }

  static BehaviorModel* model_;
};
BehaviorModel* ShippedModel::model_ = nullptr;

// ---- the shipped model -------------------------------------------------------------------------

TEST_F(ShippedModel, ValidatesWithTheHandCountedSizes) {
  const ValidationReport r = validateBehaviorModel(model());
  // 2 * 2 * 2 * 3 * 2 * 2 (the paper's "96 possible states").
  EXPECT_EQ(r.combinations, 96u);
  // Both clamps closed, J3 home: 3 * 2 * 2 = 12; J3 extended: 1 (parked); one clamp open (two
  // ways) with J3 home or extended, parked: 4. 12 + 1 + 4 = 17.
  EXPECT_EQ(r.allowed_poses, 17u);
  EXPECT_EQ(r.forbidden_poses, 79u);
  EXPECT_EQ(r.states, 13u);      // q1..q13
  EXPECT_EQ(r.poses_used, 13u);  // no two states share a pose
  EXPECT_EQ(r.behaviors, 9u);
  EXPECT_EQ(r.events, 6u);
  EXPECT_EQ(r.summary(),
            "state vector: 96 combinations, 17 allowed, 79 forbidden\n"
            "FSM states: 13 (13 distinct poses)\n"
            "basic behaviours: 9\n"
            "events: 6\n"
            "CB1: 6 states, 6 transitions, 4 events\n"
            "CB2: 8 states, 8 transitions, 4 events\n"
            "CB3: 6 states, 6 transitions, 4 events\n");
  EXPECT_EQ(model().name, "insulator_cleaner_behaviors");
  ASSERT_TRUE(model().robot.has_value());
  EXPECT_EQ(model().robot->name, "insulator_cleaner");
}

TEST_F(ShippedModel, Cb1IsTheIssuesTableWithTheMovingClampClosingLast) {
  const CombinedBehavior& cb1 = cb("CB1");
  EXPECT_THAT(cb1.states, ElementsAre("q1", "q2", "q3", "q4", "q5", "q6"));
  EXPECT_EQ(cb1.initial, "q1");
  EXPECT_THAT(cb1.finals, ElementsAre("q1"));
  EXPECT_THAT(rows(cb1), ElementsAre(Row{"q1", "q2", "BB_UG_Release", "", "zero_switch"},
                                     Row{"q2", "q3", "BB_MP_Extend", "", "encoder_reached"},
                                     Row{"q3", "q4", "BB_UG_Clamp", "", "current_held"},
                                     Row{"q4", "q5", "BB_LG_Release", "", "zero_switch"},
                                     Row{"q5", "q6", "BB_MP_Home", "", "encoder_zero"},
                                     Row{"q6", "q1", "BB_LG_Clamp", "", "current_held"}));
  EXPECT_THAT(cb1.events(),
              ElementsAre("zero_switch", "encoder_reached", "current_held", "encoder_zero"));
  // The poses of the inchworm step: never both clamps open, J3 out and back.
  EXPECT_EQ(pose("q1"),
            "fixed_clamp=closed moving_clamp=closed j3=home j4=retracted j5=home brush=off");
  EXPECT_EQ(pose("q3"),
            "fixed_clamp=open moving_clamp=closed j3=extended j4=retracted j5=home brush=off");
  EXPECT_EQ(pose("q6"),
            "fixed_clamp=closed moving_clamp=open j3=home j4=retracted j5=home brush=off");
}

TEST_F(ShippedModel, Cb2VisitsQ7ToQ13CleansBothShedsAndReturnsToQ1) {
  const CombinedBehavior& cb2 = cb("CB2");
  EXPECT_THAT(cb2.states, ElementsAre("q1", "q7", "q8", "q9", "q10", "q11", "q12", "q13"));
  EXPECT_EQ(cb2.initial, "q1");
  EXPECT_THAT(cb2.finals, ElementsAre("q1"));
  EXPECT_THAT(rows(cb2),
              ElementsAre(Row{"q1", "q7", "BB_Brush", "on", "speed_reached"},
                          Row{"q7", "q8", "BB_CP_Move", "upper_shed", "encoder_reached"},
                          Row{"q8", "q9", "BB_Guide_Rotate", "turned", "encoder_reached"},
                          Row{"q9", "q10", "BB_CP_Move", "retracted", "encoder_zero"},
                          Row{"q10", "q11", "BB_CP_Move", "lower_shed", "encoder_reached"},
                          Row{"q11", "q12", "BB_Guide_Rotate", "home", "encoder_zero"},
                          Row{"q12", "q13", "BB_Brush", "off", "speed_zero"},
                          Row{"q13", "q1", "BB_CP_Move", "retracted", "encoder_zero"}));
  // A full turn of the guide with the spinning brush over each shed.
  EXPECT_EQ(pose("q9"),
            "fixed_clamp=closed moving_clamp=closed j3=home j4=upper_shed j5=turned brush=on");
  EXPECT_EQ(pose("q12"),
            "fixed_clamp=closed moving_clamp=closed j3=home j4=lower_shed j5=home brush=on");
  // Phase II moves only J4, J5 and J6 (Figure 10 of Wang et al. 2018).
  std::set<std::string> actuators;
  for (const Transition& t : cb2.transitions) {
    actuators.insert(model().behavior(t.behavior)->body.actuator);
  }
  EXPECT_THAT(actuators, ElementsAre("J4", "J5", "J6"));
}

TEST_F(ShippedModel, Cb3IsCb1MirroredWithTheSameEvents) {
  const CombinedBehavior& cb3 = cb("CB3");
  EXPECT_THAT(rows(cb3), ElementsAre(Row{"q1", "q6", "BB_LG_Release", "", "zero_switch"},
                                     Row{"q6", "q5", "BB_MP_Extend", "", "encoder_reached"},
                                     Row{"q5", "q4", "BB_LG_Clamp", "", "current_held"},
                                     Row{"q4", "q3", "BB_UG_Release", "", "zero_switch"},
                                     Row{"q3", "q2", "BB_MP_Home", "", "encoder_zero"},
                                     Row{"q2", "q1", "BB_UG_Clamp", "", "current_held"}));
  std::vector<std::string> events1, events3;
  for (const Transition& t : cb("CB1").transitions) events1.push_back(t.event);
  for (const Transition& t : cb3.transitions) events3.push_back(t.event);
  EXPECT_EQ(events3, events1);  // "the same events" (Table 4), in the same order
  // q1 is shared; what runs there belongs to the pair (combined behaviour, state).
  EXPECT_EQ(cb("CB1").transitionFrom("q1")->behavior, "BB_UG_Release");
  EXPECT_EQ(cb("CB2").transitionFrom("q1")->behavior, "BB_Brush");
  EXPECT_EQ(cb3.transitionFrom("q1")->behavior, "BB_LG_Release");
}

TEST_F(ShippedModel, NineBasicBehavioursInPortAutomatonForm) {
  std::vector<std::string> names;
  for (const BasicBehavior& b : model().behaviors) names.push_back(b.name);
  EXPECT_THAT(names, ElementsAre("BB_UG_Clamp", "BB_UG_Release", "BB_LG_Clamp", "BB_LG_Release",
                                 "BB_MP_Extend", "BB_MP_Home", "BB_CP_Move", "BB_Guide_Rotate",
                                 "BB_Brush"));
  // Each drives one actuator and changes one component (the actuator's).
  const std::map<std::string, std::pair<std::string, std::string>> expected = {
      {"BB_UG_Clamp", {"J1", "fixed_clamp"}},
      {"BB_UG_Release", {"J1", "fixed_clamp"}},
      {"BB_LG_Clamp", {"J2", "moving_clamp"}},
      {"BB_LG_Release", {"J2", "moving_clamp"}},
      {"BB_MP_Extend", {"J3", "j3"}},
      {"BB_MP_Home", {"J3", "j3"}},
      {"BB_CP_Move", {"J4", "j4"}},
      {"BB_Guide_Rotate", {"J5", "j5"}},
      {"BB_Brush", {"J6", "brush"}}};
  for (const BasicBehavior& b : model().behaviors) {
    EXPECT_EQ(b.body.actuator, expected.at(b.name).first) << b.name;
    EXPECT_THAT(b.body.changes, ElementsAre(expected.at(b.name).second)) << b.name;
    EXPECT_TRUE(b.timeout_s.has_value()) << b.name;
  }
  // Figure 4 of Wang et al. 2018: BB_UG_Clamp reads the motor current Ir, servoes to I and holds.
  const BasicBehavior& clamp = *model().behavior("BB_UG_Clamp");
  ASSERT_EQ(clamp.input_ports.size(), 1u);
  EXPECT_EQ(clamp.input_ports[0].name, "Ir");
  EXPECT_EQ(clamp.input_ports[0].type, "motor_current");
  ASSERT_NE(clamp.parameter("I"), nullptr);
  EXPECT_DOUBLE_EQ(clamp.parameter("I")->value, 1.5);
  EXPECT_EQ(clamp.parameter("I")->unit, "A");
  EXPECT_DOUBLE_EQ(clamp.parameter("hold")->value, 0.5);
  EXPECT_EQ(clamp.parameter("hold")->unit, "s");
  EXPECT_DOUBLE_EQ(*clamp.timeout_s, 15.0);
  ASSERT_EQ(clamp.body.targets.size(), 1u);
  EXPECT_EQ(clamp.body.targets[0].command, "close");
  EXPECT_EQ(clamp.body.targets[0].ends_on, "current_held");
  const BasicBehavior& brush = *model().behavior("BB_Brush");
  EXPECT_DOUBLE_EQ(brush.parameter("speed")->value, 300.0);
  EXPECT_EQ(brush.parameter("speed")->unit, "rpm");
  EXPECT_EQ(brush.body.target("on")->command, "spin");
  EXPECT_EQ(brush.body.target("off")->ends_on, "speed_zero");
  EXPECT_EQ(brush.body.target("fast"), nullptr);
}

TEST_F(ShippedModel, AllowedPosesByClampsAndJ3) {
  const StateVectorSpec& spec = model().state_vector;
  ASSERT_EQ(spec.components.size(), 6u);
  // (fixed_clamp, moving_clamp, j3) -> allowed poses, worked out from the four rules.
  std::map<std::string, int> count;
  for (const Pose& p : spec.allowedPoses()) {
    ++count[spec.components[0].values[p[0]] + "," + spec.components[1].values[p[1]] + "," +
            spec.components[2].values[p[2]]];
  }
  EXPECT_EQ(count, (std::map<std::string, int>{{"closed,closed,home", 12},
                                               {"closed,closed,extended", 1},
                                               {"open,closed,home", 1},
                                               {"open,closed,extended", 1},
                                               {"closed,open,home", 1},
                                               {"closed,open,extended", 1}}));
  // Pose = (fixed, moving, j3, j4, j5, brush) value indices.
  EXPECT_EQ(spec.brokenRule({0, 0, 0, 0, 0, 0})->name, "never_both_clamps_open");
  EXPECT_EQ(spec.brokenRule({0, 1, 0, 1, 0, 0})->name, "fixed_clamp_open_parks_the_cleaner");
  EXPECT_EQ(spec.brokenRule({1, 0, 0, 0, 0, 1})->name, "moving_clamp_open_parks_the_cleaner");
  EXPECT_EQ(spec.brokenRule({1, 1, 1, 0, 1, 0})->name, "j3_extended_parks_the_cleaner");
  EXPECT_EQ(spec.brokenRule({1, 1, 0, 2, 1, 1}), nullptr);  // cleaning the lower shed
}

TEST_F(ShippedModel, EveryTransitionChangesOneComponentAsItsBehaviourSays) {
  EXPECT_TRUE(checkPoseConsistency(model()).empty());
  for (const CombinedBehavior& cb : model().combined) {
    for (const Transition& t : cb.transitions) {
      const Pose& from = model().poseOf(t.from)->pose;
      const Pose& to = model().poseOf(t.to)->pose;
      int differing = 0;
      for (std::size_t k = 0; k < from.size(); ++k) differing += from[k] != to[k];
      EXPECT_EQ(differing, 1) << cb.name << " " << t.from << " -> " << t.to;
    }
  }
}

TEST_F(ShippedModel, StringAndPositions) {
  EXPECT_EQ(model().insulator.type, "XWP2-160");
  EXPECT_DOUBLE_EQ(model().insulator.pitch_mm, 155.0);
  EXPECT_DOUBLE_EQ(model().insulator.upper_shed_diameter_mm, 300.0);
  EXPECT_DOUBLE_EQ(model().insulator.lower_shed_diameter_mm, 220.0);
  const StateVectorSpec& spec = model().state_vector;
  const StateComponent& j3 = spec.components[spec.componentIndex("j3")];
  EXPECT_THAT(j3.values, ElementsAre("home", "extended"));
  EXPECT_THAT(j3.positions, ElementsAre(0.0, model().insulator.pitch_mm));  // one pitch
  EXPECT_EQ(j3.position_unit, "mm");
  const StateComponent& j4 = spec.components[spec.componentIndex("j4")];
  EXPECT_THAT(j4.values, ElementsAre("retracted", "upper_shed", "lower_shed"));
  EXPECT_THAT(j4.positions, ElementsAre(0.0, 60.0, 100.0));
  // The brush hub is 180 - J4 mm from the string axis: 120 mm over the 150 mm radius upper
  // shed, 80 mm over the 110 mm radius lower shed.
  EXPECT_LT(180.0 - j4.positions[1], model().insulator.upper_shed_diameter_mm / 2);
  EXPECT_LT(180.0 - j4.positions[2], model().insulator.lower_shed_diameter_mm / 2);
  EXPECT_GT(180.0 - j4.positions[0], model().insulator.upper_shed_diameter_mm / 2);
  const StateComponent& j5 = spec.components[spec.componentIndex("j5")];
  EXPECT_THAT(j5.positions, ElementsAre(0.0, 360.0));
  EXPECT_EQ(j5.position_unit, "deg");
  // The number of discs is a run parameter: the model has no field for it.
  const std::string text = shippedText();
  const std::string with_discs =
      replaced(text, "  type: XWP2-160\n", "  type: XWP2-160\n  discs: 28\n");
  expectError(parseError(with_discs), with_discs, "  discs: 28",
              "insulator: unknown key 'discs' (allowed: lower_shed_diameter, pitch, type, "
              "upper_shed_diameter)");
}

TEST_F(ShippedModel, ResolvesWhatEachTransitionRuns) {
  const BehaviorRun shed = resolveRun(model(), cb("CB2").transitions[1]);  // q7 -> q8
  EXPECT_EQ(shed.behavior->name, "BB_CP_Move");
  EXPECT_EQ(shed.target->value, "upper_shed");
  EXPECT_EQ(shed.target->command, "move_to");
  EXPECT_EQ(shed.target->ends_on, "encoder_reached");
  EXPECT_EQ(model().state_vector.components[shed.component].name, "j4");
  EXPECT_EQ(shed.value, 1);
  ASSERT_TRUE(shed.position.has_value());
  EXPECT_DOUBLE_EQ(*shed.position, 60.0);
  const BehaviorRun release = resolveRun(model(), cb("CB1").transitions[0]);  // q1 -> q2
  EXPECT_EQ(release.target->command, "release");
  EXPECT_EQ(release.target->value, "open");
  EXPECT_FALSE(release.position.has_value());
  EXPECT_EQ(applyRun(release, model().poseOf("q1")->pose), model().poseOf("q2")->pose);
  const BehaviorRun extend = resolveRun(model(), cb("CB1").transitions[1]);  // q2 -> q3
  EXPECT_DOUBLE_EQ(*extend.position, 155.0);
}

// ---- the robot file ----------------------------------------------------------------------------

TEST(InsulatorCleanerRobot, ClampJointsTurnAboutTheStringAndAddNoReachablePoint) {
  const Robot robot = loadRobot(test::robotPath("insulator_cleaner"));
  ASSERT_EQ(robot.dof(), 6);
  const char* names[] = {"J1", "J2", "J3", "J5", "J4", "J6"};
  for (int j = 0; j < 6; ++j) EXPECT_EQ(robot.joints[j].name, names[j]);
  constexpr double kDeg = M_PI / 180.0;
  for (int j : {0, 1}) {
    EXPECT_EQ(robot.joints[j].type, JointType::kRevolute);
    EXPECT_DOUBLE_EQ(robot.joints[j].lower, 0.0);
    EXPECT_DOUBLE_EQ(robot.joints[j].upper, 40 * kDeg);
  }
  EXPECT_EQ(robot.joints[2].type, JointType::kPrismatic);
  EXPECT_EQ(robot.joints[4].type, JointType::kPrismatic);
  EXPECT_DOUBLE_EQ(robot.joints[3].upper, 360 * kDeg);
  // q = (J1, J2, J3, J5, J4, J6): the hub is 180 - J4 mm from the string axis (world z) at
  // z = J3 - 370 mm; J1 and J2 only add to J5's angle.
  constexpr double kTol = 1e-9;  // mm; a few D-H products of doubles
  Eigen::VectorXd q(6);
  q << 30 * kDeg, 10 * kDeg, 155, 100 * kDeg, 60, 45 * kDeg;
  const Eigen::Vector3d p = toolPose(robot, q).translation();
  EXPECT_NEAR(std::hypot(p.x(), p.y()), 120.0, kTol);
  EXPECT_NEAR(p.z(), 155.0 - 370.0, kTol);
  Eigen::VectorXd same = q;
  same << 0, 0, 155, 140 * kDeg, 60, 45 * kDeg;
  EXPECT_LT((toolPose(robot, same).translation() - p).norm(), kTol);
}

// ---- malformed models: the validator -----------------------------------------------------------

const char* const kCb1Q2Q3 =
    "      - {from: q2, to: q3, run: BB_MP_Extend, event: encoder_reached}\n";
const char* const kCb1Q6Q1 = "      - {from: q6, to: q1, run: BB_LG_Clamp, event: current_held}";
const char* const kCb1States = "    states: [q1, q2, q3, q4, q5, q6]";

TEST(BehaviorModelParsing, ACombinedBehavioursNameMustBeAPlainFileNameOfItsOwn) {
  // The name is the stem of its diagram's file (mcws_behave --dot DIR writes DIR/<name>.dot):
  // a path, a hidden or relative name, a control byte or the task diagram's name would write
  // outside DIR or over another diagram. Each is one line naming the file, line, field and name.
  struct Case {
    std::string yaml;    // as written in the file
    std::string quoted;  // as the message quotes it
    std::string why;
  };
  const std::string plain = "it names the file of its diagram and ";
  for (const Case& c : {
           Case{"\"../../x\"", "'../../x'", plain + "must not start with '.'"},
           Case{"x/../../y", "'x/../../y'", plain + "must not contain '/' or '\\'"},
           Case{"/tmp/x", "'/tmp/x'", plain + "must not contain '/' or '\\'"},
           Case{"'a\\b'", "'a\\x5cb'", plain + "must not contain '/' or '\\'"},
           Case{"\"..\"", "'..'", plain + "must not start with '.'"},
           Case{".hidden", "'.hidden'", plain + "must not start with '.'"},
           Case{"\"a\\nb\"", "'a\\x0ab'", plain + "must not contain a control byte"},
           Case{"\"a\\tb\"", "'a\\x09b'", plain + "must not contain a control byte"},
           Case{std::string(201, 'c'), "'" + std::string(201, 'c') + "'",
                plain + "has 201 bytes, more than 200"},
           Case{"task", "'task'", "the task machine's diagram has that file name (task.dot)"},
           Case{"Task", "'Task'", "the task machine's diagram has that file name (task.dot)"},
           Case{"cb1", "'cb1'",
                "differs from combined behaviour 'CB1' (line " +
                    std::to_string(lineOf(shippedText(), "  - name: CB1\n")) +
                    ") only in case: their diagrams would share a file name"},
       }) {
    const std::string text =
        replaced(shippedText(), "  - name: CB3\n", "  - name: " + c.yaml + "\n");
    expectError(parseError(text), text, "  - name: " + c.yaml + "\n",
                "combined behaviour 3: name " + c.quoted + ": " + c.why);
  }
  // A name that is a fine file name passes (CB3 is not needed to parse).
  const std::string fine = replaced(shippedText(), "  - name: CB3\n", "  - name: CB3 up\n");
  EXPECT_NO_THROW(parseBehaviorModel(fine, "model.yaml"));
}

TEST(BehaviorModelValidation, UnreachableState) {
  const std::string text = replaced(shippedText(), kCb1Q2Q3, "");
  expectError(validationError(text), text, kCb1States,
              "CB1: state 'q3' is unreachable from the initial state q1");
}

TEST(BehaviorModelValidation, MissingInitialState) {
  const std::string shipped = shippedText();
  // CB1's "initial: q1" is the first of three.
  std::string text = shipped;
  text.erase(text.find("    initial: q1\n"), 16);
  expectError(validationError(text), text, "  - name: CB1", "CB1: no initial state (initial: q0)");
  const std::string elsewhere =
      replaced(shipped, "    states: [q1, q2, q3, q4, q5, q6]\n    initial: q1",
               "    states: [q1, q2, q3, q4, q5, q6]\n    initial: q0");
  expectError(validationError(elsewhere), elsewhere, "    initial: q0",
              "CB1: initial state 'q0' is not in its states");
}

TEST(BehaviorModelValidation, MissingFinalState) {
  std::string text = shippedText();
  text.erase(text.find("    final: [q1]\n"), 16);  // CB1's
  expectError(validationError(text), text, "  - name: CB1", "CB1: no final state (final: F)");
  const std::string empty = replaced(shippedText(), "q6]\n    initial: q1\n    final: [q1]",
                                     "q6]\n    initial: q1\n    final: []");
  expectError(validationError(empty), empty, "    final: []", "CB1: no final state (final: F)");
  const std::string outside = replaced(shippedText(), "q6]\n    initial: q1\n    final: [q1]",
                                       "q6]\n    initial: q1\n    final: [q1, q9]");
  expectError(validationError(outside), outside, "    final: [q1, q9]",
              "CB1: final state 'q9' is not in its states");
}

TEST(BehaviorModelValidation, TwoTransitionsOnOneEventFromOneState) {
  const std::string second = "      - {from: q1, to: q3, run: BB_UG_Release, event: zero_switch}\n";
  const std::string text = replaced(shippedText(), kCb1Q2Q3, kCb1Q2Q3 + second);
  const int first = lineOf(text, "{from: q1, to: q2, run: BB_UG_Release");
  expectError(validationError(text), text, "{from: q1, to: q3, run: BB_UG_Release",
              "CB1: transition q1 -> q3: q1 already has a transition on zero_switch (line " +
                  std::to_string(first) + ")");
}

TEST(BehaviorModelValidation, UnknownBehaviour) {
  const std::string text = replaced(shippedText(), "{from: q2, to: q3, run: BB_MP_Extend",
                                    "{from: q2, to: q3, run: BB_MP_Fly");
  expectError(validationError(text), text, "BB_MP_Fly",
              "CB1: transition q2 -> q3: unknown behaviour 'BB_MP_Fly'");
}

TEST(BehaviorModelValidation, UnknownEvent) {
  const std::string text =
      replaced(shippedText(), "run: BB_UG_Release, event: zero_switch}\n      - {from: q2",
               "run: BB_UG_Release, event: zero_swich}\n      - {from: q2");
  expectError(validationError(text), text, "zero_swich",
              "CB1: transition q1 -> q2: unknown event 'zero_swich' (zero_switch, encoder_reached, "
              "encoder_zero, current_held, speed_reached, speed_zero)");
  // A behaviour ending on an event that does not exist.
  const std::string body =
      replaced(shippedText(), "upper_shed: {command: move_to, ends_on: encoder_reached}",
               "upper_shed: {command: move_to, ends_on: encoder_hit}");
  expectError(validationError(body), body, "encoder_hit",
              "basic behaviour 'BB_CP_Move': target 'upper_shed': ends on unknown event "
              "'encoder_hit' (zero_switch, encoder_reached, encoder_zero, current_held, "
              "speed_reached, speed_zero)");
  // An existing event that is not the behaviour's ending event.
  const std::string wrong =
      replaced(shippedText(), "run: BB_UG_Release, event: zero_switch}\n      - {from: q2",
               "run: BB_UG_Release, event: encoder_zero}\n      - {from: q2");
  expectError(validationError(wrong), wrong, "{from: q1, to: q2,",
              "CB1: transition q1 -> q2: event 'encoder_zero' is not the ending event of "
              "BB_UG_Release (zero_switch)");
}

TEST(BehaviorModelValidation, NoWayBackToTheFinalState) {
  const std::string text = replaced(
      shippedText(), kCb1Q6Q1, "      - {from: q6, to: q6, run: BB_LG_Clamp, event: current_held}");
  expectError(validationError(text), text, kCb1States,
              "CB1: state 'q2' has no way back to a final state (q1)");
}

TEST(BehaviorModelValidation, ForbiddenPose) {
  const std::string q3 =
      "  q3:  {fixed_clamp: open, moving_clamp: closed, j3: extended, j4: retracted,";
  const std::string text =
      replaced(shippedText(), q3,
               "  q3:  {fixed_clamp: open, moving_clamp: closed, j3: extended, j4: upper_shed,");
  expectError(validationError(text), text, "  q3:",
              "poses: state 'q3': pose fixed_clamp=open moving_clamp=closed j3=extended "
              "j4=upper_shed j5=home brush=off is forbidden by rule "
              "'fixed_clamp_open_parks_the_cleaner' (line " +
                  std::to_string(lineOf(text, "- name: fixed_clamp_open_parks_the_cleaner")) + ")");
  const std::string open =
      replaced(shippedText(), "  q2:  {fixed_clamp: open, moving_clamp: closed",
               "  q2:  {fixed_clamp: open, moving_clamp: open");
  EXPECT_THAT(validationError(open),
              HasSubstr("poses: state 'q2': pose fixed_clamp=open moving_clamp=open j3=home "
                        "j4=retracted j5=home brush=off is forbidden by rule "
                        "'never_both_clamps_open'"));
}

TEST(BehaviorModelValidation, BehaviourChangingTwoComponentsOrNone) {
  const std::string clamp =
      "      actuator: J1\n      changes: fixed_clamp\n      targets:\n        closed";
  const std::string text = replaced(shippedText(), clamp,
                                    "      actuator: J1\n      changes: [fixed_clamp, "
                                    "moving_clamp]\n      targets:\n        closed");
  expectError(validationError(text), text, "changes: [fixed_clamp, moving_clamp]",
              "basic behaviour 'BB_UG_Clamp': changes 2 state-vector components (fixed_clamp, "
              "moving_clamp); a basic behaviour changes exactly one");
  const std::string none =
      replaced(shippedText(), clamp,
               "      actuator: J1\n      changes: []\n      targets:\n        closed");
  expectError(validationError(none), none, "changes: []",
              "basic behaviour 'BB_UG_Clamp': changes no state-vector component; a basic "
              "behaviour changes exactly one");
}

TEST(BehaviorModelValidation, OtherMismatchesNameTheItem) {
  // A behaviour commanding one joint but changing the component another joint drives.
  const std::string actuator =
      replaced(shippedText(),
               "      actuator: J1\n      changes: fixed_clamp\n      targets:\n        closed",
               "      actuator: J2\n      changes: fixed_clamp\n      targets:\n        closed");
  EXPECT_THAT(validationError(actuator),
              HasSubstr(": basic behaviour 'BB_UG_Clamp': commands J2 but changes fixed_clamp, "
                        "which J1 drives"));
  // A target that is not a value of the component.
  const std::string target = replaced(shippedText(), "        turned: {command: move_to",
                                      "        half: {command: move_to");
  expectError(validationError(target), target, "half: {command",
              "basic behaviour 'BB_Guide_Rotate': target 'half': not a value of j5 (home, turned)");
  // A behaviour with several targets run without one.
  const std::string missing =
      replaced(shippedText(), "run: BB_Brush, target: \"on\", ", "run: BB_Brush, ");
  expectError(validationError(missing), missing, "{from: q1, to: q7",
              "CB2: transition q1 -> q7: BB_Brush needs a target (on, off)");
  // A state without a pose.
  const std::string nopose = replaced(shippedText(), "  q13: {", "  q14: {");
  expectError(validationError(nopose), nopose, "    states: [q1, q7,",
              "CB2: state 'q13' has no pose (poses:)");
  // A position outside the robot's joint limits.
  const std::string far = replaced(shippedText(), "turned: 360 deg", "turned: 400 deg");
  expectError(validationError(far), far, "turned: 400 deg",
              "state vector: component 'j5': position 'turned' = 400 deg is outside joint 'J5' "
              "limits [0, 6.283185307] rad ([0, 360] deg)");
  // An actuator the robot does not have.
  const std::string seventh =
      replaced(shippedText(), "{name: brush, actuator: J6,", "{name: brush, actuator: J7,");
  expectError(validationError(seventh), seventh, "actuator: J7",
              "state vector: component 'brush': actuator 'J7' is not a joint of robot "
              "'insulator_cleaner' (J1, J2, J3, J5, J4, J6)");
}

// ---- malformed models: the reader --------------------------------------------------------------

TEST(BehaviorModelParsing, UnknownKey) {
  const std::string top = replaced(shippedText(), "name: insulator_cleaner_behaviors\n",
                                   "name: insulator_cleaner_behaviors\ndiscs: 28\n");
  expectError(parseError(top), top, "discs: 28",
              "model: unknown key 'discs' (allowed: basic_behaviors, combined_behaviors, events, "
              "insulator, name, pose_rules, poses, robot, state_vector)");
  const std::string in_transition = replaced(
      shippedText(),
      "{from: q5, to: q6, run: BB_MP_Home, event:", "{from: q5, to: q6, run: BB_MP_Home, on:");
  expectError(parseError(in_transition), in_transition, "{from: q5, to: q6",
              "CB1: transition 5: unknown key 'on' (allowed: event, from, run, target, to)");
  const std::string in_body =
      replaced(shippedText(), "      actuator: J6\n", "      actuator: J6\n      speed: 300 rpm\n");
  expectError(parseError(in_body), in_body, "      speed: 300 rpm",
              "basic behaviour 'BB_Brush': body: unknown key 'speed' (allowed: actuator, changes, "
              "targets)");
}

TEST(BehaviorModelParsing, DuplicateKey) {
  const std::string text =
      replaced(shippedText(), "{from: q1, to: q2, run: BB_UG_Release, event: zero_switch}",
               "{from: q1, to: q2, run: BB_UG_Release, event: zero_switch, event: zero_switch}");
  expectError(parseError(text), text, "event: zero_switch, event",
              "CB1: transition 1: key 'event' given twice");
  // The second "q12" key of poses, where q13 was.
  const std::string shipped = shippedText();
  const std::string pose = replaced(shipped, "  q13: {", "  q12: {");
  EXPECT_EQ(parseError(pose), "model.yaml:" + std::to_string(lineOf(shipped, "  q13: {")) +
                                  ": poses: key 'q12' given twice");
}

TEST(BehaviorModelParsing, OtherReaderErrorsNameTheLine) {
  const std::string text = shippedText();
  const std::string nameless = replaced(text, "  - name: BB_MP_Home ", "  - title: BB_MP_Home ");
  EXPECT_THAT(parseError(nameless),
              HasSubstr(": basic behaviour 6: unknown key 'title' (allowed: body, input_ports, "
                        "name, output_ports, parameters, timeout)"));
  const std::string unit =
      replaced(text, "parameters: {speed: 300 rpm}", "parameters: {speed: 300 rps}");
  expectError(parseError(unit), unit, "300 rps",
              "basic behaviour 'BB_Brush': parameter speed: unknown unit 'rps' in '300 rps' (A, N, "
              "V, deg, deg/s, mA, mm, mm/s, ms, rpm, s)");
  const std::string value =
      replaced(text, "  q4:  {fixed_clamp: closed,", "  q4:  {fixed_clamp: shut,");
  expectError(parseError(value), value, "fixed_clamp: shut",
              "poses: state 'q4': 'shut' is not a value of fixed_clamp (open, closed)");
  const std::string robot =
      replaced(text, "/insulator_cleaner.yaml   # relative", "/no_such_robot.yaml   # relative");
  EXPECT_THAT(parseError(robot),
              HasSubstr("model.yaml:" + std::to_string(lineOf(text, "robot: /")) + ": robot: '"));
  EXPECT_THAT(parseError(robot), HasSubstr("no_such_robot.yaml' does not exist"));
  EXPECT_EQ(parseError("name: [unclosed"),
            "model.yaml:1: YAML syntax: end of sequence flow not found");
}

TEST(BehaviorModelRobot, AMapChoosesAUrdfsChainAsTheToolsBaseAndTipDo) {
  const test::TempDir dir;
  const std::string urdf = dir.file("ur5.urdf");
  test::writeFile(urdf, test::kUr5ShapedUrdf);
  const std::string yaml = std::string(MCWS_ROBOTS_DIR) + "/insulator_cleaner.yaml";
  const std::string named = "robot: " + yaml;
  const std::string text = shippedText();
  const BehaviorModel model =
      parseBehaviorModel(replaced(text, named, "robot: {file: " + urdf + ", tip: ee_link}"),
                         "model.yaml");  // parsed only: its actuators are not the UR's joints
  EXPECT_EQ(model.robot_path, urdf);
  ASSERT_TRUE(model.robot);
  EXPECT_EQ(model.robot->tip_link, "ee_link");
  const std::string leaves = replaced(text, named, "robot: {file: " + urdf + "}");
  expectError(parseError(leaves), leaves, "robot: {",
              "robot: " + urdf +
                  ": link 'world' has 2 leaf links below it (tool0, ee_link): choose one with "
                  "robot: {file: FILE, tip: LINK}");
  const std::string tip = replaced(text, named, "robot: {file: " + urdf + ", tip: hand}");
  expectError(parseError(tip), tip, "robot: {",
              "robot: tip: 'hand' is not a link of robot 'ur5_shaped' in " + urdf);
  const std::string dh = replaced(text, named, "robot: {file: " + yaml + ", tip: tool0}");
  expectError(parseError(dh), dh, "robot: {",
              "robot: tip: base and tip need a .urdf robot ('" + yaml + "' is not)");
}

// ---- the literal CB1 of Wang et al. 2018
// ----------------------------------------------------------------------

TEST(LiteralModel, IsTheShippedModelWithTheFixedClampClosingAtQ6) {
  const std::string shipped = test::readFile(kModelPath);
  const std::string literal = test::readFile(kLiteralPath);
  std::istringstream a(shipped), b(literal);
  std::vector<std::string> differing;
  for (std::string x, y; std::getline(a, x) && std::getline(b, y);) {
    if (x != y) differing.push_back(y);
  }
  EXPECT_EQ(test::lineCount(shipped), test::lineCount(literal));
  EXPECT_THAT(differing,
              ElementsAre(HasSubstr("LITERAL"), "robot: ../../../robots/insulator_cleaner.yaml",
                          "      - {from: q6, to: q1, run: BB_UG_Clamp, event: current_held}  # "
                          "the paper's literal text"));
}

TEST(LiteralModel, ValidatesStructurallyAndOnlyThePoseCheckFlagsIt) {
  const BehaviorModel model = loadBehaviorModel(kLiteralPath);
  const ValidationReport report = validateBehaviorModel(model);  // no throw
  EXPECT_EQ(report.allowed_poses, 17u);
  EXPECT_EQ(model.combinedBehavior("CB1")->transitions.back().behavior, "BB_UG_Clamp");
  const std::vector<PoseFinding> findings = checkPoseConsistency(model);
  ASSERT_EQ(findings.size(), 1u);
  EXPECT_EQ(findings[0].combined, "CB1");
  EXPECT_EQ(findings[0].transition.from, "q6");
  EXPECT_EQ(findings[0].transition.to, "q1");
  EXPECT_EQ(findings[0].reached, model.poseOf("q6")->pose);  // the robot stays in q6's pose
  const int line =
      lineOf(test::readFile(kLiteralPath), "run: BB_UG_Clamp, event: current_held}  #");
  EXPECT_EQ(findings[0].message,
            kLiteralPath + ":" + std::to_string(line) +
                ": CB1: q6 -> q1: BB_UG_Clamp sets fixed_clamp to closed, which it already is in "
                "q6; it leaves moving_clamp=open where q1 has moving_clamp=closed");
}

}  // namespace
}  // namespace mcws
