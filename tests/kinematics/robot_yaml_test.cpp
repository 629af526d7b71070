#include "mcws/kinematics/robot_yaml.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "mcws/core/error.h"
#include "test_support.h"

namespace mcws {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

// A valid two-joint robot; the tests below break one thing at a time.
const std::string kValid = R"(name: two
units: {length: mm, angle: deg}
convention: standard
joints:
  - {name: j1, type: revolute, a: 100, alpha: 0, d: 0, limits: [-90, 90]}
  - {name: j2, type: prismatic, a: 0, alpha: 0, d: 10, limits: [0, 50]}
)";

std::string yamlError(const std::string& yaml) {
  try {
    parseRobotYaml(yaml, "bad.yaml");
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for:\n" << yaml;
  return "";
}

TEST(RobotYaml, LoadsEveryShippedRobot) {
  for (const char* name : test::kShippedRobots) {
    const Robot robot = loadRobot(test::robotPath(name));
    EXPECT_EQ(robot.name, name);
    EXPECT_GE(robot.dof(), 4);
    for (const Joint& joint : robot.joints) EXPECT_LE(joint.lower, joint.upper) << joint.name;
  }
}

TEST(RobotYaml, ConvertsDegreesToRadiansButKeepsLengths) {
  const Robot robot = parseRobotYaml(kValid, "two.yaml");
  ASSERT_EQ(robot.dof(), 2);
  EXPECT_DOUBLE_EQ(robot.joints[0].lower, -M_PI / 2);
  EXPECT_DOUBLE_EQ(robot.joints[0].upper, M_PI / 2);
  EXPECT_DOUBLE_EQ(robot.joints[1].upper, 50.0);  // prismatic limits stay in mm
  EXPECT_EQ(robot.length_unit, LengthUnit::kMillimetre);
  EXPECT_EQ(robot.joints[1].type, JointType::kPrismatic);
}

TEST(RobotYaml, NamesTheDeicingJointsAsThePaper) {
  const Robot robot = loadRobot(test::robotPath("deicing"));
  EXPECT_EQ(robot.jointIndex("theta3"), 0);
  EXPECT_EQ(robot.jointIndex("theta1"), 1);
  EXPECT_EQ(robot.jointIndex("theta2"), 2);
  EXPECT_EQ(robot.jointIndex("a2"), 3);
  EXPECT_EQ(robot.length_unit, LengthUnit::kCentimetre);
}

TEST(RobotYaml, ReportsMissingFile) {
  try {
    loadRobot("/nonexistent/robot.yaml");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/robot.yaml: robot file does not exist");
  }
}

TEST(RobotYaml, ReportsADirectoryGivenAsRobotFile) {
  test::TempDir dir;
  try {
    loadRobot(dir.file(""));
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("is not a regular file"));
  }
}

TEST(RobotYaml, ReportsUnknownKeyWithLine) {
  const std::string msg = yamlError(test::replaceOnce(kValid, "d: 10,", "d: 10, offset: 3,"));
  EXPECT_THAT(msg, HasSubstr("bad.yaml:6: joint 2 'j2': unknown key 'offset'"));
}

TEST(RobotYaml, ReportsUnknownTopLevelKey) {
  EXPECT_THAT(yamlError(kValid + "colour: red\n"),
              HasSubstr("bad.yaml:7: robot: unknown key 'colour'"));
}

TEST(RobotYaml, ReportsMissingLimits) {
  const std::string msg = yamlError(test::replaceOnce(kValid, ", limits: [0, 50]", ""));
  EXPECT_THAT(msg, HasSubstr("joint 2 'j2': missing field 'limits'"));
}

TEST(RobotYaml, ReportsLimitsInTheWrongOrder) {
  const std::string msg = yamlError(test::replaceOnce(kValid, "[-90, 90]", "[90, -90]"));
  EXPECT_THAT(msg, HasSubstr("bad.yaml:5: joint 1 'j1': limits min 90 is greater than max -90"));
}

TEST(RobotYaml, ReportsNaNAndInfinity) {
  EXPECT_THAT(yamlError(test::replaceOnce(kValid, "a: 100", "a: .nan")),
              HasSubstr("joint 1 'j1': field 'a': '.nan' is not a finite number"));
  EXPECT_THAT(yamlError(test::replaceOnce(kValid, "[0, 50]", "[0, .inf]")),
              HasSubstr("joint 2 'j2': limits max: '.inf' is not a finite number"));
}

