/// \file
/// \brief libFuzzer target: a behaviour model (robots/*_behaviors.yaml) as `mcws_behave --check`
/// reads it: parsed (with the robot file it names), validated, its poses checked.

#include <cstddef>
#include <cstdint>

#include "fuzz_input.h"
#include "mcws/behavior/behavior_model.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = mcws::fuzz::text(data, size);
  // Named as a file of robots/ so that `robot: insulator_cleaner.yaml` finds the robot.
  mcws::fuzz::expectOnlyMcwsErrors([&] {
    const mcws::BehaviorModel model =
        mcws::parseBehaviorModel(text, MCWS_ROBOTS_DIR "/fuzz_input.yaml");
    mcws::validateBehaviorModel(model);
    mcws::checkPoseConsistency(model);
  });
  return 0;
}
