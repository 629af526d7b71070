#include "mcws/io/boundary_record.h"

#include <optional>

#include "mcws/core/error.h"
#include "mcws/io/cloud_io.h"
#include "mcws/io/provenance.h"

namespace mcws::io {

namespace {

/// "20000 points, sha256 0123456789ab..." for a message.
std::string describeCloud(std::uint64_t points, const std::string& sha256) {
  return std::to_string(points) + " points, sha256 " + sha256.substr(0, 12) + "...";
}

}  // namespace

std::optional<CloudProvenance> boundaryProvenance(const std::string& input, std::uint64_t points,
                                                  std::uint64_t boundary_points) {
  std::optional<CloudProvenance> recorded = readProvenance(input);
  if (recorded) recorded->input = InputCloud{points, sha256OfFile(input), boundary_points};
  return recorded;
}

void requireBoundaryOf(const std::string& path, const std::string& input, std::uint64_t points,
                       std::uint64_t boundary_points) {
  const std::optional<CloudProvenance> boundary = readProvenance(path);
  const std::optional<CloudProvenance> cloud = readProvenance(input);
  if (!boundary && !cloud) return;
  const std::string sha256 = sha256OfFile(input);
  if (sha256OfFile(path) == sha256) return;  // the cloud is its own boundary
  const std::string remake = ": re-make it with mcws_boundary --input " + input;
  if (!boundary || !boundary->input) {
    throw Error("--boundary " + path + " does not record the cloud it is the boundary of (" +
                (boundary ? "its '# mcws' line predates input_points=, input_sha256="
                          : "no '# mcws' header line, but --input records its robot") +
                ")" + remake);
  }
  if (boundary->input->points != points || boundary->input->sha256 != sha256) {
    throw Error("--boundary " + path + " is the boundary of a cloud of " +
                describeCloud(boundary->input->points, boundary->input->sha256) +
                ", not of --input " + input + " (" + describeCloud(points, sha256) + ")" + remake);
  }
  if (boundary->input->boundary_points != boundary_points) {
    throw Error("--boundary " + path + " has " + std::to_string(boundary_points) +
                " points, but mcws_boundary found " +
                std::to_string(boundary->input->boundary_points) + " on the boundary of --input " +
                input + ": a part of the boundary (mcws_select?) or its --interior" + remake);
  }
}

}  // namespace mcws::io