TEST(RobotYaml, ReportsTextWhereANumberBelongs) {
  EXPECT_THAT(yamlError(test::replaceOnce(kValid, "a: 100", "a: 100x")),
              HasSubstr("joint 1 'j1': field 'a': '100x' is not a number"));
}

TEST(RobotYaml, ReportsBadUnits) {
  EXPECT_THAT(yamlError(test::replaceOnce(kValid, "length: mm", "length: ''")),
              HasSubstr("units: length unit '' is not m, cm or mm"));
  EXPECT_THAT(yamlError(test::replaceOnce(kValid, "length: mm", "length: inch")),
              HasSubstr("units: length unit 'inch' is not m, cm or mm"));
  EXPECT_THAT(yamlError(test::replaceOnce(kValid, "angle: deg", "angle: grad")),
              HasSubstr("units: angle unit 'grad' is not deg or rad"));
}

TEST(RobotYaml, ReportsBadConventionTypeAndDuplicates) {
  EXPECT_THAT(yamlError(test::replaceOnce(kValid, "convention: standard", "convention: craig")),
              HasSubstr("bad.yaml:3: convention: 'craig' is not a D-H convention"));
  EXPECT_THAT(yamlError(test::replaceOnce(kValid, "type: prismatic", "type: spherical")),
              HasSubstr("joint 2 'j2': type 'spherical' is not revolute or prismatic"));
  EXPECT_THAT(yamlError(test::replaceOnce(kValid, "name: j2", "name: j1")),
              HasSubstr("joint 2 'j1': duplicate joint name"));
}

TEST(RobotYaml, ReportsEmptyJointListAndSyntaxErrors) {
  const std::string no_joints = kValid.substr(0, kValid.find("joints:")) + "joints: []\n";
  EXPECT_THAT(yamlError(no_joints), HasSubstr("joints: must be a non-empty list"));
  EXPECT_THAT(yamlError("name: [unclosed\n"), HasSubstr("bad.yaml:2: YAML syntax"));
  EXPECT_THAT(yamlError("just text"), HasSubstr("the document must be a map"));
}

TEST(RobotYaml, RefusesControlBytesBeforeYamlCppSeesThem) {
  // Found by the robot_yaml fuzzer: yaml-cpp 0.7 looped forever on a file with NUL bytes.
  EXPECT_EQ(yamlError(test::replaceOnce(kValid, "convention: standard",
                                        std::string("convention: sta\0d", 17))),
            "bad.yaml:3: control byte \\x00 at column 16 (a robot file is text)");
  EXPECT_EQ(yamlError(test::replaceOnce(kValid, "name: two", "name: t\x1bwo")),
            "bad.yaml:1: control byte \\x1b at column 8 (a robot file is text)");
  EXPECT_EQ(parseRobotYaml(test::replaceOnce(kValid, "name: two", "name:\ttwo\r"), "ok.yaml").name,
            "two");
}

TEST(RobotYaml, ReportsTextAfterTheDocumentThatTheParserCannotPlace) {
  // Found by the robot_yaml fuzzer: yaml-cpp's LoadAll() looped for ever, allocating, on a stray
  // ',' at the start of a line after an indented map's list (the fuzzer's input, shortened).
  EXPECT_EQ(yamlError("    j1:\n      - {a: 1}\n , 0]}\n"),
            "bad.yaml:3: YAML syntax: text the parser cannot place in the document (a stray ',', "
            "']' or '}', or a wrong indentation?)");
}

TEST(RobotYaml, ReportsAnUnterminatedQuoteWhereItStarts) {
  // yaml-cpp reads the rest of the file into the name; it was reported as a missing 'units'.
  const std::string text = test::replaceOnce(kValid, "name: two", "name: \"two");
  EXPECT_THAT(yamlError(text), StartsWith("bad.yaml:1: a quoted value runs over"));
  EXPECT_THAT(yamlError(text), HasSubstr("several lines: a missing closing quote (\")?"));
  // Quotes that close, with escaped quotes inside, are fine.
  EXPECT_EQ(
      parseRobotYaml(test::replaceOnce(kValid, "name: two", "name: 'tw''o\\'"), "ok.yaml").name,
      "tw'o\\");
  EXPECT_EQ(
      parseRobotYaml(test::replaceOnce(kValid, "name: two", "name: \"t\\\"wo\""), "ok.yaml").name,
      "t\"wo");
  EXPECT_THAT(yamlError(test::replaceOnce(kValid, "convention: standard", "convention: 'standard")),
              StartsWith("bad.yaml:3: a quoted value runs over"));
}

