// YAML aliases in every mcws YAML file (mcws::loadYamlDocument, shared by the robot, collision,
// behaviour model, fault and scenario readers): an "alias bomb" of a few hundred bytes whose
// aliases of aliases expand to billions of nodes, or a node that contains itself, is refused with
// one line naming the file and the line of the alias, before any reader walks it (issue 31: a
// 727-byte robot file hung mcws_fk). Before the bound, each of these documents made the loader
// run for ever.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "mcws/behavior/behavior_model.h"
#include "mcws/behavior/fault_script.h"
#include "mcws/collision/collision_model.h"
#include "mcws/core/error.h"
#include "mcws/core/yaml_reader.h"
#include "mcws/kinematics/robot_yaml.h"
#include "test_support.h"

namespace mcws {
namespace {

using test::errorOf;

std::string bombMessage(const std::string& source, int line) {
  return source + ":" + std::to_string(line) +
         ": YAML aliases expand the document by more than 1000000 nodes (the limit; an alias "
         "bomb?)";
}

/// Lines "&a0 [x, x, ...]", then "&aK [*aK-1, *aK-1, ...]" for K = 1 .. levels, `width` items
/// each, every line starting with `prefix` ("  - " for list items).
std::string sequenceBomb(int levels, int width, const std::string& prefix) {
  std::string text;
  for (int level = 0; level <= levels; ++level) {
    text += prefix + "&a" + std::to_string(level) + " [";
    for (int k = 0; k < width; ++k) {
      text += (k ? ", " : "") + (level ? "*a" + std::to_string(level - 1) : std::string("x"));
    }
    text += "]\n";
  }
  return text;
}

const std::string kRobotHead =
    "name: bomb\n"                       // 1
    "units: {length: mm, angle: deg}\n"  // 2
    "convention: standard\n"             // 3
    "description:\n";                    // 4, the bomb's level 0 on line 5
const std::string kRobotJoints =
    "joints:\n  - {name: j1, type: revolute, a: 100, alpha: 0, d: 0, limits: [-90, 90]}\n";

TEST(YamlAliases, RefuseTheIssuesBombInARobotFileAndItsCollisionSection) {
  // Ten levels of ten aliases: 10^10 nodes. Level 0 has 11 nodes (a list and 10 scalars), level
  // k 1 + 10 * size(k - 1): 111, 1111, 11111, 111111, 1111111. The aliases of levels 1-4 add
  // 110 + 1110 + 11110 + 111110 = 123440 nodes; level 5's add 111111 each, the eighth passing a
  // million (123440 + 8 * 111111 = 1012328). Level 5 is on line 10.
  const std::string text = kRobotHead + sequenceBomb(10, 10, "  - ") + kRobotJoints;
  EXPECT_EQ(errorOf([&] { parseRobotYaml(text, "bomb.yaml"); }), bombMessage("bomb.yaml", 10));
  const Robot robot = parseRobotYaml(kRobotHead + "  plain\n" + kRobotJoints, "ok.yaml");
  EXPECT_EQ(errorOf([&] { parseCollisionYaml(robot, text, "bomb.yaml"); }),
            bombMessage("bomb.yaml", 10));
}

TEST(YamlAliases, RefuseABombOfMapsInAFaultFile) {
  // Maps of ten keys: level 0 has 21 nodes (a map, 10 keys, 10 values), level k 1 + 10 + 10 *
  // size(k - 1): 221, 2221, 22221, 222221. Levels 1-4 add 210 + 2210 + 22210 + 222210 = 246840
  // nodes; level 5's aliases 222221 each, the fourth passing a million. Level 5 is on line 10.
  std::string text = "policy:\n  link_wait: 30 s\nfaults:\n  - {at: 120 s, type: link_down}\n";
  text += "l0: &l0 {a: x, b: x, c: x, d: x, e: x, f: x, g: x, h: x, i: x, j: x}\n";  // line 5
  for (int level = 1; level <= 9; ++level) {
    const std::string alias = "*l" + std::to_string(level - 1);
    text += "l" + std::to_string(level) + ": &l" + std::to_string(level) + " {";
    for (char key = 'a'; key <= 'j'; ++key)
      text += std::string(key == 'a' ? "" : ", ") + key + ": " + alias;
    text += "}\n";
  }
  EXPECT_EQ(errorOf([&] { parseFaultScript(text, "f.yaml"); }), bombMessage("f.yaml", 10));
}

TEST(YamlAliases, RefuseADoublingBombInABehaviourModel) {
  // Forty levels of two aliases: 2^41 nodes. Level k has 2^(k+2) - 1 nodes; the aliases of
  // levels 1..k add 2^(k+3) - 8 - 2k in all: 524248 up to level 16, then level 17's add 2^18 - 1
  // = 262143 each, the second passing a million (1048534). Level 0 is on line 3, level 17 on 20.
  const std::string text = "name: m\nbomb:\n" + sequenceBomb(40, 2, "  - ");
  EXPECT_EQ(errorOf([&] { parseBehaviorModel(text, "m.yaml"); }), bombMessage("m.yaml", 20));
}

TEST(YamlAliases, MayAddAMillionNodesButNotOneMore) {
  // A list of 999 scalars is 1000 nodes; 1000 aliases of it add exactly 1000000.
  std::string text = "a: &s [x";
  for (int k = 1; k < 999; ++k) text += ", x";
  text += "]\nb: [*s";
  for (int k = 1; k < 1000; ++k) text += ", *s";
  text += "]\n";
  const YAML::Node root = loadYamlDocument(text, "limit.yaml", "a test file");
  ASSERT_EQ(root["b"].size(), 1000u);
  EXPECT_EQ(root["b"][999].size(), 999u);
  // One more: an alias of a scalar, line 4.
  text += "c: &t y\nd: *t\n";
  EXPECT_EQ(errorOf([&] { loadYamlDocument(text, "limit.yaml", "a test file"); }),
            bombMessage("limit.yaml", 4));
}

TEST(YamlAliases, RefuseANodeThatContainsItself) {
  // yaml-cpp builds such a node as a cycle: walking it never ends.
  const std::string message =
      ": YAML alias inside the node its anchor names (a node that contains itself)";
  EXPECT_EQ(errorOf([&] { loadYamlDocument("a: &x [1, *x]\n", "c.yaml", "a test file"); }),
            "c.yaml:1" + message);
  EXPECT_EQ(errorOf([&] { loadYamlDocument("a: &m\n  k: [v, *m]\n", "c.yaml", "a test file"); }),
            "c.yaml:2" + message);
  const std::string robot = kRobotHead + "  - &d {x: [*d]}\n" + kRobotJoints;
  EXPECT_EQ(errorOf([&] { parseRobotYaml(robot, "c.yaml"); }), "c.yaml:5" + message);
}

TEST(YamlAliases, OrdinaryAliasesStillWork) {
  // Shared limits, an anchor named twice (the alias takes the latest), an alias as a key.
  const std::string text =
      "name: shared\nunits: {length: mm, angle: deg}\nconvention: standard\njoints:\n"
      "  - {name: j1, type: revolute, a: 100, alpha: 0, d: 0, limits: &lim [-90, 90]}\n"
      "  - {name: j2, type: revolute, a: 100, alpha: 0, d: 0, limits: *lim}\n"
      "  - {name: j3, type: revolute, a: 100, alpha: 0, d: 0, limits: &lim [-45, 45]}\n"
      "  - {name: j4, type: revolute, a: 100, alpha: 0, d: 0, limits: *lim}\n";
  const Robot robot = parseRobotYaml(text, "shared.yaml");
  ASSERT_EQ(robot.dof(), 4);
  EXPECT_DOUBLE_EQ(robot.joints[1].upper, M_PI / 2);
  EXPECT_DOUBLE_EQ(robot.joints[3].upper, M_PI / 4);
  const YAML::Node keys = loadYamlDocument("k: &k key\n*k : value\n", "k.yaml", "a test file");
  EXPECT_EQ(keys["key"].as<std::string>(), "value");
}

}  // namespace
}  // namespace mcws
