#include "mcws/report/detail/scene_data.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "mcws/core/error.h"

namespace mcws::report::detail {
namespace {

const char kBase64Alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/// Little-endian bytes of 32-bit words.
std::vector<unsigned char> littleEndian(const std::uint32_t* words, std::size_t count) {
  std::vector<unsigned char> bytes(4 * count);
  for (std::size_t i = 0; i < count; ++i)
    for (int b = 0; b < 4; ++b) bytes[4 * i + b] = static_cast<unsigned char>(words[i] >> (8 * b));
  return bytes;
}

std::string quoted(const std::string& name) { return "\"" + name + "\""; }

void checkPositions(const std::string& what, const std::vector<float>& positions) {
  if (positions.size() % 3 != 0)
    throw Error("report scene: " + what + ": " + std::to_string(positions.size()) +
                " position numbers, not a multiple of 3");
  for (std::size_t i = 0; i < positions.size(); ++i)
    if (!std::isfinite(positions[i]))
      throw Error("report scene: " + what + ": point " + std::to_string(i / 3) + " is not finite");
}

void checkTriangles(const std::string& what, const std::vector<std::uint32_t>& triangles,
                    std::size_t vertices) {
  if (triangles.size() % 3 != 0)
    throw Error("report scene: " + what + ": " + std::to_string(triangles.size()) +
                " triangle indices, not a multiple of 3");
  for (std::size_t i = 0; i < triangles.size(); ++i)
    if (triangles[i] >= vertices)
      throw Error("report scene: " + what + ": triangle " + std::to_string(i / 3) +
                  " has vertex index " + std::to_string(triangles[i]) + ", past its " +
                  std::to_string(vertices) + " vertices");
}

void checkLayer(const Layer& layer) {
  const std::string what = "layer " + quoted(layer.name);
  checkPositions(what, layer.positions);
  const std::size_t points = layer.positions.size() / 3;
  if (layer.kind == Layer::Kind::kMesh)
    checkTriangles(what, layer.triangles, points);
  else if (!layer.triangles.empty())
    throw Error("report scene: " + what + ": triangles given for a point or voxel layer");
  if (!layer.values.empty() && layer.values.size() != points)
    throw Error("report scene: " + what + ": " + std::to_string(layer.values.size()) +
                " values for " + std::to_string(points) + " points");
  if (!(layer.value_min <= layer.value_max))
    throw Error("report scene: " + what + ": value_min " + std::to_string(layer.value_min) +
                " above value_max " + std::to_string(layer.value_max));
}

void checkAnimation(const Animation& animation, std::size_t bodies) {
  const std::string what = "animation " + quoted(animation.name);
  const std::size_t expected = animation.frames * bodies * 16;
  if (animation.poses.size() != expected)
    throw Error("report scene: " + what + ": " + std::to_string(animation.poses.size()) +
                " pose numbers, not frames x bodies x 16 = " + std::to_string(animation.frames) +
                " x " + std::to_string(bodies) + " x 16");
  for (std::size_t i = 0; i < animation.poses.size(); ++i)
    if (!std::isfinite(animation.poses[i]))
      throw Error("report scene: " + what + ": pose number " + std::to_string(i) +
                  " is not finite");
  if (!animation.parameter.empty() && animation.parameter.size() != animation.frames)
    throw Error("report scene: " + what + ": " + std::to_string(animation.parameter.size()) +
                " parameter values for " + std::to_string(animation.frames) + " frames");
}

/// Bytes a layer embeds per point (position, and value when it has values).
std::size_t bytesPerPoint(const Layer& layer) { return layer.values.empty() ? 12 : 16; }

template <typename T>
std::vector<T> everyKth(const std::vector<T>& values, std::size_t width, std::size_t stride) {
  if (stride == 1) return values;
  std::vector<T> kept;
  for (std::size_t i = 0; i * width < values.size(); i += stride)
    kept.insert(kept.end(), values.begin() + i * width, values.begin() + (i + 1) * width);
  return kept;
}

nlohmann::json colorJson(const std::array<float, 3>& color) {
  return nlohmann::json::array({color[0], color[1], color[2]});
}

nlohmann::json layerJson(const Layer& layer, std::size_t stride) {
  static const char* const kKinds[] = {"mesh", "points", "voxels"};
  const std::size_t total = layer.positions.size() / 3;
  nlohmann::json out = {{"name", layer.name},
                        {"kind", kKinds[static_cast<int>(layer.kind)]},
                        {"color", colorJson(layer.color)},
                        {"opacity", layer.opacity},
                        {"size", layer.size},
                        {"visible", layer.visible},
                        {"points", keptCount(total, stride)},
                        {"total_points", total},
                        {"positions", base64Floats(everyKth(layer.positions, 3, stride))},
                        {"triangles", base64Words(layer.triangles)}};
  if (!layer.values.empty()) {
    out["values"] = base64Floats(everyKth(layer.values, 1, stride));
    out["value_label"] = layer.value_label;
    out["value_unit"] = layer.value_unit;
    out["value_min"] = layer.value_min;
    out["value_max"] = layer.value_max;
  }
  return out;
}

}  // namespace

std::string base64(const unsigned char* bytes, std::size_t size) {
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  for (std::size_t i = 0; i < size; i += 3) {
    const std::size_t n = std::min<std::size_t>(3, size - i);
    std::uint32_t group = std::uint32_t{bytes[i]} << 16;
    if (n > 1) group |= std::uint32_t{bytes[i + 1]} << 8;
    if (n > 2) group |= bytes[i + 2];
    for (std::size_t c = 0; c < 4; ++c)
      out += c <= n ? kBase64Alphabet[(group >> (18 - 6 * c)) & 63] : '=';
  }
  return out;
}

std::string base64Floats(const std::vector<float>& values) {
  std::vector<std::uint32_t> words(values.size());
  if (!values.empty()) std::memcpy(words.data(), values.data(), 4 * values.size());
  return base64Words(words);
}

std::string base64Words(const std::vector<std::uint32_t>& values) {
  const std::vector<unsigned char> bytes = littleEndian(values.data(), values.size());
  return base64(bytes.data(), bytes.size());
}

void checkScene(const Scene& scene) {
  for (const Layer& layer : scene.layers) checkLayer(layer);
  for (const Body& body : scene.bodies) {
    const std::string what = "body " + quoted(body.name);
    checkPositions(what, body.positions);
    checkTriangles(what, body.triangles, body.positions.size() / 3);
  }
  for (const Animation& animation : scene.animations)
    checkAnimation(animation, scene.bodies.size());
}

std::size_t keptCount(std::size_t points, std::size_t stride) {
  return (points + stride - 1) / stride;
}

Decimation decimation(const Scene& scene, std::size_t max_bytes) {
  Decimation out;
  out.stride.assign(scene.layers.size(), 1);
  std::size_t fixed = 0;         // bytes that are kept whole
  std::vector<std::size_t> cut;  // the layers that may be cut (points, voxels)
  for (std::size_t i = 0; i < scene.layers.size(); ++i) {
    const Layer& layer = scene.layers[i];
    if (layer.kind == Layer::Kind::kMesh)
      fixed += 4 * (layer.positions.size() + layer.triangles.size() + layer.values.size());
    else
      cut.push_back(i);
  }
  for (const Body& body : scene.bodies)
    fixed += 4 * (body.positions.size() + body.triangles.size());
  for (const Animation& animation : scene.animations)
    fixed += 4 * (animation.poses.size() + animation.parameter.size());
  auto bytes = [&](std::size_t i) {
    return scene.layers[i].positions.size() / 3 * bytesPerPoint(scene.layers[i]);
  };
  std::sort(cut.begin(), cut.end(), [&](std::size_t a, std::size_t b) {
    return bytes(a) != bytes(b) ? bytes(a) < bytes(b) : a < b;
  });
  // Water filling: the smallest layers stay whole while the rest, cut to one common size `cap`,
  // fits what is left of the budget.
  std::size_t budget = max_bytes > fixed ? max_bytes - fixed : 0;
  for (std::size_t j = 0; j < cut.size(); ++j) {
    const std::size_t left = cut.size() - j;
    if (bytes(cut[j]) * left <= budget) {
      budget -= bytes(cut[j]);
      continue;
    }
    const std::size_t cap = budget / left;
    for (std::size_t m = j; m < cut.size(); ++m) {
      const Layer& layer = scene.layers[cut[m]];
      const std::size_t points = layer.positions.size() / 3;
      const std::size_t keep = std::max<std::size_t>(1, cap / bytesPerPoint(layer));
      out.stride[cut[m]] = (points + keep - 1) / keep;
    }
    break;
  }
  return out;
}

nlohmann::json sceneJson(const Scene& scene, const Decimation& decimation) {
  nlohmann::json out = {{"length_unit", scene.length_unit},
                        {"layers", nlohmann::json::array()},
                        {"bodies", nlohmann::json::array()},
                        {"animations", nlohmann::json::array()}};
  for (std::size_t i = 0; i < scene.layers.size(); ++i)
    out["layers"].push_back(layerJson(scene.layers[i], decimation.stride[i]));
  for (const Body& body : scene.bodies)
    out["bodies"].push_back({{"name", body.name},
                             {"color", colorJson(body.color)},
                             {"positions", base64Floats(body.positions)},
                             {"triangles", base64Words(body.triangles)}});
  for (const Animation& animation : scene.animations)
    out["animations"].push_back({{"name", animation.name},
                                 {"frames", animation.frames},
                                 {"poses", base64Floats(animation.poses)},
                                 {"parameter", base64Floats(animation.parameter)},
                                 {"parameter_label", animation.parameter_label},
                                 {"parameter_unit", animation.parameter_unit}});
  return out;
}

}  // namespace mcws::report::detail
