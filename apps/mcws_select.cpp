// mcws_select: keeps the points of a labelled workspace cloud whose label is in a list (splits
// mcws_sample --collision output into seed 002's clouds: free, link-link, tool-link, ...).
#include <pcl/io/pcd_io.h>

#include <iostream>
#include <nlohmann/json.hpp>
#include <set>

#include "common/app.h"
#include "common/cloud_io.h"

int main(int argc, char** argv) {
  using namespace mcws;
  return app::run("mcws_select", [&] {
    app::CommandLine cli(
        "mcws_select --input CLOUD.pcd --label L[,L...] --output OUT.pcd [--json]",
        "Writes the points whose uint32 'label' field is one of the given values (mcws_sample\n"
        "--collision: 0 free, 1 link-link, 2 tool-link, 3 environment). PCL's own\n"
        "pcl_passthrough_filter cannot do this: it reads fields as float and the label of\n"
        "pcl::PointXYZL is a uint32.");
    cli.add()("input", app::po::value<std::string>(), "labelled cloud (PCD with a label field)")(
        "label", app::po::value<std::string>(), "labels to keep, e.g. 0 or 1,2,3")(
        "output", app::po::value<std::string>(), "output PCD file")(
        "json", "print a JSON summary on stdout");
    if (!cli.parse(argc, argv)) return app::kExitOk;
    const std::string input = cli.required("input"), output = cli.required("output");
    std::set<std::uint32_t> labels;
    for (double value : app::parseNumberList(cli.required("label"), "label")) {
      if (!(value >= 0.0 && value <= 4294967295.0) || value != static_cast<std::uint32_t>(value))
        throw app::UsageError("--label: " + cli.required("label") +
                              " is not a list of whole numbers >= 0");
      labels.insert(static_cast<std::uint32_t>(value));
    }

    app::Progress clock("mcws_select", "points");
    const app::WorkspaceCloud::Ptr cloud = app::loadCloud(input);
    pcl::PCLPointCloud2 header;
    pcl::PCDReader().readHeader(input, header);
    if (pcl::getFieldIndex(header, "label") < 0) throw Error(input + ": has no field 'label'");
    pcl::Indices kept;
    for (std::size_t i = 0; i < cloud->size(); ++i) {
      if (labels.count((*cloud)[i].label)) kept.push_back(static_cast<pcl::index_t>(i));
    }
    app::saveCloud(*cloud, kept, output);
    if (cli.has("json")) {
      std::cout << nlohmann::json{{"input", input},
                                  {"output", output},
                                  {"points_in", cloud->size()},
                                  {"points_out", kept.size()},
                                  {"labels", labels}}
                       .dump()
                << "\n";
    } else {
      std::cerr << "[done, " << static_cast<int>(clock.seconds() * 1000) << " ms : " << kept.size()
                << " of " << cloud->size() << " points] -> " << output << "\n";
    }
    return app::kExitOk;
  });
}
