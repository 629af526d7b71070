#include "mcws/collision/collision_model.h"

#include <pcl/PolygonMesh.h>
#include <pcl/common/io.h>
#include <pcl/io/vtk_lib_io.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>

#include "mcws/core/error.h"
#include "mcws/core/text_file.h"
#include "mcws/core/yaml_reader.h"

namespace mcws {
namespace {

constexpr double kDegree = M_PI / 180.0;

/// Reads the `collision:` section; every mistake becomes "file:line: collision: ...".
class CollisionYamlReader : YamlReader {
 public:
  CollisionYamlReader(const Robot& robot, std::string source)
      : YamlReader(std::move(source)), robot_(robot) {}

  CollisionModel read(const YAML::Node& root) {
    CollisionModel model;
    model.links.resize(robot_.joints.size() + 1);
    model.links[0].name = "base";
    for (std::size_t i = 0; i < robot_.joints.size(); ++i)
      model.links[i + 1].name = robot_.joints[i].name;
    model.tool.name = "tool";
    if (!root.IsMap() || !root["collision"]) return model;
    if (root["units"] && root["units"].IsMap() && root["units"]["angle"] &&
        root["units"]["angle"].IsScalar() && root["units"]["angle"].Scalar() == "rad") {
      angle_scale_ = 1.0;
    }
    const YAML::Node section = root["collision"];
    if (!section.IsMap())
      fail(section, "collision: must be a map (links, tool, environment, allowed)");
    checkKeys(section, "collision", {"links", "tool", "environment", "allowed"});

    if (const YAML::Node links = section["links"]) {
      if (!links.IsMap()) fail(links, "collision: links: must be a map from link name to shapes");
      checkNames(links, "collision: links");
      for (const auto& item : links) {
        const std::string name = item.first.Scalar();
        BodySpec* body = nullptr;
        for (BodySpec& link : model.links) body = link.name == name ? &link : body;
        if (!body) {
          std::string known;
          for (const BodySpec& link : model.links) known += (known.empty() ? "" : ", ") + link.name;
          fail(item.first, "collision: links: '" + name + "' is not a link of robot '" +
                               robot_.name + "' (links: " + known + ")");
        }
        readShapes(item.second, "collision: link '" + name + "'", *body);
      }
    }
    if (const YAML::Node tool = section["tool"]) readShapes(tool, "collision: tool", model.tool);
    if (const YAML::Node environment = section["environment"]) {
      if (!environment.IsSequence())
        fail(environment, "collision: environment: must be a list of named shapes");
      std::set<std::string> names;
      for (std::size_t i = 0; i < environment.size(); ++i) {
        const YAML::Node item = environment[i];
        const std::string where = "collision: environment object " + std::to_string(i + 1);
        if (!item.IsMap() || !item["name"] || !item["name"].IsScalar())
          fail(item, where + ": must be a map with a 'name' and a shape");
        BodySpec body;
        body.name = item["name"].Scalar();
        if (body.name.empty()) fail(item["name"], where + ": name must not be empty");
        if (body.name == "tool" || body.name == "base" || isJoint(body.name) ||
            !names.insert(body.name).second) {
          fail(item["name"], where + ": name '" + body.name + "' is already used");
        }
        body.shapes.push_back(readShape(item, where + " '" + body.name + "'", true));
        model.environment.push_back(std::move(body));
      }
    }
    if (const YAML::Node allowed = section["allowed"]) {
      if (!allowed.IsSequence())
        fail(allowed, "collision: allowed: must be a list of [body, body]");
      for (const YAML::Node& pair : allowed) {
        if (!pair.IsSequence() || pair.size() != 2 || !pair[0].IsScalar() || !pair[1].IsScalar())
          fail(pair, "collision: allowed: each entry must be [body, body]");
        for (int k = 0; k < 2; ++k) {
          const std::string name = pair[k].Scalar();
          bool known = name == "tool";
          for (const BodySpec& link : model.links) known = known || link.name == name;
          for (const BodySpec& object : model.environment) known = known || object.name == name;
          if (!known)
            fail(pair[k], "collision: allowed: unknown body '" + name +
                              "' (a link: base or a joint name, tool, or an environment object)");
        }
        if (pair[0].Scalar() == pair[1].Scalar())
          fail(pair, "collision: allowed: pair of '" + pair[0].Scalar() + "' with itself");
        model.allowed.emplace_back(pair[0].Scalar(), pair[1].Scalar());
      }
    }
    return model;
  }

 private:
  bool isJoint(const std::string& name) const {
    for (const Joint& joint : robot_.joints)
      if (joint.name == name) return true;
    return false;
  }

  double positive(const YAML::Node& map, const std::string& key, const std::string& where) const {
    if (!map[key]) fail(map, where + ": missing field '" + key + "'");
    const double value = finiteNumber(map[key], where + ": " + key);
    if (value <= 0.0) fail(map[key], where + ": " + key + " " + map[key].Scalar() + " must be > 0");
    return value;
  }

