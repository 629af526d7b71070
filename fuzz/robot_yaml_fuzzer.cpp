/// \file
/// \brief libFuzzer target: a robot YAML file (robots/*.yaml), its kinematic chain and its
/// `collision:` section, as mcws_collide and mcws_sample read them.

#include <cstddef>
#include <cstdint>

#include "fuzz_input.h"
#include "mcws/collision/collision_model.h"
#include "mcws/kinematics/robot_yaml.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = mcws::fuzz::text(data, size);
  // Named as a file of robots/ so that mesh paths relative to it find robots/meshes/.
  const std::string source = MCWS_ROBOTS_DIR "/fuzz_input.yaml";
  mcws::fuzz::expectOnlyMcwsErrors([&] {
    const mcws::Robot robot = mcws::parseRobotYaml(text, source);
    mcws::parseCollisionYaml(robot, text, source);
  });
  return 0;
}
