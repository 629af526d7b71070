/// \file
/// \brief libFuzzer target: a URDF robot file (robots/*.urdf), read as its whole tree's chain.

#include <cstddef>
#include <cstdint>

#include "fuzz_input.h"
#include "mcws/kinematics/robot_urdf.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = mcws::fuzz::text(data, size);
  mcws::fuzz::expectOnlyMcwsErrors(
      [&] { mcws::parseRobotUrdf(text, MCWS_ROBOTS_DIR "/fuzz_input.urdf"); });
  return 0;
}