  Eigen::Vector3d vector3(const YAML::Node& map, const std::string& key, const std::string& where,
                          bool required) const {
    const YAML::Node node = map[key];
    if (!node) {
      if (required) fail(map, where + ": missing field '" + key + "'");
      return Eigen::Vector3d::Zero();
    }
    if (!node.IsSequence() || node.size() != 3)
      fail(node, where + ": " + key + " must be [x, y, z]");
    Eigen::Vector3d v;
    for (int k = 0; k < 3; ++k) v[k] = finiteNumber(node[k], where + ": " + key);
    return v;
  }

  void readShapes(const YAML::Node& list, const std::string& where, BodySpec& body) const {
    if (!list.IsSequence() || list.size() == 0)
      fail(list, where + ": must be a non-empty list of shapes");
    for (std::size_t i = 0; i < list.size(); ++i) {
      body.shapes.push_back(readShape(list[i], where + " shape " + std::to_string(i + 1), false));
    }
  }

  ShapeSpec readShape(const YAML::Node& node, const std::string& where, bool named) const {
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
          fail(node["size"], where + ": size " + std::to_string(shape.size[k]) + " must be > 0");
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

  const Robot& robot_;
  double angle_scale_{kDegree};
};

}  // namespace

const char* shapeTypeName(ShapeType type) {
  switch (type) {
    case ShapeType::kCapsule:
      return "capsule";
    case ShapeType::kSphere:
      return "sphere";
    case ShapeType::kBox:
      return "box";
    case ShapeType::kCylinder:
      return "cylinder";
    case ShapeType::kMesh:
      return "mesh";
  }
  return "?";
}

CollisionModel parseCollisionYaml(const Robot& robot, const std::string& text,
                                  const std::string& source) {
  return CollisionYamlReader(robot, source).read(loadYamlDocument(text, source, "a robot file"));
}

CollisionModel loadCollisionModel(const Robot& robot, const std::string& path) {
  return parseCollisionYaml(robot, readTextFile(path, "robot file"), path);
}

bool hasGeometry(const CollisionModel& model) {
  bool any = !model.tool.shapes.empty() || !model.environment.empty();
  for (const BodySpec& link : model.links) any = any || !link.shapes.empty();
  return any;
}

CollisionModel loadRequiredCollisionModel(const Robot& robot, const std::string& path) {
  CollisionModel model = loadCollisionModel(robot, path);
  if (!hasGeometry(model)) throw Error(path + ": has no collision geometry (collision: key)");
  return model;
}

TriangleMesh loadMesh(const std::string& path, double scale) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw Error("'" + path + "': file does not exist");
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension != ".stl" && extension != ".obj")
    throw Error("'" + path + "': not an STL or OBJ file (by its extension)");
  pcl::PolygonMesh polygons;
  if (pcl::io::loadPolygonFile(path, polygons) == 0 && polygons.polygons.empty())
    throw Error("'" + path + "': holds no triangles (or cannot be read as " + extension.substr(1) +
                ")");
  // The vertices are read from the blob directly: no pcl::PointCloud<pcl::PointXYZ> is
  // instantiated here, because under AddressSanitizer Eigen's aligned allocator in this binary
  // differs from the one compiled into libpcl_io, and the library would free with the wrong one.
  const pcl::PCLPointCloud2& blob = polygons.cloud;
  int offsets[3];
  for (int k = 0; k < 3; ++k) {
    const int field = pcl::getFieldIndex(blob, std::string(1, "xyz"[k]));
    if (field < 0 || blob.fields[field].datatype != pcl::PCLPointField::FLOAT32)
      throw Error("'" + path + "': the reader gave no float vertex coordinates");
    offsets[k] = static_cast<int>(blob.fields[field].offset);
  }
  TriangleMesh mesh;
  const std::size_t count = std::size_t(blob.width) * blob.height;
  if (blob.data.size() < count * blob.point_step || blob.point_step < 3 * sizeof(float))
    throw Error("'" + path + "': the reader gave fewer vertex bytes than vertices");
  mesh.vertices.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    Eigen::Vector3d v;
    for (int k = 0; k < 3; ++k) {
      float value = 0.f;
      std::memcpy(&value, blob.data.data() + i * blob.point_step + offsets[k], sizeof value);
      v[k] = scale * double(value);
    }
    mesh.vertices.push_back(v);
  }
  for (const pcl::Vertices& polygon : polygons.polygons) {
    const auto& v = polygon.vertices;
    for (std::size_t k = 2; k < v.size(); ++k) {
      const std::array<int, 3> triangle{int(v[0]), int(v[k - 1]), int(v[k])};
      for (int index : triangle) {
        if (index < 0 || std::size_t(index) >= mesh.vertices.size())
          throw Error("'" + path + "': a triangle refers to a missing vertex");
      }
      mesh.triangles.push_back(triangle);
    }
  }
  if (mesh.triangles.empty()) throw Error("'" + path + "': holds no triangles");
  return mesh;
}

}  // namespace mcws
