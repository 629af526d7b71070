#pragma once
// A small report and scene built in code, known to the last number: the browser test's page
// (write_test_report.cpp) and the page writer's unit tests (report_page_test.cpp) use it.

#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

#include "mcws/report/report_page.h"

namespace mcws::test {

/// A 1 x 1 PNG picture (a grey pixel), base64.
inline constexpr const char* kTinyPngBase64 =
    "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mNk+"
    "M9QDwADhgGAWjR9awAAAABJRU5ErkJggg==";

/// The report JSON: its own members and a "view" of four answers (one through an escaped "~1"
/// pointer, one with an interval) and a table, picture, chart, timeline and text.
inline nlohmann::json syntheticReport() {
  using nlohmann::json;
  json report = {{"placement", {{"best", {{"offset_along", -5.0}}}}},
                 {"planning", {{"p", 0.0123456789}, {"p_interval", {0.0101, 0.0152}}}},
                 {"workspace", {{"volume", 1234567.89}}},
                 {"odd/key", {{"tiny", 1.5e-7}}},
                 {"units", {{"offset_along", "cm"}, {"volume", "cm^3"}, {"p", "fraction"}}}};
  json answers = json::array();
  answers.push_back({{"label", "Stop the robot at"},
                     {"value", -5.0},
                     {"unit", "cm"},
                     {"source", "/placement/best/offset_along"},
                     {"note", "4 of 4 targets reached (IK)"}});
  answers.push_back({{"label", "Collision probability"},
                     {"value", 0.0123456789},
                     {"unit", "fraction"},
                     {"source", "/planning/p"},
                     {"interval", {0.0101, 0.0152}},
                     {"interval_source", "/planning/p_interval"}});
  answers.push_back({{"label", "Workspace volume"},
                     {"value", 1234567.89},
                     {"unit", "cm^3"},
                     {"source", "/workspace/volume"}});
  answers.push_back({{"label", "A tiny number </script>"},
                     {"value", 1.5e-7},
                     {"unit", "cm"},
                     {"source", "/odd~1key/tiny"}});
  json sections = json::array();
  sections.push_back(
      {{"kind", "table"},
       {"title", "Reach study"},
       {"columns", {{{"name", "target"}, {"unit", ""}}, {{"name", "P"}, {"unit", "fraction"}}}},
       {"rows",
        json::array({json::array({"spacer_1", 0.02}), json::array({"damper_2", 0.987654321})})},
       {"note", "P: the share of the samples that reach the target"}});
  sections.push_back({{"kind", "image"},
                      {"title", "Datasheet drawing"},
                      {"png_base64", kTinyPngBase64},
                      {"alt", "a grey pixel"}});
  sections.push_back(
      {{"kind", "chart"},
       {"title", "P against the base offset"},
       {"x", {{"label", "base offset along the line"}, {"unit", "cm"}}},
       {"y", {{"label", "P"}, {"unit", "fraction"}}},
       {"series",
        {{{"name", "best path"},
          {"x", {-10, -5, 0, 5, 10}},
          {"y", {0.05, 0.02, 0.03, 0.06, 0.1}},
          {"lo", {0.04, 0.015, 0.02, 0.05, 0.08}},
          {"hi", {0.06, 0.025, 0.04, 0.07, 0.12}}},
         {{"name", "shortest path"}, {"x", {-10, 0, 10}}, {"y", {0.2, 0.15, 0.25}}}}}});
  sections.push_back({{"kind", "timeline"},
                      {"title", "Behaviour rehearsal"},
                      {"unit", "s"},
                      {"lanes", json::array({"arm", "brush"})},
                      {"events",
                       {{{"lane", "arm"}, {"start", 0.0}, {"end", 2.5}, {"label", "approach"}},
                        {{"lane", "brush"}, {"start", 2.5}, {"end", 6.0}, {"label", "clean"}},
                        {{"lane", "arm"}, {"start", 6.0}, {"end", 7.5}, {"label", "retreat"}}}}});
  sections.push_back(
      {{"kind", "text"}, {"title", "Notes"}, {"text", "A synthetic report.\nTwo lines."}});
  report["view"] = {{"title", "synthetic study"}, {"answers", answers}, {"sections", sections}};
  return report;
}

/// An axis-aligned box [lo, hi] as 8 vertices and 12 triangles, appended to a mesh.
inline void appendBox(std::vector<float>& positions, std::vector<std::uint32_t>& triangles,
                      const std::array<float, 3>& lo, const std::array<float, 3>& hi) {
  const auto first = static_cast<std::uint32_t>(positions.size() / 3);
  for (int corner = 0; corner < 8; ++corner)
    for (int axis = 0; axis < 3; ++axis)
      positions.push_back((corner >> axis) & 1 ? hi[axis] : lo[axis]);
  static const std::uint32_t kFaces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6},
                                              {0, 1, 4}, {1, 5, 4}, {2, 6, 3}, {3, 6, 7},
                                              {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& face : kFaces)
    for (std::uint32_t v : face) triangles.push_back(first + v);
}