TEST(RobotYaml, ReportsDuplicateAndNonScalarKeys) {
  EXPECT_THAT(yamlError(test::replaceOnce(kValid, "a: 100,", "a: 100, a: 5,")),
              HasSubstr("joint 1 'j1': key 'a' given twice"));
  EXPECT_THAT(yamlError(kValid + "name: again\n"), HasSubstr("robot: key 'name' given twice"));
  EXPECT_THAT(yamlError(kValid + "[1, 2]: 3\n"),
              HasSubstr("bad.yaml:7: robot: a key must be a plain name"));
}

TEST(RobotYaml, ReportsSeveralDocumentsEmptyFileAndOddNames) {
  EXPECT_THAT(yamlError(kValid + "---\n" + kValid),
              HasSubstr("bad.yaml: holds more than one YAML document; a robot file holds one"));
  EXPECT_THAT(yamlError(""), HasSubstr("bad.yaml: the document must be a map"));
  EXPECT_THAT(yamlError(test::replaceOnce(kValid, "name: j2", "name: 'j 2'")),
              HasSubstr("joint 2: name 'j 2' contains '=', ',' or a space"));
}

TEST(RobotYaml, ReportsNumbersTooLargeForCoordinates) {
  EXPECT_THAT(yamlError(test::replaceOnce(kValid, "[0, 50]", "[0, 1e308]")),
              HasSubstr("joint 2 'j2': limits max: 1e308 is out of range"));
}

TEST(RobotYaml, ReportsEmptyFileName) {
  try {
    loadRobot("");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "robot file name is empty");
  }
}

TEST(RobotYaml, ReportsBadToolPose) {
  EXPECT_THAT(yamlError(kValid + "tool: {xyz: [1, 2]}\n"),
              HasSubstr("tool: xyz must be [x, y, z]"));
  EXPECT_THAT(yamlError(kValid + "tool: {rot: [1, 2, 3]}\n"), HasSubstr("tool: unknown key 'rot'"));
}

TEST(RobotYaml, RefusesControlCharactersInRobotAndJointNames) {
  // Written with YAML escapes ("\n", "\t", "\x7f") or as a block scalar: the file itself holds no
  // control byte, the name does. Such a name broke the header of every cloud mcws_sample wrote.
  EXPECT_EQ(yamlError(test::replaceOnce(kValid, "name: two", R"(name: "two\narms")")),
            "bad.yaml:1: name 'two\\x0aarms' holds a control byte (names are printable "
            "text)");
  EXPECT_EQ(yamlError(test::replaceOnce(kValid, "name: two", "name: \"\\ttwo\"")),
            "bad.yaml:1: name '\\x09two' holds a control byte (names are printable text)");
  EXPECT_EQ(yamlError(test::replaceOnce(kValid, "name: two", "name: |\n  two\n")),
            "bad.yaml:1: name 'two\\x0a' holds a control byte (names are printable text)");
  EXPECT_EQ(yamlError(test::replaceOnce(kValid, "name: j2", R"(name: "j\x7f2")")),
            "bad.yaml:6: joint 2: name 'j\\x7f2' holds a control byte (names are printable "
            "text)");
  EXPECT_EQ(yamlError(test::replaceOnce(kValid, "name: j1", R"(name: "j\r1")")),
            "bad.yaml:5: joint 1: name 'j\\x0d1' holds a control byte (names are printable "
            "text)");
  // Bytes from 0x80 up are text (UTF-8).
  EXPECT_EQ(
      parseRobotYaml(test::replaceOnce(kValid, "name: two", "name: zwei_\xc3\xa4rme"), "ok.yaml")
          .name,
      "zwei_\xc3\xa4rme");
}

TEST(RobotYaml, RefusesControlCharactersInTheRobotFileName) {
  // The file name goes into every cloud's provenance line, which the readers then refuse.
  test::TempDir dir;
  for (const char* name : {"two\tarms.yaml", "two\narms.urdf"}) {
    const std::string path = dir.file(name);
    test::writeFile(path, kValid);
    try {
      loadRobot(path);
      ADD_FAILURE() << "no error for " << name;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), std::string("robot file name 'two\\x") +
                                           (name[3] == '\t' ? "09" : "0a") + "arms." +
                                           (name[3] == '\t' ? "yaml" : "urdf") +
                                           "' holds a control byte (names are printable text)");
    }
  }
}

}  // namespace
}  // namespace mcws
