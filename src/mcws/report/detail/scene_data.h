#pragma once
/// \file
/// \brief The scene of the report page as it is embedded: checked, decimated to the page's size
/// limit, its binary arrays base64 (little-endian float32 and uint32).

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mcws/report/report_page.h"

namespace mcws::report::detail {

/// \brief Base64 (RFC 4648, with padding) of `size` bytes.
std::string base64(const unsigned char* bytes, std::size_t size);

/// \brief Base64 of the floats as little-endian IEEE 754 binary32, whatever the machine's order.
std::string base64Floats(const std::vector<float>& values);

/// \brief Base64 of the integers as little-endian 32-bit words.
std::string base64Words(const std::vector<std::uint32_t>& values);

/// \brief Checks the scene: positions in triplets and finite, triangle indices in triplets and
/// below their vertex count, values one per point (vertex, voxel), value_min <= value_max, a
/// point or voxel layer without triangles, every animation's poses frames x bodies x 16 and its
/// parameter one per frame (or none).
/// \throws mcws::Error "report scene: <what>: <the bad value>".
void checkScene(const Scene& scene);

/// \brief How many points (vertices, voxels) of each layer the page keeps: every k-th, k = the
/// layer's stride (1: all).
struct Decimation {
  std::vector<std::size_t> stride;  ///< per layer, 1 for a mesh layer
};

/// \brief The strides that bring the scene's binary data within `max_bytes`: the largest point
/// and voxel layers are cut to one common size (the smaller ones, and meshes, bodies and
/// animations are kept whole); a layer keeps at least one point.
/// \param max_bytes the limit on the binary bytes (before base64) [bytes].
Decimation decimation(const Scene& scene, std::size_t max_bytes);

/// \brief Every k-th point, from the first: ceil(n / k) of n.
std::size_t keptCount(std::size_t points, std::size_t stride);

/// \brief The scene as the page reads it: layers, bodies and animations with their settings and
/// their arrays in base64 ("positions", "triangles", "values", "poses", "parameter"); a layer
/// records "points" (kept) and "total_points".
nlohmann::json sceneJson(const Scene& scene, const Decimation& decimation);

}  // namespace mcws::report::detail
