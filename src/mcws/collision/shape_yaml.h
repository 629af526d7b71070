#pragma once
/// \file
/// \brief The reader of one collision shape of a YAML file (the `collision:` section's shapes,
/// parseCollisionYaml(); the fittings of a study's line), for the readers that link yaml-cpp.

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <cmath>
#include <string>

#include "mcws/collision/collision_model.h"
#include "mcws/core/yaml_reader.h"

namespace mcws {

/// \brief Reads collision shapes: every mistake "file:line: where: ...".
///
/// Shapes: capsule (from, to, radius), sphere (center, radius), box (size, xyz, rpy), cylinder
/// (radius, length, xyz, rpy), mesh (file relative to the YAML file, STL, OBJ or COLLADA, scale,
/// xyz, rpy). Lengths as written (the file's length unit), angles in degrees unless
/// setAngleScale() says otherwise.
class ShapeYamlReader : public YamlReader {
 public:
  /// \param source the file name, for messages and for mesh paths.
  explicit ShapeYamlReader(std::string source) : YamlReader(std::move(source)) {}

  /// \brief Radians per angle unit of `rpy` (default one degree's).
  void setAngleScale(double radians_per_unit) { angle_scale_ = radians_per_unit; }

  /// \brief One shape; `named`: the map may (and for an environment object does) carry a
  /// `name`, which the caller reads.
  /// \throws mcws::Error "file:line: where: ..." for an unknown type ("type 't' is not capsule,
  ///   sphere, box, cylinder or mesh") or key, a non-positive radius or size, a missing mesh.
  ShapeSpec readShape(const YAML::Node& node, const std::string& where, bool named) const;

  /// \brief The positive number `map[key]`. \throws mcws::Error when missing or not > 0.
  double positive(const YAML::Node& map, const std::string& key, const std::string& where) const;

  /// \brief `map[key]` as [x, y, z] (zero when absent and not `required`).
  Eigen::Vector3d vector3(const YAML::Node& map, const std::string& key, const std::string& where,
                          bool required) const;

 private:
  double angle_scale_{M_PI / 180.0};
};

}  // namespace mcws
