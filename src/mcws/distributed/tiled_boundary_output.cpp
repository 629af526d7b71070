#include "mcws/distributed/tiled_boundary_output.h"

#include "mcws/io/atomic_file.h"
#include "mcws/io/pcd_stream_writer.h"

namespace mcws::distributed {

void writeTiledBoundary(io::PcdPointReader& reader, const TiledBoundary& found,
                        const std::string& output, const std::string& interior,
                        std::uint64_t interior_points,
                        const std::optional<io::CloudProvenance>& provenance) {
  const bool with_interior = !interior.empty();
  io::OutputSet outputs;
  io::PcdStreamWriter<WorkspacePoint> boundary_file(output, found.kept, io::PcdFormat::kBinary,
                                                    provenance);
  std::optional<io::PcdStreamWriter<WorkspacePoint>> interior_file;
  if (with_interior) {
    interior_file.emplace(interior, interior_points, io::PcdFormat::kBinary, provenance);
  }
  io::WorkspaceCloud kept, rest;
  forEachPiece(reader, [&](std::uint64_t first, const io::WorkspaceCloud& piece) {
    kept.clear();
    rest.clear();
    for (std::size_t k = 0; k < piece.size(); ++k) {
      if (found.boundary[first + k]) {
        kept.push_back(piece[k]);
      } else if (with_interior && pcl::isFinite(piece[k])) {
        rest.push_back(piece[k]);
      }
    }
    boundary_file.write(kept.data(), kept.size());
    if (with_interior) interior_file->write(rest.data(), rest.size());
  });
  boundary_file.commit();
  if (with_interior) interior_file->commit();
  outputs.commit();
}

}  // namespace mcws::distributed
