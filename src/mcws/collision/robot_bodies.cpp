#include "mcws/collision/robot_bodies.h"

#include <algorithm>
#include <string>
#include <utility>

namespace mcws {

CollisionModel robotBodiesOnly(CollisionModel model) {
  auto inEnvironment = [&](const std::string& name) {
    return std::any_of(model.environment.begin(), model.environment.end(),
                       [&](const BodySpec& body) { return body.name == name; });
  };
  model.allowed.erase(std::remove_if(model.allowed.begin(), model.allowed.end(),
                                     [&](const auto& pair) {
                                       return inEnvironment(pair.first) ||
                                              inEnvironment(pair.second);
                                     }),
                      model.allowed.end());
  model.environment.clear();
  return model;
}

std::unique_ptr<CollisionChecker> checkerIfModelled(const Robot& robot, const std::string& path,
                                                    bool environment) {
  CollisionModel model = loadCollisionModel(robot, path);
  if (!environment) model = robotBodiesOnly(std::move(model));
  if (!hasGeometry(model)) return nullptr;
  return std::make_unique<CollisionChecker>(robot, model);
}

}  // namespace mcws
