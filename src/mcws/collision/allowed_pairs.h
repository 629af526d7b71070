#pragma once
/// \file
/// \brief The pairs of links a collision check may skip, found by sampling as MoveIt's setup
/// assistant does (its "self-collisions" step, moveit_setup_srdf_plugins' compute_default_
/// collisions): adjacent links, pairs in collision at the default joint values, pairs in collision
/// in every sample and pairs in collision in none.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "mcws/collision/collision_model.h"
#include "mcws/collision/srdf.h"
#include "mcws/kinematics/robot.h"

namespace mcws {

/// \brief The link pairs of `model` that need no check, each with MoveIt's reason.
///
/// Works on the checker's bodies (CollisionChecker over `model` without its allowed pairs), then
/// names each body pair by every pair of their links that carry geometry (linkBodies()):
/// - "Adjacent": two links of one body (fixed together), and body pairs the checker never tests
///   (base and link 1, link i and i+1, the last link and the tool, the base and the environment);
/// - "Default": pairs in collision at the default joint values (each joint at 0, or the limit
///   nearest 0 when 0 is outside its limits);
/// - "Always": pairs in collision in every one of the `samples` joint vectors;
/// - "Never": pairs in collision in none of them.
/// The joint vectors are RobotSampler's samples 0 .. samples-1 for `seed` (uniform within the
/// limits), checked in order on one thread, so the result depends on the seed only. "Never" is a
/// sampling verdict: a pair that collides in a small region of the joint space may be missed
/// (MoveIt uses 10000 samples or more).
/// \param samples number of joint vectors (>= 1). \param seed the sampler's seed.
/// \return Adjacent entries first, then Default, Always and Never; within each, in body order
///   (base, joints, tool, environment) and then link order.
/// \throws mcws::Error as CollisionChecker and RobotSampler, and for samples == 0.
std::vector<DisabledCollision> findAllowedPairs(const Robot& robot, const CollisionModel& model,
                                                std::size_t samples, std::uint64_t seed);

}  // namespace mcws