/// `count` points on a sphere of `radius` about `centre` (a Fibonacci lattice).
inline std::vector<float> spherePoints(std::size_t count, float radius, float centre_z) {
  std::vector<float> points;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (std::size_t i = 0; i < count; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / count, r = std::sqrt(1.0 - z * z);
    points.push_back(static_cast<float>(radius * r * std::cos(golden * i)));
    points.push_back(static_cast<float>(radius * r * std::sin(golden * i)));
    points.push_back(static_cast<float>(centre_z + radius * z));
  }
  return points;
}

/// Body 0 turns about z by 90 degrees over the frames; body 1 rides on its end, 30 cm out.
inline std::vector<float> syntheticPoses(std::size_t frames) {
  std::vector<float> poses;
  for (std::size_t k = 0; k < frames; ++k) {
    const double angle = M_PI / 2 * k / (frames - 1), c = std::cos(angle), s = std::sin(angle);
    const float turn[16] = {float(c), float(s), 0, 0, float(-s), float(c), 0, 0,
                            0,        0,        1, 0, 0,         0,        0, 1};
    poses.insert(poses.end(), turn, turn + 16);
    const float end[16] = {float(c), float(s), 0, 0, float(-s),     float(c),      0,  0,
                           0,        0,        1, 0, float(30 * c), float(30 * s), 20, 1};
    poses.insert(poses.end(), end, end + 16);
  }
  return poses;
}

inline report::Layer namedLayer(const std::string& name, report::Layer::Kind kind) {
  report::Layer layer;
  layer.name = name;
  layer.kind = kind;
  return layer;
}

/// The scene: the line (a mesh), an envelope (a translucent mesh), boundary points, a reach map
/// (voxels with values), targets (points with values), two bodies and a 20-frame animation.
inline report::Scene syntheticScene(std::size_t boundary_points = 2000) {
  report::Scene scene;
  scene.length_unit = "cm";
  report::Layer line = namedLayer("line", report::Layer::Kind::kMesh);
  appendBox(line.positions, line.triangles, {-60, -1, 48}, {60, 1, 50});
  appendBox(line.positions, line.triangles, {-60, 19, 48}, {60, 21, 50});
  line.color = {0.3f, 0.3f, 0.35f};
  report::Layer envelope = namedLayer("envelope", report::Layer::Kind::kMesh);
  appendBox(envelope.positions, envelope.triangles, {-40, -40, -10}, {40, 40, 45});
  envelope.color = {0.2f, 0.5f, 0.9f};
  envelope.opacity = 0.25f;
  envelope.visible = false;
  report::Layer boundary = namedLayer("boundary points", report::Layer::Kind::kPoints);
  boundary.positions = spherePoints(boundary_points, 38, 10);
  boundary.color = {0.1f, 0.6f, 0.2f};
  boundary.size = 1.5f;
  report::Layer reach = namedLayer("reach map", report::Layer::Kind::kVoxels);
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j)
      for (int k = 0; k < 4; ++k) {
        reach.positions.insert(reach.positions.end(),
                               {-35.0f + 10 * i, -35.0f + 10 * j, 10.0f * k});
        reach.values.push_back(static_cast<float>((i + j + k) / 17.0));
      }
  reach.size = 3;
  reach.value_label = "reachability";
  reach.value_unit = "fraction";
  report::Layer targets = namedLayer("targets", report::Layer::Kind::kPoints);
  targets.positions = {10, 0, 48, 20, 0, 48, 30, 20, 48};
  targets.values = {1, 0, 1};
  targets.size = 4;
  targets.value_label = "reached";
  scene.layers = {line, envelope, boundary, reach, targets};
  report::Body link1, link2;
  link1.name = "link1";
  link2.name = "link2";
  appendBox(link1.positions, link1.triangles, {0, -3, 0}, {30, 3, 20});
  appendBox(link2.positions, link2.triangles, {-3, -3, 0}, {3, 3, 25});
  link2.color = {0.8f, 0.2f, 0.2f};
  scene.bodies = {link1, link2};
  report::Animation path;
  path.name = "path to target spacer_1";
  path.frames = 20;
  path.poses = syntheticPoses(path.frames);
  for (std::size_t k = 0; k < path.frames; ++k)
    path.parameter.push_back(static_cast<float>(30 * M_PI / 2 * k / (path.frames - 1)));
  path.parameter_label = "path length D";
  path.parameter_unit = "cm";
  scene.animations = {path};
  return scene;
}

}  // namespace mcws::test
