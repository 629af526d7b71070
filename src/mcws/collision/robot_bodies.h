#pragma once
/// \file
/// \brief The part of a collision model that moves with the robot's base.

#include "mcws/collision/collision_model.h"

namespace mcws {

/// \brief `model` without its environment: the robot's links and tool only, with the allowed
/// pairs that name an environment body dropped. For what is meant for other base positions (a
/// reachability map used to place the base): moved with the base, the environment's shadow
/// would move too.
CollisionModel robotBodiesOnly(CollisionModel model);

}  // namespace mcws
