/// \file
/// \brief libFuzzer target: a fault file of a behaviour rehearsal (scenarios/faults/*.yaml).

#include <cstddef>
#include <cstdint>

#include "fuzz_input.h"
#include "mcws/behavior/fault_script.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = mcws::fuzz::text(data, size);
  mcws::fuzz::expectOnlyMcwsErrors([&] { mcws::parseFaultScript(text, "fuzz_input.yaml"); });
  return 0;
}
