#include "mcws/reach/targets_file.h"

#include <pcl/common/io.h>
#include <pcl/console/print.h>
#include <pcl/conversions.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "mcws/core/error.h"
#include "mcws/core/text_file.h"
#include "mcws/io/cloud_io.h"
#include "mcws/kinematics/robot.h"
#include "mcws/reach/orientation_bins.h"

namespace mcws {

namespace {

bool endsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::vector<ReachTarget> targetsFromPcd(const std::string& path) {
  const pcl::PCLPointCloud2 blob = io::readPcd(path);
  for (const char* field : {"normal_x", "normal_y", "normal_z"}) {
    if (pcl::getFieldIndex(blob, field) < 0) {
      throw Error(path + ": has no field '" + field +
                  "': a target is a point and its surface normal (pcl::PointNormal)");
    }
  }
  // PCL's conversion leaves a field of another type at 0 without a word: insist on
  // pcl::PointNormal's.
  for (const pcl::PCLPointField& f : blob.fields) {
    const bool used = f.name == "x" || f.name == "y" || f.name == "z" || f.name == "normal_x" ||
                      f.name == "normal_y" || f.name == "normal_z";
    if (used && (f.datatype != pcl::PCLPointField::FLOAT32 || f.count != 1)) {
      throw Error(path + ": field '" + f.name +
                  "' is not one 4-byte float (TYPE F, SIZE 4, COUNT 1)");
    }
  }
  pcl::PointCloud<pcl::PointNormal> cloud;
  const pcl::console::VERBOSITY_LEVEL level = pcl::console::getVerbosityLevel();
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);  // a missing curvature is fine
  pcl::fromPCLPointCloud2(blob, cloud);
  pcl::console::setVerbosityLevel(level);
  std::vector<ReachTarget> targets;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const pcl::PointNormal& p = cloud[i];
    try {
      targets.push_back(targetFromNormal(p.getVector3fMap().cast<double>(),
                                         p.getNormalVector3fMap().cast<double>()));
    } catch (const Error& e) {
      throw Error(path + ": point " + std::to_string(i) + ": " + e.what());
    }
  }
  return targets;
}

std::vector<ReachTarget> targetsFromCsv(const std::string& path) {
  std::istringstream text(readTextFile(path, "targets file"));
  std::string line, header;
  int number = 0;
  std::vector<ReachTarget> targets;
  while (std::getline(text, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    const std::string where = path + ":" + std::to_string(number) + ": ";
    if (header.empty()) {
      header = line;
      header.erase(std::remove_if(header.begin(), header.end(),
                                  [](char c) { return c == ' ' || c == '\t'; }),
                   header.end());
      if (header != "x,y,z,normal_x,normal_y,normal_z" && header != "x,y,z,roll,pitch,yaw") {
        throw Error(where + "header '" + line +
                    "' is neither x,y,z,normal_x,normal_y,normal_z nor x,y,z,roll,pitch,yaw");
      }
      continue;
    }
    if (line.find_last_not_of(" \t") != std::string::npos &&
        line[line.find_last_not_of(" \t")] == ',') {
      throw Error(where + "ends with a comma: an empty value");
    }
    double v[6];
    std::istringstream fields(line);
    std::string field;
    int count = 0;
    while (std::getline(fields, field, ',')) {
      if (count == 6) throw Error(where + "more than 6 values");
      char* end = nullptr;
      v[count] = std::strtod(field.c_str(), &end);
      const bool decimal = field.find_first_of("xXpP") == std::string::npos;  // no hex floats
      if (end == field.c_str() || !decimal ||
          field.find_first_not_of(" \t", end - field.c_str()) != std::string::npos ||
          !std::isfinite(v[count])) {
        throw Error(where + "value " + std::to_string(count + 1) + " '" + field +
                    "' is not a finite number");
      }
      ++count;
    }
    if (count != 6) throw Error(where + std::to_string(count) + " values, 6 wanted");
    const Eigen::Vector3d point(v[0], v[1], v[2]), rest(v[3], v[4], v[5]);
    try {
      if (header == "x,y,z,roll,pitch,yaw") {
        ReachTarget target;
        target.pose = poseFromXyzRpy(point, rest);
        target.free_roll = false;
        targets.push_back(target);
      } else {
        targets.push_back(targetFromNormal(point, rest));
      }
    } catch (const Error& e) {
      throw Error(where + e.what());
    }
  }
  if (header.empty()) throw Error(path + ": no header line (x,y,z,normal_x,... or x,y,z,roll,...)");
  return targets;
}

}  // namespace

std::vector<ReachTarget> loadTargets(const std::string& path) {
  std::vector<ReachTarget> targets =
      endsWith(path, ".csv") ? targetsFromCsv(path) : targetsFromPcd(path);
  if (targets.empty()) throw Error(path + ": no targets");
  return targets;
}

void applyStandoff(std::vector<ReachTarget>& targets, double standoff) {
  for (ReachTarget& target : targets) {
    target.pose.translation() -= standoff * target.pose.linear().col(2);
  }
}

// Declared in reach_study.h, with ReachTarget; here with the readers that make targets of points
// and normals (also what the study reader needs, without the IK).
ReachTarget targetFromNormal(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
  if (!point.allFinite()) throw Error("target point is not finite");
  const double length = normal.norm();
  if (!std::isfinite(length) || !(length > 0.0)) {
    std::ostringstream msg;
    msg << "target normal (" << normal.transpose() << ") is not a non-zero finite vector";
    throw Error(msg.str());
  }
  const Eigen::Vector3d approach = -normal / length;
  const Eigen::Vector3d x = OrientationBins::rollReference(approach);
  ReachTarget target;
  target.pose.linear() << x, approach.cross(x), approach;
  target.pose.translation() = point;
  target.free_roll = true;
  return target;
}

}  // namespace mcws
