/// \file
/// \brief libFuzzer target: a collision mesh file (binary or ASCII STL, OBJ, COLLADA) through
/// mcws::loadMesh(), as the mesh shapes of a robot file are read. The first byte picks the format
/// ('o': OBJ, 'd': COLLADA, anything else: STL; all three read by mcws's own readers, COLLADA's
/// on TinyXML), the rest is the file, written to a file of this process (the reader takes a
/// path). A mesh that loads must keep the reader's promises: every triangle's corners are
/// vertices, every coordinate finite and at most 1e9 in size.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "fuzz_input.h"
#include "mcws/collision/collision_model.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const char* name = data[0] == 'o' ? "input.obj" : data[0] == 'd' ? "input.dae" : "input.stl";
  const std::string path = mcws::fuzz::writeInputFile(mcws::fuzz::text(data + 1, size - 1), name);
  mcws::fuzz::expectOnlyMcwsErrors([&] {
    const mcws::TriangleMesh mesh = mcws::loadMesh(path, 1.0);
    if (mesh.triangles.empty()) std::abort();
    for (const auto& triangle : mesh.triangles) {
      for (const int corner : triangle) {
        if (corner < 0 || std::size_t(corner) >= mesh.vertices.size()) std::abort();
      }
    }
    for (const auto& vertex : mesh.vertices) {
      if (!vertex.allFinite() || vertex.cwiseAbs().maxCoeff() > mcws::kLargestMeshCoordinate)
        std::abort();
    }
  });
  return 0;
}
