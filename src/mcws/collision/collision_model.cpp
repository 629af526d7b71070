#include "mcws/collision/collision_model.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "mcws/collision/package_uri.h"
#include "mcws/collision/shape_yaml.h"
#include "mcws/collision/srdf.h"
#include "mcws/core/decimal.h"
#include "mcws/core/error.h"
#include "mcws/core/file_name.h"
#include "mcws/core/text_file.h"
#include "mcws/core/yaml_reader.h"

namespace mcws {
namespace {

/// How far a sphere's centre and radius may be from a cylinder's end-face centre and radius, as a
/// fraction of the cylinder's length plus radius, for the two to be read as one capsule
/// (mergeCapsules()). URDF numbers carry about 16 digits, and the end of a cylinder turned by
/// rpy = pi/2 lies some 1e-16 of its length off the axis; 1e-9 is far above that rounding and far
/// below any gap a designer would draw.
constexpr double kCapsuleMatch = 1e-9;

/// A model with a body for the base, one per joint and the tool, and no shapes.
CollisionModel emptyModel(const Robot& robot) {
  CollisionModel model;
  model.links.resize(robot.joints.size() + 1);
  model.links[0].name = "base";
  for (std::size_t i = 0; i < robot.joints.size(); ++i)
    model.links[i + 1].name = robot.joints[i].name;
  model.tool.name = "tool";
  return model;
}

bool isUrdfPath(const std::string& path) {
  return std::filesystem::path(path).extension() == ".urdf";
}

/// Reads the `collision:` section; every mistake becomes "file:line: collision: ...".
class CollisionYamlReader : ShapeYamlReader {
 public:
  CollisionYamlReader(const Robot& robot, std::string source)
      : ShapeYamlReader(std::move(source)), robot_(robot) {}

