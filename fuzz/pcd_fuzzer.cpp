/// \file
/// \brief libFuzzer target: the PCD reading path of the library (mcws/io/cloud_io.h): the header
/// and data checks, PCL's reader, the field and coordinate checks, then the volume check
/// mcws_boundary and mcws_measure make. io::readCloud() takes a path, so each input is written to
/// a file of this process first.

#include <cstddef>
#include <cstdint>

#include "fuzz_input.h"
#include "mcws/io/cloud_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = mcws::fuzz::writeInputFile(mcws::fuzz::text(data, size), "input.pcd");
  mcws::fuzz::expectOnlyMcwsErrors([&] {
    const mcws::io::WorkspaceCloud::Ptr cloud = mcws::io::readCloud(path);
    mcws::io::requireVolume(*cloud, path);
  });
  return 0;
}
