#pragma once
/// \file
/// \brief The part of a collision model that moves with the robot's base.

#include <memory>
#include <string>

#include "mcws/collision/collision_checker.h"
#include "mcws/collision/collision_model.h"

namespace mcws {

/// \brief `model` without its environment: the robot's links and tool only, with the allowed
/// pairs that name an environment body dropped. For what is meant for other base positions (a
/// reachability map used to place the base): moved with the base, the environment's shadow
/// would move too.
CollisionModel robotBodiesOnly(CollisionModel model);

/// \brief The checker of the collision model of the robot file `path` (loadCollisionModel()),
/// without its environment unless `environment` (robotBodiesOnly()); none when that model has no
/// geometry (a robot file without collision geometry), so that a study counts every pose free.
std::unique_ptr<CollisionChecker> checkerIfModelled(const Robot& robot, const std::string& path,
                                                    bool environment);

}  // namespace mcws
