#pragma once
/// \file
/// \brief The study report as one self-contained HTML page: the report's JSON, its tables and
/// pictures, and an interactive 3-D view (Debian's three.js inlined), working offline from a
/// file URL.
///
/// The page shows what the report JSON's "view" member lists (see docs/report.md): the answers at
/// the top, tables, pictures, a timeline; the 3-D scene comes as a Scene (binary arrays, embedded
/// base64). Every number the page shows is read from the JSON, so the page and report.json agree.

#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace mcws::report {

/// \brief One layer of the 3-D view, toggled on and off by its name.
struct Layer {
  enum class Kind { kMesh, kPoints, kVoxels };
  std::string name;  ///< shown in the layer list, e.g. "envelope", "reach map"
  Kind kind{Kind::kPoints};
  std::vector<float> positions;  ///< x y z triplets [length unit]: vertices, points, centres
  std::vector<std::uint32_t> triangles;  ///< kMesh: vertex index triplets
  /// Optional: one value per point (vertex, voxel), drawn through a colour bar labelled with
  /// value_label [value_unit] from value_min to value_max; empty: the layer is drawn in `color`.
  std::vector<float> values;
  std::string value_label, value_unit;
  float value_min{0.0f}, value_max{1.0f};
  std::array<float, 3> color{0.6f, 0.6f, 0.6f};  ///< RGB in [0, 1]
  float opacity{1.0f};
  float size{1.0f};    ///< kPoints: point size, kVoxels: voxel edge [length unit]
  bool visible{true};  ///< shown when the page opens
};

/// \brief A rigid body of the robot drawn in the 3-D view: a triangle mesh in its own frame.
struct Body {
  std::string name;                      ///< e.g. the link's name
  std::vector<float> positions;          ///< vertices in the body frame [length unit]
  std::vector<std::uint32_t> triangles;  ///< vertex index triplets
  std::array<float, 3> color{0.9f, 0.55f, 0.1f};
};

/// \brief The robot's bodies moving along a path: frame k places every body.
struct Animation {
  std::string name;  ///< e.g. "path to target spacer_1"
  std::size_t frames{0};
  /// frames x bodies 4x4 matrices, column-major, body frame -> world [length unit]
  std::vector<float> poses;
  std::vector<float> parameter;  ///< per frame, e.g. the path's length D so far (may be empty)
  std::string parameter_label, parameter_unit;
};

/// \brief The 3-D scene of the report.
struct Scene {
  std::string length_unit;  ///< "m", "cm" or "mm": the unit of every coordinate
  std::vector<Layer> layers;
  std::vector<Body> bodies;           ///< the robot; drawn at frame 0 of the animation shown
  std::vector<Animation> animations;  ///< each over all `bodies`
};

/// \brief Settings of the page.
struct PageOptions {
  /// Embedded binary data larger than this is decimated (every k-th point of the largest point
  /// layers, deterministically), and the page says which layer kept how many of how many.
  std::size_t max_embedded_bytes{20u << 20};
  std::string title{"mcws study"};
};

/// \brief The HTML page of `report` (the study's JSON, shown through its "view" member) with
/// `scene`; three.js read from Debian's libjs-three (threeJsDirectory()) and inlined.
/// \throws mcws::Error when three.js cannot be read or the scene is malformed (a triangle index
///   past its vertices, values not one per point, a pose count not frames x bodies x 16).
std::string reportHtml(const nlohmann::json& report, const Scene& scene,
                       const PageOptions& options = {});

/// \brief Where three.js is read from: MCWS_THREE_JS_DIR if set, else
/// /usr/share/javascript/three (Debian's libjs-three).
std::string threeJsDirectory();

}  // namespace mcws::report
