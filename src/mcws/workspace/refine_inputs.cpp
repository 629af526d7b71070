#include "mcws/workspace/refine_inputs.h"

#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <optional>

#include "mcws/core/error.h"
#include "mcws/io/cloud_io.h"

namespace mcws {

namespace {

/// The header of the cloud of --`flag`.
pcl::PCLPointCloud2 readHeader(const std::string& flag, const std::string& path) {
  pcl::PCLPointCloud2 header;
  if (pcl::PCDReader().readHeader(path, header) < 0) {
    throw Error("--" + flag + " '" + path + "': cannot read the PCD header");
  }
  return header;
}

bool hasField(const pcl::PCLPointCloud2& header, const std::string& name) {
  return std::any_of(header.fields.begin(), header.fields.end(),
                     [&](const pcl::PCLPointField& f) { return f.name == name; });
}

/// Checks that the cloud of --`flag` has the joint fields q1..qn of an n-joint robot.
void requireJointFields(const std::string& flag, const std::string& path, int dof) {
  const pcl::PCLPointCloud2 header = readHeader(flag, path);
  for (int j = 1; j <= dof; ++j) {
    const std::string name = "q" + std::to_string(j);
    if (!hasField(header, name)) {
      throw Error("--" + flag + " '" + path + "' has no field " + name +
                  ": refinement needs the joint values of each point (fields q1..q" +
                  std::to_string(dof) +
                  ", as mcws_sample writes them; a mcws_reach map cloud has none)");
    }
  }
}

/// How the cloud of --`flag` was sampled, as its header records it.
/// \throws mcws::Error when it records nothing or predates the record.
io::SamplingRecord recordedSampling(const std::string& flag, const std::string& path,
                                    const std::optional<io::CloudProvenance>& recorded) {
  if (!recorded) {
    throw Error("--" + flag + " '" + path +
                "' does not record how it was sampled (no '# mcws' header line): refine "
                "draws new samples the same way; make the cloud with mcws_sample (then "
                "mcws_boundary)");
  }
  if (!recorded->sampling) {
    throw Error("--" + flag + " '" + path +
                "' predates the record of how it was sampled (its '# mcws' header line has "
                "no point=, collision=, fix=): re-make it with mcws_sample (then "
                "mcws_boundary) of this version");
  }
  return *recorded->sampling;
}

}  // namespace

void recordRefineSampling(const std::vector<RefineCloud>& clouds, int dof,
                          io::CloudProvenance& provenance) {
  for (std::size_t i = 0; i < clouds.size(); ++i) {
    const auto& [flag, path] = clouds[i];
    const std::optional<io::CloudProvenance> recorded = io::readProvenance(path);
    io::requireSameRobot(flag, path, recorded, provenance);
    requireJointFields(flag, path, dof);
    const io::SamplingRecord sampling = recordedSampling(flag, path, recorded);
    if (provenance.sampling && sampling != *provenance.sampling) {
      throw Error("--" + flag + " '" + path + "' was sampled with " +
                  io::describeSampling(sampling) + " but --" + clouds[0].first + " '" +
                  clouds[0].second + "' with " + io::describeSampling(*provenance.sampling));
    }
    provenance.sampling = sampling;
  }
}

pcl::PointCloud<WorkspacePoint> labelledParents(const RefineCloud& cloud,
                                                const pcl::PointCloud<WorkspacePoint>& points,
                                                const io::SamplingRecord& sampling,
                                                std::uint32_t label,
                                                const std::string& label_name) {
  const auto& [flag, path] = cloud;
  if (!hasField(readHeader(flag, path), "label")) {
    throw Error("--collision: --" + flag + " '" + path +
                "' has no field 'label': it refines the points labelled " + label_name +
                ", which needs a cloud of mcws_sample --collision (then mcws_boundary)");
  }
  if (!sampling.collision) {
    throw Error("--collision: --" + flag + " '" + path +
                "' was sampled without collision labels (its header records collision=0, so "
                "every label reads 0): sample it with mcws_sample --collision");
  }
  pcl::PointCloud<WorkspacePoint> parents;
  for (const WorkspacePoint& p : points) {
    if (p.label == label) parents.push_back(p);
  }
  if (parents.empty()) {
    throw Error("--collision: none of the " + std::to_string(points.size()) + " points of --" +
                flag + " '" + path + "' is labelled " + label_name + " (label " +
                std::to_string(label) + "): nothing to refine");
  }
  return parents;
}

}  // namespace mcws
