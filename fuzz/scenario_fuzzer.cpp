/// \file
/// \brief libFuzzer target: a planning scenario (scenarios/*.yaml) as mcws_plan reads it,
/// including the robot file and collision geometry it names.

#include <cstddef>
#include <cstdint>

#include "fuzz_input.h"
#include "mcws/planning/scenario.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = mcws::fuzz::text(data, size);
  // Named as a file of scenarios/ so that `robot: ../robots/...` finds the repository's robots.
  mcws::fuzz::expectOnlyMcwsErrors(
      [&] { mcws::parseScenario(text, MCWS_SCENARIOS_DIR "/fuzz_input.yaml"); });
  return 0;
}
