/// \file
/// \brief libFuzzer target: the PCD reading path of the stage tools (apps/common/cloud_io.h):
/// the header and data checks, PCL's reader, the field and coordinate checks, then the volume
/// check mcws_boundary and mcws_measure make. loadCloud() takes a path, so each input is
/// written to a file of this process first.

#include <cstddef>
#include <cstdint>

#include "common/cloud_io.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = mcws::fuzz::writeInputFile(mcws::fuzz::text(data, size), "input.pcd");
  mcws::fuzz::expectOnlyMcwsErrors([&] {
    const mcws::app::WorkspaceCloud::Ptr cloud = mcws::app::loadCloud(path);
    mcws::app::requireVolume(*cloud, path);
  });
  return 0;
}