  CollisionModel read(const YAML::Node& root) {
    CollisionModel model = emptyModel(robot_);
    if (!root.IsMap() || !root["collision"]) return model;
    if (root["units"] && root["units"].IsMap() && root["units"]["angle"] &&
        root["units"]["angle"].IsScalar() && root["units"]["angle"].Scalar() == "rad") {
      setAngleScale(1.0);
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
        if (hasControlByte(body.name)) {
          fail(item["name"], where + ": name '" + escapedControlBytes(body.name) +
                                 "' holds a control byte (names are printable text)");
        }
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

  void readShapes(const YAML::Node& list, const std::string& where, BodySpec& body) const {
    if (!list.IsSequence() || list.size() == 0)
      fail(list, where + ": must be a non-empty list of shapes");
    for (std::size_t i = 0; i < list.size(); ++i) {
      body.shapes.push_back(readShape(list[i], where + " shape " + std::to_string(i + 1), false));
    }
  }

  const Robot& robot_;
};

/// The file a URDF `<mesh filename>` names: a path relative to the URDF file's directory, an
/// absolute path, a `file://` URI or a `package://` URI (resolvePackageUri()).
/// \throws mcws::Error for other URIs and packages not found.
std::string urdfMeshPath(const std::string& filename, const std::string& source,
                         const std::string& where, const PackageSearch& packages) {
  std::string path = filename;
  if (filename.rfind("file://", 0) == 0) {
    path = filename.substr(7);
  } else if (filename.rfind("package://", 0) == 0) {
    try {
      path = resolvePackageUri(filename, source, packages);
    } catch (const Error& e) {
      throw Error(where + ": " + e.what());
    }
  } else if (filename.find("://") != std::string::npos) {
    throw Error(where + ": mesh '" + filename +
                "': URI scheme not supported (a path relative to the URDF file, an absolute path, "
                "file:// or package://)");
  }
  std::filesystem::path file = path;
  if (file.is_relative()) file = std::filesystem::path(source).parent_path() / file;
  const std::string extension = lowercaseExtension(file);
  if (extension != ".stl" && extension != ".obj" && extension != ".dae") {
    throw Error(where + ": mesh '" + filename +
                "': " + (extension.empty() ? std::string("a file without extension") : extension) +
                " meshes are not supported (STL, OBJ or COLLADA .dae)");
  }
  return file.string();
}

/// The shape of one URDF `<collision>` element, with lengths times `unit` (robot length units
/// per metre).
ShapeSpec urdfShape(const UrdfCollision& in, double unit, const std::string& source,
                    const PackageSearch& packages) {
  const std::string where =
      source + ": link '" + in.link + "' <collision> " + std::to_string(in.element);
  ShapeSpec shape;
  shape.source = where;
  shape.T_body_shape = in.T_body_geometry;
  shape.T_body_shape.translation() *= unit;
  switch (in.type) {
    case UrdfGeometry::kSphere:
      shape.type = ShapeType::kSphere;
      shape.p_from = shape.p_to = shape.T_body_shape.translation();
      shape.T_body_shape = Eigen::Isometry3d::Identity();  // a sphere is placed by p_from
      shape.radius = in.radius * unit;
      break;
    case UrdfGeometry::kBox:
      shape.type = ShapeType::kBox;
      shape.size = in.size * unit;
      break;
    case UrdfGeometry::kCylinder:
      shape.type = ShapeType::kCylinder;
      shape.radius = in.radius * unit;
      shape.length = in.length * unit;
      break;
    case UrdfGeometry::kMesh: {
      shape.type = ShapeType::kMesh;
      const std::string path = urdfMeshPath(in.filename, source, where, packages);
      TriangleMesh mesh;
      try {
        mesh = readMeshFile(path);
        scaleMesh(mesh, in.scale * unit, path);
      } catch (const Error& e) {
        throw Error(where + ": mesh " + e.what());
      }
      shape.mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
      break;
    }
  }
  return shape;
}

/// Replaces each cylinder that has, in the same body, a sphere of its radius centred on each of
/// its end faces by one capsule between the two spheres' centres: the same set of points (a
/// capsule is the union of such a cylinder and spheres), tested by the exact segment distance as
/// a capsule of a YAML file. Each sphere closes one cylinder at most.
void mergeCapsules(BodySpec& body) {
  std::vector<ShapeSpec>& shapes = body.shapes;
  std::vector<bool> dropped(shapes.size(), false);
  const auto sphereAt = [&](const Eigen::Vector3d& p, double radius, double tolerance) {
    for (std::size_t j = 0; j < shapes.size(); ++j) {
      if (!dropped[j] && shapes[j].type == ShapeType::kSphere &&
          std::abs(shapes[j].radius - radius) <= tolerance &&
          (shapes[j].p_from - p).norm() <= tolerance) {
        return int(j);
      }
    }
    return -1;
  };
  for (ShapeSpec& shape : shapes) {
    if (shape.type != ShapeType::kCylinder) continue;
    const Eigen::Vector3d half = 0.5 * shape.length * Eigen::Vector3d::UnitZ();
    const double tolerance = kCapsuleMatch * (shape.length + shape.radius);
    const int from = sphereAt(shape.T_body_shape * (-half), shape.radius, tolerance);
    if (from < 0) continue;
    dropped[from] = true;
    const int to = sphereAt(shape.T_body_shape * half, shape.radius, tolerance);
    if (to < 0) {
      dropped[from] = false;
      continue;
    }
    dropped[to] = true;
    shape.type = ShapeType::kCapsule;
    shape.p_from = shapes[from].p_from;
    shape.p_to = shapes[to].p_from;
    shape.T_body_shape = Eigen::Isometry3d::Identity();
    shape.length = 0.0;
  }
  std::vector<ShapeSpec> kept;
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    if (!dropped[i]) kept.push_back(std::move(shapes[i]));
  }
  shapes = std::move(kept);
}

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

CollisionModel parseCollisionUrdf(const Robot& robot, const std::string& text,
                                  const std::string& source, const UrdfChainOptions& chain) {
  const UrdfRobotGeometry urdf = parseRobotUrdfGeometry(text, source, chain);
  const auto jointNames = [](const Robot& r) {
    std::string names;
    for (const Joint& joint : r.joints) names += (names.empty() ? "" : ", ") + joint.name;
    return names;
  };
  if (jointNames(urdf.robot) != jointNames(robot)) {
    throw Error(source + ": the URDF chain's joints (" + jointNames(urdf.robot) +
                ") are not those of robot '" + robot.name + "' (" + jointNames(robot) + ")");
  }
  const double unit = 1.0 / unitInMetres(robot.length_unit);
  CollisionModel model = emptyModel(robot);
  const PackageSearch packages = packageSearchFromEnvironment(robot.package_path);
  model.link_names = urdf.links;
  for (const UrdfCollision& element : urdf.collisions) {
    ShapeSpec shape = urdfShape(element, unit, source, packages);
    const std::string body = element.body == UrdfBody::kBase   ? model.links[0].name
                             : element.body == UrdfBody::kLink ? model.links[element.joint + 1].name
                             : element.body == UrdfBody::kTool ? model.tool.name
                                                               : element.link;
    const std::pair<std::string, std::string> carried{element.link, body};
    if (std::find(model.link_bodies.begin(), model.link_bodies.end(), carried) ==
        model.link_bodies.end()) {
      model.link_bodies.push_back(carried);
    }
    switch (element.body) {
      case UrdfBody::kBase:
        model.links[0].shapes.push_back(std::move(shape));
        break;
      case UrdfBody::kLink:
        model.links[std::size_t(element.joint) + 1].shapes.push_back(std::move(shape));
        break;
      case UrdfBody::kTool:
        model.tool.shapes.push_back(std::move(shape));
        break;
      case UrdfBody::kEnvironment: {
        // The environment is placed in the world frame, the URDF's base link frame in the base's.
        shape.T_body_shape = robot.T_world_base * shape.T_body_shape;
        shape.p_from = robot.T_world_base * shape.p_from;
        shape.p_to = robot.T_world_base * shape.p_to;
        auto object = std::find_if(model.environment.begin(), model.environment.end(),
                                   [&](const BodySpec& b) { return b.name == element.link; });
        if (object == model.environment.end()) {
          const bool taken = element.link == "tool" || element.link == "base" ||
                             std::any_of(robot.joints.begin(), robot.joints.end(),
                                         [&](const Joint& j) { return j.name == element.link; });
          if (taken) {
            throw Error(source + ": link '" + element.link +
                        "' is fixed to the base off the chain, so it is an environment object, "
                        "but its name is already a body's (base, tool or a joint)");
          }
          model.environment.push_back(BodySpec{element.link, {}});
          object = model.environment.end() - 1;
        }
        object->shapes.push_back(std::move(shape));
        break;
      }
    }
  }
  for (BodySpec& link : model.links) mergeCapsules(link);
  mergeCapsules(model.tool);
  for (BodySpec& object : model.environment) mergeCapsules(object);
  return model;
}

CollisionModel loadCollisionUrdf(const Robot& robot, const std::string& path,
                                 const UrdfChainOptions& chain) {
  std::error_code ec;  // a file that cannot be sized is left to readTextFile's messages
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (!ec && bytes > kMaxUrdfBytes) {
    throw Error(path + ": URDF of " + std::to_string(bytes) + " bytes is larger than " +
                std::to_string(kMaxUrdfBytes >> 20) + " MiB");
  }
  return parseCollisionUrdf(robot, readTextFile(path, "robot file"), path, chain);
}

CollisionModel loadCollisionModel(const Robot& robot, const std::string& path) {
  CollisionModel model = isUrdfPath(path)
                             ? loadCollisionUrdf(robot, path, {robot.base_link, robot.tip_link})
                             : parseCollisionYaml(robot, readTextFile(path, "robot file"), path);
  if (!robot.srdf.empty()) applySrdf(model, loadSrdf(robot.srdf), robot.srdf);
  return model;
}

std::vector<std::pair<std::string, std::string>> linkBodies(const CollisionModel& model) {
  if (!model.link_names.empty()) return model.link_bodies;
  std::vector<std::pair<std::string, std::string>> out;
  const auto add = [&](const BodySpec& body) {
    if (!body.shapes.empty()) out.emplace_back(body.name, body.name);
  };
  for (const BodySpec& link : model.links) add(link);
  add(model.tool);
  for (const BodySpec& object : model.environment) add(object);
  return out;
}

bool hasGeometry(const CollisionModel& model) {
  bool any = !model.tool.shapes.empty() || !model.environment.empty();
  for (const BodySpec& link : model.links) any = any || !link.shapes.empty();
  return any;
}

CollisionModel loadRequiredCollisionModel(const Robot& robot, const std::string& path) {
  CollisionModel model = loadCollisionModel(robot, path);
  if (!hasGeometry(model)) {
    throw Error(path + ": has no collision geometry " +
                (isUrdfPath(path) ? "(no <collision> element on a link of its chain)"
                                  : "(collision: key)"));
  }
  return model;
}

void scaleMesh(TriangleMesh& mesh, const Eigen::Vector3d& factor, const std::string& path) {
  for (Eigen::Vector3d& v : mesh.vertices) {
    for (int k = 0; k < 3; ++k) {
      const double scaled = v[k] * factor[k];
      if (!(std::abs(scaled) <= kLargestMeshCoordinate)) {
        std::ostringstream message;
        message.precision(9);
        message << "'" << path << "': coordinate " << v[k] << " times scale " << factor[k]
                << " is out of range (at most 1e9 in size)";
        throw Error(message.str());
      }
      v[k] = scaled;
    }
  }
}

TriangleMesh loadMesh(const std::string& path, double scale) {
  TriangleMesh mesh = readMeshFile(path);
  scaleMesh(mesh, Eigen::Vector3d::Constant(scale), path);
  return mesh;
}

}  // namespace mcws
