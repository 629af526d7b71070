// mcws_select: keeps the points of a labelled workspace cloud whose label is in a list (splits
// mcws_sample --collision output into the clouds of Fu, Hu, Chen & Pan 2016: free, link-link,
// tool-link, ...).
#include <pcl/io/pcd_io.h>

#include <iostream>
#include <nlohmann/json.hpp>
#include <set>

#include "common/app.h"
#include "common/units.h"
#include "mcws/io/cloud_io.h"
#include "mcws/sampling/sample_report.h"

namespace {

constexpr char kUsage[] =
    "mcws_select --input CLOUD.pcd --label L[,L...] --output OUT.pcd [--json]";

constexpr char kSummary[] =
    R"(Writes the points whose uint32 'label' field is one of the given values (mcws_sample
--collision: 0 free, 1 link-link, 2 tool-link, 3 environment). PCL's own pcl_passthrough_filter
cannot do this: it reads fields as float and the label of pcl::PointXYZL is a uint32.)";

void declareFlags(mcws::app::CommandLine& cli) {
  cli.addValue("input", "labelled cloud (PCD with a label field)");
  cli.addValue("label", "labels to keep, e.g. 0 or 1,2,3");
  cli.addValue("output", "output PCD file");
  cli.addSwitch("json", "print a JSON summary on stdout");
}

/// --label: whole numbers >= 0 that fit a uint32.
std::set<std::uint32_t> readLabels(const mcws::app::CommandLine& cli) {
  std::set<std::uint32_t> labels;
  for (double value : mcws::app::parseNumberList(cli.required("label"), "label")) {
    if (!(value >= 0.0 && value <= 4294967295.0) || value != static_cast<std::uint32_t>(value))
      throw mcws::app::UsageError("--label: " + cli.required("label") +
                                  " is not a list of whole numbers >= 0");
    labels.insert(static_cast<std::uint32_t>(value));
  }
  return labels;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace mcws;
  return app::run("mcws_select", [&] {
    app::CommandLine cli(kUsage, kSummary);
    declareFlags(cli);
    if (!cli.parse(argc, argv)) return app::kExitOk;
    const std::string input = cli.required("input"), output = cli.required("output");
    const std::set<std::uint32_t> labels = readLabels(cli);
    app::checkOutputs({{"output", output}}, {{"input", input}});

    app::Progress clock("mcws_select", "points");
    const io::WorkspaceCloud::Ptr cloud = io::readCloud(input);
    pcl::PCLPointCloud2 header;
    pcl::PCDReader().readHeader(input, header);
    if (pcl::getFieldIndex(header, "label") < 0) throw Error(input + ": has no field 'label'");
    pcl::Indices kept;
    for (std::size_t i = 0; i < cloud->size(); ++i) {
      if (labels.count((*cloud)[i].label)) kept.push_back(static_cast<pcl::index_t>(i));
    }
    const std::optional<io::CloudProvenance> recorded = io::readProvenance(input);
    io::writeCloud(*cloud, kept, output, recorded);  // the input's robot
    if (cli.has("json")) {
      nlohmann::json out{
          {"input", input},
          {"output", output},
          {"points_in", cloud->size()},
          {"points_out", kept.size()},
          {"labels", labels},
          {"length_unit", ResultUnits(io::recordedUnit(input), std::nullopt).lengthName()},
          {"seconds", clock.seconds()},
          {"units", {{"seconds", "s"}}}};
      addRecordedRobotNames(out, recorded);
      std::cout << out.dump() << "\n";
    } else {
      std::cerr << "[done, " << static_cast<int>(clock.seconds() * 1000) << " ms : " << kept.size()
                << " of " << cloud->size() << " points] -> " << output << "\n";
    }
    return app::kExitOk;
  });
}
