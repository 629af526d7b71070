// The report page's structure, read back from C++: the embedded JSON, the base64 arrays, the
// decimation, and the errors of malformed scenes and views.

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/report/detail/scene_data.h"
#include "mcws/report/report_page.h"
#include "report/synthetic_report.h"

namespace {

using mcws::report::Layer;
using mcws::report::Scene;
using nlohmann::json;

/// The text of the <script type="application/json" id="ID"> element of a page.
std::string scriptContent(const std::string& page, const std::string& id) {
  const std::string open = "<script type=\"application/json\" id=\"" + id + "\">";
  const std::size_t start = page.find(open);
  if (start == std::string::npos) throw std::runtime_error("no script " + id);
  const std::size_t end = page.find("</script>", start);
  return page.substr(start + open.size(), end - start - open.size());
}

/// Base64 decoding written for the test (RFC 4648 alphabet, '=' padding).
std::vector<unsigned char> decodeBase64(const std::string& text) {
  static const std::string kAlphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> bytes;
  unsigned bits = 0, count = 0;
  for (char c : text) {
    if (c == '=') break;
    bits = (bits << 6) | static_cast<unsigned>(kAlphabet.find(c));
    count += 6;
    if (count >= 8) {
      count -= 8;
      bytes.push_back(static_cast<unsigned char>((bits >> count) & 0xff));
    }
  }
  return bytes;
}

/// Little-endian 32-bit words from base64.
std::vector<std::uint32_t> decodeWords(const std::string& text) {
  const std::vector<unsigned char> bytes = decodeBase64(text);
  std::vector<std::uint32_t> words(bytes.size() / 4);
  for (std::size_t i = 0; i < words.size(); ++i)
    words[i] = bytes[4 * i] | bytes[4 * i + 1] << 8 | bytes[4 * i + 2] << 16 |
               std::uint32_t{bytes[4 * i + 3]} << 24;
  return words;
}

std::vector<float> decodeFloats(const std::string& text) {
  const std::vector<std::uint32_t> words = decodeWords(text);
  std::vector<float> floats(words.size());
  if (!words.empty()) std::memcpy(floats.data(), words.data(), 4 * words.size());
  return floats;
}

std::string page(const Scene& scene, std::size_t max_bytes = 20u << 20) {
  mcws::report::PageOptions options;
  options.max_embedded_bytes = max_bytes;
  return mcws::report::reportHtml(mcws::test::syntheticReport(), scene, options);
}

/// The message reportHtml() throws for `scene` (empty when it throws nothing).
std::string errorOf(const Scene& scene, const json& report = mcws::test::syntheticReport()) {
  try {
    mcws::report::reportHtml(report, scene);
  } catch (const mcws::Error& e) {
    return e.what();
  }
  return "";
}

TEST(ReportPage, Base64OfFloatsIsLittleEndianBinary32) {
  // 1.0f is 0x3f800000: bytes 00 00 80 3f, base64 "AACAPw==" (worked by hand).
  EXPECT_EQ(mcws::report::detail::base64Floats({1.0f}), "AACAPw==");
  EXPECT_EQ(mcws::report::detail::base64Words({0x01020304u}), "BAMCAQ==");
  const unsigned char man[] = {'M', 'a', 'n', 'M', 'a'};
  EXPECT_EQ(mcws::report::detail::base64(man, 5), "TWFuTWE=");  // RFC 4648's example
}

TEST(ReportPage, EmbeddedReportJsonParsesBackToTheInput) {
  const std::string html = page(mcws::test::syntheticScene());
  const std::string embedded = scriptContent(html, "mcws-report");
  // The label "A tiny number </script>" must not end the element early.
  EXPECT_EQ(embedded.find("</"), std::string::npos);
  EXPECT_EQ(json::parse(embedded), mcws::test::syntheticReport());
  EXPECT_NE(html.find("<title>mcws study</title>"), std::string::npos);
}

TEST(ReportPage, SceneArraysDecodeToTheExactFloatsAndIndices) {
  const Scene scene = mcws::test::syntheticScene();
  const json embedded = json::parse(scriptContent(page(scene), "mcws-scene"));
  EXPECT_EQ(embedded["length_unit"], "cm");
  ASSERT_EQ(embedded["layers"].size(), scene.layers.size());
  for (std::size_t i = 0; i < scene.layers.size(); ++i) {
    const json& layer = embedded["layers"][i];
    SCOPED_TRACE(scene.layers[i].name);
    EXPECT_EQ(layer["name"], scene.layers[i].name);
    EXPECT_EQ(decodeFloats(layer["positions"]), scene.layers[i].positions);
    EXPECT_EQ(decodeWords(layer["triangles"]), scene.layers[i].triangles);
    if (!scene.layers[i].values.empty()) {
      EXPECT_EQ(decodeFloats(layer["values"]), scene.layers[i].values);
    }
    EXPECT_EQ(layer["points"], scene.layers[i].positions.size() / 3);
  }
  EXPECT_EQ(embedded["layers"][3]["kind"], "voxels");
  EXPECT_EQ(embedded["layers"][3]["value_label"], "reachability");
  ASSERT_EQ(embedded["bodies"].size(), 2u);
  EXPECT_EQ(decodeFloats(embedded["bodies"][1]["positions"]), scene.bodies[1].positions);
  EXPECT_EQ(decodeWords(embedded["bodies"][1]["triangles"]), scene.bodies[1].triangles);
  const json& animation = embedded["animations"][0];
  EXPECT_EQ(animation["frames"], 20);
  EXPECT_EQ(decodeFloats(animation["poses"]), scene.animations[0].poses);
  EXPECT_EQ(decodeFloats(animation["parameter"]), scene.animations[0].parameter);
}

TEST(ReportPage, DecimationKeepsEveryKthPointOfTheLargestLayerAndStatesTheCount) {
  // 100 000 boundary points (1 200 000 bytes) under a 200 000-byte limit. Kept whole: the meshes
  // (line 480, envelope 240 bytes), the bodies (480), the animation (2 560 + 80), the reach map
  // (256 voxels x 16 = 4 096) and the targets (48): 7 984 bytes. The boundary points get
  // 200 000 - 7 984 = 192 016 bytes, 16 001 points: every 7th (ceil(100 000 / 16 001)), 14 286.
  const Scene scene = mcws::test::syntheticScene(100000);
  const json embedded = json::parse(scriptContent(page(scene, 200000), "mcws-scene"));
  const json& boundary = embedded["layers"][2];
  EXPECT_EQ(boundary["total_points"], 100000);
  EXPECT_EQ(boundary["points"], 14286);
  const std::vector<float> kept = decodeFloats(boundary["positions"]);
  ASSERT_EQ(kept.size(), 3u * 14286);
  for (std::size_t i = 0; i < 14286; ++i)
    for (std::size_t axis = 0; axis < 3; ++axis)
      ASSERT_EQ(kept[3 * i + axis], scene.layers[2].positions[3 * (7 * i) + axis]) << i;
  for (std::size_t i : {0u, 1u, 3u, 4u})
    EXPECT_EQ(embedded["layers"][i]["points"], embedded["layers"][i]["total_points"]);
  std::size_t bytes = 0;  // what the page embeds, before base64
  for (const json& layer : embedded["layers"])
    for (const char* key : {"positions", "triangles", "values"})
      if (layer.contains(key)) bytes += decodeBase64(layer[key]).size();
  for (const json& body : embedded["bodies"])
    bytes += decodeBase64(body["positions"]).size() + decodeBase64(body["triangles"]).size();
  bytes += decodeBase64(embedded["animations"][0]["poses"]).size() +
           decodeBase64(embedded["animations"][0]["parameter"]).size();
  EXPECT_LE(bytes, 200000u);
}

TEST(ReportPage, DecimationStartsOneBytePastTheLimit) {
  // The scene of 2 000 boundary points embeds 7 984 + 24 000 = 31 984 bytes (see above).
  const Scene scene = mcws::test::syntheticScene();
  const json whole = json::parse(scriptContent(page(scene, 31984), "mcws-scene"));
  for (const json& layer : whole["layers"]) EXPECT_EQ(layer["points"], layer["total_points"]);
  // One byte less: 23 999 bytes for the boundary points, 1 999 points, every 2nd: 1 000.
  const json cut = json::parse(scriptContent(page(scene, 31983), "mcws-scene"));
  EXPECT_EQ(cut["layers"][2]["points"], 1000);
  EXPECT_EQ(cut["layers"][3]["points"], 256);
}

TEST(ReportPage, MalformedScenesThrowOneLineErrorsNamingTheLayerBodyOrAnimation) {
  const Scene good = mcws::test::syntheticScene(10);
  std::vector<std::pair<Scene, std::string>> cases;
  Scene s = good;
  s.layers[0].triangles.push_back(16), s.layers[0].triangles.push_back(0),
      s.layers[0].triangles.push_back(1);
  cases.emplace_back(s, "layer \"line\": triangle 24 has vertex index 16, past its 16 vertices");
  s = good, s.layers[3].values.pop_back();
  cases.emplace_back(s, "layer \"reach map\": 255 values for 256 points");
  s = good, s.layers[2].positions.push_back(1.0f);
  cases.emplace_back(s, "layer \"boundary points\": 31 position numbers, not a multiple of 3");
  s = good, s.layers[4].positions[4] = std::nanf("");
  cases.emplace_back(s, "layer \"targets\": point 1 is not finite");
  s = good, s.layers[2].triangles = {0, 1, 2};
  cases.emplace_back(s, "layer \"boundary points\": triangles given for a point or voxel layer");
  s = good, s.layers[3].value_min = 2.0f;
  cases.emplace_back(s, "layer \"reach map\": value_min 2.000000 above value_max 1.000000");
  s = good, s.bodies[1].triangles.pop_back();
  cases.emplace_back(s, "body \"link2\": 35 triangle indices, not a multiple of 3");
  s = good, s.animations[0].poses.resize(16 * 39);
  cases.emplace_back(s,
                     "animation \"path to target spacer_1\": 624 pose numbers, not frames x "
                     "bodies x 16 = 20 x 2 x 16");
  s = good, s.animations[0].parameter.pop_back();
  cases.emplace_back(s, "animation \"path to target spacer_1\": 19 parameter values for 20 frames");
  for (const auto& [scene, message] : cases) {
    const std::string error = errorOf(scene);
    EXPECT_EQ(error, "report scene: " + message);
    EXPECT_EQ(error.find('\n'), std::string::npos);
  }
}

TEST(ReportPage, ViewAnswersMustPointAtTheirNumbersInTheReport) {
  const Scene scene = mcws::test::syntheticScene(10);
  json report = mcws::test::syntheticReport();
  report["view"]["answers"][0]["source"] = "/placement/best/offset_across";
  EXPECT_EQ(errorOf(scene, report),
            "report view: answer 0 (\"Stop the robot at\"): source "
            "/placement/best/offset_across is not in the report");
  report = mcws::test::syntheticReport();
  report["view"]["answers"][2]["value"] = 1234567.0;
  EXPECT_EQ(errorOf(scene, report),
            "report view: answer 2 (\"Workspace volume\"): source "
            "/workspace/volume holds 1234567.89, the answer states value "
            "1234567.0");
  report = mcws::test::syntheticReport();
  report["view"]["answers"][1]["interval_source"] = "planning";
  EXPECT_EQ(errorOf(scene, report),
            "report view: answer 1 (\"Collision probability\"): "
            "interval_source \"planning\" is not a JSON pointer");
  report = mcws::test::syntheticReport();
  report["view"]["sections"][0]["kind"] = "tabel";
  EXPECT_EQ(errorOf(scene, report),
            "report view: section 0: kind \"tabel\" is none of table, "
            "image, chart, timeline, text");
  report = mcws::test::syntheticReport();
  // nlohmann's {{"a", 1}, {"b", 2}} is an object, not rows: the classic slip.
  report["view"]["sections"][0]["rows"] = {{"spacer_1", 0.02}, {"damper_2", 0.5}};
  EXPECT_EQ(errorOf(scene, report),
            "report view: section 0: rows is not an array: "
            "{\"damper_2\":0.5,\"spacer_1\":0.02}");
  report = mcws::test::syntheticReport();
  report["view"]["sections"][2]["series"][1]["y"].erase(0);
  EXPECT_EQ(errorOf(scene, report), "report view: section 2: series 1: 3 x values, 2 y values");
  report = mcws::test::syntheticReport();
  report["view"]["answers"][0]["label"] = 3;
  EXPECT_EQ(errorOf(scene, report),
            "report view: [json.exception.type_error.302] type must be "
            "string, but is number");
  EXPECT_EQ(errorOf(scene, json::array()), "report: a JSON object expected, not array");
}

TEST(ReportPage, MissingThreeJsNamesTheFileAndThePackage) {
  ASSERT_EQ(setenv("MCWS_THREE_JS_DIR", "/nonexistent/three", 1), 0);
  const std::string error = errorOf(mcws::test::syntheticScene(10));
  unsetenv("MCWS_THREE_JS_DIR");
  EXPECT_NE(error.find("/nonexistent/three/build/three.min.js"), std::string::npos) << error;
  EXPECT_NE(error.find("libjs-three"), std::string::npos) << error;
}

}  // namespace
