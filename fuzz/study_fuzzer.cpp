/// \file
/// \brief libFuzzer target: a line study (studies/*.yaml) as mcws_study reads it, including the
/// robot file, the collision shapes of its fittings and the targets files it names.

#include <cstddef>
#include <cstdint>

#include "fuzz_input.h"
#include "mcws/study/study.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = mcws::fuzz::text(data, size);
  // Named as a file of studies/ so that `robot: ../robots/...` finds the repository's robots.
  mcws::fuzz::expectOnlyMcwsErrors(
      [&] { mcws::parseStudy(text, MCWS_STUDIES_DIR "/fuzz_input.yaml"); });
  return 0;
}
