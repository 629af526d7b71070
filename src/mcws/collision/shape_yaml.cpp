#include "mcws/collision/shape_yaml.h"

#include <filesystem>
#include <memory>
#include <set>

#include "mcws/core/decimal.h"
#include "mcws/core/error.h"

namespace mcws {

double ShapeYamlReader::positive(const YAML::Node& map, const std::string& key,
                                 const std::string& where) const {
  if (!map[key]) fail(map, where + ": missing field '" + key + "'");
  const double value = finiteNumber(map[key], where + ": " + key);
  if (value <= 0.0) fail(map[key], where + ": " + key + " " + map[key].Scalar() + " must be > 0");
  return value;
}

Eigen::Vector3d ShapeYamlReader::vector3(const YAML::Node& map, const std::string& key,
                                         const std::string& where, bool required) const {
  const YAML::Node node = map[key];
  if (!node) {
    if (required) fail(map, where + ": missing field '" + key + "'");
    return Eigen::Vector3d::Zero();
  }
  if (!node.IsSequence() || node.size() != 3) fail(node, where + ": " + key + " must be [x, y, z]");
  Eigen::Vector3d v;
  for (int k = 0; k < 3; ++k) v[k] = finiteNumber(node[k], where + ": " + key);
  return v;
}

ShapeSpec ShapeYamlReader::readShape(const YAML::Node& node, const std::string& where,
                                     bool named) const {
  if (!node.IsMap()) fail(node, where + ": must be a map with a 'type'");
  if (!node["type"] || !node["type"].IsScalar()) fail(node, where + ": missing field 'type'");
  const std::string type = node["type"].Scalar();
  std::set<std::string> keys{"type"};
  if (named) keys.insert("name");
  ShapeSpec shape;
  shape.source = atLine(source(), lineOf(node));
  auto placement = [&] {
    keys.insert({"xyz", "rpy"});
    shape.T_body_shape = poseFromXyzRpy(vector3(node, "xyz", where, false),
                                        vector3(node, "rpy", where, false) * angle_scale_);
  };
  if (type == "capsule") {
    keys.insert({"from", "to", "radius"});
    checkKeys(node, where, keys);
    shape.type = ShapeType::kCapsule;
    shape.p_from = vector3(node, "from", where, true);
    shape.p_to = vector3(node, "to", where, true);
    shape.radius = positive(node, "radius", where);
  } else if (type == "sphere") {
    keys.insert({"center", "radius"});
    checkKeys(node, where, keys);
    shape.type = ShapeType::kSphere;
    shape.p_from = shape.p_to = vector3(node, "center", where, false);
    shape.radius = positive(node, "radius", where);
  } else if (type == "box") {
    checkKeys(node, where, {"type", "name", "size", "xyz", "rpy"});
    placement();
    shape.type = ShapeType::kBox;
    shape.size = vector3(node, "size", where, true);
    for (int k = 0; k < 3; ++k) {
      if (shape.size[k] <= 0.0)
        fail(node["size"], where + ": size " + formatNumber(shape.size[k]) + " must be > 0");
    }
  } else if (type == "cylinder") {
    checkKeys(node, where, {"type", "name", "radius", "length", "xyz", "rpy"});
    placement();
    shape.type = ShapeType::kCylinder;
    shape.radius = positive(node, "radius", where);
    shape.length = positive(node, "length", where);
  } else if (type == "mesh") {
    checkKeys(node, where, {"type", "name", "file", "scale", "xyz", "rpy"});
    placement();
    shape.type = ShapeType::kMesh;
    if (!node["file"] || !node["file"].IsScalar() || node["file"].Scalar().empty())
      fail(node, where + ": missing field 'file'");
    const double scale = node["scale"] ? positive(node, "scale", where) : 1.0;
    std::filesystem::path file = node["file"].Scalar();
    if (file.is_relative()) file = std::filesystem::path(source()).parent_path() / file;
    try {
      shape.mesh = std::make_shared<const TriangleMesh>(loadMesh(file.string(), scale));
    } catch (const Error& e) {
      fail(node["file"], where + ": mesh " + e.what());
    }
  } else {
    fail(node["type"],
         where + ": type '" + type + "' is not capsule, sphere, box, cylinder or mesh");
  }
  if (!named && node["name"]) fail(node["name"], where + ": unknown key 'name'");
  return shape;
}

}  // namespace mcws
